/* hermite.h: the cubic Hermite interpolant of one step, for locating
 * events between the end states of a step (return maps, the coupled
 * model's peaks, contact onsets and releases).  Private to the library.
 *
 * On theta in [0, 1] over a step of length dt, from value p0 and
 * derivative d0 (per unit time) at its start to p1, d1 at its end:
 *   p(theta) = h00 p0 + h10 dt d0 + h01 p1 + h11 dt d1,
 *   h00 = 2th^3 - 3th^2 + 1, h10 = th^3 - 2th^2 + th,
 *   h01 = -2th^3 + 3th^2,    h11 = th^3 - th^2.
 * Its derivative divided by dt is the quadratic
 *   q(theta) = 6 th (1 - th) D + (1 - th)(1 - 3th) d0 + th (3th - 2) d1,
 * D = (p1 - p0)/dt, with q(0) = d0 and q(1) = d1.  Third order: the error
 * in p is O(dt^4) for a smooth trajectory.  Derivatives per unit theta
 * are those per unit time with dt = 1. */
#ifndef BALLFILM_DIAG_HERMITE_H
#define BALLFILM_DIAG_HERMITE_H

static inline double bf_hermite(double th, double dt, double p0, double d0,
                                double p1, double d1)
{
    const double t2 = th * th, t3 = t2 * th;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + th) * dt * d0 +
           (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * dt * d1;
}

/* the interpolant's derivative over dt (per unit time), from the mean
 * slope D = (p1 - p0)/dt (formed once by a search along the step) */
static inline double bf_hermite_slope_mean(double th, double D, double d0,
                                           double d1)
{
    return 6 * th * (1 - th) * D + (1 - th) * (1 - 3 * th) * d0 +
           th * (3 * th - 2) * d1;
}

/* The zero of the slope q on [0, 1] where it turns from < 0 to >= 0 (q(0)
 * = d0 < 0 <= q(1) = d1), by bisection from [0, 1] until the ends are
 * adjacent doubles, at most 60 halvings: the midpoint of the last
 * bracket.  Two halvings per pass: the midpoints of both halves of the
 * current bracket are evaluated with its own (three independent
 * evaluations instead of two in a chain) and the second halving takes the
 * one of its half.  The same brackets, the same midpoints from the same
 * operands and the same tests as one halving at a time, so the same bits;
 * the chain of dependent evaluations is half as long. */
static inline double bf_hermite_slope_root(double D, double d0, double d1)
{
    double lo = 0.0, hi = 1.0;
    int k = 0; /* halvings made */
    while (k < 60) {
        const double m = 0.5 * (lo + hi);
        if (m == lo || m == hi)
            break;
        const double mL = 0.5 * (lo + m), mR = 0.5 * (m + hi);
        const int below = bf_hermite_slope_mean(m, D, d0, d1) < 0;
        const int belowL = bf_hermite_slope_mean(mL, D, d0, d1) < 0;
        const int belowR = bf_hermite_slope_mean(mR, D, d0, d1) < 0;
        const double lo1 = below ? m : lo, hi1 = below ? hi : m;
        /* the next midpoint, 0.5 (lo1 + hi1), is mR or mL */
        const double m2 = below ? mR : mL;
        lo = lo1;
        hi = hi1;
        if (++k == 60 || m2 == lo1 || m2 == hi1)
            break;
        const int below2 = below ? belowR : belowL;
        lo = below2 ? m2 : lo1;
        hi = below2 ? hi1 : m2;
        k++;
    }
    return 0.5 * (lo + hi);
}

#endif
