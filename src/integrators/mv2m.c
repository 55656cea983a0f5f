/* mv2m.c: the modified Verlet method with the second-order mid-point rule,
 * Yasuda eqs 2.19-2.21 and 2.24.
 *
 *   a0 = a(x^n)
 *   xV = x^n + dt v^n + dt^2/2 a0           (Verlet predictor, in 2.19)
 *   xT = x^n + dt/2 v^n + dt^2/8 a0         (second-order mid-point, 2.20)
 *   vV = v^n + dt (a(xV) + a0)/2            (2.19)
 *   vT = v^n + dt a(xT)                     (2.20)
 *   v^{n+1} = (vV + 2 vT)/3                 (2.21)
 *   x^{n+1} = x^n + dt v^n + dt^2/3 a0 + dt^2/6 a(xV)      (2.24)
 *
 * Three force evaluations per step, none reusable by the next step (no
 * evaluation happens at x^{n+1}).  Third order; on the harmonic oscillator
 * one step is the matrix of eq. 2.25 with determinant 1 - dt^6/72, so the
 * method is not symplectic but its amplitude error is sixth order per step.
 *
 * The increments x^{n+1} - x^n and v^{n+1} - v^n are formed first and added
 * once: adding several small terms to a large x one by one would lose more
 * to round-off over 10^7 steps.  The formulas live in step_kernels.h;
 * ball_steps.h makes the specialised steps for balls under effects from
 * them (the `balls` slot).
 */
#include "ball_steps.h"
#include "fixed_step.h"

enum { NVEC = 5 }; /* a0, aV, aT, xV, xT (step_kernels.h) */

static bf_status mv2m_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    return bf_fixed_step_init(it, params, NVEC, err);
}

static bf_status mv2m_step(bf_integrator *it, const bf_ode *ode, double t,
                           double dt, double *x, double *v, bf_err *err)
{
    return bf_mv2m_kernel(it, ode, ode->accel, ode->ctx, ode->n, it->work, t,
                          dt, x, v, err);
}

BF_BALL_STEPPER(mv2m, bf_mv2m_kernel, bf_mv2m_run, NVEC)

const bf_integrator_type bf_integrator_mv2m = {
    .name = "mv2m",
    .doc = "modified Verlet with the second-order mid-point rule (Yasuda eqs "
           "2.19-2.21, 2.24), order 3, 3 force evaluations per step",
    .order = 3,
    .evals_per_step = 3,
    .flags = BF_INT_POSITION_ONLY,
    .spec = &bf_fixed_step_spec,
    .init = mv2m_init,
    .step = mv2m_step,
    .balls = &mv2m_balls,
};
