/* lyapunov.c: largest Lyapunov exponent by a renormalised shadow
 * trajectory (see lyapunov.h): the bookkeeping shared by the models
 * (bf_lyap_sum) and the shadow of a plain ball system (bf_lyap). */
#include "ballfilm/lyapunov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param lyap_params[] = {
    {"enabled", BF_BOOL, 0, "", "no",
     "estimate the largest Lyapunov exponent (integrates a second, shadow "
     "trajectory: doubles the cost; in the coupled model the shadow has its "
     "own film, and the whole difference, balls and film, is pulled back "
     "while the distance is measured on the balls)",
     0, 0, 0, NULL},
    {"d0", BF_REAL, 0, "cm", "1e-8",
     "distance of the shadow trajectory in the scaled phase space (x, tau v) "
     "of the balls",
     BF_POS, 0, 0, NULL},
    {"tau", BF_REAL, 0, "s", "0.01",
     "time scale that turns velocity differences into lengths", BF_POS, 0, 0,
     NULL},
    {"renormalise_every", BF_INTERVAL, 0, "steps | s", "0.1 s",
     "interval between renormalisations ('N' steps or 'T s'); the shadow "
     "is pulled back to d0 only if it has moved further away, and "
     "re-seeded at d0 if it has come closer than 1e-4 d0",
     0, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_lyap_spec = {
    "lyapunov", "largest Lyapunov exponent by two nearby trajectories",
    lyap_params, 0};

/* ------------------------------------------------ shared bookkeeping */

int bf_lyap_enabled(const bf_scene *sc)
{
    return bf_scene_bool(sc, "lyapunov", "enabled");
}

bf_status bf_lyap_sum_init(bf_lyap_sum *ls, const bf_scene *sc, size_t n,
                           const bf_integrator *it, bf_err *err)
{
    memset(ls, 0, sizeof *ls);
    if (it->type->flags & BF_INT_ADAPTIVE)
        return bf_scene_fail(sc, err, "lyapunov", "enabled",
                             "needs a fixed-step integrator: with '%s' the "
                             "two trajectories take different internal "
                             "steps and their difference measures the error "
                             "control, not the dynamics (README)",
                             it->type->name);
    const double dt = bf_scene_real(sc, "scene", "dt");
    bf_interval iv = bf_scene_interval(sc, "lyapunov", "renormalise_every");
    long every = iv.in_time ? (long)floor(iv.time / dt + 0.5) : iv.steps;
    if (every < 1)
        return bf_scene_fail(sc, err, "lyapunov", "renormalise_every",
                             "must be at least one step (dt = %g s)", dt);
    ls->n = n;
    ls->every = every;
    ls->d0 = bf_scene_real(sc, "lyapunov", "d0");
    ls->tau = bf_scene_real(sc, "lyapunov", "tau");
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

void bf_lyap_sum_report(const bf_lyap_sum *ls, const bf_counters *shadow,
                        FILE *f)
{
    double tr, l = bf_lyap_sum_estimate(ls, &tr);
    fprintf(f, "lyapunov exponent: %.6g 1/s (at t = %g s; shadow "
               "trajectory: %llu force evaluations)\n",
            l, tr, shadow->evals);
}

bf_status bf_lyap_sum_output_open(bf_lyap_sum *ls, bf_out *out, bf_err *err)
{
    ls->s_t = bf_out_series(out, "/lyapunov/time", 0, 0, "s",
                            "time of each renormalisation", err);
    if (!ls->s_t)
        return err->status;
    ls->s_l = bf_out_series(out, "/lyapunov/estimate", 0, 0, "1/s",
                            "running estimate of the largest Lyapunov "
                            "exponent: sum of log(d/d_start) over time",
                            err);
    return ls->s_l ? BF_OK : err->status;
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

/* ------------------------------------------------ a ball system's shadow */

struct bf_lyap {
    bf_lyap_sum sum;
    double *x, *v; /* shadow state */
    bf_integrator *it;
};

bf_status bf_lyap_create(bf_lyap **out, const bf_scene *sc,
                         const bf_ballsys *sys, bf_err *err)
{
    *out = NULL;
    if (!bf_lyap_enabled(sc))
        return BF_OK;
    bf_lyap_sum sum;
    bf_status st = bf_lyap_sum_init(&sum, sc, sys->b.n, sys->it, err);
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
    bf_lyap_sum_report(&ly->sum, &ly->it->count, f);
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
