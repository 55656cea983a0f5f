/* returnmap.h: first-return maps of balls falling on a floor (Yasuda
 * sec. 2.5, Figs 2-3; Whelan et al.): the state (z, v) of one ball (the
 * "recorded" ball, default the upper ball 2) each time another ball (the
 * "trigger", default the lower ball 1) is at its lowest point after
 * hitting the floor.
 *
 * Locating the instant.  The trigger ball's lowest point is where its
 * velocity changes sign from negative to non-negative (during free flight
 * gravity and the ball above can only decrease v, so an increase through 0
 * happens only in floor contact).  For fixed-step integrators the step in
 * which this happens is found from the end states, and the instant inside
 * it from the cubic Hermite interpolant of the trigger's position through
 * (z, v) at both ends: its derivative, a quadratic, changes sign in the
 * step and its root theta* in [0, 1] is found by bisection to round-off.
 * The cubic Hermite interpolant is third order (error O(dt^4) in z), so
 * theta* carries an O(dt^3) error.  The recorded ball's z and v at theta*
 * come from the cubic Hermite interpolants through (z, v) and through
 * (v, a) at both ends (a: two force evaluations per event, not counted as
 * integrator work).  For integrators with rootfinding (ARKODE) the event
 * g = v_trigger (increasing) is located by ARKODE inside its steps and the
 * state there is ARKODE's dense output.
 *
 * Several minima in one contact.  When the ball above lands on the
 * trigger ball while it is on the floor, the trigger can go down, up, down
 * and up again without leaving the floor: two or more minima in one floor
 * contact.  We record ONE point per floor contact, at its deepest minimum
 * (the paper's "lowest position after colliding with the floor"); a
 * contact is over when a step ends with the trigger ball at or above its
 * radius.  /return_map/minima stores how many minima the contact had, and
 * the count of contacts with more than one is reported.  A contact still in
 * progress when the run ends is not recorded.
 *
 * Output (when [return_map] enabled = yes): /return_map/time (s),
 * /return_map/z (cm), /return_map/v (cm/s) of the recorded ball,
 * /return_map/z_trigger (cm, the trigger's lowest position) and
 * /return_map/minima; root attributes return_map_points and
 * return_map_multi_minima.
 *
 * It is an analysis of the time loop (sim.h): an observer of the balls
 * of a model through its ball view.  Private to the library.
 */
#ifndef BALLFILM_ANALYSIS_RETURNMAP_H
#define BALLFILM_ANALYSIS_RETURNMAP_H

#include <stddef.h>

#include "ballfilm/sim.h"

/* The keys of [return_map]. */
typedef struct bf_retmap_keys {
    int enabled;
    long trigger, record; /* 1-based ball numbers */
} bf_retmap_keys;

typedef struct bf_retmap bf_retmap;

extern const bf_series_table bf_retmap_series; /* its datasets */
extern const bf_analysis_type bf_retmap_analysis; /* [return_map] */
extern const bf_observer_type bf_retmap_observer;

/* The points held in memory (arrays of length return value; any pointer
 * may be NULL): every point of a run without an output file.  With an
 * output file the points are streamed to /return_map/... as they are found
 * and none is kept (the run's memory does not grow with its length; with
 * bf_run_ctx keep_map their z and v alone, for bf_results): this returns
 * 0, read them from the file. */
size_t bf_retmap_points(const bf_retmap *rm, const double **t,
                        const double **z, const double **v,
                        const double **z_trigger);
/* Contacts recorded that had more than one minimum. */
size_t bf_retmap_multi_minima(const bf_retmap *rm);

#endif
