/* lyapsum.c: the bookkeeping of a Lyapunov estimate (see lyapsum.h). */
#include "lyapsum.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param lyap_params[] = {
    {"enabled", BF_AT(bf_lyap_keys, enabled, BF_BOOL), "", "no",
     "estimate the largest Lyapunov exponent (integrates a second, shadow "
     "trajectory: doubles the cost; in the coupled model the shadow has its "
     "own film, and the whole difference, balls and film, is pulled back "
     "while the distance is measured on the balls)",
     0, 0, 0, NULL},
    {"d0", BF_AT(bf_lyap_keys, d0, BF_REAL), "cm", "1e-8",
     "distance of the shadow trajectory in the scaled phase space (x, tau v) "
     "of the balls",
     BF_POS, 0, 0, NULL},
    {"tau", BF_AT(bf_lyap_keys, tau, BF_REAL), "s", "0.01",
     "time scale that turns velocity differences into lengths", BF_POS, 0, 0,
     NULL},
    {"renormalise_every",
     BF_AT(bf_lyap_keys, renormalise_every, BF_INTERVAL), "steps | s", "0.1 s",
     "interval between renormalisations ('N' steps or 'T s'); the shadow "
     "is pulled back to d0 only if it has moved further away, and "
     "re-seeded at d0 if it has come closer than 1e-4 d0",
     0, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_lyap_spec =
    BF_SECTION("lyapunov", "largest Lyapunov exponent by two nearby "
               "trajectories", lyap_params, bf_lyap_keys);

/* ------------------------------------------------ shared bookkeeping */

bf_status bf_lyap_sum_init(bf_lyap_sum *ls, const bf_lyap_keys *k, double dt,
                           size_t n, const char *adaptive, bf_err *err)
{
    memset(ls, 0, sizeof *ls);
    if (adaptive)
        return bf_fail_key(err, BF_EINPUT, "lyapunov", "enabled",
                           "needs a fixed-step integrator: with '%s' the two "
                           "trajectories take different internal steps and "
                           "their difference measures the error control, "
                           "not the dynamics (docs/models/balls.md)",
                           adaptive);
    bf_interval iv = k->renormalise_every;
    /* less than half a step would round to none */
    if (iv.in_time ? !(iv.time / dt >= 0.5) : iv.steps < 1)
        return bf_fail_key(err, BF_EINPUT, "lyapunov", "renormalise_every",
                           "must be at least one step (dt = %g s)", dt);
    ls->n = n;
    ls->every = bf_interval_steps(iv, dt);
    ls->d0 = k->d0;
    ls->tau = k->tau;
    ls->d_start = ls->d0;
    return BF_OK;
}

void bf_lyap_displace(const bf_lyap_sum *ls, const double *x, const double *v,
                      double *xs, double *vs)
{
    /* the fixed initial direction: equal components in (x, tau v) */
    const double c = ls->d0 / sqrt(2.0 * (double)ls->n);
    for (size_t i = 0; i < ls->n; i++) {
        xs[i] = x[i] + c;
        vs[i] = v[i] + c / ls->tau;
    }
}

bf_status bf_lyap_measure(bf_lyap_sum *ls, const double *x, const double *v,
                          const double *xs, const double *vs, double t_end,
                          double *factor, bf_err *err)
{
    double d2 = 0.0;
    for (size_t i = 0; i < ls->n; i++) {
        double dx = xs[i] - x[i], dv = ls->tau * (vs[i] - v[i]);
        d2 += dx * dx + dv * dv;
    }
    double d = sqrt(d2);
    if (!(d > 0) || !isfinite(d))
        return bf_fail(err, BF_EUNSTABLE,
                       "Lyapunov estimate: the shadow trajectory is at "
                       "distance %g (merged with the run or blown up); "
                       "change [lyapunov] d0",
                       d);
    ls->logsum += log(d / ls->d_start);
    ls->nrenorm++;
    ls->t_last = t_end;
    if (d > ls->d0) {
        *factor = ls->d0 / d;
        ls->d_start = ls->d0;
    } else if (d < BF_LYAP_RESEED_BELOW * ls->d0) {
        *factor = 0.0; /* the caller re-seeds: shadow = run + displacement */
        ls->d_start = ls->d0;
    } else {
        *factor = 1.0;
        ls->d_start = d;
    }
    if (ls->s_t) {
        double est = ls->logsum / ls->t_last;
        if (bf_series_append(ls->s_t, &ls->t_last) ||
            bf_series_append(ls->s_l, &est))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    return BF_OK;
}

void bf_lyap_pull(size_t n, double factor, const double *run, double *shadow)
{
    for (size_t i = 0; i < n; i++)
        shadow[i] = run[i] + (shadow[i] - run[i]) * factor;
}

double bf_lyap_sum_estimate(const bf_lyap_sum *ls, double *t_ref)
{
    if (t_ref)
        *t_ref = ls->t_last;
    return ls->nrenorm ? ls->logsum / ls->t_last : NAN;
}

void bf_lyap_sum_report(const bf_lyap_sum *ls, unsigned long long evals,
                        FILE *f)
{
    double tr, l = bf_lyap_sum_estimate(ls, &tr);
    /* NaN: no renormalisation yet, so no estimate at all */
    if (isnan(l))
        fprintf(f, "lyapunov exponent: not measured (no renormalisation "
                   "yet; shadow trajectory: %llu force evaluations)\n",
                evals);
    else
        fprintf(f, "lyapunov exponent: %.6g 1/s (at t = %g s; shadow "
                   "trajectory: %llu force evaluations)\n",
                l, tr, evals);
}

static const bf_series_spec lyap_series[] = {
    {.path = "/lyapunov/time", .unit = "s", .kind = BF_SK_EVENTS,
     .role = BF_SR_TIME, .doc = "time of each renormalisation",
     .slot = BF_SLOT(bf_lyap_sum, s_t)},
    {.path = "/lyapunov/estimate", .unit = "s-1", .kind = BF_SK_EVENTS,
     .doc = "running estimate of the largest Lyapunov exponent: sum of "
            "log(d/d_start) over time",
     .slot = BF_SLOT(bf_lyap_sum, s_l)},
};

const bf_series_table bf_lyap_series = {"lyapunov", lyap_series,
                                        BF_NSERIES(lyap_series)};

bf_status bf_lyap_sum_output_open(bf_lyap_sum *ls, bf_out *out, bf_err *err)
{
    return bf_out_open_table(out, lyap_series, BF_NSERIES(lyap_series), ls,
                             NULL, 0, 0, err);
}

bf_status bf_lyap_sum_output_close(const bf_lyap_sum *ls, bf_out *out,
                                   bf_err *err)
{
    double tr, l = bf_lyap_sum_estimate(ls, &tr);
    bf_status st = bf_out_attr_real(out, "/", "lyapunov_exponent", l, err);
    if (!st)
        st = bf_out_attr_str(out, "/", "lyapunov_exponent.unit", "1/s", err);
    if (!st)
        st = bf_out_attr_real(out, "/", "lyapunov_time", tr, err);
    return st;
}

bf_status bf_lyap_sum_save(const bf_lyap_sum *ls, bf_ckpt *ck, bf_err *err)
{
    double r[3] = {ls->logsum, ls->t_last, ls->d_start};
    bf_status st = bf_ckpt_put(ck, "lyapunov.sum", r, 3, err);
    if (!st)
        st = bf_ckpt_put_int(ck, "lyapunov.nrenorm", ls->nrenorm, err);
    return st;
}

bf_status bf_lyap_sum_load(bf_lyap_sum *ls, const bf_ckpt *ck, bf_err *err)
{
    double r[3];
    int64_t k;
    bf_status st = bf_ckpt_get(ck, "lyapunov.sum", r, 3, err);
    if (!st)
        st = bf_ckpt_get_int(ck, "lyapunov.nrenorm", &k, err);
    if (st)
        return st;
    ls->logsum = r[0];
    ls->t_last = r[1];
    ls->d_start = r[2];
    ls->nrenorm = (long)k;
    return BF_OK;
}
