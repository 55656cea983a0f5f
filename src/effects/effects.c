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
                     const double *x, double *acc)
{
    return bf_effects_accel_inline(e, ne, b, t, x, acc);
}

double bf_effects_potential(const bf_effect *e, size_t ne, const bf_balls *b,
                            double t, const double *x)
{
    return bf_effects_potential_inline(e, ne, b, t, x);
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
