/* spring.c: a linear restoring force f = -s (x - x_rest) on every ball,
 * for the harmonic-oscillator checks of Yasuda sec. 2.3 (omega^2 = s/m).
 * Potential (1/2) s (x - x_rest)^2. */
#include <stdlib.h>

#include "ballfilm/effect_kernels.h"

typedef bf_spring spring;

static const bf_param spring_params[] = {
    {"stiffness", BF_REAL, 0, "g/s^2", "1",
     "spring constant s (dyn/cm); omega = sqrt(s/m)", BF_POS, 0, 0, NULL},
    {"rest", BF_REAL, 0, "cm", "0", "rest position x_rest", 0, 0, 0, NULL},
    {0},
};

static const bf_section_spec spring_spec = {
    "spring", "linear restoring force towards x_rest (harmonic oscillator)",
    spring_params, 0};

static bf_status spring_create(void **self, const bf_scene *sc,
                               const bf_balls *b, const bf_effect_env *env,
                               bf_err *err)
{
    (void)b;
    (void)env;
    spring *s = malloc(sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->s = bf_scene_real(sc, "spring", "stiffness");
    s->rest = bf_scene_real(sc, "spring", "rest");
    *self = s;
    return BF_OK;
}

static int spring_accel(const void *self, const bf_balls *b, double t,
                        const double *x, double *acc)
{
    (void)t;
    bf_spring_accel(self, b, x, acc);
    return 0;
}

static double spring_potential(const void *self, const bf_balls *b, double t,
                               const double *x)
{
    (void)t;
    return bf_spring_potential(self, b, x);
}

const bf_effect_type bf_effect_spring = {
    .name = "spring",
    .kind = BF_EFFECT_SPRING,
    .doc = "linear restoring force (harmonic oscillator)",
    .spec = &spring_spec,
    .create = spring_create,
    .accel = spring_accel,
    .potential = spring_potential,
    .destroy = free,
};
