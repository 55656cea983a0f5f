/* gravity.c: uniform gravity along -x (the line is vertical; x is the
 * height above the floor).  Yasuda eqs 2.3-2.4: the -g term.
 * Potential: sum_i m_i g x_i (erg). */
#include <stdlib.h>

#include "ballfilm/effect_kernels.h"

typedef bf_gravity gravity;

static const bf_param gravity_params[] = {
    {"g", BF_REAL, 0, "cm/s^2", "980", "gravitational acceleration (downward)",
     BF_NONNEG, 0, 0, NULL},
    {0},
};

static const bf_section_spec gravity_spec = {
    "gravity", "uniform gravity pulling balls towards the floor (x decreasing)",
    gravity_params, 0};

static bf_status gravity_create(void **self, const bf_scene *sc,
                                const bf_balls *b, const bf_effect_env *env,
                                bf_err *err)
{
    (void)b;
    (void)env;
    gravity *g = malloc(sizeof *g);
    if (!g)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    g->g = bf_scene_real(sc, "gravity", "g");
    *self = g;
    return BF_OK;
}

static int gravity_accel(const void *self, const bf_balls *b, double t,
                         const double *x, double *acc)
{
    (void)t;
    bf_gravity_accel(self, b, x, acc);
    return 0;
}

static double gravity_potential(const void *self, const bf_balls *b, double t,
                                const double *x)
{
    (void)t;
    return bf_gravity_potential(self, b, x);
}

const bf_effect_type bf_effect_gravity = {
    .name = "gravity",
    .kind = BF_EFFECT_GRAVITY,
    .doc = "uniform gravity g along -x",
    .spec = &gravity_spec,
    .create = gravity_create,
    .accel = gravity_accel,
    .potential = gravity_potential,
    .destroy = free,
};
