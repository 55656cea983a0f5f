/* effects.h: composable forces on balls on a line.
 *
 * A scene lists the effects it uses ([scene] effects = gravity floor
 * contact); only those are created and evaluated.  Each effect adds its
 * acceleration (force / mass, cm/s^2) and reports its potential energy (erg)
 * so that the total energy is checkable.  Effects live in src/effects/, one
 * file each, and are listed in registry.c.
 *
 * Balls are numbered along the line in increasing position: bottom to top
 * for falling balls (Yasuda sec. 2), left to right in the film (sec. 3).
 */
#ifndef BALLFILM_EFFECTS_H
#define BALLFILM_EFFECTS_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/scene.h"

typedef struct bf_balls {
    size_t n;
    double *x;     /* centre position, cm */
    double *v;     /* velocity, cm/s */
    double *m;     /* mass, g */
    double *inv_m; /* 1/m, 1/g */
    double *R;     /* radius, cm */
} bf_balls;

/* What an effect may need besides the balls (NULL members are absent).
 * The coupled ball-film model passes its film here. */
typedef struct bf_effect_env {
    void *film;
} bf_effect_env;

/* Built-in effects have a kind so that the dispatch point
 * (effect_kernels.h) can inline their force kernels; effects without a
 * kernel there (BF_EFFECT_OTHER) are called through `accel`. */
typedef enum bf_effect_kind {
    BF_EFFECT_OTHER = 0,
    BF_EFFECT_GRAVITY,
    BF_EFFECT_FLOOR,
    BF_EFFECT_CONTACT,
    BF_EFFECT_SPRING
} bf_effect_kind;

typedef struct bf_effect_type {
    const char *name;
    bf_effect_kind kind;
    const char *doc;
    const bf_section_spec *spec; /* its section, or NULL */
    bf_status (*create)(void **self, const bf_scene *sc, const bf_balls *b,
                        const bf_effect_env *env, bf_err *err);
    /* acc[i] += a_i(t, x); returns 0 or non-zero if undefined at x */
    int (*accel)(const void *self, const bf_balls *b, double t,
                 const double *x, double *acc);
    /* potential energy at x, erg */
    double (*potential)(const void *self, const bf_balls *b, double t,
                        const double *x);
    void (*destroy)(void *self);
} bf_effect_type;

const bf_effect_type *bf_effect_find(const char *name);
const bf_effect_type *const *bf_effect_types(size_t *n);

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

#endif
