/* converge.h: convergence and work-precision study of the time integrators
 * of any model (`ballfilm converge`).
 *
 * Every method runs the scene's model from t = 0 to T.  Fixed-step
 * methods run at each step size (rounded so that a whole number of steps
 * ends on each output row: n = R ceil(T/(R dt)) steps of T/n), adaptive
 * ones at each tolerance (rtol = tol, atol = tol/100 unless the method
 * string sets atol), one call of the model's step per output row, so that
 * ARKODE chooses every step in between.  The state is compared with a
 * reference at R output rows t_j = j T/R (j = 1..R; `rows`, default 10):
 * per group of state values (ball positions and velocities; the film's
 * psi, h and phase fluxes alpha_k h u_k; particle positions and
 * velocities; ...) the largest absolute difference at T, its maximum and
 * its root mean square over the rows.  Each run also reports the largest relative change of the model's
 * energy, or of its conserved totals (the film's phase totals), checked
 * after every step (and after every internal step of ARKODE on balls),
 * the counters (right-hand-side evaluations), and the wall time of the
 * stepping loop (minimum over `repeats` runs without checks, whose
 * counters are the ones reported).  The observed order between
 * successive runs of a method is log(e1/e2)/log(h1/h2) for each group's
 * error at T, with h the step (fixed) or the mean internal step T/steps
 * (adaptive).
 *
 * A measured run whose relative energy error exceeds the scene's
 * [scene] max_energy_error (when set) stops and is reported as unstable;
 * a fixed step above the model's stable limit (the film's) is reported as
 * unstable without running.
 *
 * The reference is the model's ARKODE integrator at rtol = ref_rtol (each
 * model's study has its own default: 1e-12 for balls and particles,
 * 1e-10 for the film), with a Butcher table that none of the compared methods uses,
 * run twice, at ref_rtol and ref_rtol/10: the tighter one is the
 * reference, and the difference of the two is reported as its estimated
 * error (an over-estimate when the error scales with the tolerance).
 * What each model's reference is, and why, is written in the study of the
 * model (study.h; the built-in models' in src/models/study_*.c) and in
 * docs/accuracy.md.
 *
 * Balls (models balls): the reference uses VERNER_8_5_6 with the issue-311
 * padding, else DORMAND_PRINCE_7_4_5, else CASH_KARP_6_4_5 (not
 * FEHLBERG_13_7_8, whose error estimate is blind to contacts), with
 * rootfinding at every contact onset and release; on scenes with Hertz
 * contacts adaptive methods and the reference get a largest internal step
 * (default 10 x [scene] dt): in free flight under gravity the motion is
 * quadratic, every embedded error estimate is zero and ARKODE grows the
 * step by its maximum factor until one step jumps deep into the floor.
 *
 * Method strings are "name" or "name:key=value:..." where name is the
 * model's time integrator (for balls [scene] integrator, for the film
 * [film] scheme, for greenspan73 [greenspan73] integrator) and
 * each key=value a key of the section that integrator reads ([integrator]
 * for balls: "alpha:alpha=0.25", "arkode:table=ARKODE_CASH_KARP_6_4_5";
 * [film] for the film: "arkode-imex:rtol=1e-6"); a key written
 * section.key ("mv2m:coupled.film_every=10") goes to that section.
 */
#ifndef BALLFILM_CONVERGE_H
#define BALLFILM_CONVERGE_H

#include <signal.h>
#include <stdio.h>

#include "ballfilm/integrator.h"
#include "ballfilm/scene.h"
#include "ballfilm/study.h"

/* groups of compared state values (a model's study, study.h) */
enum { BF_CONVERGE_MAX_GROUPS = BF_STUDY_MAX_GROUPS };

typedef struct bf_converge_opts {
    const char *const *methods;
    size_t nmethods;
    const double *dts; /* NULL: the scene's dt times 4, 2, 1, 1/2 */
    size_t ndts;
    const double *tols; /* NULL: 1e-4, 1e-6, 1e-8, 1e-10 */
    size_t ntols;
    double t_end;          /* 0: [scene] t_end */
    int repeats;           /* timing repeats (0: 3; < 0: none, the measured
                              run's time) */
    long rows;             /* output rows compared (0: 10) */
    double ref_rtol;       /* 0: the model's default */
    const char *ref_table; /* NULL: automatic */
    double max_step;       /* largest internal step of adaptive methods and
                              the reference, s (0: the model's default, for
                              balls with Hertz contacts 10 x [scene] dt,
                              else none; < 0: no limit) */
    int ref_may_be_compared; /* 1: allow a compared method to use the
                                reference's table (at tolerances far above
                                the reference's, benchmarks); 0: refuse */
    int skip_checks;       /* 1: no invariant checks in the runs compared
                              (invariant_err NAN; benchmarks that need the
                              errors and the cost only) */
    FILE *progress;        /* one line per finished run, or NULL */
    /* Set asynchronously (signal handler) to stop the study: checked
     * between runs, after every step and inside ARKODE's internal steps;
     * the study then fails with BF_INTERRUPTED (NULL: never). */
    const volatile sig_atomic_t *stop_flag;
} bf_converge_opts;

typedef struct bf_converge_group {
    char name[32];
    char unit[16];
    size_t n; /* its values in ref_state */
} bf_converge_group;

typedef struct bf_converge_row {
    int method;       /* index into the methods */
    char label[160];  /* integrator description with its parameters */
    int adaptive;
    int order;        /* nominal order (0: unknown) */
    double dt;        /* step (fixed) or T/steps (adaptive), s */
    double tol;       /* rtol (adaptive), 0 otherwise */
    /* per group: max |y - y_ref| at T, its max and RMS over the rows, and
     * the observed order of the first (NAN for a method's first run) */
    double err[BF_CONVERGE_MAX_GROUPS];
    double err_max[BF_CONVERGE_MAX_GROUPS];
    double err_rms[BF_CONVERGE_MAX_GROUPS];
    double order_obs[BF_CONVERGE_MAX_GROUPS];
    double invariant_err; /* max relative change of the energy (or the
                             conserved totals) over the run; NAN: none */
    bf_counters count;
    double wall;      /* s, minimum over the repeats */
    bf_status status; /* BF_OK, or why the run stopped */
    char msg[BF_ERR_MSG];
} bf_converge_row;

typedef struct bf_converge_priv bf_converge_priv;

typedef struct bf_converge_result {
    char scene[512];
    char model[32];
    double t_end;
    long out_rows;     /* output rows compared */
    size_t nmethods;
    char **methods;
    bf_converge_row *rows; /* one per run */
    size_t nrows;
    size_t ngroups;
    bf_converge_group groups[BF_CONVERGE_MAX_GROUPS];
    char invariant[48]; /* what invariant_err measures ("energy", ...) */
    /* the reference */
    char ref_label[160];
    double ref_rtol;
    double ref_err[BF_CONVERGE_MAX_GROUPS];     /* estimated error at T */
    double ref_err_max[BF_CONVERGE_MAX_GROUPS]; /* and its max over rows */
    double ref_invariant_err;  /* its relative energy (totals) error */
    double max_step;           /* applied to adaptive runs, s (0: none) */
    bf_counters ref_count;
    double ref_wall;
    size_t nstate;             /* values of the state compared */
    double *ref_state;         /* the reference's state at T, group after
                                  group */
    char notes[2048];          /* the model's notes on the study ("" none) */
    bf_converge_priv *priv;    /* the study's own state (scene, rows) */
} bf_converge_result;

/* Run the study on a loaded scene (its --set overrides applied; it is
 * cloned for every run, never modified). */
bf_status bf_converge_run(const bf_scene *sc, const bf_converge_opts *opts,
                          bf_converge_result **out, bf_err *err);
/* The same on a scene file with overrides "section.key=value". */
bf_status bf_converge_file(const char *scene_path, const char *const *sets,
                           size_t nsets, const bf_converge_opts *opts,
                           bf_converge_result **out, bf_err *err);

/* The study step by step (drivers that choose the step sizes as they go,
 * bench/bench_accuracy.c): begin validates every method and computes the
 * reference (no rows yet); add runs method m at step size or tolerance
 * `h` (a tolerance for adaptive methods) with `repeats` timing repeats
 * (< 0: none) and appends its row (observed orders against the previous
 * row of the same method); retime runs row k again `repeats` times and
 * keeps the smaller wall time. */
bf_status bf_converge_begin(const bf_scene *sc, const bf_converge_opts *opts,
                            bf_converge_result **out, bf_err *err);
bf_status bf_converge_add(bf_converge_result *r, size_t m, double h,
                          int repeats, bf_err *err);
bf_status bf_converge_retime(bf_converge_result *r, size_t k, int repeats,
                             bf_err *err);
/* Whether method m is adaptive (tolerances) or fixed-step (step sizes). */
int bf_converge_adaptive(const bf_converge_result *r, size_t m);

void bf_converge_free(bf_converge_result *r);
void bf_converge_print(const bf_converge_result *r, FILE *f);
/* The table as HDF5 (/converge/...; docs/output.md). */
bf_status bf_converge_write(const bf_converge_result *r, const char *path,
                            bf_err *err);

#endif
