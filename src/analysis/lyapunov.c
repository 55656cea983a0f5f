/* lyapunov.c: the largest Lyapunov exponent of a ball system by a
 * renormalised shadow trajectory (see lyapunov.h and src/diag/lyapsum.h). */
#include "lyapunov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------ a ball system's shadow */

struct bf_lyap {
    bf_lyap_sum sum;
    double *x, *v; /* shadow state */
    bf_integrator *it;
};

bf_status bf_lyap_create(bf_lyap **out, const void *keys, double dt,
                         const bf_ballsys *sys, bf_err *err)
{
    *out = NULL;
    const bf_lyap_keys *k = keys;
    if (!k->enabled)
        return BF_OK;
    bf_lyap_sum sum;
    const bf_integrator_type *t = sys->it->type;
    bf_status st = bf_lyap_sum_init(&sum, k, dt, sys->b.n,
                                    t->flags & BF_INT_ADAPTIVE ? t->name : NULL,
                                    err);
    if (st)
        return st;
    bf_lyap *ly = calloc(1, sizeof *ly);
    if (!ly)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    const size_t n = sys->b.n;
    ly->sum = sum;
    ly->x = calloc(2 * n, sizeof *ly->x);
    if (!ly->x) {
        free(ly);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    ly->v = ly->x + n;
    st = bf_integrator_create(&ly->it, sys->it->type, n, sys->it_params, err);
    if (st) {
        bf_lyap_free(ly);
        return st;
    }
    bf_lyap_displace(&ly->sum, sys->b.x, sys->b.v, ly->x, ly->v);
    *out = ly;
    return BF_OK;
}

void bf_lyap_free(bf_lyap *ly)
{
    if (!ly)
        return;
    bf_integrator_free(ly->it);
    free(ly->x);
    free(ly);
}

bf_status bf_lyap_after_step(bf_lyap *ly, const bf_ballsys *sys, long n_done,
                             double t, double dt, bf_err *err)
{
    bf_status st = bf_integrator_step(ly->it, &sys->ode, t, dt, ly->x, ly->v,
                                      err);
    if (st) {
        bf_err_prefix(err, "Lyapunov shadow trajectory");
        return st;
    }
    if (!bf_lyap_due(&ly->sum, n_done))
        return BF_OK;
    double factor;
    st = bf_lyap_measure(&ly->sum, sys->b.x, sys->b.v, ly->x, ly->v, t + dt,
                         &factor, err);
    if (st || factor == 1.0)
        return st;
    if (factor == 0.0) {
        bf_lyap_displace(&ly->sum, sys->b.x, sys->b.v, ly->x, ly->v);
        return BF_OK;
    }
    bf_lyap_pull(ly->sum.n, factor, sys->b.x, ly->x);
    bf_lyap_pull(ly->sum.n, factor, sys->b.v, ly->v);
    return BF_OK;
}

double bf_lyap_estimate(const bf_lyap *ly, double *t_ref)
{
    return bf_lyap_sum_estimate(&ly->sum, t_ref);
}

void bf_lyap_report(const bf_lyap *ly, FILE *f)
{
    bf_lyap_sum_report(&ly->sum, ly->it->count.evals, f);
}

const bf_counters *bf_lyap_counters(const bf_lyap *ly)
{
    return &ly->it->count;
}

bf_status bf_lyap_output_open(bf_lyap *ly, bf_out *out, bf_err *err)
{
    return bf_lyap_sum_output_open(&ly->sum, out, err);
}

bf_status bf_lyap_output_close(const bf_lyap *ly, bf_out *out, bf_err *err)
{
    return bf_lyap_sum_output_close(&ly->sum, out, err);
}

bf_status bf_lyap_save(const bf_lyap *ly, bf_ckpt *ck, bf_err *err)
{
    bf_status st = bf_ckpt_put(ck, "lyapunov.x", ly->x, 2 * ly->sum.n, err);
    if (!st)
        st = bf_lyap_sum_save(&ly->sum, ck, err);
    if (!st)
        st = bf_integrator_save(ly->it, ck, "lyapunov.integrator", err);
    return st;
}

bf_status bf_lyap_load(bf_lyap *ly, const bf_ckpt *ck, bf_err *err)
{
    bf_status st = bf_ckpt_get(ck, "lyapunov.x", ly->x, 2 * ly->sum.n, err);
    if (!st)
        st = bf_lyap_sum_load(&ly->sum, ck, err);
    if (!st)
        st = bf_integrator_load(ly->it, ck, "lyapunov.integrator", err);
    return st;
}
