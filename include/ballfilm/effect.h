/* effect.h: composable forces on balls on a line.
 *
 * A scene lists the effects it uses ([scene] effects = gravity floor
 * contact); only those are created and evaluated.  Each effect adds its
 * acceleration a_i(t, x, v) (force / mass, cm/s^2) at the stage values the
 * integrator evaluates at, and reports its potential energy (erg) when it
 * has one, so that the total energy is checkable.  An effect whose force
 * depends on the velocities or explicitly on time says so in its flags
 * (BF_EFFECT_VELOCITY, BF_EFFECT_TIME): integrators built for a = a(x)
 * then refuse the scene rather than lose their order (docs/forces.md).  An effect is one descriptor
 * (bf_effect_type) with its parameter section (params.h); the built-in
 * ones live in src/effects/, one file each, and are listed in the catalog
 * (src/compose/catalog.c).  Adding an effect is one new file and one
 * catalog line.
 *
 * Balls are numbered along the line in increasing position: bottom to top
 * for falling balls (Yasuda sec. 2), left to right in the film (sec. 3).
 */
#ifndef BALLFILM_EFFECT_H
#define BALLFILM_EFFECT_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"

typedef struct bf_balls {
    size_t n;
    double *x;     /* centre position, cm */
    double *v;     /* velocity, cm/s */
    double *m;     /* mass, g */
    double *inv_m; /* 1/m, 1/g */
    double *R;     /* radius, cm */
} bf_balls;

/* Properties an effect declares (flags). */
enum {
    /* a rigid floor at x = 0: falling balls' first-return maps are taken
     * at its contacts (returnmap.h) */
    BF_EFFECT_FLOOR = 1u << 0,
    /* the force is odd under the mirror x -> -x (ball i <-> ball n+1-i):
     * the coupled model's forced symmetry may use it */
    BF_EFFECT_MIRROR_ODD = 1u << 1,
    /* the force is minus the gradient of `potential`, which does not
     * depend on t: with only such effects the balls' energy is conserved
     * and the loop bounds its error (model.h, energy_bound) */
    BF_EFFECT_CONSERVATIVE = 1u << 2,
    /* the force depends on the velocities v (drag, damping): integrators
     * that evaluate a at predicted positions with the step's initial
     * velocities (BF_INT_POSITION_ONLY, integrator.h) refuse the scene */
    BF_EFFECT_VELOCITY = 1u << 3,
    /* the force depends explicitly on t (a driven wall): every integrator
     * evaluates it at its stages' times; the specialised ball steps are not
     * used for such a scene */
    BF_EFFECT_TIME = 1u << 4
};

typedef struct bf_effect_type {
    const char *name;
    const char *doc;
    const bf_section_spec *spec; /* its section, or NULL */
    unsigned flags;              /* BF_EFFECT_* */
    /* Create from the filled struct of `spec` (NULL without one); may
     * refuse the initial state in b (ball.N position), naming the key. */
    bf_status (*create)(void **self, const void *params, const bf_balls *b,
                        bf_err *err);
    /* acc[i] += a_i(t, x, v) (cm/s^2) at the time t (s), positions x (cm)
     * and velocities v (cm/s) of the integrator's stage: read x and v, not
     * b->x and b->v (the state at the step's start); b gives the masses and
     * radii.  Returns 0, or non-zero if undefined there. */
    int (*accel)(const void *self, const bf_balls *b, double t,
                 const double *x, const double *v, double *acc);
    /* potential energy at x, erg (NULL: none, e.g. a dissipative force) */
    double (*potential)(const void *self, const bf_balls *b, double t,
                        const double *x);
    void (*destroy)(void *self); /* NULL: nothing to free */
} bf_effect_type;

/* A list of created effects. */
typedef struct bf_effect {
    const bf_effect_type *type;
    void *self;
} bf_effect;

/* acc = sum of all effects' accelerations at (t, x, v) (acc is zeroed
 * first). */
int bf_effects_accel(const bf_effect *e, size_t ne, const bf_balls *b, double t,
                     const double *x, const double *v, double *acc);
double bf_effects_potential(const bf_effect *e, size_t ne, const bf_balls *b,
                            double t, const double *x);

/* The failure of a state that is not finite, naming the first ball whose
 * position or velocity is not (BF_EUNSTABLE). */
bf_status bf_balls_not_finite(const bf_balls *b, bf_err *err);

#endif
