/* effect_kernels.h: the force kernels of the built-in ball effects, inline,
 * and the one dispatch point that sums them.
 *
 * Why inline: the two-ball problem evaluates forces 3*10^7 times per 1000 s
 * run and each evaluation is a few flops.  Calling each effect through a
 * pointer cost four times a hand-fused loop (bench/bench_balls.c); a switch
 * over the effect kind with inlined kernels keeps the effects composable
 * (a scene lists them; absent effects cost nothing) at close to fused speed.
 * Each effect's .c file uses the same kernel for its `accel` pointer, so
 * there is one definition of every force.  Private to the library.
 *
 * The parameter struct of each built-in effect is its kernel's struct
 * (the section's keys are its members).
 *
 * A built-in effect is recognised by the address of its descriptor
 * (bf_effect_kernel_of): the public descriptor names no kernel, and an
 * effect defined outside the library is called through its `accel`.  The
 * inline kernels below are forces of the positions only (a = a(x)); they
 * ignore t and v, but for drag's (of v).  A damped or driven floor or
 * contact (`law` not 0) goes to its general kernel in damped.c instead,
 * which reads t and v.
 */
#ifndef BALLFILM_EFFECT_KERNELS_H
#define BALLFILM_EFFECT_KERNELS_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/effect.h"
#include "contact/hertz.h"

/* Forced inlining: the dispatch point is called three times per MV2M step;
 * left to itself GCC keeps one out-of-line copy (with a memset call for
 * the zeroing loop) and the specialised steps of ballsys.c lose most of
 * their gain. */
#if defined(__GNUC__)
#define BF_EFFECT_INLINE static inline __attribute__((always_inline))
#else
#define BF_EFFECT_INLINE static inline
#endif
/* Loops over the balls: unrolled when n is known at compile time (the
 * specialised steps of ballsys.c), harmless otherwise. */
#if defined(__GNUC__) && !defined(__clang__)
#define BF_UNROLL _Pragma("GCC unroll 4")
#else
#define BF_UNROLL
#endif

/* The built-in effects whose forces are inlined below. */
typedef enum bf_effect_kernel {
    BF_KERNEL_NONE = 0, /* called through its accel */
    BF_KERNEL_GRAVITY,
    BF_KERNEL_FLOOR,
    BF_KERNEL_CONTACT,
    BF_KERNEL_SPRING,
    BF_KERNEL_DRAG
} bf_effect_kernel;

extern const bf_effect_type bf_effect_gravity;
extern const bf_effect_type bf_effect_floor;
extern const bf_effect_type bf_effect_contact;
extern const bf_effect_type bf_effect_spring;
extern const bf_effect_type bf_effect_drag;

/* the kernel of an effect, by its descriptor's address */
BF_EFFECT_INLINE bf_effect_kernel bf_effect_kernel_of(const bf_effect_type *t)
{
    if (t == &bf_effect_gravity)
        return BF_KERNEL_GRAVITY;
    if (t == &bf_effect_floor)
        return BF_KERNEL_FLOOR;
    if (t == &bf_effect_contact)
        return BF_KERNEL_CONTACT;
    if (t == &bf_effect_spring)
        return BF_KERNEL_SPRING;
    if (t == &bf_effect_drag)
        return BF_KERNEL_DRAG;
    return BF_KERNEL_NONE;
}

typedef struct bf_gravity {
    double g; /* cm/s^2, pulls towards x = -inf ([gravity] g) */
} bf_gravity;

/* The damped, driven contacts (src/effects/damped.c, docs/forces.md):
 * restitution e and viscosity A of a Hertz contact, and the floor's
 * driving.  `law` (bf_contact_law, set at creation) says which of them is
 * active; when it is not 0 the kernels below are bypassed for
 * bf_floor_accel_general / bf_contact_accel_general, so that elastic
 * scenes take exactly the elastic path. */
enum {
    BF_LAW_DAMPED = 1u << 0, /* restitution < 1 or viscosity > 0 */
    BF_LAW_DRIVEN = 1u << 1  /* the floor moves */
};
/* The law of a contact with restitution e, viscosity A (s) and driving
 * amplitude (cm): the one place that says when a contact is damped or
 * driven (the kernels' choice, the effect's flags, the events). */
unsigned bf_contact_law(double e, double A, double amplitude);

/* Which branch of the clipped force max(0, f) a damped contact takes
 * (bf_floor.branch, bf_contact.branch: one per ball, one per pair):
 * BF_BRANCH_CLIP the maximum itself; BF_BRANCH_PUSH f as it is (also
 * where it has turned negative) and BF_BRANCH_FREE 0 while the bodies
 * overlap: what the event splitting sets for a whole substep, so that
 * each substep integrates one smooth force (ballsys.c, "Releases"). */
enum { BF_BRANCH_FREE = -1, BF_BRANCH_CLIP = 0, BF_BRANCH_PUSH = 1 };

typedef struct bf_floor {
    double k;         /* Hertz constant, g cm^-1/2 s^-2 */
    double e;         /* coefficient of restitution, 1 */
    double A;         /* Kuwabara-Kono viscosity, s */
    double amplitude; /* floor height A_f sin(2 pi f t), cm */
    double frequency; /* f, Hz */
    double alpha;     /* damping of e, 1: c = alpha sqrt(m k) (derived) */
    unsigned law;     /* bf_contact_law (derived) */
    const signed char *branch; /* per ball, or NULL: clip (set by the
                                  event splitting of the ball system) */
} bf_floor;

typedef struct bf_contact {
    double k;     /* Hertz constant, g cm^-1/2 s^-2 */
    double e;     /* coefficient of restitution, 1 */
    double A;     /* Kuwabara-Kono viscosity, s */
    double alpha; /* derived, as bf_floor's */
    unsigned law; /* bf_contact_law (derived) */
    const signed char *branch; /* per pair, or NULL: clip */
} bf_contact;

/* The powers (erg/s) of the non-conservative forces, summed by the
 * kernels that take one (NULL: not wanted): dissipated (>= 0) and
 * injected by the driven floor; scratch: n doubles for an effect called
 * through its accel. */
typedef struct bf_power {
    double diss, inj;
    double *scratch;
} bf_power;

/* the general kernels (damped.c); t in s, v in cm/s; the powers of the
 * applied forces added to *pw when not NULL */
void bf_floor_accel_general(const bf_floor *p, const bf_balls *b, double t,
                            const double *x, const double *v, double *acc,
                            bf_power *pw);
void bf_contact_accel_general(const bf_contact *p, const bf_balls *b,
                              const double *x, const double *v, double *acc,
                              bf_power *pw);
/* The floor's height (cm) and its rate (cm/s) at t (s). */
void bf_floor_height(const bf_floor *p, double t, double *h, double *hdot);
/* The damped force before the clipping (dyn, eq. 1 of damped.c without
 * the maximum) of the floor on ball i, with the floor at height h moving
 * at hdot, and of pair i; 0 where the bodies do not overlap.  *scale: the
 * sum of the magnitudes of its terms (its round-off is a few ulps of
 * that).  Its zero inside a contact is the release (ballsys.c). */
double bf_floor_unclipped(const bf_floor *p, const bf_balls *b, double h,
                          double hdot, size_t i, const double *x,
                          const double *v, double *scale);
double bf_contact_unclipped(const bf_contact *p, const bf_balls *b, size_t i,
                            const double *x, const double *v, double *scale);
/* alpha of restitution e (0 < e <= 1; 0 at e = 1) */
double bf_damping_alpha(double e);
/* An effect's flags for its parameters (a damped contact is velocity-
 * dependent and not conservative, a driven floor time-dependent): the
 * descriptor's flags otherwise. */
unsigned bf_effect_flags(const bf_effect *e);

/* the keys of [drag] (drag.c) */
typedef struct bf_drag {
    double gamma; /* 1/s */
    double c;     /* 1/cm */
} bf_drag;

typedef struct bf_spring {
    double s;    /* stiffness, g/s^2 */
    double rest; /* cm */
} bf_spring;

BF_EFFECT_INLINE void bf_gravity_accel(const bf_gravity *p, const bf_balls *b,
                                    const double *x, double *acc)
{
    (void)x;
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        acc[i] -= p->g;
}

BF_EFFECT_INLINE void bf_floor_accel(const bf_floor *p, const bf_balls *b,
                                  const double *x, double *acc)
{
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        if (x[i] < b->R[i])
            acc[i] += bf_hertz_floor_force(p->k, b->R[i], x[i]) * b->inv_m[i];
}

BF_EFFECT_INLINE void bf_contact_accel(const bf_contact *p, const bf_balls *b,
                                    const double *x, double *acc)
{
    BF_UNROLL
    for (size_t i = 0; i + 1 < b->n; i++) {
        double d = x[i + 1] - x[i];
        if (d < b->R[i] + b->R[i + 1]) {
            double f = bf_hertz_pair_force(p->k, b->R[i], b->R[i + 1], d);
            acc[i] -= f * b->inv_m[i];
            acc[i + 1] += f * b->inv_m[i + 1];
        }
    }
}

BF_EFFECT_INLINE void bf_spring_accel(const bf_spring *p, const bf_balls *b,
                                   const double *x, double *acc)
{
    for (size_t i = 0; i < b->n; i++)
        acc[i] -= p->s * (x[i] - p->rest) * b->inv_m[i];
}

/* drag: a_i = -(gamma + c |v_i|) v_i; it dissipates m_i a_i v_i >= 0 */
BF_EFFECT_INLINE void bf_drag_accel(const bf_drag *p, const bf_balls *b,
                                    const double *v, double *acc,
                                    bf_power *pw)
{
    for (size_t i = 0; i < b->n; i++) {
        const double a = (p->gamma + p->c * fabs(v[i])) * v[i];
        acc[i] -= a;
        if (pw)
            pw->diss += b->m[i] * a * v[i];
    }
}

/* ---- potential energies (erg), the exact antiderivatives of the forces
 * above: the energy check of a long run evaluates them every step, so they
 * are inline too (one definition each; the effects' .c files use them). */

BF_EFFECT_INLINE double bf_gravity_potential(const bf_gravity *p,
                                             const bf_balls *b,
                                             const double *x)
{
    double u = 0.0;
    for (size_t i = 0; i < b->n; i++)
        u += b->m[i] * p->g * x[i];
    return u;
}

BF_EFFECT_INLINE double bf_floor_potential(const bf_floor *p, const bf_balls *b,
                                           const double *x)
{
    double u = 0.0;
    for (size_t i = 0; i < b->n; i++)
        if (x[i] < b->R[i])
            u += bf_hertz_floor_energy(p->k, b->R[i], x[i]);
    return u;
}

/* the floor's potential with its height h(t): (2/5) k delta^{5/2},
 * delta = h(t) + R - x (damping has none) */
double bf_floor_potential_general(const bf_floor *p, const bf_balls *b,
                                  double t, const double *x);

BF_EFFECT_INLINE double bf_contact_potential(const bf_contact *p,
                                             const bf_balls *b,
                                             const double *x)
{
    double u = 0.0;
    for (size_t i = 0; i + 1 < b->n; i++)
        if (x[i + 1] - x[i] < b->R[i] + b->R[i + 1])
            u += bf_hertz_pair_energy(p->k, b->R[i], b->R[i + 1],
                                      x[i + 1] - x[i]);
    return u;
}

BF_EFFECT_INLINE double bf_spring_potential(const bf_spring *p,
                                            const bf_balls *b, const double *x)
{
    double u = 0.0;
    for (size_t i = 0; i < b->n; i++)
        u += 0.5 * p->s * (x[i] - p->rest) * (x[i] - p->rest);
    return u;
}

/* ---- discrete gradients (integrator.h, bf_daccel_fn): abar(x, xn) =
 * -Dbar V(x, xn)/m per effect, exact discrete gradients of the
 * potentials above, so that sum_i m_i abar_i (xn_i - x_i) is
 * -(V(xn) - V(x)) to round-off and abar(x, x) is the acceleration.  Each
 * is symmetric in (x, xn).  Greenspan's pair form: for a term phi(r) of
 * one variable r (a deformation, a gap), Dbar = (phi(r') - phi(r))/(r' -
 * r), formed by bf_hertz_energy_dd without cancellation. */

/* gravity: linear, its gradient is its discrete gradient */
BF_EFFECT_INLINE void bf_gravity_daccel(const bf_gravity *p, const bf_balls *b,
                                        double *abar)
{
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        abar[i] -= p->g;
}

/* floor: V = E(R - z); Dbar = (E(R - z') - E(R - z))/(z' - z) = -dd */
BF_EFFECT_INLINE void bf_floor_daccel(const bf_floor *p, const bf_balls *b,
                                      const double *x, const double *xn,
                                      double *abar)
{
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        if (x[i] < b->R[i] || xn[i] < b->R[i])
            abar[i] += bf_hertz_energy_dd(p->k, b->R[i] - x[i],
                                          b->R[i] - xn[i]) *
                       b->inv_m[i];
}

/* pair: V = 2 E(delta), delta = (R_i + R_j - r)/2, r = x_j - x_i:
 * dV/dr = -E'(delta), so the pair pushes apart with dd(delta, delta') */
BF_EFFECT_INLINE void bf_contact_daccel(const bf_contact *p, const bf_balls *b,
                                        const double *x, const double *xn,
                                        double *abar)
{
    BF_UNROLL
    for (size_t i = 0; i + 1 < b->n; i++) {
        const double s = b->R[i] + b->R[i + 1];
        const double d = x[i + 1] - x[i], dn = xn[i + 1] - xn[i];
        if (d < s || dn < s) {
            double f = bf_hertz_energy_dd(p->k, 0.5 * (s - d), 0.5 * (s - dn));
            abar[i] -= f * b->inv_m[i];
            abar[i + 1] += f * b->inv_m[i + 1];
        }
    }
}

/* spring: quadratic, the discrete gradient is the gradient at the mid-point */
BF_EFFECT_INLINE void bf_spring_daccel(const bf_spring *p, const bf_balls *b,
                                       const double *x, const double *xn,
                                       double *abar)
{
    for (size_t i = 0; i < b->n; i++)
        abar[i] -= p->s * (0.5 * (x[i] + xn[i]) - p->rest) * b->inv_m[i];
}

/* Any other effect: the symmetrised coordinate-increment (Itoh-Abe)
 * discrete gradient of its potential (effects.c); through its force at the
 * mid-point if it has no potential (with the velocities b->v: only
 * integrators for a = a(x) use discrete gradients). */
int bf_effect_daccel_generic(const bf_effect *e, const bf_balls *b, double t,
                             const double *x, const double *xn, double *abar);

/* abar = the sum over the effects (zeroed first); non-zero on failure */
BF_EFFECT_INLINE int bf_effects_daccel_inline(const bf_effect *e, size_t ne,
                                              const bf_balls *b, double t,
                                              const double *x,
                                              const double *xn, double *abar)
{
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        abar[i] = 0.0;
    for (size_t k = 0; k < ne; k++) {
        switch (bf_effect_kernel_of(e[k].type)) {
        case BF_KERNEL_GRAVITY:
            bf_gravity_daccel(e[k].self, b, abar);
            break;
        case BF_KERNEL_FLOOR:
            /* elastic and fixed: the only integrator that steps with
             * these, greenspan73 (BF_INT_POTENTIAL), refuses a damped
             * floor (a force of v) and a driven one (of t) at set-up
             * (ballsys.c, check_velocity_forces) */
            bf_floor_daccel(e[k].self, b, x, xn, abar);
            break;
        case BF_KERNEL_CONTACT:
            bf_contact_daccel(e[k].self, b, x, xn, abar);
            break;
        case BF_KERNEL_SPRING:
            bf_spring_daccel(e[k].self, b, x, xn, abar);
            break;
        default:
            if (bf_effect_daccel_generic(&e[k], b, t, x, xn, abar))
                return 1;
        }
    }
    return 0;
}

/* The accel and potential functions of an effect descriptor for a kernel
 * above: bf_NAME_accel and bf_NAME_potential behind the generic
 * signatures (the effect's .c file instantiates them once). */
#define BF_EFFECT_KERNEL_WRAPPERS(NAME)                                        \
    static int NAME##_accel(const void *self, const bf_balls *b, double t,     \
                            const double *x, const double *v, double *acc)     \
    {                                                                          \
        (void)t;                                                               \
        (void)v;                                                               \
        bf_##NAME##_accel(self, b, x, acc);                                    \
        return 0;                                                              \
    }                                                                          \
    static double NAME##_potential(const void *self, const bf_balls *b,        \
                                   double t, const double *x)                  \
    {                                                                          \
        (void)t;                                                               \
        return bf_##NAME##_potential(self, b, x);                              \
    }

/* An effect whose state is a copy of its parameter struct (size bytes):
 * what the built-in kernels' create functions do. */
bf_status bf_effect_copy_params(void **self, const void *params, size_t size,
                                bf_err *err);

/* sum of the effects' potentials at x */
BF_EFFECT_INLINE double bf_effects_potential_inline(const bf_effect *e,
                                                    size_t ne,
                                                    const bf_balls *b,
                                                    double t, const double *x)
{
    double u = 0.0;
    for (size_t k = 0; k < ne; k++) {
        switch (bf_effect_kernel_of(e[k].type)) {
        case BF_KERNEL_GRAVITY:
            u += bf_gravity_potential(e[k].self, b, x);
            break;
        case BF_KERNEL_FLOOR:
            if (((const bf_floor *)e[k].self)->law)
                u += bf_floor_potential_general(e[k].self, b, t, x);
            else
                u += bf_floor_potential(e[k].self, b, x);
            break;
        case BF_KERNEL_CONTACT:
            u += bf_contact_potential(e[k].self, b, x);
            break;
        case BF_KERNEL_SPRING:
            u += bf_spring_potential(e[k].self, b, x);
            break;
        default:
            if (e[k].type->potential)
                u += e[k].type->potential(e[k].self, b, t, x);
        }
    }
    return u;
}

/* acc = sum over the effects at (t, x, v); with pw (NULL: none), also the
 * powers of the non-conservative forces, from the same evaluation of each
 * force (an effect outside the library without a potential that is not
 * conservative dissipates -sum_i m_i a_i v_i: it adds its acceleration to
 * pw->scratch, then to acc).  Returns non-zero if an effect fails. */
BF_EFFECT_INLINE int bf_effects_accel_inline(const bf_effect *e, size_t ne,
                                          const bf_balls *b, double t,
                                          const double *x, const double *v,
                                          double *acc, bf_power *pw)
{
    BF_UNROLL
    for (size_t i = 0; i < b->n; i++)
        acc[i] = 0.0;
    for (size_t k = 0; k < ne; k++) {
        switch (bf_effect_kernel_of(e[k].type)) {
        case BF_KERNEL_GRAVITY:
            bf_gravity_accel(e[k].self, b, x, acc);
            break;
        case BF_KERNEL_FLOOR:
            if (((const bf_floor *)e[k].self)->law)
                bf_floor_accel_general(e[k].self, b, t, x, v, acc, pw);
            else
                bf_floor_accel(e[k].self, b, x, acc);
            break;
        case BF_KERNEL_CONTACT:
            if (((const bf_contact *)e[k].self)->law)
                bf_contact_accel_general(e[k].self, b, x, v, acc, pw);
            else
                bf_contact_accel(e[k].self, b, x, acc);
            break;
        case BF_KERNEL_SPRING:
            bf_spring_accel(e[k].self, b, x, acc);
            break;
        case BF_KERNEL_DRAG:
            bf_drag_accel(e[k].self, b, v, acc, pw);
            break;
        default:
            if (!pw || e[k].type->potential ||
                (e[k].type->flags & BF_EFFECT_CONSERVATIVE)) {
                if (e[k].type->accel(e[k].self, b, t, x, v, acc))
                    return 1;
                break;
            }
            for (size_t i = 0; i < b->n; i++)
                pw->scratch[i] = 0.0;
            if (e[k].type->accel(e[k].self, b, t, x, v, pw->scratch))
                return 1;
            for (size_t i = 0; i < b->n; i++) {
                acc[i] += pw->scratch[i];
                pw->diss -= b->m[i] * pw->scratch[i] * v[i];
            }
        }
    }
    return 0;
}

#endif
