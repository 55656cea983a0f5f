/* converge.h: convergence and work-precision study of the integrators on a
 * ball scene (`ballfilm converge`).
 *
 * Every method runs the scene's ball system from t = 0 to T: fixed-step
 * methods at each step size (T/dt rounded up to whole steps, the step then
 * shrunk to T/n so that all runs end exactly at T), adaptive ones at each
 * tolerance (rtol = tol, atol = tol/100 unless the method string sets
 * atol) in one call from 0 to T, so that ARKODE chooses every step.  Each
 * run reports the error at T against a reference, the maximum relative
 * energy error (after every step, internal steps of adaptive methods
 * included), the counters, and the wall time of the stepping loop
 * (minimum over `repeats` runs without energy checks, whose counters are
 * the ones reported).  The observed order
 * between successive runs of a method is log(e1/e2)/log(h1/h2), with h the
 * step (fixed) or the mean internal step T/steps (adaptive).
 *
 * A measured run whose relative energy error exceeds the scene's
 * [scene] max_energy_error (when set) stops and is reported as unstable.
 *
 * The reference is ARKODE's adaptive ERK at rtol = ref_rtol (<= 1e-12)
 * with a Butcher table that none of the compared methods uses (default
 * VERNER_8_5_6 with the issue-311 padding, else DORMAND_PRINCE_7_4_5, else
 * CASH_KARP_6_4_5; not FEHLBERG_13_7_8, whose error estimate is blind to
 * contacts, see converge.c),
 * run twice, at ref_rtol and ref_rtol/10: the tighter one is the
 * reference, and the difference of the two is reported as its estimated
 * error (an over-estimate when the error scales with the tolerance).
 *
 * On scenes with Hertz contacts (floor, contact effects) adaptive methods
 * and the reference get a largest internal step (default 10 x [scene]
 * dt): in free flight under gravity the motion is
 * quadratic, every embedded error estimate is zero and ARKODE grows the
 * step by its maximum factor until one step jumps deep into the floor;
 * without the limit the reference on runs/bouncing_ball.ini took 28 steps
 * to T = 100 s and ended at 9e35 cm.  The reference's own relative energy
 * error at T is reported as a second sanity check.
 *
 * Method strings are "name" or "name:key=value:key=value" where the keys
 * are [integrator] keys of that integrator ("alpha:alpha=0.25",
 * "arkode:table=ARKODE_CASH_KARP_6_4_5").
 */
#ifndef BALLFILM_CONVERGE_H
#define BALLFILM_CONVERGE_H

#include <stdio.h>

#include "ballfilm/integrator.h"
#include "ballfilm/scene.h"

typedef struct bf_converge_opts {
    const char *const *methods;
    size_t nmethods;
    const double *dts; /* NULL: the scene's dt times 4, 2, 1, 1/2 */
    size_t ndts;
    const double *tols; /* NULL: 1e-4, 1e-6, 1e-8, 1e-10 */
    size_t ntols;
    double t_end;          /* 0: [scene] t_end */
    int repeats;           /* timing repeats (0: 3) */
    double ref_rtol;       /* 0: 1e-12 */
    const char *ref_table; /* NULL: automatic */
    double max_step;       /* largest internal step of adaptive methods and
                              the reference, s (0: 10 x [scene] dt when the
                              scene has Hertz contacts, else none; < 0:
                              no limit) */
    FILE *progress;        /* one line per finished run, or NULL */
} bf_converge_opts;

typedef struct bf_converge_row {
    int method;       /* index into the methods */
    char label[160];  /* integrator description with its parameters */
    int adaptive;
    int order;        /* nominal order */
    double dt;        /* step (fixed) or T/steps (adaptive), s */
    double tol;       /* rtol (adaptive), 0 otherwise */
    double err_x;     /* max over balls of |x - x_ref| at T, cm */
    double err_v;     /* max over balls of |v - v_ref| at T, cm/s */
    double energy_err;/* max |E - E0|/|E0| over the run */
    double order_x, order_v; /* observed, NAN for a method's first run */
    bf_counters count;
    double wall;      /* s, minimum over the repeats */
    bf_status status; /* BF_OK, or why the run stopped */
    char msg[BF_ERR_MSG];
} bf_converge_row;

typedef struct bf_converge_result {
    char scene[512];
    double t_end;
    size_t nmethods;
    char **methods;
    bf_converge_row *rows;
    size_t nrows;
    /* the reference */
    char ref_label[160];
    double ref_rtol;
    double ref_err_x, ref_err_v; /* estimated errors of the reference */
    double ref_energy_err;       /* its relative energy error at T */
    double max_step;             /* applied to adaptive runs, s (0: none) */
    bf_counters ref_count;
    double ref_wall;
    size_t n;          /* balls */
    double *x_ref, *v_ref;
    int hertz;         /* the scene has Hertz contacts (floor, contact) */
} bf_converge_result;

/* Run the study on a loaded scene (its --set overrides applied; it is
 * cloned for every run, never modified). */
bf_status bf_converge_run(const bf_scene *sc, const bf_converge_opts *opts,
                          bf_converge_result **out, bf_err *err);
/* The same on a scene file with overrides "section.key=value". */
bf_status bf_converge_file(const char *scene_path, const char *const *sets,
                           size_t nsets, const bf_converge_opts *opts,
                           bf_converge_result **out, bf_err *err);
void bf_converge_free(bf_converge_result *r);
void bf_converge_print(const bf_converge_result *r, FILE *f);
/* The table as HDF5 (/converge/...; see README). */
bf_status bf_converge_write(const bf_converge_result *r, const char *path,
                            bf_err *err);

#endif
