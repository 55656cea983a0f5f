/* damped.c: the damped and driven Hertz contacts of `floor` and `contact`
 * (docs/forces.md).  With deformation delta (cm) and its rate ddelta (cm/s)
 * the normal force (dyn, pushing the bodies apart) is
 *
 *   f = max(0, k delta^{3/2} + c delta^{1/4} ddelta
 *               + (3/2) A k delta^{1/2} ddelta),                       (1)
 *
 * the elastic Hertz force (Yasuda eq. 2.5), the restitution damping of
 * Tsuji et al. (1992), whose coefficient of restitution does not depend on
 * the impact speed, and the viscoelastic damping of Kuwabara & Kono (1987)
 * with the relaxation time A (s).  The maximum keeps the force from ever
 * pulling: the bodies part where f reaches 0, before delta does.
 *
 * Restitution: for the contact alone, M delta'' + c delta^{1/4} delta' +
 * k delta^{3/2} = 0, with M the mass of the deformation coordinate (m for
 * the floor, 2 mu = 2 m_i m_j / (m_i + m_j) for a pair: delta is half the
 * overlap).  Scaling delta by the maximal compression and t by delta/v0
 * leaves the one number alpha = c / sqrt(M k), so e = e(alpha) for every
 * impact speed.  Antypov & Elliott (2011) solved this oscillator in phase
 * space: the substitution delta ~ u^{4/5} turns it into a linear spring-
 * dashpot, giving
 *
 *   alpha = sqrt(5) (-ln e) / sqrt(pi^2 + ln^2 e),                      (2)
 *
 * which tests/test_contacts_damped.c checks against this code's own
 * integration of a bounce (e = 0.9 and 0.5 within 0.5 % from 1 to 100
 * cm/s).  Kuwabara-Kono: 1 - e grows as v0^{1/5} for small A.
 *
 * The driven floor: height h(t) = a sin(2 pi f t) (cm); a ball of radius R
 * at x touches it with delta = h + R - x, ddelta = h' - v, and its
 * potential (2/5) k delta^{5/2} depends on t.
 *
 * Power (erg/s): the damping part of (1) as applied, fd = f - k
 * delta^{3/2}, dissipates fd ddelta >= 0 (floor; twice that for a pair,
 * whose potential is 2 (2/5) k delta^{5/2}), and the driving injects f h'
 * (the floor's force times its velocity): the balls' energy E obeys
 * dE/dt = -D + J. */
#include <math.h>

#include "effect_kernels.h"

static const double PI = 3.14159265358979323846;

/* The restitution of the clipped law (1) for alpha, in the scaled
 * variables (M = k = 1, impact speed 1: the scaling of eq. 2 makes e
 * depend on alpha only): d'' = -(d^{3/2} + alpha d^{1/4} d'), d(0) = 0,
 * d'(0) = 1, by RK4 at h = 1e-4 until the force vanishes (or d does);
 * the leaving speed, interpolated linearly at that zero, is e.  The
 * force grows as s^{1/4} after the onset, which limits the scheme to
 * O(h^{5/4}) there: ~1e-5 in e, far below the 0.5 % the tests ask. */
static double restitution_of(double alpha)
{
    const double h = 1e-4;
    double d = 0.0, w = 1.0;
    for (long n = 0; n < 100000000L; n++) {
        double k[4][2], dd = d, ww = w;
        for (int j = 0; j < 4; j++) {
            const double c = j == 0 ? 0 : j == 3 ? 1 : 0.5;
            if (j) {
                dd = d + c * h * k[j - 1][0];
                ww = w + c * h * k[j - 1][1];
            }
            const double dp = dd > 0 ? dd : 0.0, s = sqrt(dp);
            k[j][0] = ww;
            k[j][1] = -(dp * s + alpha * sqrt(s) * ww);
        }
        const double d1 = d + h / 6 * (k[0][0] + 2 * k[1][0] + 2 * k[2][0] +
                                        k[3][0]),
                     w1 = w + h / 6 * (k[0][1] + 2 * k[1][1] + 2 * k[2][1] +
                                        k[3][1]);
        if (w1 < 0) {
            const double s0 = sqrt(d), s1 = d1 > 0 ? sqrt(d1) : 0.0;
            const double f0 = d * s0 + alpha * sqrt(s0) * w,
                         f1 = d1 > 0 ? d1 * s1 + alpha * sqrt(s1) * w1 : -1.0;
            if (f1 <= 0) {
                /* the zero of the force, or of d if that comes first */
                double th = f0 > 0 ? f0 / (f0 - f1) : 0.0;
                if (!(d1 > 0))
                    th = fmin(th, d / (d - d1));
                return -(w + th * (w1 - w));
            }
        }
        d = d1;
        w = w1;
    }
    return 0.0;
}

/* alpha of eq. (2) for e: Antypov and Elliott's exact solution of the
 * law without the clipping (the force may pull at the end). */
static double alpha_unclipped(double e)
{
    const double L = -log(e);
    return sqrt(5.0) * L / sqrt(PI * PI + L * L);
}

/* alpha for the clipped law (1): the clipping only removes the pull at
 * the end, so e(alpha) lies above eq. (2)'s e; the root of
 * restitution_of(alpha) = e is bracketed from alpha_unclipped(e) up and
 * found by regula falsi (Illinois) to 1e-10 in e (~15 integrations,
 * milliseconds, once per effect). */
double bf_damping_alpha(double e)
{
    if (!(e < 1))
        return 0.0;
    double lo = alpha_unclipped(e), flo = restitution_of(lo) - e;
    double hi = 2 * lo + 0.1, fhi = restitution_of(hi) - e;
    while (fhi > 0 && hi < 1e6) {
        lo = hi;
        flo = fhi;
        hi *= 2;
        fhi = restitution_of(hi) - e;
    }
    if (!(flo > 0))
        return lo;
    int kept = 0;
    for (int it = 0; it < 100 && fabs(hi - lo) > 1e-12 * hi; it++) {
        const double a = (lo * fhi - hi * flo) / (fhi - flo);
        const double f = restitution_of(a) - e;
        if (fabs(f) < 1e-10)
            return a;
        if (f > 0) {
            lo = a;
            flo = f;
            if (kept == 1)
                fhi *= 0.5;
            kept = 1;
        } else {
            hi = a;
            fhi = f;
            if (kept == -1)
                flo *= 0.5;
            kept = -1;
        }
    }
    return 0.5 * (lo + hi);
}

void bf_floor_height(const bf_floor *p, double t, double *h, double *hdot)
{
    if (!(p->amplitude > 0)) {
        *h = *hdot = 0.0;
        return;
    }
    const double w = 2 * PI * p->frequency; /* 1/s */
    *h = p->amplitude * sin(w * t);
    *hdot = p->amplitude * w * cos(w * t);
}

unsigned bf_contact_law(double e, double A, double amplitude)
{
    return (e < 1 || A > 0 ? BF_LAW_DAMPED : 0u) |
           (amplitude > 0 ? BF_LAW_DRIVEN : 0u);
}

/* eq. (1) without the maximum: elastic part *fe and the sum (dyn) */
static double unclipped_force(double k, double alpha, double A, double M,
                              double delta, double ddelta, double *fe)
{
    const double s = sqrt(delta);
    *fe = k * delta * s;
    double f = *fe;
    if (alpha > 0)
        f += alpha * sqrt(M * k) * sqrt(s) * ddelta;
    if (A > 0)
        f += 1.5 * A * k * s * ddelta;
    return f;
}

/* eq. (1) as applied on the branch br (bf_floor.branch): the maximum, f
 * itself, or 0 */
static double applied_force(double f, signed char br)
{
    if (br == BF_BRANCH_PUSH)
        return f;
    if (br == BF_BRANCH_FREE)
        return 0.0;
    return f > 0 ? f : 0.0;
}

void bf_floor_accel_general(const bf_floor *p, const bf_balls *b, double t,
                            const double *x, const double *v, double *acc,
                            bf_power *pw)
{
    double h, hd, fe;
    bf_floor_height(p, t, &h, &hd);
    for (size_t i = 0; i < b->n; i++) {
        const double delta = h + b->R[i] - x[i];
        if (!(delta > 0))
            continue;
        const double dd = hd - v[i];
        const double f = applied_force(
            unclipped_force(p->k, p->alpha, p->A, b->m[i], delta, dd, &fe),
            p->branch ? p->branch[i] : BF_BRANCH_CLIP);
        acc[i] += f * b->inv_m[i];
        if (pw) {
            pw->diss += (f - fe) * dd;
            pw->inj += f * hd;
        }
    }
}

static double pair_mass(const bf_balls *b, size_t i)
{
    return 2 * b->m[i] * b->m[i + 1] / (b->m[i] + b->m[i + 1]);
}

void bf_contact_accel_general(const bf_contact *p, const bf_balls *b,
                              const double *x, const double *v, double *acc,
                              bf_power *pw)
{
    double fe;
    for (size_t i = 0; i + 1 < b->n; i++) {
        const double delta = 0.5 * (b->R[i] + b->R[i + 1] - (x[i + 1] - x[i]));
        if (!(delta > 0))
            continue;
        const double dd = -0.5 * (v[i + 1] - v[i]);
        const double f = applied_force(
            unclipped_force(p->k, p->alpha, p->A, pair_mass(b, i), delta, dd,
                            &fe),
            p->branch ? p->branch[i] : BF_BRANCH_CLIP);
        acc[i] -= f * b->inv_m[i];
        acc[i + 1] += f * b->inv_m[i + 1];
        if (pw)
            pw->diss += 2 * (f - fe) * dd;
    }
}

double bf_floor_unclipped(const bf_floor *p, const bf_balls *b, double h,
                          double hdot, size_t i, const double *x,
                          const double *v, double *scale)
{
    double fe;
    const double delta = h + b->R[i] - x[i];
    if (!(delta > 0)) {
        *scale = 0.0;
        return 0.0;
    }
    const double f = unclipped_force(p->k, p->alpha, p->A, b->m[i], delta,
                                     hdot - v[i], &fe);
    *scale = fe + fabs(f - fe);
    return f;
}

double bf_contact_unclipped(const bf_contact *p, const bf_balls *b, size_t i,
                            const double *x, const double *v, double *scale)
{
    double fe;
    const double delta = 0.5 * (b->R[i] + b->R[i + 1] - (x[i + 1] - x[i]));
    if (!(delta > 0)) {
        *scale = 0.0;
        return 0.0;
    }
    const double f = unclipped_force(p->k, p->alpha, p->A, pair_mass(b, i),
                                     delta, -0.5 * (v[i + 1] - v[i]), &fe);
    *scale = fe + fabs(f - fe);
    return f;
}

double bf_floor_potential_general(const bf_floor *p, const bf_balls *b,
                                  double t, const double *x)
{
    double h, hd, u = 0.0;
    bf_floor_height(p, t, &h, &hd);
    for (size_t i = 0; i < b->n; i++)
        u += bf_hertz_energy(p->k, h + b->R[i] - x[i]);
    return u;
}

unsigned bf_effect_flags(const bf_effect *e)
{
    unsigned f = e->type->flags, law = 0;
    switch (bf_effect_kernel_of(e->type)) {
    case BF_KERNEL_FLOOR:
        law = ((const bf_floor *)e->self)->law;
        break;
    case BF_KERNEL_CONTACT:
        law = ((const bf_contact *)e->self)->law;
        break;
    default:
        break;
    }
    if (law & BF_LAW_DAMPED)
        f = (f | BF_EFFECT_VELOCITY) & ~(unsigned)BF_EFFECT_CONSERVATIVE;
    if (law & BF_LAW_DRIVEN)
        f = (f | BF_EFFECT_TIME) & ~(unsigned)BF_EFFECT_CONSERVATIVE;
    return f;
}
