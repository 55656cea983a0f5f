/* impmid.c: the implicit mid-point rule (Yasuda sec. 2.5, Fig. 3E),
 * symmetric and symplectic, for y = (x, v), y' = (v, a(t, x, v)):
 *
 *   y^{n+1} = y^n + dt F(t + dt/2, (y^n + y^{n+1})/2)
 *
 * In terms of the mid-point velocity vm = (v^n + v^{n+1})/2 this is one
 * equation for vm,
 *
 *   vm = v^n + dt/2 a(t + dt/2, x^n + dt/2 vm, vm),
 *   x^{n+1} = x^n + dt vm,   v^{n+1} = 2 vm - v^n,
 *
 * solved by fixed-point iteration from the explicit predictor
 * vm_0 = v^n + dt/2 a(x^n, v^n), until the update is below
 * [integrator] tol relative to the velocity scale max(|vm|, |v^n|) (max
 * norm; the paper asks 1e-14).  The iteration contracts when
 * dt^2/4 |da/dx| < 1 (for a Hertz contact of stiffness k x^{1/2}/m this
 * bounds dt); each iteration costs one force evaluation.  Iterations are
 * counted in bf_counters.iterations.  If the tolerance is not met within
 * [integrator] max_iter iterations the step fails with BF_ENOCONV and a
 * message (it never continues with an unconverged value).
 */
#include <math.h>
#include <stdlib.h>

#include "ballfilm/integrator.h"
#include "fixed_step.h"

enum { A, XM, VM, VN, NVEC };

/* the keys of [integrator], also the integrator's private state */
typedef struct impmid_priv {
    double tol;
    long max_iter;
    int events; /* [integrator] events (integrator.h) */
    double events_zone;
} impmid_priv;

static const bf_param impmid_params[] = {
    {"tol", BF_AT(impmid_priv, tol, BF_REAL), "1", "1e-14",
     "relative tolerance of the fixed-point iteration (max norm of the "
     "mid-point velocity update over the velocity scale)",
     BF_POS, 0, 0, NULL},
    {"max_iter", BF_AT(impmid_priv, max_iter, BF_INT), "1", "50",
     "iterations allowed per step before the step fails (exit 4)", BF_MIN, 1,
     0, NULL},
    BF_EVENTS_PARAMS(impmid_priv),
    {0},
};

static const bf_section_spec impmid_spec =
    BF_SECTION("integrator", "parameters of the implicit mid-point rule",
               impmid_params, impmid_priv);

static bf_status impmid_init(bf_integrator *it, const void *params,
                             bf_err *err)
{
    const impmid_priv *p = params;
    return bf_fixed_step_init_copy(it, p, sizeof *p, p->events,
                                   p->events_zone, NVEC, err);
}

static void impmid_free(bf_integrator *it) { free(it->priv); }

static bf_status impmid_step(bf_integrator *it, const bf_ode *ode, double t,
                             double dt, double *x, double *v, bf_err *err)
{
    const impmid_priv *p = it->priv;
    const size_t n = ode->n, nc = ode->n_check ? ode->n_check : n;
    double *a = it->work + A * n, *xm = it->work + XM * n,
           *vm = it->work + VM * n, *vn = it->work + VN * n;
    const double hdt = 0.5 * dt, tm = t + hdt;
    bf_status st = bf_ode_eval(it, ode, t, x, v, a, err);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++)
        vm[i] = v[i] + hdt * a[i];
    double change = INFINITY, scale = 0.0;
    long k;
    for (k = 1; k <= p->max_iter; k++) {
        for (size_t i = 0; i < n; i++)
            xm[i] = x[i] + hdt * vm[i];
        if ((st = bf_ode_eval(it, ode, tm, xm, vm, a, err)))
            return st;
        change = 0.0;
        scale = 0.0;
        for (size_t i = 0; i < n; i++) {
            vn[i] = v[i] + hdt * a[i];
            if (i >= nc) /* follows from the others (bf_ode.n_check) */
                continue;
            double d = fabs(vn[i] - vm[i]);
            if (!(d <= change)) /* also catches NaN */
                change = d;
            scale = fmax(scale, fmax(fabs(vn[i]), fabs(v[i])));
        }
        for (size_t i = 0; i < n; i++)
            vm[i] = vn[i];
        if (change <= p->tol * scale)
            break;
        if (!isfinite(change))
            break;
    }
    it->count.iterations += (unsigned long long)(k > p->max_iter ? p->max_iter
                                                                 : k);
    if (!(change <= p->tol * scale))
        return bf_fail(err, BF_ENOCONV,
                       "implicit mid-point: the fixed-point iteration did not "
                       "converge in %ld iterations (last relative change "
                       "%.3g, tolerance %.3g); dt = %g s is too large for "
                       "the stiffness here (it contracts only while "
                       "dt^2/4 |da/dx| < 1)",
                       k > p->max_iter ? p->max_iter : k,
                       scale > 0 ? change / scale : change, p->tol, dt);
    for (size_t i = 0; i < n; i++) {
        x[i] += dt * vm[i];
        v[i] = 2.0 * vm[i] - v[i];
    }
    it->count.steps++;
    return BF_OK;
}

const bf_integrator_type bf_integrator_impmid = {
    .name = "impmid",
    .doc = "implicit mid-point rule by fixed-point iteration to "
           "[integrator] tol (1e-14), order 2, symmetric; 1 + iterations "
           "force evaluations per step",
    .order = 2,
    .evals_per_step = 0,
    .flags = BF_INT_SYMMETRIC | BF_INT_IMPLICIT,
    .spec = &impmid_spec,
    .init = impmid_init,
    .step = impmid_step,
    .free = impmid_free,
};
