/* effects.c: summing the accelerations and potentials of a scene's effects
 * (the accelerations through the dispatch point of effect_kernels.h). */
#include "ballfilm/effect_kernels.h"
#include "ballfilm/effects.h"

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
