/* sim_state.c: the state of a run as named arrays (read at any time, set
 * before the first step) and the heartbeats (see sim.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/sim_impl.h"

/* Enough for every model of the library; a model with more shows the
 * first ones to bf_sim_get. */
enum { MAX_VARS = 64 };

size_t bf_sim_state(bf_sim *s, bf_state_var *vars, size_t cap)
{
    bf_state_var none[1];
    if (!s)
        return 0;
    if (!vars) /* only how many */
        vars = none, cap = 0;
    return s->mt->state ? s->mt->state(s->model, vars, cap) : 0;
}

const double *bf_sim_get(bf_sim *s, const char *name, size_t *n)
{
    bf_state_var v[MAX_VARS];
    size_t nv = name ? bf_sim_state(s, v, MAX_VARS) : 0;
    for (size_t k = 0; k < nv && k < MAX_VARS; k++)
        if (!strcmp(v[k].name, name)) {
            if (n)
                *n = v[k].n;
            return v[k].data;
        }
    if (n)
        *n = 0;
    return NULL;
}

/* The names of the settable arrays, for messages. */
static void settable_names(bf_sim *s, char *buf, size_t cap)
{
    bf_state_var v[MAX_VARS];
    size_t nv = bf_sim_state(s, v, MAX_VARS), used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < nv && k < MAX_VARS; k++) {
        if (!v[k].settable)
            continue;
        int w = snprintf(buf + used, cap - used, "%s%s", used ? ", " : "",
                         v[k].name);
        if (w < 0 || (size_t)w >= cap - used)
            break;
        used += (size_t)w;
    }
    if (!used)
        snprintf(buf, cap, "none");
}

bf_status bf_sim_set(bf_sim *s, const char *name, const double *v, size_t n,
                     bf_err *err)
{
    char names[512];
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_sim_null_(s, "bf_sim_set", "sim", err);
    if (!st)
        st = bf_sim_null_(name, "bf_sim_set", "name", err);
    if (!st && !v && n)
        st = bf_fail(err, BF_EINPUT, "bf_sim_set: %s: v is NULL with n = "
                     "%zu", name, n);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return bf_fail(err, BF_EINPUT, "bf_sim_set: %s[%zu] = %g is not "
                           "finite", name, i, v[i]);
    if (s->n > 0 || s->last_row >= 0 || s->hb_started)
        return bf_fail(err, BF_EINPUT, "cannot set %s at step %ld: initial "
                       "fields are set before the first step (and before "
                       "the first output row)", name, s->n);
    bf_state_var vars[MAX_VARS];
    size_t nv = bf_sim_state(s, vars, MAX_VARS), k = 0;
    while (k < nv && k < MAX_VARS && strcmp(vars[k].name, name))
        k++;
    if (k == nv || k == MAX_VARS || !vars[k].settable || !s->mt->set_state) {
        settable_names(s, names, sizeof names);
        return bf_fail(err, BF_EINPUT, "model '%s' has no settable array "
                       "'%s' (settable: %s)", s->mt->name, name, names);
    }
    if (n != vars[k].n)
        return bf_fail(err, BF_EINPUT, "%s has %zu values; %zu given",
                       name, vars[k].n, n);
    st = s->mt->set_state(s->model, name, v, n, err);
    if (!st)
        st = bf_sim_check_stable_dt(s, err);
    EACH_OBSERVER(s, st, state_set, err);
    if (st)
        return st;
    if (s->has_energy) {
        double kin, pot;
        s->mt->energy(s->model, 0.0, &kin, &pot);
        bf_energy_start(&s->en, kin + pot);
    }
    return BF_OK;
}

bf_status bf_sim_heartbeat(bf_sim *s, long every, bf_heartbeat_fn fn,
                           void *ctx, bf_err *err)
{
    bf_status st = bf_sim_null_(s, "bf_sim_heartbeat", "sim", err);
    if (!st && !fn)
        st = bf_fail(err, BF_EINPUT, "bf_sim_heartbeat: fn is NULL");
    if (st)
        return st;
    if (every < 0)
        return bf_fail(err, BF_EINPUT, "bf_sim_heartbeat: every = %ld is "
                       "negative", every);
    heartbeat *h = realloc(s->hb, (s->nhb + 1) * sizeof *h);
    if (!h)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->hb = h;
    s->hb[s->nhb++] = (heartbeat){every, fn, ctx};
    return BF_OK;
}

bf_status bf_sim_beat(bf_sim *s, int rows, bf_err *err)
{
    bf_status st = BF_OK;
    for (size_t k = 0; !st && k < s->nhb; k++) {
        const heartbeat *h = &s->hb[k];
        if (rows ? h->every == 0 : h->every > 0 && s->n % h->every == 0) {
            err->msg[0] = '\0';
            bf_status r = h->fn(h->ctx, s, err);
            if (r != BF_OK) { /* the step named only when it failed */
                char at[48];
                snprintf(at, sizeof at, "at step %ld", s->n);
                st = bf_sim_hook_status_(r, "heartbeat", NULL, at, err);
            }
        }
    }
    return st;
}

void bf_sim_energy(const bf_sim *s, double *kin, double *pot)
{
    *kin = *pot = NAN;
    if (s->has_energy)
        s->mt->energy(s->model, (double)s->n * s->dt, kin, pot);
}

double bf_sim_initial_energy(const bf_sim *s)
{
    return s->has_energy ? s->en.e0 : NAN;
}

double bf_sim_balance_(const bf_sim *s, double t, double *k, double *p)
{
    return bf_model_balance(s->mt, s->model, t, s->has_work, k, p);
}

/* The state of step s->n against finiteness and the energy bound, the
 * diagnostics left as they are: what the output records
 * (max_relative_energy_error) stays that of the scheduled checks. */
bf_status bf_sim_check_state_(bf_sim *s, bf_err *err)
{
    const double t = (double)s->n * s->dt;
    if (s->has_energy) {
        double k, p;
        const double e = bf_sim_balance_(s, t, &k, &p);
        bf_energy_diag d = s->en;
        double rel = bf_energy_check(&d, e);
        if (!isfinite(k + p))
            return bf_fail(err, BF_EUNSTABLE,
                           "step %ld (t = %.9g s): the state has no finite "
                           "energy (kinetic %g erg, potential %g erg); the "
                           "time step is too large for this integrator",
                           s->n, t, k, p);
        if (s->energy_bound > 0 && !(rel <= s->energy_bound))
            return bf_sim_energy_exceeded_(s, rel, err);
    }
    bf_state_var v[MAX_VARS];
    size_t nv = bf_sim_state(s, v, MAX_VARS);
    for (size_t a = 0; a < nv && a < MAX_VARS; a++)
        for (size_t i = 0; i < v[a].n; i++)
            if (!isfinite(v[a].data[i]))
                return bf_fail(err, BF_EUNSTABLE,
                               "step %ld (t = %.9g s): %s[%zu] = %g is not "
                               "finite", s->n, t, v[a].name, i,
                               v[a].data[i]);
    return BF_OK;
}
