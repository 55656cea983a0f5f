/* sim.h: the single time loop shared by every model.
 *
 * The loop owns time (t = n dt, never accumulated), the output schedule
 * ([scene] output_every), energy bookkeeping (relative error against the
 * initial energy, every [scene] energy_every steps), the stop conditions
 * (non-finite state reported by the model, energy bound: [scene]
 * max_energy_error, or the model's own for a model whose energy is
 * conserved, interruption), the
 * progress line and the summary.  It ends with a named status (error.h).
 *
 * Observers (Basilisk's events, REBOUND's heartbeat) hook into the loop
 * without knowing the model's insides: before and after every step, at
 * output rows, when the output opens and closes, in checkpoints and in the
 * summary.  The analyses of balls (return maps, Lyapunov exponents,
 * integrator comparisons) are observers; so is a library user's callback.
 *
 * The loop never reads a scene: the composition layer (run.h) builds the
 * model, hands over the filled [scene] keys and the scene's text for the
 * provenance of the output and of checkpoints.
 */
/* Misuse is refused, never a crash or a success: a NULL sim, path, name
 * or function, a non-finite time or value, a negative count, and a call
 * out of order (an observer after the run started, a second output or one
 * after the first step, steps after a failed run or after the output
 * closed, an output closed as ok before t_end) return BF_EINPUT with a
 * message naming the function and the argument ("bf_sim_run_until: t =
 * nan is not finite").  err may be NULL wherever a call takes one (the
 * message is then dropped).  A callback (a model's hook, an observer's, a
 * heartbeat) that returns a value no status of error.h is ends the run
 * with BF_EINTERNAL naming it; one that fails without a message gets a
 * message naming it. */
#ifndef BALLFILM_SIM_H
#define BALLFILM_SIM_H

#include <signal.h>
#include <stdio.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/h5out.h"
#include "ballfilm/integrator.h"
#include "ballfilm/model.h"
#include "ballfilm/params.h"
#include "ballfilm/series.h"

typedef struct bf_sim bf_sim;

/* The datasets of the loop itself: /time, /step and, for a model with an
 * energy, /energy/{kinetic,potential,total} (series.h). */
extern const bf_series_table bf_sim_series;

/* The keys of [scene], the section every scene has. */
typedef struct bf_sim_keys {
    const char *title;
    const char *model;
    const char *integrator;
    bf_names effects;
    double dt;                    /* s */
    double t_end;                 /* s */
    bf_interval output_every;     /* steps or s */
    long energy_every;            /* steps (0: at output rows) */
    double max_energy_error;      /* 1 (0: no bound) */
    int energy_bound;             /* 1: the model's bound applies when
                                     max_energy_error is 0 (model.h,
                                     energy_bound) */
    double flush_seconds;         /* s of wall time */
    bf_interval checkpoint_every; /* steps or s (0: when interrupted) */
    long compress;                /* deflate level of large datasets (0: off) */
} bf_sim_keys;

extern const bf_section_spec bf_sim_scene_spec; /* [scene] */

/* The run context of [scene]: dt, t_end, ceil(t_end/dt) steps (refused,
 * naming [scene] t_end, when too many), the output interval in steps.
 * Keys a program filled itself are checked as a scene's are: dt and t_end
 * finite and positive, no negative interval, count or bound, compress 0
 * to 9 (BF_EINPUT naming the key). */
bf_status bf_sim_run_ctx(const bf_sim_keys *k, bf_run_ctx *run,
                         bf_err *err);

typedef struct bf_sim_opts {
    int progress; /* 1: print an updating progress line on stderr */
    /* Set asynchronously (signal handler) to stop after the current step
     * (or run of steps, at most 1024: model.h, advance). */
    const volatile sig_atomic_t *stop_flag;
    /* Stop as if interrupted after this many steps of this invocation
     * (0: never); used to run in chunks and by the restart tests. */
    long stop_after;
    /* Keep OUT.ckpt when the run ends normally (it is removed otherwise:
     * a finished run needs no restart). */
    int keep_checkpoint;
    /* Take every step one at a time, never runs of steps (model.h,
     * advance): the same results, slower; for the tests that show it. */
    int step_by_step;
    /* Hold the return map's points in memory although they go to the
     * output file, so that bf_sim_results has them (model.h, bf_run_ctx
     * keep_map; 16 B a point): what a sweep's result columns need. */
    int keep_map_points;
    /* This process is rank `rank` of `nranks` that run one model split
     * between them (models that support it: greenspan72; nranks <= 1: one
     * process).  The model is built for the split (it does not allocate
     * its work for all particles), and only rank 0 writes: on the others
     * the model's output rows and checkpoints are still taken at the
     * steps where rank 0 takes them, with no file (the model gathers its
     * state there for rank 0), so rank 0 must open an output (or none of
     * the ranks run with nranks > 1). */
    int rank, nranks;
} bf_sim_opts;

/* Where the run comes from, for the output's provenance and for
 * checkpoints (strings are copied): the scene's path and text, the
 * overrides applied to it (one per line), and a function that writes
 * every resolved parameter as root attributes of the output. */
typedef struct bf_provenance {
    const char *scene_path;
    const char *scene_text;
    const char *scene_sets;
    bf_status (*write_params)(void *ctx, bf_out *out, bf_err *err);
    void *ctx;
} bf_provenance;

/* A loop over `model` (of type mt, built for the run context of k; the
 * sim owns it from now on, also on failure).  Refuses a [scene] dt above
 * the model's stable step (model.h, stable_dt) and checkpoint_every for a
 * model that cannot write checkpoints, naming the key.  Failures that
 * name a key are left for the caller to locate in the scene. */
bf_status bf_sim_create(bf_sim **sim, const bf_sim_keys *k,
                        const bf_model_type *mt, void *model,
                        const bf_provenance *prov, const bf_sim_opts *opts,
                        bf_err *err);
void bf_sim_free(bf_sim *sim);

/* Something the sim frees with itself (the composition layer's setup). */
void bf_sim_own(bf_sim *sim, void *ctx, void (*free_fn)(void *));

/* ---- observers ---- */

enum {
    /* before_step/after_step are called around every step (the loop then
     * takes one step at a time instead of runs of steps) */
    BF_OBS_STEPS = 1u << 0
};

typedef struct bf_observer_type {
    const char *name;
    unsigned flags;
    /* around the step from t = n dt to t + dt; after_step gets n + 1, the
     * number of steps done */
    bf_status (*before_step)(void *self, long n, double t, double dt,
                             bf_err *err);
    bf_status (*after_step)(void *self, long n_done, double t, double dt,
                            bf_err *err);
    /* Optional, for observers with BF_OBS_STEPS of a model with
     * BF_MODEL_WATCH: the observer needs its step hooks only at the steps
     * where a check of the ball state fires.  `watch` fills the events of
     * w (low, above, above_x) for the next run of steps and returns 1, or
     * returns 0 when it needs every step for now; after a run that ended
     * on an event or noted one (w->fired: BF_WATCH_ABOVE does not end a
     * run, integrator.h) the loop calls `watched` with the run's watch
     * (the state at the start of the last step in w->x_start, w->v_start)
     * in place of before_step/after_step around the steps of its events,
     * and also after a run that failed having noted BF_WATCH_ABOVE (then
     * that bit alone; what it returns is not looked at).  At most one
     * observer of a run is watched this way (more: every step is taken
     * one at a time). */
    int (*watch)(void *self, bf_ball_watch *w);
    bf_status (*watched)(void *self, const bf_ball_watch *w, long n_done,
                         double t, double dt, bf_err *err);
    bf_status (*output_open)(void *self, bf_out *out, bf_err *err);
    bf_status (*output_row)(void *self, long n, double t, bf_err *err);
    bf_status (*output_close)(void *self, bf_out *out, bf_err *err);
    void (*report)(const void *self, FILE *f);
    bf_status (*save)(const void *self, bf_ckpt *ck, bf_err *err);
    bf_status (*load)(void *self, const bf_ckpt *ck, bf_err *err);
    void (*results)(const void *self, bf_results *r);
    void (*destroy)(void *self);
    /* the state was replaced before the first step (bf_sim_set): start
     * again from it (the Lyapunov shadow is seeded anew) */
    bf_status (*state_set)(void *self, bf_err *err);
} bf_observer_type;

/* Attach an observer (called in the order attached, after the model's own
 * hooks); the sim owns `self` and destroys it with itself (also when it
 * is refused).  Refused after the output opened or the first step. */
bf_status bf_sim_observe(bf_sim *sim, const bf_observer_type *t, void *self,
                         bf_err *err);
/* The first attached observer of type t, or NULL. */
void *bf_sim_observer(bf_sim *sim, const bf_observer_type *t);

/* A heartbeat (REBOUND's): fn(ctx, sim, err) at t = 0 and then every
 * `every` steps, or (every = 0) after each output row is written, with
 * the whole sim to read (bf_sim_time, bf_sim_get, bf_sim_state, the
 * energy error); it runs in the loop's thread.  It must not change the
 * state.  Returning BF_INTERRUPTED stops the run as an interruption does
 * (checkpoint written when there is an output); any other failure stops
 * it with that status and message.  Heartbeats every N steps end the
 * loop's runs of steps there (model.h, advance): the same bits. */
typedef bf_status (*bf_heartbeat_fn)(void *ctx, bf_sim *sim, bf_err *err);
bf_status bf_sim_heartbeat(bf_sim *sim, long every, bf_heartbeat_fn fn,
                           void *ctx, bf_err *err);

/* ---- analyses of balls ----
 * An analysis is an observer made from its section's keys for a model
 * that shows its balls (model.h, ball_view; models with the flag
 * BF_MODEL_BALL_ANALYSES).  The composition layer creates the analyses
 * its catalog lists whose keys enable them. */
typedef struct bf_analysis_env {
    const bf_ball_view *view;
    const bf_run_ctx *run;
    /* integrator types by name (the catalog's); NULL if unknown */
    const bf_integrator_type *(*integrator)(const void *ctx,
                                            const char *name);
    const void *ctx;
} bf_analysis_env;

typedef struct bf_analysis_type {
    const char *name;
    const bf_section_spec *spec;
    const bf_observer_type *observer;
    /* the datasets its observer writes (series.h; NULL: none) */
    const bf_series_table *series;
    /* *self = NULL when the keys leave it off; failures name the key */
    bf_status (*create)(void **self, const void *keys,
                        const bf_analysis_env *env, bf_err *err);
} bf_analysis_type;

/* ---- running ---- */

/* Create the output file and its datasets; write the provenance (version,
 * scene text, every resolved parameter with its unit).  A checkpoint OUT.ckpt
 * left by an earlier run on the same path is removed (this run owns OUT
 * now).  Without an output file the run still tracks energy and counters.
 * Refused (a run has one output, whose rows start at t = 0): a second
 * output, and one after the first step or after bf_sim_run_until(sim, 0). */
bf_status bf_sim_open_output(bf_sim *sim, const char *path, bf_err *err);

/* Run to t_end.  On failure the message names step, time and cause; the
 * output file keeps every row up to the last good step and records the
 * status in its root attributes.  These three are refused after a run
 * that failed (other than BF_INTERRUPTED: its state is no result to go on
 * from) and after the output closed; bf_sim_run_until refuses a t that is
 * not finite, bf_sim_steps a negative k. */
bf_status bf_sim_run(bf_sim *sim, bf_err *err);
/* The same, stopping (BF_OK) at the first step whose time reaches t
 * (at most t_end), or after k more steps (at most to t_end); call again
 * to go on.  The output's rows and the results are those of one
 * bf_sim_run. */
bf_status bf_sim_run_until(bf_sim *sim, double t, bf_err *err);
bf_status bf_sim_steps(bf_sim *sim, long k, bf_err *err);

/* Finish the output (final datasets, status, counters) and close it.
 * Refused: a run_status that is no status of error.h, BF_OK for a run
 * that failed or has not reached t_end (the output stays open), and a
 * second close.  A failure's cause in the file is run_err's message, or
 * the status's name when there is none. */
bf_status bf_sim_close_output(bf_sim *sim, bf_status run_status,
                              const bf_err *run_err, bf_err *err);

void bf_sim_summary(const bf_sim *sim, FILE *f);

/* Rough size of the output the rest of the run will write, in bytes (every
 * series at the main output interval), so that the front end can warn
 * before a long run fills the disk. */
double bf_sim_output_estimate(const bf_sim *sim);

/* ---- checkpoints and restart ----
 * With an output file OUT, checkpoints go to OUT.ckpt (atomically), every
 * [scene] checkpoint_every and when a run is interrupted (BF_INTERRUPTED).
 * A restarted run produces bit for bit the datasets of an uninterrupted
 * one.  The composition layer rebuilds the run from the checkpoint's scene
 * (run.h) and calls bf_sim_resume. */
int bf_sim_can_checkpoint(const bf_sim *sim);
const char *bf_sim_checkpoint_path(const bf_sim *sim); /* NULL: none */
bf_status bf_sim_checkpoint_write(bf_sim *sim, const char *path, bf_err *err);
/* Continue from checkpoint ck of the output OUT: the loop's state, the
 * model's and the observers', OUT reopened with the rows written after
 * the checkpoint dropped. */
bf_status bf_sim_resume(bf_sim *sim, const bf_ckpt *ck, const char *out_path,
                        bf_err *err);
/* The same without the output: the loop's, the model's and the observers'
 * state only (OUT is not read nor touched; its name is for messages), for
 * a process that computes and does not write (the ranks other than 0 of a
 * run over ranks). */
bf_status bf_sim_resume_state(bf_sim *sim, const bf_ckpt *ck,
                              const char *out_path, bf_err *err);

/* ---- read-only views for drivers and tests ---- */
void *bf_sim_model(bf_sim *sim);
const bf_model_type *bf_sim_model_type(const bf_sim *sim);
long bf_sim_steps_done(const bf_sim *sim);
long bf_sim_steps_total(const bf_sim *sim);
double bf_sim_time(const bf_sim *sim);
double bf_sim_dt(const bf_sim *sim);
double bf_sim_max_energy_error(const bf_sim *sim); /* relative; NAN if none */
/* The energy now (erg; NAN for a model without one) and at t = 0. */
void bf_sim_energy(const bf_sim *sim, double *kin, double *pot);
double bf_sim_initial_energy(const bf_sim *sim);
double bf_sim_wall_seconds(const bf_sim *sim);
void bf_sim_counters(const bf_sim *sim, bf_counters *c);
/* The analyses' results (the model's and every observer's). */
void bf_sim_results(const bf_sim *sim, bf_results *r);

/* ---- the state as arrays (model.h, bf_state_var) ---- */
/* The model's state arrays (at most cap into vars); returns how many
 * there are (0: the model shows none). */
size_t bf_sim_state(bf_sim *sim, bf_state_var *vars, size_t cap);
/* The current values of one array (*n its length), or NULL when the model
 * has no array of that name (or name is NULL).  bf_sim_state with vars
 * NULL only counts. */
const double *bf_sim_get(bf_sim *sim, const char *name, size_t *n);
/* Initial fields from arrays: replace the array `name` by v[0..n-1]
 * before the first step (BF_EINPUT afterwards, for an unknown or not
 * settable name, a wrong length, v NULL, a value that is not finite or
 * otherwise bad, naming it).  The energy
 * reference, the stable-step check and the observers start again from the
 * new state. */
bf_status bf_sim_set(bf_sim *sim, const char *name, const double *v,
                     size_t n, bf_err *err);

#endif
