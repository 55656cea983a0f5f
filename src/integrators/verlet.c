/* verlet.c: velocity Verlet, Yasuda eqs 2.9-2.11.
 *
 *   x^{n+1} = x^n + dt v^n + dt^2/2 a^n                         (2.9)
 *   a^{n+1} = a(x^{n+1})                                        (2.10)
 *   v^{n+1} = v^n + dt (a^{n+1} + a^n)/2                        (2.11)
 *
 * Second order, symplectic and time-symmetric.  a^{n+1} is kept for the next
 * step, so a step costs one force evaluation.  The formulas live in
 * step_kernels.h; ball_steps.h makes the specialised steps for balls under
 * effects from them (the `balls` slot).
 *
 * Forces that depend on velocity (bf_ode.velocity_dependent): (2.10) is
 * a^{n+1} = a(t + dt, x^{n+1}, v^{n+1}), so (2.11) is an equation for
 * v^{n+1},
 *   v^{n+1} = v^n + dt/2 (a^n + a(t + dt, x^{n+1}, v^{n+1}))     (2.11')
 * with a^n = a(t, x^n, v^n).  It is solved by fixed-point iteration from
 * v_0 = v^n + dt a^n, v_{k+1} = v^n + dt/2 (a^n + a(t + dt, x^{n+1}, v_k)),
 * which contracts by dt/2 |da/dv| per iteration (gamma dt/2 for linear
 * drag), to round-off: until the update is at most 2 ulps of the velocity
 * scale max(|v_{k+1}|, |v^n|, dt |a|) (max norm), or stops falling while
 * below 64 ulps of it.  The step stays second order: (2.9) is the Taylor
 * expansion of x to dt^2 with the exact a^n, and (2.11') the trapezoid
 * rule for v' = a with end values that are exact to O(dt^3), so the local
 * errors are O(dt^3) (tests/test_forces.c measures 2.00).  Each iteration
 * is one force evaluation (counted in bf_counters.evals and .iterations);
 * a^n is evaluated afresh each step (the first-same-as-last cache is keyed
 * by x only).  A step that does not converge in MAX_ITER iterations fails
 * with BF_ENOCONV, leaving the state at its start.  For a = a(x) this is
 * eqs 2.9-2.11 as above, bit for bit (the iteration is not entered).
 */
#include <float.h>

#include "ball_steps.h"
#include "fixed_step.h"

enum { NVEC = 3 }; /* a0, a1, xn (step_kernels.h) */
enum { NVEC_V = 5, MAX_ITER = 50 }; /* with vk, vn for the iteration */

static bf_status verlet_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    return bf_fixed_step_init(it, params, NVEC_V, err);
}

/* the step for a = a(t, x, v): eqs 2.9, 2.11' (see above) */
static bf_status verlet_vstep(bf_integrator *it, const bf_ode *ode, double t,
                              double dt, double *x, double *v, bf_err *err)
{
    const size_t n = ode->n, nc = ode->n_check ? ode->n_check : n;
    double *a0 = it->work, *a1 = a0 + n, *xn = a1 + n, *vk = xn + n,
           *vn = vk + n;
    const double hdt = 0.5 * dt, h2 = 0.5 * dt * dt;
    bf_status st = bf_ode_eval(it, ode, t, x, v, a0, err);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++) {
        xn[i] = x[i] + (dt * v[i] + h2 * a0[i]);
        vk[i] = v[i] + dt * a0[i];
    }
    double change = INFINITY, prev = INFINITY, scale = 0.0;
    int done = 0;
    long k;
    for (k = 1; k <= MAX_ITER; k++) {
        if ((st = bf_ode_eval(it, ode, t + dt, xn, vk, a1, err)))
            return st;
        change = 0.0;
        scale = 0.0;
        for (size_t i = 0; i < n; i++) {
            vn[i] = v[i] + hdt * (a1[i] + a0[i]);
            if (i >= nc) { /* follows from the others (bf_ode.n_check) */
                vk[i] = vn[i];
                continue;
            }
            double d = fabs(vn[i] - vk[i]);
            if (!(d <= change)) /* also catches NaN */
                change = d;
            scale = fmax(scale, fmax(fmax(fabs(vn[i]), fabs(v[i])),
                                     fabs(dt * a1[i])));
            vk[i] = vn[i];
        }
        done = change <= 2 * DBL_EPSILON * scale ||
               (change >= prev && change <= 64 * DBL_EPSILON * scale);
        if (done || !isfinite(change))
            break;
        prev = change;
    }
    it->count.iterations += (unsigned long long)(k > MAX_ITER ? MAX_ITER : k);
    if (!done)
        return bf_fail(err, BF_ENOCONV,
                       "verlet: the velocity of a velocity-dependent force "
                       "did not converge in %d iterations (last relative "
                       "change %.3g); dt = %g s is too large for it (the "
                       "iteration contracts only while dt/2 |da/dv| < 1)",
                       MAX_ITER, scale > 0 ? change / scale : change, dt);
    for (size_t i = 0; i < n; i++) {
        x[i] = xn[i];
        v[i] = vk[i];
    }
    it->count.steps++;
    return BF_OK;
}

static bf_status verlet_step(bf_integrator *it, const bf_ode *ode, double t,
                             double dt, double *x, double *v, bf_err *err)
{
    if (ode->velocity_dependent)
        return verlet_vstep(it, ode, t, dt, x, v, err);
    return bf_verlet_kernel(it, ode, ode->accel, ode->ctx, ode->n, it->work, t,
                            dt, x, v, err);
}

BF_BALL_STEPPER(verlet, bf_verlet_kernel, bf_verlet_run, NVEC)

const bf_integrator_type bf_integrator_verlet = {
    .name = "verlet",
    .doc = "velocity Verlet (Yasuda eqs 2.9-2.11), order 2, symplectic, "
           "1 force evaluation per step (velocity-dependent forces: the "
           "last half-kick solved for v^{n+1}, order 2)",
    .order = 2,
    .evals_per_step = 1,
    .flags = BF_INT_SYMMETRIC,
    .spec = &bf_fixed_step_spec,
    .init = verlet_init,
    .step = verlet_step,
    .balls = &verlet_balls,
};
