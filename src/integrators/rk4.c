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
 * Not symmetric: on a conservative problem its energy error drifts.  The
 * step is erk.c's with this tableau.
 */
#include "erk.h"
#include "fixed_step.h"

static const bf_erk_tableau rk4 = {
    .s = 4,
    .a = {{0}, {0.5}, {0, 0.5}, {0, 0, 1}},
    .b = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6},
    .c = {0, 0.5, 0.5, 1},
};

static bf_status rk4_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    return bf_erk_init(it, params, rk4.s, err);
}

static bf_status rk4_step(bf_integrator *it, const bf_ode *ode, double t,
                          double h, double *x, double *v, bf_err *err)
{
    return bf_erk_step(&rk4, it, ode, t, h, x, v, err);
}

const bf_integrator_type bf_integrator_rk4 = {
    .name = "rk4",
    .doc = "classical Runge-Kutta (the paper's RK41), order 4, 4 force "
           "evaluations per step",
    .order = 4,
    .evals_per_step = 4,
    .flags = 0,
    .spec = &bf_fixed_step_spec,
    .init = rk4_init,
    .step = rk4_step,
};
