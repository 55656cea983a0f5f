/* sim.c: the time loop (see sim.h).
 *
 * Time is t = n dt with n the step counter, never a running sum, so the
 * time of step 10^7 carries no accumulated round-off.
 *
 * A model with an `advance` hook (model.h) gets the steps between two
 * events of the loop in one call; the events (rows, energy checks,
 * checkpoints, stops) happen at the same steps as with one call per step,
 * and the results are the same bits.  Observers that watch every step
 * (BF_OBS_STEPS) make the loop take one step at a time.
 */
#include "ballfilm/sim.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ballfilm/version.h"
#include "base/clock.h"
#include "core/sim_impl.h"
#include "diag/energy.h"
#include "integrators/stop.h"
#include "io/h5lock.h"
#include "io/outpath.h"

static const bf_param scene_params[] = {
    {"title", BF_AT(bf_sim_keys, title, BF_STR), "", "",
     "free text describing the scene", 0, 0, 0, NULL},
    {"model", BF_AT(bf_sim_keys, model, BF_STR), "", "balls",
     "what is simulated (see Models below)", 0, 0, 0, NULL},
    {"integrator", BF_AT(bf_sim_keys, integrator, BF_STR), "", "mv2m",
     "time integrator for ball models (see Integrators below)", 0, 0, 0, NULL},
    {"effects", BF_AT(bf_sim_keys, effects, BF_NAMES), "", "",
     "ball effects to switch on, e.g. 'gravity floor contact' (see Effects "
     "below); nothing else is computed",
     0, 0, 0, NULL},
    {"dt", BF_AT(bf_sim_keys, dt, BF_REAL), "s", NULL, "time step", BF_POS,
     0, 0, NULL},
    {"t_end", BF_AT(bf_sim_keys, t_end, BF_REAL), "s", NULL,
     "final time; the run takes ceil(t_end/dt) steps", BF_POS, 0, 0, NULL},
    {"output_every", BF_AT(bf_sim_keys, output_every, BF_INTERVAL),
     "steps | s", "1",
     "output interval: 'N' steps or 'T s' of simulated time (rounded to "
     "whole steps); the final state is always written",
     0, 0, 0, NULL},
    {"energy_every", BF_AT(bf_sim_keys, energy_every, BF_INT), "steps", "1",
     "check the energy every N steps (0: only at output rows)", BF_NONNEG, 0,
     0, NULL},
    {"max_energy_error", BF_AT(bf_sim_keys, max_energy_error, BF_REAL), "1",
     "0",
     "stop the run when the relative energy error exceeds this (0: no "
     "bound); when given, it replaces the model's bound (energy_bound)",
     BF_NONNEG, 0, 0, NULL},
    {"energy_bound", BF_AT(bf_sim_keys, energy_bound, BF_BOOL), "", "yes",
     "stop the run as unstable when the relative energy error exceeds the "
     "model's bound, for models whose energy is conserved: balls whose "
     "effects are all conservative 0.5, greenspan73 1e-6 (no: off)",
     0, 0, 0, NULL},
    {"flush_seconds", BF_AT(bf_sim_keys, flush_seconds, BF_REAL),
     "s (wall)", "5",
     "wall-clock interval between HDF5 flushes (what a killed run keeps)",
     BF_POS, 0, 0, NULL},
    {"checkpoint_every", BF_AT(bf_sim_keys, checkpoint_every, BF_INTERVAL),
     "steps | s", "0",
     "write a checkpoint (OUT.ckpt) every 'N' steps or 'T s' (0: only when "
     "interrupted); continue with ballfilm run --restart OUT",
     0, 0, 0, NULL},
    {"compress", BF_AT(bf_sim_keys, compress, BF_INT), "1", "0",
     "compress the series and large arrays of the output with HDF5's "
     "shuffle and deflate filters at this level (1-9; 0: off)",
     BF_MIN | BF_MAX, 0, 9, NULL},
    {0},
};

const bf_section_spec bf_sim_scene_spec =
    BF_SECTION("scene", "what to simulate and how long (every scene has it)",
               scene_params, bf_sim_keys);

bf_status bf_sim_run_ctx(const bf_sim_keys *k, bf_run_ctx *run, bf_err *err)
{
    bf_status st = bf_sim_null_(k, "bf_sim_run_ctx", "k", err);
    if (!st)
        st = bf_sim_null_(run, "bf_sim_run_ctx", "run", err);
    if (!st)
        st = bf_sim_keys_ok_(k, err);
    if (st)
        return st;
    /* t = n dt with n whole: a step longer than the run would end it at
     * dt, past t_end */
    if (k->dt > k->t_end)
        return bf_fail_key(err, BF_EINPUT, "scene", "dt",
                           "dt = %g s exceeds t_end = %g s: the run would "
                           "end at t = dt, past t_end",
                           k->dt, k->t_end);
    double steps = ceil(k->t_end / k->dt * (1.0 - 1e-12));
    if (!(steps < 9e15))
        return bf_fail_key(err, BF_EINPUT, "scene", "t_end",
                           "t_end/dt = %g steps is too many", steps);
    run->keep_map = 0; /* bf_sim_opts keep_map_points sets it */
    run->dt = k->dt;
    run->t_end = k->t_end;
    run->nsteps = (long)steps;
    run->output_every = bf_interval_steps(k->output_every, k->dt);
    if (run->output_every < 1)
        run->output_every = 1;
    return BF_OK;
}

static char *dup_or_empty(const char *s)
{
    return strdup(s ? s : "");
}

void bf_sim_free(bf_sim *s)
{
    if (!s)
        return;
    if (s->out) {
        bf_h5_lock();
        bf_out_close_keep(s->out, NULL);
        bf_h5_unlock();
    }
    free(s->hb);
    for (size_t k = s->nobs; k-- > 0;)
        if (s->obs[k].t->destroy)
            s->obs[k].t->destroy(s->obs[k].self);
    free(s->obs);
    if (s->mt && s->mt->destroy)
        s->mt->destroy(s->model);
    if (s->owned_free)
        s->owned_free(s->owned);
    free(s->scene_path);
    free(s->scene_text);
    free(s->scene_sets);
    free(s->ckpt_path);
    free(s);
}

void bf_sim_own(bf_sim *s, void *ctx, void (*free_fn)(void *))
{
    s->owned = ctx;
    s->owned_free = free_fn;
}

/* The model's largest stable step, refused when [scene] dt exceeds it. */
bf_status bf_sim_check_stable_dt(const bf_sim *s, bf_err *err)
{
    if (!s->mt->stable_dt)
        return BF_OK;
    bf_dt_limit lim = {0};
    s->mt->stable_dt(s->model, &lim);
    if (!(lim.dt_max > 0) || s->dt <= lim.dt_max)
        return BF_OK;
    return bf_fail_key(err, BF_EINPUT, lim.section[0] ? lim.section : "scene",
                       lim.section[0] ? lim.key : "dt",
                       "dt = %g s exceeds %s%s%s", s->dt, lim.why,
                       lim.advice[0] ? "; " : "", lim.advice);
}

bf_status bf_sim_create(bf_sim **out, const bf_sim_keys *k,
                        const bf_model_type *mt, void *model,
                        const bf_provenance *prov, const bf_sim_opts *opts,
                        bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    if (!out || !mt || !mt->step) {
        /* the sim owns the model also on failure */
        if (mt && mt->destroy)
            mt->destroy(model);
        return bf_fail(err, BF_EINPUT, "bf_sim_create: %s is NULL",
                       !out ? "sim" : !mt ? "the model type" : "its step");
    }
    *out = NULL;
    bf_run_ctx run;
    bf_status st = bf_sim_run_ctx(k, &run, err);
    bf_sim *s = st ? NULL : calloc(1, sizeof *s);
    if (!s) {
        if (mt->destroy)
            mt->destroy(model);
        return st ? st : bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    s->mt = mt;
    s->model = model;
    if (opts)
        s->opts = *opts;
    s->scene_path = dup_or_empty(prov ? prov->scene_path : NULL);
    s->scene_text = dup_or_empty(prov ? prov->scene_text : NULL);
    s->scene_sets = dup_or_empty(prov ? prov->scene_sets : NULL);
    if (prov) {
        s->write_params = prov->write_params;
        s->params_ctx = prov->ctx;
    }
    s->dt = run.dt;
    s->t_end = run.t_end;
    s->nsteps = run.nsteps;
    s->out_every = run.output_every;
    s->ckpt_every = bf_interval_steps(k->checkpoint_every, s->dt);
    s->energy_every = k->energy_every;
    s->energy_bound = k->max_energy_error;
    if (!(s->energy_bound > 0) && k->energy_bound && mt->energy_bound) {
        s->energy_bound = mt->energy_bound(model);
        s->bound_is_models = s->energy_bound > 0;
    }
    s->flush_seconds = k->flush_seconds;
    s->compress = (int)k->compress;
    if (!s->scene_path || !s->scene_text || !s->scene_sets)
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    else {
        bf_sim_new_run_id_(s->run_id);
        bf_sim_scene_hash_(s->scene_text, s->scene_sets, s->scene_hash);
    }
    if (!st)
        st = bf_sim_check_stable_dt(s, err);
    if (!st && s->ckpt_every && !bf_sim_can_checkpoint(s))
        st = bf_fail_key(err, BF_EINPUT, "scene", "checkpoint_every",
                         "model '%s' cannot write checkpoints yet", mt->name);
    /* kept at the end is the last checkpoint_every's checkpoint: without
     * one nothing would be kept, which the caller asked for */
    if (!st && s->opts.keep_checkpoint && !s->ckpt_every)
        st = bf_fail_key(err, BF_EINPUT, "scene", "checkpoint_every",
                         "--keep-checkpoint keeps the checkpoint written "
                         "every checkpoint_every, which is 0: nothing would "
                         "be kept; set it (e.g. --set "
                         "scene.checkpoint_every=1000)");
    if (st) {
        bf_sim_free(s);
        return st;
    }
    s->last_row = -1;
    s->has_energy = s->mt->energy != NULL;
    s->has_work = s->has_energy && bf_model_tracks_work(s->mt, s->model);
    bf_energy_start(&s->en, 0.0);
    if (s->has_energy) {
        double kk, p;
        s->mt->energy(s->model, 0.0, &kk, &p);
        bf_energy_start(&s->en, kk + p);
        /* a model names the key of a state it can blame (ball.N
         * velocity); this catches the rest before any row is written */
        if (!isfinite(kk + p)) {
            bf_fail(err, BF_EINPUT, "the initial state has no finite energy "
                    "(kinetic %g erg, potential %g erg): check the initial "
                    "positions and velocities", kk, p);
            bf_sim_free(s);
            return BF_EINPUT;
        }
    }
    *out = s;
    return BF_OK;
}

bf_status bf_sim_observe(bf_sim *s, const bf_observer_type *t, void *self,
                         bf_err *err)
{
    bf_status st = bf_sim_may_observe_(s, t, err);
    if (st) {
        if (t && t->destroy)
            t->destroy(self);
        return st;
    }
    observer *o = realloc(s->obs, (s->nobs + 1) * sizeof *o);
    if (!o) {
        if (t->destroy)
            t->destroy(self);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    s->obs = o;
    s->obs[s->nobs++] = (observer){t, self};
    s->obs_steps |= (t->flags & BF_OBS_STEPS) != 0;
    return BF_OK;
}

void *bf_sim_observer(bf_sim *s, const bf_observer_type *t)
{
    for (size_t k = 0; k < s->nobs; k++)
        if (s->obs[k].t == t)
            return s->obs[k].self;
    return NULL;
}

/* ------------------------------------------------------------- output */

bf_status bf_sim_set_ckpt_path_(bf_sim *s, const char *path, bf_err *err)
{
    size_t len = strlen(path) + 6;
    free(s->ckpt_path);
    s->ckpt_path = malloc(len);
    if (!s->ckpt_path)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(s->ckpt_path, len, "%s.ckpt", path);
    /* the checkpoint's temporary (checkpoint.c) checked now, not at the
     * first checkpoint, which may come hours later */
    char *tmp = malloc(len + 4);
    if (!tmp)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(tmp, len + 4, "%s.tmp", s->ckpt_path);
    bf_status st = bf_path_check_own(tmp, err);
    free(tmp);
    return st;
}

static bf_status open_output(bf_sim *s, const char *path, bf_err *err)
{
    bf_status st = bf_sim_set_ckpt_path_(s, path, err);
    if (st)
        return st;
    st = bf_out_create(&s->out, path, err);
    if (st)
        return st;
    /* under the output's lock: a checkpoint of an earlier run is not ours */
    unlink(s->ckpt_path);
    bf_out *o = s->out;
    bf_out_set_compression(o, s->compress);
    /* the output rows of the whole run: row 0, every out_every-th step
     * and the last */
    bf_out_expect_rows(o, (size_t)(s->nsteps / s->out_every) + 2);
    if ((st = bf_out_attr_str(o, "/", "version", bf_version_string(), err)) ||
        (st = bf_out_attr_str(o, "/", "scene_file", s->scene_path, err)) ||
        (st = bf_out_attr_str(o, "/", "scene_text", s->scene_text, err)) ||
        (st = bf_out_attr_str(o, "/", "scene_hash", s->scene_hash, err)) ||
        (st = bf_out_attr_str(o, "/", "run_id", s->run_id, err)) ||
        (st = bf_out_attr_str(o, "/", "status", "running", err)))
        return st;
    if (s->write_params && (st = s->write_params(s->params_ctx, o, err)))
        return st;
    if ((st = bf_sim_open_series_(s, err)))
        return st;
    /* from here on rows only: a kill leaves a file that opens (h5out.h) */
    return bf_out_start_appending(o, err);
}

bf_status bf_sim_open_output(bf_sim *s, const char *path, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_may_open_(s, path, err);
    if (st)
        return st;
    H5_LOCKED(open_output(s, path, err));
}

/* A follower's row: the model's part of it, which writes nothing. */
static bf_status follow_row(bf_sim *s, bf_err *err)
{
    bf_status st = BF_OK;
    if (s->mt->output_row)
        st = bf_sim_hook_status_(s->mt->output_row(s->model, s->n,
                                                   (double)s->n * s->dt, err),
                                 "model", s->mt->name, "output_row", err);
    s->last_row = s->n;
    return st;
}

static bf_status write_row(bf_sim *s, bf_err *err)
{
    if (!s->out && bf_sim_follower_(s) && s->last_row != s->n)
        return follow_row(s, err);
    if (!s->out || s->last_row == s->n)
        return BF_OK;
    double t = (double)s->n * s->dt;
    int64_t step = s->n;
    if (bf_series_append(s->s_time, &t) ||
        bf_series_append_i64(s->s_step, &step))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (s->has_energy) {
        double k, p, e;
        s->mt->energy(s->model, t, &k, &p);
        e = k + p;
        if (bf_series_append(s->s_ek, &k) || bf_series_append(s->s_ep, &p) ||
            bf_series_append(s->s_et, &e))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (s->has_work) {
        double wd, wi;
        s->mt->work(s->model, &wd, &wi);
        if (bf_series_append(s->s_wd, &wd) || bf_series_append(s->s_wi, &wi))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    bf_status st = BF_OK;
    if (s->mt->output_row)
        st = bf_sim_hook_status_(s->mt->output_row(s->model, s->n, t, err),
                                 "model", s->mt->name, "output_row", err);
    EACH_OBSERVER(s, st, output_row, s->n, t, err);
    if (!st) /* takes the HDF5 lock when it flushes */
        st = bf_out_maybe_flush(s->out, s->flush_seconds, err);
    s->last_row = s->n;
    return st;
}

/* relative energy error now; updates the maximum */
static double check_energy(bf_sim *s)
{
    double k, p;
    return bf_energy_check(
        &s->en, bf_sim_balance_(s, (double)s->n * s->dt, &k, &p));
}

static void progress(bf_sim *s, double t0, int final)
{
    double now = bf_wall_time();
    if (!final && now - s->prog_last < 0.25)
        return;
    s->prog_last = now;
    double frac = s->nsteps ? (double)s->n / (double)s->nsteps : 1.0;
    double el = now - t0;
    double rate = el > 0 ? (double)s->n / el : 0.0;
    double eta = rate > 0 ? (double)(s->nsteps - s->n) / rate : 0.0;
    fprintf(stderr, "\r  t = %-12.6g s  %5.1f%%  %9.3g steps/s  ETA %7.1f s",
            (double)s->n * s->dt, 100.0 * frac, rate, eta);
    if (s->has_energy)
        fprintf(stderr, "  dE/E %.2e (max %.2e)", s->en.last_rel, s->en.max_rel);
    fprintf(stderr, "   ");
    if (final)
        fprintf(stderr, "\n");
    fflush(stderr);
}

/* Stop cleanly: flush, write a checkpoint when possible, and say how to
 * continue. */
static bf_status interrupt(bf_sim *s, bf_err *err)
{
    double t = (double)s->n * s->dt;
    if ((s->out || bf_sim_follower_(s)) && bf_sim_can_checkpoint(s)) {
        bf_status st = bf_sim_checkpoint_write(s, s->ckpt_path, err);
        if (st)
            return st;
        return bf_fail(err, BF_INTERRUPTED,
                       "interrupted at step %ld (t = %.9g s); checkpoint "
                       "written; continue with: ballfilm run --restart %s",
                       s->n, t, s->out ? bf_out_path(s->out) : "OUT.h5");
    }
    return bf_fail(err, BF_INTERRUPTED,
                   "interrupted at step %ld (t = %.9g s); this %s cannot be "
                   "continued (no checkpoint)",
                   s->n, t, s->out ? "model" : "run without output");
}

/* The loop checks the interruption flag and the progress line at least
 * every RUN_MAX steps of a run (and after every step of a model without
 * advance). */
enum { RUN_MAX = 1024 };

static long min_long(long a, long b) { return a < b ? a : b; }

/* The next steps at which the loop has work: an output row, an energy
 * check, a checkpoint (LONG_MAX: never).  Kept as step numbers rather than
 * tested as s->n % every after every run, which cost several integer
 * divisions per run on scenes whose runs end at frequent events. */
typedef struct due_steps {
    long row, energy, ckpt;
} due_steps;

/* the smallest multiple of every above n (every >= 1) */
static long next_multiple(long n, long every)
{
    return every == 1 ? n + 1 : (n / every + 1) * every;
}

static due_steps due_after(const bf_sim *s, long n)
{
    due_steps d;
    d.row = next_multiple(n, s->out_every);
    d.energy = s->has_energy && s->energy_every
                   ? next_multiple(n, s->energy_every)
                   : LONG_MAX;
    d.ckpt = s->ckpt_every && (s->out || bf_sim_follower_(s))
                 ? next_multiple(n, s->ckpt_every)
                 : LONG_MAX;
    return d;
}

/* Steps from s->n to the next event the loop must see: an energy check
 * (unless the run makes it, energy_in_run), an output row, a checkpoint, a
 * heartbeat, the target step, the --stop-after limit, a multiple of
 * RUN_MAX (progress line, interruption flag).  At least 1. */
static long run_length(const bf_sim *s, const due_steps *d, long target,
                       int energy_in_run)
{
    const long n = s->n;
    long k = min_long(target - n, RUN_MAX - (n & (RUN_MAX - 1)));
    k = min_long(k, d->row - n);
    for (size_t h = 0; h < s->nhb; h++)
        if (s->hb[h].every)
            k = min_long(k, s->hb[h].every - n % s->hb[h].every);
    if (!energy_in_run)
        k = min_long(k, d->energy - n);
    k = min_long(k, d->ckpt - n);
    if (s->opts.stop_after)
        k = min_long(k, s->opts.stop_after - s->steps_this_run);
    return k;
}

/* One step of the model with the observers around it; *done: 1 if the
 * step and its observers succeeded (a failing observer fails the step). */
static bf_status one_step(bf_sim *s, bf_err *err, long *done)
{
    const double t = (double)s->n * s->dt;
    bf_status st = BF_OK;
    if (s->obs_steps)
        EACH_OBSERVER(s, st, before_step, s->n, t, s->dt, err);
    if (!st)
        st = s->mt->step(s->model, s->n, t, s->dt, err);
    if (!st && s->obs_steps)
        EACH_OBSERVER(s, st, after_step, s->n + 1, t, s->dt, err);
    *done = st ? 0 : 1;
    return st;
}

bf_status bf_sim_energy_exceeded_(const bf_sim *s, double rel, bf_err *err)
{
    return bf_fail(err, BF_EUNSTABLE,
                   "step %ld (t = %.9g s): relative energy error %.3g "
                   "exceeds %s%g%s; the time step is too large for this "
                   "integrator",
                   s->n, (double)s->n * s->dt, rel,
                   s->bound_is_models ? "" : "[scene] max_energy_error = ",
                   s->energy_bound,
                   s->bound_is_models
                       ? ", the bound of this model, whose energy is "
                         "conserved ([scene] max_energy_error sets another, "
                         "energy_bound = no turns it off)"
                       : "");
}

/* Can runs of steps make the per-step checks themselves (model.h,
 * BF_MODEL_WATCH; integrator.h, bf_ball_watch)?  Every observer with step
 * hooks must offer a watch, and at most one may: *watcher is its index
 * (-1: none). */
static int watch_plan(const bf_sim *s, long *watcher)
{
    *watcher = -1;
    if (!(s->mt->flags & BF_MODEL_WATCH) || !s->mt->advance)
        return 0;
    for (size_t k = 0; k < s->nobs; k++) {
        const bf_observer_type *t = s->obs[k].t;
        if (!(t->flags & BF_OBS_STEPS))
            continue;
        if (!t->watch || !t->watched || *watcher >= 0)
            return 0;
        *watcher = (long)k;
    }
    return 1;
}

/* A run of k > 1 steps that makes the per-step checks itself: the energy
 * check of the loop (energy_in_run) and the events of the watching
 * observer.  Returns 0 without stepping (*done = 0) when the observer
 * wants every step for now.  *named: the failure's message already names
 * its step (the energy bound's, as in the loop). */
static int watched_run(bf_sim *s, long watcher, int energy_in_run, long k,
                       long *done, bf_status *st, int *named, bf_err *err)
{
    *named = 0;
    bf_ball_watch w = {0};
    w.low = w.above = -1;
    w.energy = energy_in_run;
    w.e0 = s->en.e0;
    w.bound = s->energy_bound;
    w.max_rel = s->en.max_rel;
    w.last_rel = s->en.last_rel;
    const observer *o = watcher >= 0 ? &s->obs[watcher] : NULL;
    *done = 0;
    if (o && !o->t->watch(o->self, &w))
        return 0;
    *st = s->mt->advance(s->model, s->n, k, s->dt, &w, done, err);
    if (energy_in_run) {
        s->en.max_rel = w.max_rel;
        s->en.last_rel = w.last_rel;
    }
    s->n += *done;
    s->steps_this_run += *done;
    if (*st) {
        /* an event noted before the failing step (`above` does not end a
         * run) is the observer's all the same, as if the run had ended
         * there */
        if (o && (w.fired & BF_WATCH_ABOVE)) {
            bf_err e2 = {0};
            w.fired = BF_WATCH_ABOVE;
            o->t->watched(o->self, &w, s->n, (double)s->n * s->dt, s->dt,
                          &e2);
        }
        return 1;
    }
    if (o && (w.fired & (BF_WATCH_LOW | BF_WATCH_ABOVE)) &&
        (*st = bf_sim_hook_status_(
             o->t->watched(o->self, &w, s->n, (double)(s->n - 1) * s->dt,
                           s->dt, err),
             "observer", o->t->name, "watched", err))) {
        /* as one_step: a failing observer fails its step */
        s->n--;
        s->steps_this_run--;
        return 1;
    }
    if (w.fired & BF_WATCH_ENERGY) {
        *st = bf_sim_energy_exceeded_(s, w.last_rel, err);
        *named = 1;
    }
    return 1;
}

/* The output row of step s->n (when due) and the heartbeats of rows. */
static bf_status row_and_beat(bf_sim *s, bf_err *err)
{
    int wrote = s->out && s->last_row != s->n;
    bf_status st = write_row(s, err);
    if (!st && (wrote || !s->out))
        st = bf_sim_beat(s, 1, err);
    return st;
}

/* Run from s->n to step target (<= nsteps). */
static bf_status run_to(bf_sim *s, long target, bf_err *err)
{
    bf_status st = BF_OK;
    double t0 = bf_wall_time();
    s->prog_last = t0;
    if (s->n == 0 && !s->hb_started) {
        s->hb_started = 1;
        if ((st = row_and_beat(s, err)) || (st = bf_sim_beat(s, 0, err))) {
            if (st == BF_INTERRUPTED)
                st = interrupt(s, err);
            else
                bf_err_prefix(err, "step 0 (t = 0 s)");
            return s->run_status = st;
        }
    }
    const long every = s->out_every, eevery = s->energy_every;
    /* Runs of more than one step: a model with advance, rows not every
     * step, and no check the loop must make after every step (energy
     * every step, observers' step hooks), unless the run makes them
     * itself (watch_plan). */
    long watcher = -1;
    const int energy_every_step = s->has_energy && eevery == 1;
    const int watchable = every > 1 && watch_plan(s, &watcher) &&
                          !s->opts.step_by_step;
    const int plain_runs = s->mt->advance && every > 1 && !s->obs_steps &&
                           !energy_every_step && !s->opts.step_by_step;
    /* (a watched run checks E - E0, not a balance with work) */
    const int energy_in_run = watchable && !plain_runs && energy_every_step &&
                              !s->has_work;
    due_steps due = due_after(s, s->n);
    while (s->n < target) {
        if ((s->opts.stop_flag && *s->opts.stop_flag) ||
            (s->opts.stop_after && s->steps_this_run >= s->opts.stop_after)) {
            st = interrupt(s, err);
            break;
        }
        /* a run of steps up to the next event, or one step */
        long k = plain_runs || watchable
                     ? run_length(s, &due, target, energy_in_run)
                     : 1;
        long done = 1;
        int energy_checked = 0, named = 0;
        if (k > 1 && plain_runs) {
            st = s->mt->advance(s->model, s->n, k, s->dt, NULL, &done, err);
            s->n += done;
            s->steps_this_run += done;
        } else if (k > 1 && watched_run(s, watcher, energy_in_run, k, &done,
                                        &st, &named, err)) {
            energy_checked = energy_in_run;
        } else {
            st = one_step(s, err, &done);
            s->n += done;
            s->steps_this_run += done;
        }
        st = bf_sim_hook_status_(st, "model", s->mt->name, "step", err);
        if (st == BF_INTERRUPTED) {
            /* the stop flag ended a long step inside (ARKODE's internal
             * steps), the state left at the step's start */
            st = interrupt(s, err);
            break;
        }
        if (st) {
            if (!named)
                bf_err_prefix(err, "step %ld (t = %.9g s to %.9g s)",
                              s->n + 1, (double)s->n * s->dt,
                              (double)(s->n + 1) * s->dt);
            break;
        }
        if (s->n >= due.energy) {
            /* a run that checks the energy itself may pass the check's
             * step (energy_in_run: every step) */
            const int on_step = s->n == due.energy;
            due.energy = on_step ? due.energy + eevery
                                 : next_multiple(s->n, eevery);
            if (on_step && !energy_checked) {
                double rel = check_energy(s);
                if (s->energy_bound > 0 && !(rel <= s->energy_bound)) {
                    st = bf_sim_energy_exceeded_(s, rel, err);
                    break;
                }
            }
        }
        const int row_due = s->n == due.row;
        if (row_due)
            due.row += every;
        if (row_due || s->n == s->nsteps) {
            double rel = s->has_energy && !eevery ? check_energy(s) : 0.0;
            /* energy_every = 0 checks at the rows; the last state is
             * checked whatever the intervals: no blown-up row is written
             * as a result */
            if (s->energy_bound > 0 && !(rel <= s->energy_bound))
                st = bf_sim_energy_exceeded_(s, rel, err);
            else if (s->n == s->nsteps)
                st = bf_sim_check_state_(s, err);
            if (st)
                break;
            st = row_and_beat(s, err);
        }
        if (!st)
            st = bf_sim_beat(s, 0, err);
        if (st == BF_INTERRUPTED) {
            st = interrupt(s, err);
            break;
        }
        if (st) {
            bf_err_prefix(err, "step %ld (t = %.9g s)", s->n,
                          (double)s->n * s->dt);
            break;
        }
        const int ckpt_due = s->n == due.ckpt;
        if (ckpt_due)
            due.ckpt += s->ckpt_every;
        if (ckpt_due && s->n < s->nsteps &&
            (st = bf_sim_checkpoint_write(s, s->ckpt_path, err))) {
            bf_err_prefix(err, "step %ld (t = %.9g s): checkpoint", s->n,
                          (double)s->n * s->dt);
            break;
        }
        if (s->opts.progress && (s->n & 1023) == 0)
            progress(s, t0, 0);
    }
    if (s->opts.progress)
        progress(s, t0, 1);
    s->wall += bf_wall_time() - t0;
    return s->run_status = st;
}

/* run_to with the run's stop flag watched inside the model's steps
 * (integrators/stop.h) */
static bf_status run_watched(bf_sim *s, long target, bf_err *err)
{
    /* a failure's cause is what this run writes (bf_sim_hook_status_) */
    bf_err_clear(err);
    bf_stop_flag before = bf_stop_watch(s->opts.stop_flag);
    bf_status st = run_to(s, target, err);
    bf_stop_watch(before);
    return st;
}

bf_status bf_sim_run(bf_sim *s, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_may_run_(s, "bf_sim_run", err);
    return st ? st : run_watched(s, s->nsteps, err);
}

bf_status bf_sim_run_until(bf_sim *s, double t, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_may_run_(s, "bf_sim_run_until", err);
    if (!st && !isfinite(t))
        st = bf_fail(err, BF_EINPUT, "bf_sim_run_until: t = %g is not "
                     "finite", t);
    if (st)
        return st;
    double steps = ceil(t / s->dt * (1.0 - 1e-12));
    long target = !(steps < (double)s->nsteps) ? s->nsteps
                  : steps > 0                  ? (long)steps
                                               : 0;
    return run_watched(s, target > s->n ? target : s->n, err);
}

bf_status bf_sim_steps(bf_sim *s, long k, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_may_run_(s, "bf_sim_steps", err);
    if (st)
        return st;
    if (k < 0)
        return bf_fail(err, BF_EINPUT, "bf_sim_steps: k = %ld < 0", k);
    return run_watched(s, k > s->nsteps - s->n ? s->nsteps : s->n + k, err);
}

static bf_status close_output(bf_sim *s, bf_status run_status,
                              const bf_err *run_err, bf_err *err)
{
    if (!s->out)
        return BF_OK;
    bf_out *o = s->out;
    s->out = NULL;
    s->closed = 1;
    if (bf_out_failed(o)) {
        /* the file holds what the last good flush wrote: leave it */
        bf_fail(err, BF_EIO, "%s.part keeps the rows up to the last flush "
                "before the failed write", bf_out_path(o));
        bf_out_close_keep(o, NULL);
        return BF_EIO;
    }
    bf_status st = BF_OK;
    if (s->mt->output_close)
        st = bf_sim_hook_status_(s->mt->output_close(s->model, o, err),
                                 "model", s->mt->name, "output_close", err);
    EACH_OBSERVER(s, st, output_close, o, err);
    bf_counters c;
    bf_sim_counters(s, &c);
    if (!st)
        st = bf_out_attr_str(o, "/", "status", bf_status_name(run_status), err);
    /* a failure's cause is never left empty */
    const char *cause = !run_status                    ? ""
                        : run_err && run_err->msg[0] ? run_err->msg
                                                     : bf_status_name(run_status);
    if (!st)
        st = bf_out_attr_str(o, "/", "message", cause, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "steps_done", s->n, err);
    if (!st)
        st = bf_out_attr_real(o, "/", "t_final", (double)s->n * s->dt, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "force_evaluations", (int64_t)c.evals, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "rejected_steps", (int64_t)c.rejected, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "iterations", (int64_t)c.iterations, err);
    if (!st && s->has_energy)
        st = bf_out_attr_real(o, "/", "max_relative_energy_error",
                              s->en.max_rel, err);
    if (!st && s->has_work) /* what max_relative_energy_error measures */
        st = bf_out_attr_str(o, "/", "energy_balance",
                             "E - E0 + W_dissipated - W_injected", err);
    /* an interrupted run is continued in OUT.part; every other run's
     * file becomes the result */
    bf_status cst = run_status == BF_INTERRUPTED || st
                        ? bf_out_close_keep(o, st ? NULL : err)
                        : bf_out_close(o, err);
    /* a run that ended well needs no restart */
    if (!st && !cst && run_status == BF_OK && !s->opts.keep_checkpoint)
        unlink(s->ckpt_path);
    return st ? st : cst;
}

bf_status bf_sim_close_output(bf_sim *s, bf_status run_status,
                              const bf_err *run_err, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_may_close_(s, run_status, err);
    if (st)
        return st;
    H5_LOCKED(close_output(s, run_status, run_err, err));
}
