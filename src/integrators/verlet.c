/* verlet.c: velocity Verlet, Yasuda eqs 2.9-2.11.
 *
 *   x^{n+1} = x^n + dt v^n + dt^2/2 a^n                         (2.9)
 *   a^{n+1} = a(x^{n+1})                                        (2.10)
 *   v^{n+1} = v^n + dt (a^{n+1} + a^n)/2                        (2.11)
 *
 * Second order, symplectic and time-symmetric.  a^{n+1} is kept for the next
 * step, so a step costs one force evaluation.  Requires a = a(x).  The
 * formulas live in step_kernels.h; ball_steps.h makes the specialised
 * steps for balls under effects from them (the `balls` slot).
 */
#include "ball_steps.h"
#include "fixed_step.h"

enum { NVEC = 3 }; /* a0, a1, xn (step_kernels.h) */

static bf_status verlet_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    return bf_fixed_step_init(it, params, NVEC, err);
}

static bf_status verlet_step(bf_integrator *it, const bf_ode *ode, double t,
                             double dt, double *x, double *v, bf_err *err)
{
    return bf_verlet_kernel(it, ode, ode->accel, ode->ctx, ode->n, it->work, t,
                            dt, x, v, err);
}

BF_BALL_STEPPER(verlet, bf_verlet_kernel, bf_verlet_run, NVEC)

const bf_integrator_type bf_integrator_verlet = {
    .name = "verlet",
    .doc = "velocity Verlet (Yasuda eqs 2.9-2.11), order 2, symplectic, "
           "1 force evaluation per step",
    .order = 2,
    .evals_per_step = 1,
    .flags = BF_INT_SYMMETRIC | BF_INT_POSITION_ONLY,
    .spec = &bf_fixed_step_spec,
    .init = verlet_init,
    .step = verlet_step,
    .balls = &verlet_balls,
};
