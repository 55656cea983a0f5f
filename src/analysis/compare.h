/* compare.h: local comparison of two integrators along one trajectory.
 *
 * At every output row, from the state (x, v) of the run at that time, one
 * step of integrator a and one step of integrator b are taken (on copies;
 * the run is not touched) and the difference of the resulting velocities
 * v_a - v_b is written to /compare/dv [rows x balls] (cm/s).  With a =
 * verlet and b = alpha (alpha = 1/8, the default) along an MV2M run this
 * is the difference between the two velocity formulas that MV2M averages,
 * Yasuda eqs 2.19 and 2.20: zero in free fall (both are exact for a
 * constant force), non-zero only during collisions (Fig. 4).  Both use
 * their default parameters.  Costs two steps per output row, nothing per
 * step.  An analysis of the time loop (sim.h) over a model's ball view;
 * private to the library.
 */
#ifndef BALLFILM_ANALYSIS_COMPARE_H
#define BALLFILM_ANALYSIS_COMPARE_H

#include "ballfilm/sim.h"

/* The keys of [compare]. */
typedef struct bf_compare_keys {
    const char *a, *b; /* integrator names ("": no comparison) */
} bf_compare_keys;

extern const bf_series_table bf_compare_series; /* its datasets */
extern const bf_analysis_type bf_compare_analysis; /* [compare] */
extern const bf_observer_type bf_compare_observer;

#endif
