/* rk3.c: Kutta's third-order method (the paper's "RK32", Yasuda sec. 2.5,
 * Fig. 3D), applied to the first-order system y = (x, v),
 * y' = F(t, y) = (v, a(t, x, v)):
 *
 *   k1 = F(t, y)
 *   k2 = F(t + h/2, y + h/2 k1)
 *   k3 = F(t + h, y - h k1 + 2h k2)
 *   y^{n+1} = y^n + h/6 (k1 + 4 k2 + k3)
 *
 * Order 3, three force evaluations per step (as many as MV2M), none
 * reusable.  Not symmetric: its energy error drifts.
 */
#include "ballfilm/integrator.h"

enum { A1, A2, A3, X2, V2, X3, V3, NVEC };

static bf_status rk3_init(bf_integrator *it, const bf_scene *sc, bf_err *err)
{
    (void)sc;
    return bf_integrator_alloc_work(it, NVEC, err);
}

static bf_status rk3_step(bf_integrator *it, const bf_ode *ode, double t,
                          double h, double *x, double *v, bf_err *err)
{
    const size_t n = ode->n;
    double *w = it->work;
    double *a1 = w + A1 * n, *a2 = w + A2 * n, *a3 = w + A3 * n,
           *x2 = w + X2 * n, *v2 = w + V2 * n, *x3 = w + X3 * n,
           *v3 = w + V3 * n;
    const double hh = 0.5 * h, h6 = h / 6.0;
    bf_status st = bf_ode_eval(it, ode, t, x, v, a1, err);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++) {
        x2[i] = x[i] + hh * v[i];
        v2[i] = v[i] + hh * a1[i];
    }
    if ((st = bf_ode_eval(it, ode, t + hh, x2, v2, a2, err)))
        return st;
    for (size_t i = 0; i < n; i++) {
        x3[i] = x[i] + h * (2.0 * v2[i] - v[i]);
        v3[i] = v[i] + h * (2.0 * a2[i] - a1[i]);
    }
    if ((st = bf_ode_eval(it, ode, t + h, x3, v3, a3, err)))
        return st;
    for (size_t i = 0; i < n; i++) {
        double dx = h6 * (v[i] + 4.0 * v2[i] + v3[i]);
        double dv = h6 * (a1[i] + 4.0 * a2[i] + a3[i]);
        x[i] += dx;
        v[i] += dv;
    }
    it->count.steps++;
    return BF_OK;
}

const bf_integrator_type bf_integrator_rk3 = {
    .name = "rk3",
    .doc = "Kutta's third-order Runge-Kutta (the paper's RK32), order 3, 3 "
           "force evaluations per step",
    .order = 3,
    .evals_per_step = 3,
    .flags = 0,
    .init = rk3_init,
    .step = rk3_step,
};
