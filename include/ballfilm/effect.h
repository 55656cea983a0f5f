/* effect.h: composable forces on balls on a line.
 *
 * A scene lists the effects it uses ([scene] effects = gravity floor
 * contact); only those are created and evaluated.  Each effect adds its
 * acceleration (force / mass, cm/s^2) and reports its potential energy (erg)
 * so that the total energy is checkable.  An effect is one descriptor
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

/* What an effect may need besides the balls (NULL members are absent).
 * The coupled ball-film model hands its coupling over here (coupling.h);
 * the coupling effect applies its force. */
struct bf_coupling;
typedef struct bf_effect_env {
    struct bf_coupling *coupling;
} bf_effect_env;

/* Effects whose force the specialised ball steps inline (the dispatch
 * point of src/effects/effect_kernels.h) say which kernel they are; every
 * other effect (BF_KERNEL_NONE, for example one a library user defines)
 * is called through `accel`. */
typedef enum bf_effect_kernel {
    BF_KERNEL_NONE = 0,
    BF_KERNEL_GRAVITY,
    BF_KERNEL_FLOOR,
    BF_KERNEL_CONTACT,
    BF_KERNEL_SPRING
} bf_effect_kernel;

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
    BF_EFFECT_CONSERVATIVE = 1u << 2
};

typedef struct bf_effect_type {
    const char *name;
    const char *doc;
    const bf_section_spec *spec; /* its section, or NULL */
    bf_effect_kernel kernel;
    unsigned flags;
    /* Create from the filled struct of `spec` (NULL without one); may
     * refuse the initial state (ball.N position), naming the key. */
    bf_status (*create)(void **self, const void *params, const bf_balls *b,
                        const bf_effect_env *env, bf_err *err);
    /* acc[i] += a_i(t, x); returns 0 or non-zero if undefined at x */
    int (*accel)(const void *self, const bf_balls *b, double t,
                 const double *x, double *acc);
    /* potential energy at x, erg */
    double (*potential)(const void *self, const bf_balls *b, double t,
                        const double *x);
    void (*destroy)(void *self);
} bf_effect_type;

/* A list of created effects. */
typedef struct bf_effect {
    const bf_effect_type *type;
    void *self;
} bf_effect;

/* acc = sum of all effects' accelerations (acc is zeroed first). */
int bf_effects_accel(const bf_effect *e, size_t ne, const bf_balls *b, double t,
                     const double *x, double *acc);
double bf_effects_potential(const bf_effect *e, size_t ne, const bf_balls *b,
                            double t, const double *x);

/* The failure of a state that is not finite, naming the first ball whose
 * position or velocity is not (BF_EUNSTABLE). */
bf_status bf_balls_not_finite(const bf_balls *b, bf_err *err);

#endif
