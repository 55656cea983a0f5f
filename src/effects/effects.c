/* effects.c: summing the accelerations and potentials of a scene's effects
 * (the accelerations through the dispatch point of effect_kernels.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effect_kernels.h"

/* GCC would turn the zeroing loop of the dispatch point into a memset call;
 * for a few balls memset's wide stores followed by scalar loads stall store
 * forwarding (measured with perf on the two-ball run). */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-tree-loop-distribute-patterns")))
#endif
int bf_effects_accel(const bf_effect *e, size_t ne, const bf_balls *b, double t,
                     const double *x, const double *v, double *acc)
{
    return bf_effects_accel_inline(e, ne, b, t, x, v, acc, NULL);
}

double bf_effects_potential(const bf_effect *e, size_t ne, const bf_balls *b,
                            double t, const double *x)
{
    return bf_effects_potential_inline(e, ne, b, t, x);
}

/* The coordinate-increment discrete gradient of one effect's potential V
 * (Itoh & Abe 1988), averaged over the two orders of the coordinates:
 * forward, through the corners y_k = (xn_1..xn_k, x_{k+1}..x_n),
 *   Dbar_k = (V(y_k) - V(y_{k-1})) / (xn_k - x_k),
 * and the same with the coordinates taken from the last to the first.
 * Each order telescopes to V(xn) - V(x), so the average does too; the
 * forward order from x to xn uses the corners of the reverse order from
 * xn to x, so the average is symmetric in (x, xn) and the step built on
 * it second order.  Where an increment is below sqrt(eps) |x_k| the
 * quotient would lose more to the rounding of V than the mid-point
 * derivative loses to truncation, so the force at the mid-point is used
 * for that coordinate (its term in the energy balance is then of the
 * order of the increment squared times eps: round-off).  An effect
 * without a potential enters through its force at the mid-point. */
int bf_effect_daccel_generic(const bf_effect *e, const bf_balls *b, double t,
                             const double *x, const double *xn, double *abar)
{
    const size_t n = b->n;
    double buf[48] = {0}, *y = buf, *am = buf + 16, *xm = buf + 32;
    if (n > 16 && !(y = malloc(3 * n * sizeof *y)))
        return 1;
    if (n > 16) {
        am = y + n;
        xm = y + 2 * n;
    }
    for (size_t i = 0; i < n; i++) {
        xm[i] = 0.5 * (x[i] + xn[i]);
        am[i] = 0.0;
    }
    int fail = e->type->accel(e->self, b, t, xm, b->v, am);
    const bf_effect_type *T = e->type;
    for (size_t i = 0; !fail && i < n; i++) {
        double dx = xn[i] - x[i];
        if (!T->potential ||
            !(fabs(dx) > 1.4901161193847656e-08 * fmax(fabs(x[i]),
                                                       fabs(xn[i])))) {
            abar[i] += am[i];
            continue;
        }
        /* forward corners y_{i-1}, y_i; reverse corners z (coordinates
         * i+1..n new) and z with i new too */
        double dF, dR;
        for (size_t j = 0; j < n; j++)
            y[j] = j < i ? xn[j] : x[j];
        double v0 = T->potential(e->self, b, t, y);
        y[i] = xn[i];
        dF = T->potential(e->self, b, t, y) - v0;
        for (size_t j = 0; j < n; j++)
            y[j] = j > i ? xn[j] : x[j];
        v0 = T->potential(e->self, b, t, y);
        y[i] = xn[i];
        dR = T->potential(e->self, b, t, y) - v0;
        abar[i] -= 0.5 * (dF + dR) / dx * b->inv_m[i];
    }
    if (y != buf)
        free(y);
    return fail;
}

bf_status bf_effect_copy_params(void **self, const void *params, size_t size,
                                bf_err *err)
{
    void *p = malloc(size);
    if (!p)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    memcpy(p, params, size);
    *self = p;
    return BF_OK;
}

bf_status bf_balls_not_finite(const bf_balls *b, bf_err *err)
{
    for (size_t i = 0; i < b->n; i++)
        if (!isfinite(b->x[i]) || !isfinite(b->v[i]))
            return bf_fail(err, BF_EUNSTABLE,
                           "ball %zu: non-finite state (position %g cm, "
                           "velocity %g cm/s); the step is too large for "
                           "this integrator",
                           i + 1, b->x[i], b->v[i]);
    return bf_fail(err, BF_EUNSTABLE, "non-finite state");
}
