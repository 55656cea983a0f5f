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

#include <math.h>

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

/* Bisection of the slope q for its zero where it turns from < 0 to >= 0,
 * from the bracket [lo, hi] after k halvings, until the ends are adjacent
 * doubles or 60 halvings have been made: the midpoint of the last bracket.
 * Two halvings per pass: the midpoints of both halves of the current
 * bracket are evaluated with its own (three independent evaluations
 * instead of two in a chain) and the second halving takes the one of its
 * half.  The same brackets, the same midpoints from the same operands and
 * the same tests as one halving at a time, so the same bits; the chain of
 * dependent evaluations is half as long. */
static inline double bf_hermite_slope_bisect(double D, double d0, double d1,
                                             double lo, double hi, int k)
{
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

/* The bracket the bisection from [0, 1] reaches after K halvings, found
 * without making them, when that can be proved (else *k stays 0 and
 * [0, 1] is left alone).  The proof:
 *  - q(th) = A th^2 + B th + d0 with B = q'(0) = 6D - 4d0 - 2d1 and
 *    q'(1) = -6D + 2d0 + 4d1.  Both are computed with an error below
 *    12u S (u = 2^-53, S = 1.5|D| + |d0| + |d1|) < E/2, E = 2^-48 S; when
 *    both exceed E, q' > 0 on [0, 1] (q' is linear): q increases there.
 *  - The computed q(th) (bf_hermite_slope_mean, every th in [0, 1]) is
 *    within about 10.2u S of the exact one (the rounding of its nine
 *    operations, each term bounded by 1.5|D|, |d0|, |d1| on [0, 1]), so
 *    within E.
 *  - The candidate bracket [lo, hi] = [j, j + 1] 2^-K around the zero of
 *    the quadratic is checked: computed q(lo) < -2E and q(hi) >= 2E (lo =
 *    0 and hi = 1 need no check).  Then the exact q is < -E at and left
 *    of lo and > E at and right of hi, so every computed q there has the
 *    sign of the exact one: each of the bisection's first K midpoints (a
 *    multiple of 2^-K, never inside (lo, hi)) is tested as the bracket
 *    [lo, hi] requires, and no bracket of width 2^-K or more has adjacent
 *    ends.  The bisection from [lo, hi] after K halvings is the same.
 * S outside [2^-900, 2^900] (no underflow or overflow of the bounds): no
 * shortcut.  The zero and the width of the bracket are estimates only: a
 * poor one fails the check or gives a small K, never another result. */
static inline void bf_hermite_slope_skip(double D, double d0, double d1,
                                         double *lo, double *hi, int *k)
{
    const double S = 1.5 * fabs(D) + fabs(d0) + fabs(d1);
    if (!(S >= 0x1p-900 && S <= 0x1p900))
        return;
    const double E = 0x1p-48 * S;
    const double B = 6 * D - 4 * d0 - 2 * d1, G1 = -6 * D + 2 * d0 + 4 * d1;
    if (!(B > E && G1 > E))
        return;
    /* the zero of the quadratic, without cancellation (B > 0, d0 < 0) */
    const double A = 0.5 * (G1 - B), disc = B * B - 4 * A * d0;
    if (!(disc >= 0))
        return;
    const double r = -2 * d0 / (B + sqrt(disc));
    /* q rises by at least (min q' - E) per unit theta: out of the noise
     * 4E / that from the zero (and a few ulps for the zero's rounding) */
    const double w = 4 * E / ((B < G1 ? B : G1) - E) + 0x1p-50;
    double a = r - w, b = r + w;
    if (!(a > 0))
        a = 0;
    if (!(b < 1))
        b = 1 - 0x1p-52;
    if (!(a <= b))
        return;
    /* K: the common leading bits of a and b (52 after the point) */
    const unsigned long long ia = (unsigned long long)(a * 0x1p52),
                             ib = (unsigned long long)(b * 0x1p52),
                             x = ia ^ ib;
#if defined(__GNUC__)
    int K = x ? __builtin_clzll(x) - 12 : 52;
#else
    int K = 0;
    while (K < 52 && !(x >> (51 - K) & 1))
        K++;
#endif
    if (K > 48)
        K = 48;
    if (K < 8)
        return;
    const unsigned long long j = ia >> (52 - K);
    const double l = (double)(j << (52 - K)) * 0x1p-52,
                 h = (double)((j + 1) << (52 - K)) * 0x1p-52;
    if (l > 0 && !(bf_hermite_slope_mean(l, D, d0, d1) < -2 * E))
        return;
    if (h < 1 && !(bf_hermite_slope_mean(h, D, d0, d1) >= 2 * E))
        return;
    *lo = l;
    *hi = h;
    *k = K;
}

/* The zero of the slope q on [0, 1] where it turns from < 0 to >= 0 (q(0)
 * = d0 < 0 <= q(1) = d1), by bisection from [0, 1] until the ends are
 * adjacent doubles, at most 60 halvings: the midpoint of the last
 * bracket.  Most of the halvings are skipped where the bracket they reach
 * can be proved (bf_hermite_slope_skip): the same bits. */
static inline double bf_hermite_slope_root(double D, double d0, double d1)
{
    double lo = 0.0, hi = 1.0;
    int k = 0;
    bf_hermite_slope_skip(D, d0, d1, &lo, &hi, &k);
    return bf_hermite_slope_bisect(D, d0, d1, lo, hi, k);
}

#endif
