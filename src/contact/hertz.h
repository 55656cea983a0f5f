/* hertz.h: the Hertz contact law, shared by ball-floor, ball-ball and
 * particle contacts (private to the library: the kernels are inline).
 *
 * Yasuda eqs 2.5-2.6 (and 3.13-3.14): the force is f = k x^{3/2} where x is
 * the deformation of *one* ball.
 *   floor:       x = max(R - z, 0)                   (z: centre height)
 *   ball pair:   x = max((R_i + R_j - d)/2, 0)       (d: centre distance)
 * For equal radii the pair rule is the paper's x = max(R - d/2, 0).
 *
 * Energies.  The paper's eq. 2.8 writes (2/5) k x^{5/2} for every contact.
 * For the floor this is exact: dE/dz = -k x^{3/2}.  For a pair, x moves by
 * half of the change of d, so -dE/dd = f needs E = (4/5) k x^{5/2}: twice
 * the paper's value.  We use the consistent potentials; the test suite checks
 * both against finite differences (tests/test_contact.c).
 *
 * Units (CGS): k in g cm^{-1/2} s^{-2}, lengths in cm, force in dyn,
 * energy in erg.
 */
#ifndef BALLFILM_CONTACT_HERTZ_H
#define BALLFILM_CONTACT_HERTZ_H

#include <math.h>

/* k x^{3/2} for x > 0, else 0 */
static inline double bf_hertz_force(double k, double x)
{
    return x > 0 ? k * x * sqrt(x) : 0.0;
}

/* (2/5) k x^{5/2} for x > 0, else 0: the antiderivative of bf_hertz_force */
static inline double bf_hertz_energy(double k, double x)
{
    return x > 0 ? 0.4 * k * x * x * sqrt(x) : 0.0;
}

/* The divided difference of bf_hertz_energy,
 *   (E(a) - E(b)) / (a - b),   E(x) = (2/5) k max(x, 0)^{5/2},
 * for the discrete gradients of energy-conserving steps (Greenspan 1973:
 * a pair force -(phi(r+) - phi(r))/(r+ - r); src/integrators/
 * greenspan73.c).  Formed without cancellation: with s = sqrt(a),
 * u = sqrt(b) (a, b > 0),
 *   a^{5/2} - b^{5/2} = (s - u)(s^4 + s^3 u + s^2 u^2 + s u^3 + u^4),
 *   a - b = (s - u)(s + u),
 * so the quotient is (2/5) k (s^4 + s^3 u + s^2 u^2 + s u^3 + u^4)/(s + u),
 * accurate to a few ulps for any a, b, and at a = b it is the force
 * k a^{3/2} itself (no guard for a tiny increment is needed).  When only
 * a > 0 the quotient is E(a)/(a - b) with a - b >= a (no cancellation);
 * when neither is positive it is 0.  The arguments are sorted first, so
 * the result is bitwise symmetric in (a, b): a step built on it is
 * time-symmetric to the last bit.  Units: dyn. */
static inline double bf_hertz_energy_dd(double k, double a, double b)
{
    const double hi = a > b ? a : b, lo = a > b ? b : a;
    if (!(hi > 0))
        return 0.0;
    if (!(lo > 0))
        return bf_hertz_energy(k, hi) / (hi - lo);
    const double s = sqrt(hi), u = sqrt(lo);
    const double s2 = s * s, u2 = u * u;
    return 0.4 * k * (s2 * s2 + s2 * s * u + s2 * u2 + s * u2 * u + u2 * u2) /
           (s + u);
}

/* Upward force of the floor on a ball of radius R centred at height z. */
static inline double bf_hertz_floor_force(double k, double R, double z)
{
    return bf_hertz_force(k, R - z);
}

static inline double bf_hertz_floor_energy(double k, double R, double z)
{
    return bf_hertz_energy(k, R - z);
}

/* Repulsive force between two balls whose centres are a distance d apart
 * (acts along the line of centres, pushing them apart). */
static inline double bf_hertz_pair_force(double k, double Ri, double Rj,
                                         double d)
{
    return bf_hertz_force(k, 0.5 * (Ri + Rj - d));
}

/* Its potential: (4/5) k x^{5/2} (see above for why not 2/5). */
static inline double bf_hertz_pair_energy(double k, double Ri, double Rj,
                                          double d)
{
    return 2.0 * bf_hertz_energy(k, 0.5 * (Ri + Rj - d));
}

#endif
