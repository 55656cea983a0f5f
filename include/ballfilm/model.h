/* model.h: a model is a solver for one kind of scene (balls on a line, the
 * two-phase film, balls in the film, particle fluids, the MAC tank).
 *
 * Solver versus problem (Basilisk): a model owns its state, declares its
 * parameters (section specs, params.h) and advances one step.  It never
 * sees a scene: the composition layer fills the model's sections into
 * typed structs and hands them over in a bf_model_setup, with the run's
 * time step and length.  The time loop (sim.h) owns time, the output
 * schedule, energy bookkeeping, observers and stopping; it calls the model
 * through this table.  The built-in models are listed in the catalog
 * (src/compose/catalog.c).
 */
#ifndef BALLFILM_MODEL_H
#define BALLFILM_MODEL_H

#include <stdio.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/effect.h"
#include "ballfilm/error.h"
#include "ballfilm/h5out.h"
#include "ballfilm/integrator.h"
#include "ballfilm/params.h"
#include "ballfilm/series.h"

enum {
    BF_MODEL_INTEGRATOR = 1u << 0,    /* uses [scene] integrator */
    BF_MODEL_EFFECTS = 1u << 1,       /* uses [scene] effects */
    BF_MODEL_BALL_ANALYSES = 1u << 2, /* shows its balls (ball_view) to the
                                         analyses of balls (sim.h) */
    BF_MODEL_WATCH = 1u << 3          /* its advance honours a watch
                                         (integrator.h, bf_ball_watch) */
};

/* The run a model is built for. */
typedef struct bf_run_ctx {
    double dt;         /* [scene] dt, s */
    double t_end;      /* [scene] t_end, s */
    long nsteps;       /* steps of the run, ceil(t_end/dt) */
    long output_every; /* steps between output rows ([scene] output_every) */
    /* 1: hold every return-map point's position and velocity in memory
     * also when they go to an output file (16 B a point), for the results
     * (bf_results: a sweep's statistics of the map); 0: a run with an
     * output file keeps none (its memory does not grow with its length) */
    int keep_map;
} bf_run_ctx;

/* One of the model's sections, filled: `values` points to `count` structs
 * of spec->size bytes (count > 1 only for indexed sections such as
 * [ball.N]; count 0: an indexed section of which the scene has none). */
typedef struct bf_setup_section {
    const bf_section_spec *spec;
    const void *values;
    size_t count;
} bf_setup_section;

typedef struct bf_model_setup {
    bf_run_ctx run;
    const bf_setup_section *sections; /* the model's specs, in its order */
    size_t nsections;
    /* models with BF_MODEL_INTEGRATOR: the integrator and its [integrator]
     * struct (NULL when the type has no spec) */
    const bf_integrator_type *integrator;
    const void *integrator_params;
    /* models with BF_MODEL_EFFECTS: the effects in the scene's order and
     * their structs (NULL for an effect without a spec) */
    const bf_effect_type *const *effects;
    const void *const *effect_params;
    size_t neffects;
    /* processes that will run the model split between them (bf_sim_opts
     * nranks; <= 1: one process): a model that can be split allocates its
     * work for its share only, once it is split */
    int nranks;
} bf_model_setup;

/* The values of a section of the setup (*count: how many; may be NULL),
 * or NULL if the model did not declare it. */
const void *bf_setup_get(const bf_model_setup *s, const bf_section_spec *spec,
                         size_t *count);

/* A second trajectory of a model's balls that an analysis keeps (the
 * shadow of a Lyapunov estimate), stepped by the model as it steps its
 * own balls (bf_ball_view, step_twin).  The analysis owns it. */
typedef struct bf_ball_twin {
    bf_integrator *it; /* an instance of the view's integrator type with
                          the view's [integrator] parameters */
    double *x, *v;     /* bf_ode.n values each (the balls, then any work
                          the model tracks) */
    double t_cached;   /* s, the model's bookkeeping of the force cache:
                          NAN at the start and after the twin is moved */
} bf_ball_twin;

/* What analyses of balls on a line see of a model (returnmap.h,
 * lyapunov.h, compare.h): the state, read-only, the forces and the
 * integrator that advances it. */
typedef struct bf_ball_view {
    size_t n;
    const double *x, *v;        /* positions (cm), velocities (cm/s) */
    const double *m, *R;        /* masses (g), radii (cm) */
    const bf_ode *ode;          /* a(t, x, v) of the model's forces */
    bf_integrator *it;          /* its integrator (type, counters, events) */
    const void *it_params;      /* that integrator's [integrator] struct */
    const bf_effect_type *const *effects;
    size_t neffects;
    /* One step of a twin from t to t + dt, taken exactly as the model
     * takes its own (with its event splitting: the twin's own contact
     * onsets and releases located); on failure the twin is left at t.
     * ctx: the model's (step_ctx).  NULL (a model without event
     * splitting): the twin takes bf_integrator_step through ode. */
    bf_status (*step_twin)(void *step_ctx, bf_ball_twin *tw, double t,
                           double dt, bf_err *err);
    void *step_ctx;
} bf_ball_view;

/* Results of the analyses of a run, for sweeps and drivers (NAN / 0 when
 * the analysis is not on). */
typedef struct bf_results {
    int has_lyapunov;
    double lyapunov_exponent; /* 1/s; NAN before the first renormalisation */
    double lyapunov_time;     /* s, the time the estimate refers to */
    int has_return_map;
    size_t map_points;
    size_t map_multi_minima;  /* contacts with more than one minimum */
    /* the map's points, all map_points of them, with an output file or
     * without: position (cm) and velocity (cm/s) of the recorded ball;
     * NULL when the run does not hold all of them (continued from a
     * checkpoint: the earlier ones are in the file) */
    const double *map_z, *map_v;
} bf_results;

/* A model's largest stable time step (model type's stable_dt). */
typedef struct bf_dt_limit {
    double dt_max;       /* largest stable [scene] dt, s; 0: no limit */
    char why[512];       /* what decides it, completing "dt = 0.01 s exceeds
                            ...": "the film's stable limit 0.00318 s (...)" */
    char advice[256];    /* what to do about it ("" if nothing to say) */
    char section[64];    /* the key to name when dt exceeds it ("": */
    char key[64];        /* [scene] dt) */
} bf_dt_limit;

/* One array of a model's state (its state hook; sim.h, bf_sim_state),
 * named like its dataset in the output without the leading slash
 * ("balls/position", "film/h", "particles/x"). */
typedef struct bf_state_var {
    const char *name;
    const char *unit;
    size_t n;           /* elements */
    const double *data; /* the current values: read-only, valid until the
                           next step */
    int settable;       /* set_state takes it before the first step */
} bf_state_var;

/* What a run of a model will need, estimated from its setup before
 * anything is allocated (model type's memory). */
typedef struct bf_mem_need {
    double bytes;      /* the peak, B (the program's own reserve aside) */
    char what[256];    /* how it arises, completing "[film] dx: ...":
                          "5e+08 nodes (length 50 cm / dx 1e-07 cm) x 36
                          doubles" */
    char section[64];  /* the key that sets the size ("" for none) */
    char key[64];
} bf_mem_need;

typedef struct bf_model_type {
    const char *name;
    const char *doc;
    unsigned flags;
    /* sections owned by the model, NULL-terminated (may be NULL) */
    const bf_section_spec *const *specs;

    /* Build from the filled sections; validate the physics (overlaps,
     * ranges) with failures that name the key (bf_fail_key). */
    bf_status (*create)(void **self, const bf_model_setup *setup,
                        bf_err *err);
    void (*destroy)(void *self);
    /* The memory a run of the model set up so will need (bf_mem_need),
     * from the setup alone: the composition layer asks before create and
     * refuses (BF_EINPUT, naming the key) a run that needs more than the
     * process may allocate.  Optional (NULL: a few MiB at most). */
    void (*memory)(const bf_model_setup *setup, bf_mem_need *need);
    /* The largest stable step of the model as set up (bf_dt_limit; leave
     * lim->dt_max 0 for none).  The loop asks once, when the run is
     * built, and refuses a larger [scene] dt with lim's text and key.
     * Optional. */
    void (*stable_dt)(const void *self, bf_dt_limit *lim);
    /* Advance from t = n dt to t + dt.  A failure message should say what
     * went wrong and where (ball, node, cell); the loop adds step and time. */
    bf_status (*step)(void *self, long n, double t, double dt, bf_err *err);
    /* Kinetic and potential energy (erg).  Optional: NULL if the model has
     * no conserved energy to monitor. */
    void (*energy)(const void *self, double t, double *kin, double *pot);
    /* The largest relative energy error a run of the model as set up can
     * have and still be a result (0: its energy is not conserved, no
     * bound).  The loop stops a run beyond it as unstable unless [scene]
     * max_energy_error replaces it or energy_bound = no.  Optional. */
    double (*energy_bound)(const void *self);
    /* The tables of the datasets output_open creates (series.h),
     * NULL-terminated: what the model's files hold, for listings and the
     * documentation check (the loop's own are bf_sim_series). */
    const bf_series_table *const *series;
    /* Create the model's datasets; called once before the first row. */
    bf_status (*output_open)(void *self, bf_out *out, bf_err *err);
    /* Append one output row of the model's series (state at t). */
    bf_status (*output_row)(void *self, long n, double t, bf_err *err);
    /* Write anything collected during the run (optional). */
    bf_status (*output_close)(void *self, bf_out *out, bf_err *err);
    /* Counters of the time integration (optional). */
    void (*counters)(const void *self, bf_counters *c);
    /* Extra lines for the end-of-run summary (optional). */
    void (*report)(const void *self, FILE *f);
    /* Save everything needed to continue bit for bit after `load` into a
     * model freshly created from the same scene: state, integrator
     * counters and history, RNG state, events collected for output_close.
     * Both are required for `ballfilm run --restart`; a model without them
     * refuses checkpoint_every and restarts with a clear message. */
    bf_status (*checkpoint_save)(const void *self, bf_ckpt *ck, bf_err *err);
    bf_status (*checkpoint_load)(void *self, const bf_ckpt *ck, bf_err *err);
    /* Optional: k >= 1 steps in one call, step j from t = (n + j) dt to
     * (n + j + 1) dt, with exactly the results of k calls of step (same
     * bits, counters, everything a checkpoint saves); *done receives the
     * number of steps that succeeded (on failure the state is that of the
     * failed step, as with step).  The loop hands such a model the runs of
     * steps between the events it owns (output rows, energy checks,
     * checkpoints, stop conditions), so that a step of a few nanoseconds
     * does not pay for a call and the loop's bookkeeping.  A model with
     * BF_MODEL_WATCH takes a watch w (else w is NULL): the run then makes
     * the loop's energy check and the analyses' event checks after every
     * step itself and ends after the first step at which one fires
     * (integrator.h, bf_ball_watch), with the bits of the steps taken one
     * at a time. */
    bf_status (*advance)(void *self, long n, long k, double dt,
                         bf_ball_watch *w, long *done, bf_err *err);
    /* Optional: models whose state is balls on a line fill *v (analyses
     * observe them through it) and return 1. */
    int (*ball_view)(void *self, bf_ball_view *v);
    /* Optional: the model's own analysis results (the coupled model's
     * return map and Lyapunov shadow). */
    void (*results)(const void *self, bf_results *r);
    /* Optional: the arrays of the state, at most cap of them into vars;
     * returns how many the model has. */
    size_t (*state)(void *self, bf_state_var *vars, size_t cap);
    /* Optional: replace the settable array `name` of state by v[0..n-1]
     * before the first step (initial fields from arrays, where a scene
     * offers only a few shapes).  The values are checked as the scene's
     * keys would be (h > 0, |psi| <= 1, balls in order without overlap,
     * particles inside the box), failures naming the array and the
     * element; derived state (forces, totals) follows. */
    bf_status (*set_state)(void *self, const char *name, const double *v,
                           size_t n, bf_err *err);
    /* Optional: the work of the non-conservative forces since t = 0
     * (erg): dissipated (>= 0) and injected by driving.  Returns 1 when
     * the model tracks it (then the loop checks, writes and reports the
     * balance E - E0 + W_diss - W_inj instead of E - E0), else 0. */
    int (*work)(const void *self, double *diss, double *inj);
    /* Optional: the model's convergence study (study.h), for `ballfilm
     * converge` (NULL: the model has none). */
    const struct bf_study_type *study;
} bf_model_type;

#endif
