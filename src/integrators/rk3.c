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
 * reusable.  Not symmetric: its energy error drifts.  The step is erk.c's
 * with this tableau.
 */
#include "erk.h"
#include "fixed_step.h"

static const bf_erk_tableau rk3 = {
    .s = 3,
    .a = {{0}, {0.5}, {-1, 2}},
    .b = {1.0 / 6, 2.0 / 3, 1.0 / 6},
    .c = {0, 0.5, 1},
};

static bf_status rk3_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    return bf_erk_init(it, params, rk3.s, err);
}

static bf_status rk3_step(bf_integrator *it, const bf_ode *ode, double t,
                          double h, double *x, double *v, bf_err *err)
{
    return bf_erk_step(&rk3, it, ode, t, h, x, v, err);
}

const bf_integrator_type bf_integrator_rk3 = {
    .name = "rk3",
    .doc = "Kutta's third-order Runge-Kutta (the paper's RK32), order 3, 3 "
           "force evaluations per step",
    .order = 3,
    .evals_per_step = 3,
    .flags = 0,
    .spec = &bf_fixed_step_spec,
    .init = rk3_init,
    .step = rk3_step,
};
