/* sim_impl.h: the time loop's state, shared by the files of src/core
 * (private): sim.c (the loop, output), sim_state.c (the state as arrays,
 * heartbeats) and sim_ckpt.c (checkpoints and restart). */
#ifndef BALLFILM_CORE_SIM_IMPL_H
#define BALLFILM_CORE_SIM_IMPL_H

#include "ballfilm/sim.h"
#include "diag/energy.h"
#include "core/model_energy.h"

typedef struct heartbeat {
    long every; /* steps; 0: after every output row */
    bf_heartbeat_fn fn;
    void *ctx;
} heartbeat;

typedef struct observer {
    const bf_observer_type *t;
    void *self;
} observer;

struct bf_sim {
    const bf_model_type *mt;
    void *model;
    bf_sim_opts opts;
    /* provenance (owned copies) */
    char *scene_path, *scene_text, *scene_sets;
    /* what ties an output and its checkpoints together (16 hex digits
     * each): this run's identifier, and the hash of the scene it was
     * started with (its text, a NUL, the overrides); a restart takes both
     * from the checkpoint */
    char run_id[20], scene_hash[20];
    bf_status (*write_params)(void *ctx, bf_out *out, bf_err *err);
    void *params_ctx;
    /* something the composition layer hands over to be freed with us */
    void *owned;
    void (*owned_free)(void *);
    observer *obs;
    size_t nobs;
    int obs_steps; /* some observer watches every step */
    double dt, t_end;
    long nsteps, n;
    long out_every, energy_every, ckpt_every;
    long steps_this_run;
    char *ckpt_path;
    double energy_bound, flush_seconds;
    int bound_is_models; /* energy_bound is the model's default bound */
    int compress; /* deflate level of the output (0: off) */
    bf_out *out;
    bf_series *s_time, *s_step, *s_ek, *s_ep, *s_et;
    long last_row; /* step of the last output row, -1 if none */
    int has_energy;
    int has_work; /* the model tracks the work of non-conservative forces
                     (model.h, work): the energy is a balance */
    bf_series *s_wd, *s_wi;
    bf_energy_diag en;
    double wall;
    double prog_last;
    heartbeat *hb; /* bf_sim_heartbeat, in the order attached */
    size_t nhb;
    int hb_started; /* the heartbeats of t = 0 were called */
    bf_status run_status; /* how the last bf_sim_run ended */
    int closed; /* its output was closed: the run is over */
};

/* Call hook H of every observer that has it with the arguments after self,
 * the last of which is the enclosing function's `err`; stop at the first
 * failure, a status with a cause (bf_sim_hook_status_). */
#define EACH_OBSERVER(s, st, H, ...)                                           \
    for (size_t k_ = 0; !(st) && k_ < (s)->nobs; k_++)                         \
        if ((s)->obs[k_].t->H)                                                 \
    (st) = bf_sim_hook_status_(                                                \
        (s)->obs[k_].t->H((s)->obs[k_].self, __VA_ARGS__), "observer",         \
        (s)->obs[k_].t->name, #H, err)

/* [scene] dt against the model's stable step (model.h, stable_dt). */
bf_status bf_sim_check_stable_dt(const bf_sim *s, bf_err *err);

/* The heartbeats due at step s->n: those every N steps whose N divides
 * it, and (rows = 1) those of the output rows. */
bf_status bf_sim_beat(bf_sim *s, int rows, bf_err *err);

/* The state now against finiteness and the energy bound (BF_EUNSTABLE
 * naming step, time and cause), before the last output row is written. */
bf_status bf_sim_check_state_(bf_sim *s, bf_err *err);
/* The failure of a relative energy error rel beyond the run's bound,
 * naming step, time, the bound and the key that sets it (sim.c). */
bf_status bf_sim_energy_exceeded_(const bf_sim *s, double rel, bf_err *err);
/* sim_ids.c: a new random run_id (16 hex digits), and the hash of the
 * scene's text and its overrides (scene_hash), as written into the output
 * and the checkpoint. */
void bf_sim_new_run_id_(char buf[20]);
void bf_sim_scene_hash_(const char *text, const char *sets, char buf[20]);

/* OUT.ckpt of output path OUT into s->ckpt_path. */
bf_status bf_sim_set_ckpt_path_(bf_sim *s, const char *path, bf_err *err);
/* The loop's datasets (created, or reopened on restart), then the model's
 * and the observers'. */
bf_status bf_sim_open_series_(bf_sim *s, bf_err *err);

/* ---- sim_api.c: what the public calls refuse (BF_EINPUT naming the
 * function and the argument) ---- */
/* 1 if st is one of error.h's statuses. */
int bf_sim_status_valid_(bf_status st);
/* What hook `hook` of a callback (kind "model", "observer", "heartbeat";
 * name NULL: none) returned, made a status of error.h with a cause:
 * BF_EINTERNAL for a value that is none, the status named for a failure
 * without a message. */
/* A rank other than 0 of a run split over ranks (bf_sim_opts): it takes
 * the model's rows and checkpoints with rank 0, and writes nothing. */
static inline int bf_sim_follower_(const bf_sim *s)
{
    return s->opts.nranks > 1 && s->opts.rank > 0;
}
bf_status bf_sim_hook_status_(bf_status st, const char *kind,
                              const char *name, const char *hook,
                              bf_err *err);
/* p NULL: "fn: arg is NULL". */
bf_status bf_sim_null_(const void *p, const char *fn, const char *arg,
                       bf_err *err);
/* Keys a program filled itself: finite positive dt and t_end, no negative
 * interval, count or bound. */
bf_status bf_sim_keys_ok_(const bf_sim_keys *k, bf_err *err);
/* Observers come before the output and the first step. */
bf_status bf_sim_may_observe_(const bf_sim *s, const bf_observer_type *t,
                              bf_err *err);
/* One output, opened before the first step. */
bf_status bf_sim_may_open_(const bf_sim *s, const char *path, bf_err *err);
/* Steps only from a state that is a result, before the output closed. */
bf_status bf_sim_may_run_(const bf_sim *s, const char *fn, bf_err *err);
/* A status of error.h, ok only for a run that reached t_end. */
bf_status bf_sim_may_close_(const bf_sim *s, bf_status run_status,
                            bf_err *err);

/* The public calls that reach HDF5 hold its lock (io/h5lock.h; it is
 * recursive, so a locked call may make another). */
#define H5_LOCKED(call)                                                        \
    do {                                                                       \
        bf_h5_lock();                                                          \
        bf_status st_ = (call);                                                \
        bf_h5_unlock();                                                        \
        return st_;                                                            \
    } while (0)

/* k + p (erg) at t, plus W_dissipated - W_injected when the model tracks
 * the work of non-conservative forces (has_work): what the energy check
 * compares with its start (sim_state.c). */
double bf_sim_balance_(const bf_sim *s, double t, double *k, double *p);

#endif
