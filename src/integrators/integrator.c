/* integrator.c: creation, force cache and helpers shared by all
 * integrators (see integrator.h). */
#include "ballfilm/integrator.h"
#include "fixed_step.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bf_status bf_integrator_create(bf_integrator **out,
                               const bf_integrator_type *t, size_t n,
                               const void *params, bf_err *err)
{
    *out = NULL;
    bf_integrator *it = calloc(1, sizeof *it);
    if (!it)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    it->type = t;
    it->n = n;
    it->cache_x = calloc(n ? n : 1, sizeof *it->cache_x);
    it->cache_a = calloc(n ? n : 1, sizeof *it->cache_a);
    if (!it->cache_x || !it->cache_a) {
        bf_integrator_free(it);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    void *defaults = NULL;
    bf_status st = BF_OK;
    if (t->spec && !params) {
        defaults = calloc(1, t->spec->size ? t->spec->size : 1);
        st = defaults ? bf_params_defaults(t->spec, defaults, err)
                      : bf_fail(err, BF_EINTERNAL, "out of memory");
        params = defaults;
    }
    if (!st && t->init)
        st = t->init(it, t->spec ? params : NULL, err);
    free(defaults);
    if (st) {
        bf_integrator_free(it);
        return st;
    }
    *out = it;
    return BF_OK;
}

void bf_integrator_free(bf_integrator *it)
{
    if (!it)
        return;
    if (it->type && it->type->free)
        it->type->free(it);
    free(it->work);
    free(it->cache_x);
    free(it->cache_a);
    free(it);
}

void bf_integrator_reset(bf_integrator *it) { it->cache_valid = 0; }

void bf_integrator_set_events(bf_integrator *it, const bf_events *ev)
{
    it->events = ev;
}

void bf_integrator_set_kinks(bf_integrator *it, const bf_events *kinks)
{
    it->kinks = kinks;
}

static const bf_param fixed_step_params[] = {
    BF_EVENTS_PARAMS(bf_fixed_step_keys),
    {0},
};

const bf_section_spec bf_fixed_step_spec =
    BF_SECTION("integrator", "parameters of a fixed-step integrator",
               fixed_step_params, bf_fixed_step_keys);

bf_status bf_fixed_step_init(bf_integrator *it, const void *params,
                             size_t nvec, bf_err *err)
{
    const bf_fixed_step_keys *k = params;
    it->split_events = k->events;
    it->split_zone = k->events_zone;
    return bf_integrator_alloc_work(it, nvec, err);
}

bf_status bf_fixed_step_init_copy(bf_integrator *it, const void *params,
                                  size_t size, int events, double events_zone,
                                  size_t nvec, bf_err *err)
{
    void *copy = malloc(size);
    if (!copy)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    memcpy(copy, params, size);
    it->priv = copy;
    it->split_events = events;
    it->split_zone = events_zone;
    return bf_integrator_alloc_work(it, nvec, err);
}

void bf_integrator_set_monitor(bf_integrator *it, bf_monitor_fn fn, void *ctx)
{
    it->monitor = fn;
    it->monitor_ctx = ctx;
}

int bf_integrator_order(const bf_integrator *it)
{
    return it->type->order_of ? it->type->order_of(it) : it->type->order;
}

void bf_integrator_describe(const bf_integrator *it, char *buf, size_t cap)
{
    if (it->type->describe)
        it->type->describe(it, buf, cap);
    else
        snprintf(buf, cap, "%s", it->type->name);
}

bf_status bf_integrator_alloc_work(bf_integrator *it, size_t nvec, bf_err *err)
{
    free(it->work);
    it->work = calloc(nvec * (it->n ? it->n : 1), sizeof *it->work);
    if (!it->work)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

bf_status bf_ode_eval_failed(bf_err *err)
{
    return bf_fail(err, BF_EUNSTABLE, "force undefined at the current positions");
}

bf_status bf_ode_eval_cached(bf_integrator *it, const bf_ode *ode, double t,
                             const double *x, const double *v, double *acc,
                             bf_err *err)
{
    size_t n = ode->n;
    if (it->cache_valid && it->cache_epoch == ode->epoch &&
        !memcmp(it->cache_x, x, n * sizeof *x)) {
        memcpy(acc, it->cache_a, n * sizeof *acc);
        return BF_OK;
    }
    bf_status st = bf_ode_eval(it, ode, t, x, v, acc, err);
    if (!st)
        bf_integrator_cache_store(it, ode, x, acc);
    return st;
}

void bf_integrator_cache_store(bf_integrator *it, const bf_ode *ode,
                               const double *x, const double *acc)
{
    memcpy(it->cache_x, x, ode->n * sizeof *x);
    memcpy(it->cache_a, acc, ode->n * sizeof *acc);
    it->cache_epoch = ode->epoch;
    it->cache_valid = 1;
}

/* What a checkpoint keeps of every integrator (the type's private state
 * follows, under the same prefix). */
static const bf_field integrator_state[] = {
    BF_FIELD(bf_integrator, count.steps, BF_F_ULL, "1"),
    BF_FIELD(bf_integrator, count.evals, BF_F_ULL, "1"),
    BF_FIELD(bf_integrator, count.rejected, BF_F_ULL, "1"),
    BF_FIELD(bf_integrator, count.iterations, BF_F_ULL, "1"),
    BF_FIELD(bf_integrator, cache_valid, BF_F_INT, "1"),
    BF_FIELD(bf_integrator, cache_epoch, BF_F_ULONG, "1"),
    BF_FIELD_PTR(bf_integrator, cache_x, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(bf_integrator, cache_a, BF_F_DOUBLE, n, "cm/s^2"),
};

bf_status bf_integrator_save(const bf_integrator *it, bf_ckpt *ck,
                             const char *prefix, bf_err *err)
{
    bf_status st = bf_ckpt_put_fields(ck, prefix, integrator_state,
                                      BF_NFIELDS(integrator_state), it, err);
    if (!st && it->type->save)
        st = it->type->save(it, ck, prefix, err);
    return st;
}

bf_status bf_integrator_load(bf_integrator *it, const bf_ckpt *ck,
                             const char *prefix, bf_err *err)
{
    bf_status st = bf_ckpt_get_fields(ck, prefix, integrator_state,
                                      BF_NFIELDS(integrator_state), it, err);
    if (!st && it->type->load)
        st = it->type->load(it, ck, prefix, err);
    return st;
}
