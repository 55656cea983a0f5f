/* alpha.c: the alpha-family of Yasuda eqs 2.16-2.17, with a position update
 * of our choice (the paper gives none).
 *
 *   x^{n+1/2} = x^n + dt/2 v^n + alpha dt^2 a(x^n)              (2.16)
 *   v^{n+1}   = v^n + dt a(x^{n+1/2})                           (2.17)
 *
 * alpha = 0 is the improved Euler method, alpha = 1/8 the second-order
 * mid-point rule (x^{n+1/2} is then the Taylor expansion of x(t + dt/2) to
 * second order) and alpha = 1/4 the mid-point rule (x^{n+1/2} is then
 * (x^n + x^{n+1})/2 with Verlet's position update).
 *
 * Position update ([integrator] position):
 *   verlet     x^{n+1} = x^n + dt v^n + dt^2/2 a(x^n)             (2.9)
 *   trapezoid  x^{n+1} = x^n + dt (v^n + v^{n+1})/2
 * Both make every alpha second order.  They differ in stability.  On the
 * harmonic oscillator a'' = -w^2 x one step is a 2x2 matrix whose
 * determinant (the factor by which the phase-space area, hence the energy
 * for small dt, grows per step) is, with s = w dt,
 *   verlet:    det = 1 + (1/4 - alpha) s^4
 *   trapezoid: det = 1 - alpha s^4 / 2
 * so with Verlet's position update improved Euler (alpha = 0) and the
 * second-order mid-point rule (alpha = 1/8) GAIN energy every step and only
 * alpha = 1/4 conserves it, while with the trapezoid update alpha = 0
 * conserves and alpha > 0 loses energy.  tests/test_integrators.c checks
 * both determinants and the energy gain on the bouncing ball.  The default
 * is Verlet's update: it is the one under which alpha = 1/4 is the paper's
 * "mid-point method" (x^{n+1/2} = (x^n + x^{n+1})/2).
 *
 * Force evaluations per step: two (a(x^n) and a(x^{n+1/2})); one when
 * alpha = 0 with the trapezoid update, which never needs a(x^n).  Requires
 * a = a(x).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/integrator.h"
#include "fixed_step.h"

enum { A0, AH, XH, NVEC };
enum { POS_VERLET, POS_TRAPEZOID };

/* the keys of [integrator], also the integrator's private state */
typedef struct alpha_priv {
    double alpha;
    int position; /* POS_VERLET, POS_TRAPEZOID */
    int events;   /* [integrator] events (integrator.h) */
    double events_zone;
} alpha_priv;

static const bf_param alpha_params[] = {
    {"alpha", BF_AT(alpha_priv, alpha, BF_REAL), "1", "0.125",
     "alpha of eq. 2.16: 0 improved Euler, 0.125 second-order mid-point, "
     "0.25 mid-point",
     BF_MIN | BF_MAX, 0, 1, NULL},
    {"position", BF_AT(alpha_priv, position, BF_ENUM), "", "verlet",
     "position update: verlet (x += dt v + dt^2/2 a(x^n)) or trapezoid "
     "(x += dt (v^n + v^{n+1})/2); docs/integrators.md compares their "
     "stability",
     0, 0, 0, "verlet|trapezoid"},
    BF_EVENTS_PARAMS(alpha_priv),
    {0},
};

static const bf_section_spec alpha_spec = BF_SECTION(
    "integrator", "parameters of the alpha-family (Yasuda eqs 2.16-2.17)",
    alpha_params, alpha_priv);

static bf_status alpha_init(bf_integrator *it, const void *params,
                            bf_err *err)
{
    const alpha_priv *p = params;
    return bf_fixed_step_init_copy(it, p, sizeof *p, p->events,
                                   p->events_zone, NVEC, err);
}

static void alpha_free(bf_integrator *it) { free(it->priv); }

static bf_status alpha_step(bf_integrator *it, const bf_ode *ode, double t,
                            double dt, double *x, double *v, bf_err *err)
{
    const alpha_priv *p = it->priv;
    const size_t n = ode->n;
    double *a0 = it->work + A0 * n, *ah = it->work + AH * n,
           *xh = it->work + XH * n;
    const double hdt = 0.5 * dt, adt2 = p->alpha * dt * dt,
                 hdt2 = 0.5 * dt * dt;
    const int need_a0 = p->position == POS_VERLET || p->alpha != 0.0;
    bf_status st;
    if (need_a0 && (st = bf_ode_eval(it, ode, t, x, v, a0, err)))
        return st;
    for (size_t i = 0; i < n; i++)
        xh[i] = x[i] + (hdt * v[i] + (need_a0 ? adt2 * a0[i] : 0.0));
    if ((st = bf_ode_eval(it, ode, t + hdt, xh, v, ah, err)))
        return st;
    if (p->position == POS_VERLET) {
        for (size_t i = 0; i < n; i++) {
            x[i] += dt * v[i] + hdt2 * a0[i];
            v[i] += dt * ah[i];
        }
    } else {
        for (size_t i = 0; i < n; i++) {
            double dv = dt * ah[i];
            x[i] += dt * v[i] + hdt * dv; /* dt (v^n + v^{n+1})/2 */
            v[i] += dv;
        }
    }
    it->count.steps++;
    return BF_OK;
}

static void alpha_describe(const bf_integrator *it, char *buf, size_t cap)
{
    const alpha_priv *p = it->priv;
    snprintf(buf, cap, "alpha %g %s", p->alpha,
             p->position == POS_VERLET ? "verlet" : "trapezoid");
}

const bf_integrator_type bf_integrator_alpha = {
    .name = "alpha",
    .doc = "alpha-family of Yasuda eqs 2.16-2.17 ([integrator] alpha: 0 "
           "improved Euler, 1/8 second-order mid-point, 1/4 mid-point), "
           "order 2, 2 force evaluations per step",
    .order = 2,
    .evals_per_step = 2,
    .flags = BF_INT_POSITION_ONLY,
    .spec = &alpha_spec,
    .init = alpha_init,
    .step = alpha_step,
    .free = alpha_free,
    .describe = alpha_describe,
};
