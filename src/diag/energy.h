/* energy.h: the energy diagnostic every model's summary and output use:
 * the relative change of a conserved quantity against its start and the
 * largest seen (private to the library).
 *
 *   relative change   (E - E0)/|E0|      (E - E0 when E0 = 0)
 *   relative error    |E - E0|/|E0|      (the same in absolute value)
 *
 * The two are the same number up to the sign, bit for bit (IEEE division
 * rounds the magnitude independently of the signs).  A NaN or infinite
 * energy counts as an infinite error, so a blown-up state is never
 * mistaken for a small one. */
#ifndef BALLFILM_DIAG_ENERGY_H
#define BALLFILM_DIAG_ENERGY_H

#include <math.h>

/* (x - x0)/|x0|, or x - x0 when x0 = 0 */
static inline double bf_rel_change(double x, double x0)
{
    return x0 != 0.0 ? (x - x0) / fabs(x0) : x - x0;
}

/* |x - x0|/|x0|, or |x - x0| when x0 = 0 */
static inline double bf_rel_error(double x, double x0)
{
    return x0 != 0.0 ? fabs(x - x0) / fabs(x0) : fabs(x - x0);
}

/* The divisor of bf_rel_error for a fixed x0, formed once: |x0|, or 1
 * when x0 = 0 (|x - x0|/1 is |x - x0| exactly), so that
 * fabs(x - x0) / bf_rel_divisor(x0) is bf_rel_error(x, x0) to the bit
 * without a test of x0 at each use. */
static inline double bf_rel_divisor(double x0)
{
    return x0 != 0.0 ? fabs(x0) : 1.0;
}

typedef struct bf_energy_diag {
    double e0;       /* energy at the start, erg */
    double last_rel; /* relative error at the last check */
    double max_rel;  /* largest relative error seen (inf after a NaN) */
} bf_energy_diag;

static inline void bf_energy_start(bf_energy_diag *d, double e0)
{
    d->e0 = e0;
    d->last_rel = 0.0;
    d->max_rel = 0.0;
}

/* Check the energy e: the relative error now (the maximum is updated). */
static inline double bf_energy_check(bf_energy_diag *d, double e)
{
    double rel = bf_rel_error(e, d->e0);
    if (!(rel <= d->max_rel)) /* also catches NaN */
        d->max_rel = isnan(rel) ? INFINITY : rel;
    d->last_rel = rel;
    return rel;
}

#endif
