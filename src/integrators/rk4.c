/* rk4.c: the classical fourth-order Runge-Kutta method (the paper's "RK41",
 * the 1/6 formula of its ref. [1], Yasuda sec. 2.5, Fig. 3C), applied to
 * the first-order system y = (x, v), y' = (v, a(t, x, v)):
 *
 *   k1 = F(t, y)
 *   k2 = F(t + h/2, y + h/2 k1)
 *   k3 = F(t + h/2, y + h/2 k2)
 *   k4 = F(t + h, y + h k3)
 *   y^{n+1} = y^n + h/6 (k1 + 2 k2 + 2 k3 + k4)
 *
 * Order 4, four force evaluations per step, none reusable by the next step.
 * Not symmetric: on a conservative problem its energy error drifts.
 * The position part of every stage is a velocity (k_x = v_stage), so only
 * the accelerations need storage.
 */
#include "ballfilm/integrator.h"

enum { A1, A2, A3, A4, X2, V2, X3, V3, X4, V4, NVEC };

static bf_status rk4_init(bf_integrator *it, const bf_scene *sc, bf_err *err)
{
    (void)sc;
    return bf_integrator_alloc_work(it, NVEC, err);
}

static bf_status rk4_step(bf_integrator *it, const bf_ode *ode, double t,
                          double h, double *x, double *v, bf_err *err)
{
    const size_t n = ode->n;
    double *w = it->work;
    double *a1 = w + A1 * n, *a2 = w + A2 * n, *a3 = w + A3 * n,
           *a4 = w + A4 * n, *x2 = w + X2 * n, *v2 = w + V2 * n,
           *x3 = w + X3 * n, *v3 = w + V3 * n, *x4 = w + X4 * n,
           *v4 = w + V4 * n;
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
        x3[i] = x[i] + hh * v2[i];
        v3[i] = v[i] + hh * a2[i];
    }
    if ((st = bf_ode_eval(it, ode, t + hh, x3, v3, a3, err)))
        return st;
    for (size_t i = 0; i < n; i++) {
        x4[i] = x[i] + h * v3[i];
        v4[i] = v[i] + h * a3[i];
    }
    if ((st = bf_ode_eval(it, ode, t + h, x4, v4, a4, err)))
        return st;
    for (size_t i = 0; i < n; i++) {
        double dx = h6 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
        double dv = h6 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
        x[i] += dx;
        v[i] += dv;
    }
    it->count.steps++;
    return BF_OK;
}

const bf_integrator_type bf_integrator_rk4 = {
    .name = "rk4",
    .doc = "classical Runge-Kutta (the paper's RK41), order 4, 4 force "
           "evaluations per step",
    .order = 4,
    .evals_per_step = 4,
    .flags = 0,
    .init = rk4_init,
    .step = rk4_step,
};
