/* rkn6.c: an explicit Runge-Kutta-Nystrom method of order 6 for
 * x'' = a(x): RKN6(4)6FD of J. R. Dormand, M. E. A. El-Mikkawy and
 * P. J. Prince, "Families of Runge-Kutta-Nystrom formulae", IMA J. Numer.
 * Anal. 7 (1987) 235-250, used with fixed steps (its embedded fourth-
 * order formula is not needed):
 *
 *   k_1 = a(x^n),  k_i = a(x^n + c_i dt v^n + dt^2 sum_{j<i} a_ij k_j),
 *   x^{n+1} = x^n + dt v^n + dt^2 sum_j b_j k_j,     (b_j = a_6j)
 *   v^{n+1} = v^n + dt sum_j bv_j k_j,
 *
 * six stages, R = sqrt(8581): c = (0, (209 - R)/900, (209 - R)/450,
 * (209 + R)/450, 9/10, 1); the last stage is at x^{n+1} (first same as
 * last), so a step costs five force evaluations, the sixth being the next
 * step's first (kept in the force cache like Verlet's).  Order 6 for
 * positions and velocities; not symplectic.  It is specialised like MV2M
 * (step_kernels.h, ball_steps.h): the effects' kernels inline, the same
 * bits as the generic step (tests/test_advance.c, bench/bench_balls.c).
 * Time argument of stage i: t + c_i dt (unused by a = a(x)).
 */
#include "ball_steps.h"
#include "fixed_step.h"

enum { NVEC = 7 }; /* k_1..k_6, X (step_kernels.h) */

static bf_status rkn6_init(bf_integrator *it, const void *params, bf_err *err)
{
    return bf_fixed_step_init(it, params, NVEC, err);
}

static bf_status rkn6_step(bf_integrator *it, const bf_ode *ode, double t,
                           double dt, double *x, double *v, bf_err *err)
{
    return bf_rkn6_kernel(it, ode, ode->accel, ode->ctx, ode->n, it->work, t,
                          dt, x, v, err);
}

BF_BALL_STEPPER(rkn6, bf_rkn6_kernel, bf_rkn6_run, NVEC)

const bf_integrator_type bf_integrator_rkn6 = {
    .name = "rkn6",
    .doc = "Runge-Kutta-Nystrom RKN6(4)6FD (Dormand, El-Mikkawy & Prince "
           "1987), order 6, 5 force evaluations per step (first same as "
           "last)",
    .order = 6,
    .evals_per_step = 5,
    .flags = BF_INT_POSITION_ONLY,
    .spec = &bf_fixed_step_spec,
    .init = rkn6_init,
    .step = rkn6_step,
    .balls = &rkn6_balls,
};
