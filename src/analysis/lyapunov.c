/* lyapunov.c: largest Lyapunov exponent by a renormalised shadow
 * trajectory (see lyapunov.h). */
#include "ballfilm/lyapunov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param lyap_params[] = {
    {"enabled", BF_BOOL, "", "no",
     "estimate the largest Lyapunov exponent (integrates a second, shadow "
     "trajectory: doubles the cost)",
     0, 0, 0, NULL},
    {"d0", BF_REAL, "cm", "1e-8",
     "distance of the shadow trajectory in the scaled phase space (x, tau v)",
     BF_POS, 0, 0, NULL},
    {"tau", BF_REAL, "s", "0.01",
     "time scale that turns velocity differences into lengths", BF_POS, 0, 0,
     NULL},
    {"renormalise_every", BF_INTERVAL, "steps | s", "0.1 s",
     "interval between renormalisations ('N' steps or 'T s')", 0, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_lyap_spec = {
    "lyapunov", "largest Lyapunov exponent by two nearby trajectories",
    lyap_params};

struct bf_lyap {
    size_t n;
    double d0, tau;
    long every; /* steps between renormalisations */
    double *x, *v; /* shadow state */
    bf_integrator *it;
    double logsum; /* sum of log(d_k/d0) */
    long nrenorm;
    double t_last; /* time of the last renormalisation */
    bf_series *s_t, *s_l;
};

bf_status bf_lyap_create(bf_lyap **out, const bf_scene *sc,
                         const bf_ballsys *sys, bf_err *err)
{
    *out = NULL;
    if (!bf_scene_bool(sc, "lyapunov", "enabled"))
        return BF_OK;
    if (sys->it->type->flags & BF_INT_ADAPTIVE)
        return bf_scene_fail(sc, err, "lyapunov", "enabled",
                             "needs a fixed-step integrator: with '%s' the "
                             "two trajectories take different internal "
                             "steps and their difference measures the error "
                             "control, not the dynamics (README)",
                             sys->it->type->name);
    const double dt = bf_scene_real(sc, "scene", "dt");
    bf_interval iv = bf_scene_interval(sc, "lyapunov", "renormalise_every");
    long every = iv.in_time ? (long)floor(iv.time / dt + 0.5) : iv.steps;
    if (every < 1)
        return bf_scene_fail(sc, err, "lyapunov", "renormalise_every",
                             "must be at least one step (dt = %g s)", dt);
    bf_lyap *ly = calloc(1, sizeof *ly);
    if (!ly)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    const size_t n = sys->b.n;
    ly->n = n;
    ly->every = every;
    ly->d0 = bf_scene_real(sc, "lyapunov", "d0");
    ly->tau = bf_scene_real(sc, "lyapunov", "tau");
    ly->x = calloc(2 * n, sizeof *ly->x);
    if (!ly->x) {
        free(ly);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    ly->v = ly->x + n;
    bf_status st = bf_integrator_create(&ly->it, sys->it->type->name, n, sc,
                                        err);
    if (st) {
        bf_lyap_free(ly);
        return st;
    }
    /* the fixed initial direction: equal components in (x, tau v) */
    const double c = ly->d0 / sqrt(2.0 * (double)n);
    for (size_t i = 0; i < n; i++) {
        ly->x[i] = sys->b.x[i] + c;
        ly->v[i] = sys->b.v[i] + c / ly->tau;
    }
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
    if (n_done % ly->every)
        return BF_OK;
    const double *x = sys->b.x, *v = sys->b.v;
    double d2 = 0.0;
    for (size_t i = 0; i < ly->n; i++) {
        double dx = ly->x[i] - x[i], dv = ly->tau * (ly->v[i] - v[i]);
        d2 += dx * dx + dv * dv;
    }
    double d = sqrt(d2);
    if (!(d > 0) || !isfinite(d))
        return bf_fail(err, BF_EUNSTABLE,
                       "Lyapunov estimate: the shadow trajectory is at "
                       "distance %g (merged with the run or blown up); "
                       "change [lyapunov] d0",
                       d);
    ly->logsum += log(d / ly->d0);
    ly->nrenorm++;
    ly->t_last = t + dt;
    const double s = ly->d0 / d;
    for (size_t i = 0; i < ly->n; i++) {
        ly->x[i] = x[i] + (ly->x[i] - x[i]) * s;
        ly->v[i] = v[i] + (ly->v[i] - v[i]) * s;
    }
    if (ly->s_t) {
        double est = ly->logsum / ly->t_last;
        if (bf_series_append(ly->s_t, &ly->t_last) ||
            bf_series_append(ly->s_l, &est))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    return BF_OK;
}

double bf_lyap_estimate(const bf_lyap *ly, double *t_ref)
{
    if (t_ref)
        *t_ref = ly->t_last;
    return ly->nrenorm ? ly->logsum / ly->t_last : NAN;
}

const bf_counters *bf_lyap_counters(const bf_lyap *ly)
{
    return &ly->it->count;
}

bf_status bf_lyap_output_open(bf_lyap *ly, bf_out *out, bf_err *err)
{
    ly->s_t = bf_out_series(out, "/lyapunov/time", 0, 0, "s",
                            "time of each renormalisation", err);
    if (!ly->s_t)
        return err->status;
    ly->s_l = bf_out_series(out, "/lyapunov/estimate", 0, 0, "1/s",
                            "running estimate of the largest Lyapunov "
                            "exponent: sum of log(d/d0) over time",
                            err);
    return ly->s_l ? BF_OK : err->status;
}

bf_status bf_lyap_output_close(const bf_lyap *ly, bf_out *out, bf_err *err)
{
    double tr, l = bf_lyap_estimate(ly, &tr);
    bf_status st = bf_out_attr_real(out, "/", "lyapunov_exponent", l, err);
    if (!st)
        st = bf_out_attr_str(out, "/", "lyapunov_exponent.unit", "1/s", err);
    if (!st)
        st = bf_out_attr_real(out, "/", "lyapunov_time", tr, err);
    return st;
}

bf_status bf_lyap_save(const bf_lyap *ly, bf_ckpt *ck, bf_err *err)
{
    double r[2] = {ly->logsum, ly->t_last};
    bf_status st = bf_ckpt_put(ck, "lyapunov.x", ly->x, 2 * ly->n, err);
    if (!st)
        st = bf_ckpt_put(ck, "lyapunov.sum", r, 2, err);
    if (!st)
        st = bf_ckpt_put_int(ck, "lyapunov.nrenorm", ly->nrenorm, err);
    if (!st)
        st = bf_integrator_save(ly->it, ck, "lyapunov.integrator", err);
    return st;
}

bf_status bf_lyap_load(bf_lyap *ly, const bf_ckpt *ck, bf_err *err)
{
    double r[2];
    int64_t k;
    bf_status st = bf_ckpt_get(ck, "lyapunov.x", ly->x, 2 * ly->n, err);
    if (!st)
        st = bf_ckpt_get(ck, "lyapunov.sum", r, 2, err);
    if (!st)
        st = bf_ckpt_get_int(ck, "lyapunov.nrenorm", &k, err);
    if (!st)
        st = bf_integrator_load(ly->it, ck, "lyapunov.integrator", err);
    if (st)
        return st;
    ly->logsum = r[0];
    ly->t_last = r[1];
    ly->nrenorm = (long)k;
    return BF_OK;
}
