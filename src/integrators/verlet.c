/* verlet.c: velocity Verlet, Yasuda eqs 2.9-2.11.
 *
 *   x^{n+1} = x^n + dt v^n + dt^2/2 a^n                         (2.9)
 *   a^{n+1} = a(x^{n+1})                                        (2.10)
 *   v^{n+1} = v^n + dt (a^{n+1} + a^n)/2                        (2.11)
 *
 * Second order, symplectic and time-symmetric.  a^{n+1} is kept for the next
 * step, so a step costs one force evaluation.  Requires a = a(x).
 */
#include "ballfilm/integrator.h"

enum { A0, A1, XN, NVEC };

static bf_status verlet_init(bf_integrator *it, const bf_scene *sc, bf_err *err)
{
    (void)sc;
    return bf_integrator_alloc_work(it, NVEC, err);
}

static bf_status verlet_step(bf_integrator *it, const bf_ode *ode, double t,
                             double dt, double *x, double *v, bf_err *err)
{
    size_t n = ode->n;
    double *a0 = it->work + A0 * n, *a1 = it->work + A1 * n,
           *xn = it->work + XN * n;
    bf_status st = bf_ode_eval_cached(it, ode, t, x, v, a0, err);
    if (st)
        return st;
    const double h2 = 0.5 * dt * dt;
    for (size_t i = 0; i < n; i++)
        xn[i] = x[i] + (dt * v[i] + h2 * a0[i]);
    st = bf_ode_eval(it, ode, t + dt, xn, v, a1, err);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++) {
        x[i] = xn[i];
        v[i] += 0.5 * dt * (a1[i] + a0[i]);
    }
    bf_integrator_cache_store(it, ode, x, a1);
    it->count.steps++;
    return BF_OK;
}

const bf_integrator_type bf_integrator_verlet = {
    .name = "verlet",
    .doc = "velocity Verlet (Yasuda eqs 2.9-2.11), order 2, symplectic, "
           "1 force evaluation per step",
    .order = 2,
    .evals_per_step = 1,
    .flags = BF_INT_SYMMETRIC | BF_INT_POSITION_ONLY,
    .init = verlet_init,
    .step = verlet_step,
};
