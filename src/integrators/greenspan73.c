/* greenspan73.c: Greenspan's energy-conserving scheme (D. Greenspan,
 * "Arithmetic applied mathematics" / the 1973 discrete mechanics, Univ.
 * Wisconsin CS TR 171, eqs 2.1-2.4) for balls on a line: a discrete-
 * gradient step for x'' = a(x), a = -grad V / m,
 *
 *   x^{n+1} = x^n + dt (v^n + v^{n+1})/2                       (2.1)
 *   m (v^{n+1} - v^n) = -dt Dbar V(x^n, x^{n+1})               (2.2)
 *
 * with Dbar V a discrete gradient: sum_i Dbar_i V (x^{n+1}_i - x^n_i) =
 * V(x^{n+1}) - V(x^n).  Multiplying (2.2) by (v^n + v^{n+1})/2 and using
 * (2.1) gives K^{n+1} - K^n = -(V^{n+1} - V^n): the energy K + V is
 * conserved exactly (to round-off and the iteration's tolerance).
 * Greenspan's discrete gradient for a pair potential phi(r) is the force
 * -(phi(r+) - phi(r))/(r+ - r); the ball system gives it per term of its
 * effects through bf_ode.daccel (src/effects/effect_kernels.h): gravity
 * exactly, the Hertz floor and pair terms through the shared contact
 * module's potential (bf_hertz_energy_dd, src/contact/hertz.h: the
 * quotient formed without cancellation, so no guard for tiny increments
 * is needed and none loses the conservation).  Each term is symmetric in
 * (x^n, x^{n+1}), so the step is time-symmetric and second order.
 *
 * Solved by fixed-point iteration on v^{n+1} from the predictor
 * v^n + dt a(x^n):
 *   x_k = x^n + dt/2 (v^n + v_k),   v_{k+1} = v^n + dt abar(x^n, x_k),
 * until |v_{k+1} - v_k| <= tol * max(|v_{k+1}|, |v^n|, dt |abar|) (max
 * norm; [integrator] tol, default 1e-15, a few ulps: converged to round-
 * off), or until the change stops falling while below 100 tol of that
 * scale (the rounding of abar's terms: see STALL).  The map contracts with factor dt^2/4 |d abar/dx| (for a Hertz
 * contact 1.5 k x^{1/2}/m: 6e-3 for the paper's two balls at dt = 1e-4
 * s), so it converges in 4-7 iterations; each costs one evaluation of
 * abar, counted in bf_counters.evals, and is counted in
 * bf_counters.iterations.  A step that does not converge in [integrator]
 * max_iter iterations fails with BF_ENOCONV and a message, leaving the
 * state at its start: it never continues unconverged.
 *
 * An ode without daccel (a plain right-hand side a(x), e.g. the tests'
 * oscillator) has no potential to take differences of: the step then
 * uses abar = a((x^n + x^{n+1})/2), the implicit mid-point rule in this
 * form, symmetric and second order but not energy-conserving.
 */
#include <math.h>
#include <stdlib.h>

#include "ballfilm/integrator.h"
#include "fixed_step.h"

enum { AB, XN, VP, VN, XM, NVEC };

/* a change that stops falling counts as converged when within STALL tol of
 * the scale (1e-13 relative with the default tol: still round-off) */
enum { STALL = 100 };

/* the keys of [integrator], also the integrator's private state */
typedef struct g73_priv {
    double tol;
    long max_iter;
    int events;
    double events_zone;
} g73_priv;

static const bf_param g73_params[] = {
    {"tol", BF_AT(g73_priv, tol, BF_REAL), "1", "1e-15",
     "relative tolerance of the fixed-point iteration (max norm of the "
     "update of v^{n+1} over the velocity scale): a few ulps, round-off",
     BF_POS, 0, 0, NULL},
    {"max_iter", BF_AT(g73_priv, max_iter, BF_INT), "1", "50",
     "iterations allowed per step before the step fails (exit 4)", BF_MIN, 1,
     0, NULL},
    BF_EVENTS_PARAMS(g73_priv),
    {0},
};

static const bf_section_spec g73_spec = BF_SECTION(
    "integrator", "parameters of Greenspan's energy-conserving scheme",
    g73_params, g73_priv);

static bf_status g73_init(bf_integrator *it, const void *params,
                          bf_err *err)
{
    const g73_priv *p = params;
    return bf_fixed_step_init_copy(it, p, sizeof *p, p->events,
                                   p->events_zone, NVEC, err);
}

static void g73_free(bf_integrator *it) { free(it->priv); }

/* abar(x, xn) from the ode's discrete gradient, or a at the mid-point */
static bf_status g73_abar(bf_integrator *it, const bf_ode *ode, double t,
                          const double *x, const double *xn, double *xm,
                          double *ab, bf_err *err)
{
    if (!ode->daccel) {
        for (size_t i = 0; i < ode->n; i++)
            xm[i] = 0.5 * (x[i] + xn[i]);
        return bf_ode_eval(it, ode, t, xm, NULL, ab, err);
    }
    it->count.evals++;
    if (ode->daccel(ode->ctx, t, x, xn, ab))
        return bf_ode_eval_failed(err);
    return BF_OK;
}

static bf_status g73_step(bf_integrator *it, const bf_ode *ode, double t,
                          double dt, double *x, double *v, bf_err *err)
{
    const g73_priv *p = it->priv;
    const size_t n = ode->n;
    double *ab = it->work + AB * n, *xn = it->work + XN * n,
           *vp = it->work + VP * n, *vn = it->work + VN * n,
           *xm = it->work + XM * n;
    const double hdt = 0.5 * dt, tm = t + hdt;
    bf_status st = bf_ode_eval(it, ode, t, x, v, ab, err);
    if (st)
        return st;
    for (size_t i = 0; i < n; i++)
        vp[i] = v[i] + dt * ab[i];
    double change = INFINITY, prev = INFINITY, scale = 0.0;
    int done = 0;
    long k;
    for (k = 1; k <= p->max_iter; k++) {
        for (size_t i = 0; i < n; i++)
            xn[i] = x[i] + hdt * (v[i] + vp[i]);
        if ((st = g73_abar(it, ode, tm, x, xn, xm, ab, err)))
            return st;
        change = 0.0;
        scale = 0.0;
        for (size_t i = 0; i < n; i++) {
            vn[i] = v[i] + dt * ab[i];
            double d = fabs(vn[i] - vp[i]);
            if (!(d <= change)) /* also catches NaN */
                change = d;
            scale = fmax(scale, fmax(fmax(fabs(vn[i]), fabs(v[i])),
                                     fabs(dt * ab[i])));
        }
        for (size_t i = 0; i < n; i++)
            vp[i] = vn[i];
        /* converged, or stalled at round-off: the map contracts by ~1e-2
         * per iteration, so a change that no longer falls is the rounding
         * of abar's terms (gravity and a contact force that nearly cancel
         * leave a few ulps of the larger in their sum) */
        done = change <= p->tol * scale ||
               (change >= prev && change <= STALL * p->tol * scale);
        if (done || !isfinite(change))
            break;
        prev = change;
    }
    const long used = k > p->max_iter ? p->max_iter : k;
    it->count.iterations += (unsigned long long)used;
    if (!done)
        return bf_fail(err, BF_ENOCONV,
                       "greenspan73: the fixed-point iteration did not "
                       "converge in %ld iterations (last relative change "
                       "%.3g, tolerance %.3g); dt = %g s is too large for "
                       "the stiffness here (it contracts only while "
                       "dt^2/4 |da/dx| < 1), or the tolerance is below "
                       "round-off",
                       used, scale > 0 ? change / scale : change, p->tol, dt);
    for (size_t i = 0; i < n; i++) {
        x[i] += hdt * (v[i] + vp[i]);
        v[i] = vp[i];
    }
    it->count.steps++;
    return BF_OK;
}

const bf_integrator_type bf_integrator_greenspan73 = {
    .name = "greenspan73",
    .doc = "Greenspan's energy-conserving discrete-gradient scheme (1973, "
           "eqs 2.1-2.4) by fixed-point iteration to round-off, order 2, "
           "symmetric; conserves K + V of the balls to round-off",
    .order = 2,
    .evals_per_step = 0,
    .flags = BF_INT_SYMMETRIC | BF_INT_IMPLICIT | BF_INT_POSITION_ONLY |
             BF_INT_POTENTIAL,
    .spec = &g73_spec,
    .init = g73_init,
    .step = g73_step,
    .free = g73_free,
};
