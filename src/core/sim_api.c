/* sim_api.c: what the public calls of the loop refuse (sim.h) and what
 * becomes of the statuses callbacks return.
 *
 * A library user's mistake (a NULL pointer, a non-finite time, a call in
 * the wrong order) would otherwise crash, or worse, be reported as
 * success: an output opened after the last step holds no row and says
 * "ok".  Each is refused with BF_EINPUT and a message naming the function
 * and the argument.  A callback (model, observer, heartbeat) that fails
 * with a value that is no status of error.h, or without saying why,
 * would end the run with an exit code no one documents or an empty
 * cause: it becomes BF_EINTERNAL (a bug of the callback) with a message
 * naming it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/sim_impl.h"

int bf_sim_status_valid_(bf_status st)
{
    return st >= BF_OK && st <= BF_INTERRUPTED;
}

bf_status bf_sim_hook_status_(bf_status st, const char *kind,
                              const char *name, const char *hook, bf_err *err)
{
    if (st == BF_OK || (bf_sim_status_valid_(st) && err->msg[0])) {
        if (st)
            err->status = st;
        return st;
    }
    char who[160];
    snprintf(who, sizeof who, "%s%s%s%s, %s,", kind, name ? " '" : "",
             name ? name : "", name ? "'" : "", hook);
    if (!bf_sim_status_valid_(st))
        return bf_fail(err, BF_EINTERNAL, "%s returned %d, which is no "
                       "status (error.h: 0 to 6)", who, (int)st);
    return bf_fail(err, st, "%s failed (%s) without saying why", who,
                   bf_status_name(st));
}

bf_status bf_sim_null_(const void *p, const char *fn, const char *arg,
                       bf_err *err)
{
    return p ? BF_OK
             : bf_fail(err, BF_EINPUT, "%s: %s is NULL", fn, arg);
}

static bf_status interval_ok(bf_interval iv, const char *key, bf_err *err)
{
    if (iv.in_time ? !(iv.time >= 0) : iv.steps < 0)
        return bf_fail_key(err, BF_EINPUT, "scene", key,
                           "bf_sim_keys: %s = %g%s is negative or not a "
                           "number", key,
                           iv.in_time ? iv.time : (double)iv.steps,
                           iv.in_time ? " s" : " steps");
    return BF_OK;
}

/* The keys a scene's validation guarantees, for a program that fills
 * bf_sim_keys itself: without them the step count, the schedule and the
 * bound would be computed from NaN or negative numbers. */
bf_status bf_sim_keys_ok_(const bf_sim_keys *k, bf_err *err)
{
    if (!(isfinite(k->dt) && k->dt > 0))
        return bf_fail_key(err, BF_EINPUT, "scene", "dt", "bf_sim_keys: dt "
                           "= %g s is not a finite positive time", k->dt);
    if (!(isfinite(k->t_end) && k->t_end > 0))
        return bf_fail_key(err, BF_EINPUT, "scene", "t_end", "bf_sim_keys: "
                           "t_end = %g s is not a finite positive time",
                           k->t_end);
    if (k->energy_every < 0)
        return bf_fail_key(err, BF_EINPUT, "scene", "energy_every",
                           "bf_sim_keys: energy_every = %ld is negative",
                           k->energy_every);
    if (!(k->max_energy_error >= 0))
        return bf_fail_key(err, BF_EINPUT, "scene", "max_energy_error",
                           "bf_sim_keys: max_energy_error = %g is negative "
                           "or not a number", k->max_energy_error);
    if (!(k->flush_seconds > 0))
        return bf_fail_key(err, BF_EINPUT, "scene", "flush_seconds",
                           "bf_sim_keys: flush_seconds = %g s is not "
                           "positive", k->flush_seconds);
    if (k->compress < 0 || k->compress > 9)
        return bf_fail_key(err, BF_EINPUT, "scene", "compress",
                           "bf_sim_keys: compress = %ld is not 0 to 9",
                           k->compress);
    bf_status st = interval_ok(k->output_every, "output_every", err);
    return st ? st : interval_ok(k->checkpoint_every, "checkpoint_every", err);
}

bf_status bf_sim_may_observe_(const bf_sim *s, const bf_observer_type *t,
                              bf_err *err)
{
    bf_status st = bf_sim_null_(s, "bf_sim_observe", "sim", err);
    if (!st)
        st = bf_sim_null_(t, "bf_sim_observe", "the observer type", err);
    if (!st && (s->out || s->closed || s->n > 0 || s->hb_started))
        st = bf_fail(err, BF_EINPUT, "bf_sim_observe: observer '%s' comes "
                     "after the run started (step %ld%s): observers are "
                     "attached before the output opens and the first step",
                     t->name ? t->name : "", s->n,
                     s->out ? ", output open" : "");
    return st;
}

bf_status bf_sim_may_open_(const bf_sim *s, const char *path, bf_err *err)
{
    bf_status st = bf_sim_null_(s, "bf_sim_open_output", "sim", err);
    if (!st)
        st = bf_sim_null_(path, "bf_sim_open_output", "path", err);
    if (st)
        return st;
    if (!path[0])
        return bf_fail(err, BF_EINPUT, "bf_sim_open_output: path is empty");
    if (s->out)
        return bf_fail(err, BF_EINPUT, "bf_sim_open_output: %s: the run "
                       "has an output already (%s); a run writes one",
                       path, bf_out_path(s->out));
    if (s->closed)
        return bf_fail(err, BF_EINPUT, "bf_sim_open_output: %s: the run's "
                       "output was closed: the run is over", path);
    if (s->n > 0 || s->hb_started)
        return bf_fail(err, BF_EINPUT, "bf_sim_open_output: %s: the run "
                       "is at step %ld of %ld; an output opens before the "
                       "first step (its rows start at t = 0)",
                       path, s->n, s->nsteps);
    return BF_OK;
}

bf_status bf_sim_may_run_(const bf_sim *s, const char *fn, bf_err *err)
{
    bf_status st = bf_sim_null_(s, fn, "sim", err);
    if (st)
        return st;
    if (s->closed)
        return bf_fail(err, BF_EINPUT, "%s: the run's output was closed "
                       "(bf_sim_close_output): the run is over", fn);
    if (s->run_status && s->run_status != BF_INTERRUPTED)
        return bf_fail(err, BF_EINPUT, "%s: the run ended '%s' at step %ld; "
                       "its state is no result to go on from", fn,
                       bf_status_name(s->run_status), s->n);
    return BF_OK;
}

bf_status bf_sim_may_close_(const bf_sim *s, bf_status run_status,
                            bf_err *err)
{
    static const char fn[] = "bf_sim_close_output";
    bf_status st = bf_sim_null_(s, fn, "sim", err);
    if (st)
        return st;
    if (!bf_sim_status_valid_(run_status))
        return bf_fail(err, BF_EINPUT, "%s: run_status = %d is no status "
                       "(error.h: 0 to 6)", fn, (int)run_status);
    if (!s->out)
        return s->closed ? bf_fail(err, BF_EINPUT, "%s: the output was "
                                   "closed already", fn)
                         : BF_OK;
    /* a file whose status says ok is taken for the whole run */
    if (run_status == BF_OK && s->run_status)
        return bf_fail(err, BF_EINPUT, "%s: run_status = ok, but the run "
                       "ended '%s' at step %ld", fn,
                       bf_status_name(s->run_status), s->n);
    if (run_status == BF_OK && s->n < s->nsteps)
        return bf_fail(err, BF_EINPUT, "%s: run_status = ok, but the run "
                       "is at step %ld of %ld (pass the status that "
                       "stopped it: BF_INTERRUPTED keeps %s.part to go on)",
                       fn, s->n, s->nsteps, bf_out_path(s->out));
    return BF_OK;
}
