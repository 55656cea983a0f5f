/* floor.c: Hertz contact with a rigid floor at x = 0, Yasuda eq. 2.5:
 * f = k x^{3/2}, x = max(R - z, 0), potential (2/5) k x^{5/2} (eq. 2.8,
 * exact for the floor).  Only the lowest ball can reach the floor while the
 * balls keep their order, but every ball is checked: it costs nothing and
 * stays right if a scene starts with balls out of order. */
#include <stdlib.h>

#include "ballfilm/effect_kernels.h"

typedef bf_floor floor_;

static const bf_param floor_params[] = {
    {"k", BF_REAL, 0, "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-floor contact", BF_POS, 0, 0, NULL},
    {0},
};

static const bf_section_spec floor_spec = {
    "floor", "rigid floor at x = 0 with Hertz contact (Yasuda eq. 2.5)",
    floor_params, 0};

static bf_status floor_create(void **self, const bf_scene *sc, const bf_balls *b,
                              const bf_effect_env *env, bf_err *err)
{
    (void)env;
    for (size_t i = 0; i < b->n; i++) {
        if (b->x[i] < b->R[i]) {
            char sec[32];
            snprintf(sec, sizeof sec, "ball.%zu", i + 1);
            return bf_scene_fail(sc, err, sec, "position",
                                 "ball %zu at %g cm penetrates the floor "
                                 "(radius %g cm): start with position >= "
                                 "radius",
                                 i + 1, b->x[i], b->R[i]);
        }
    }
    floor_ *f = malloc(sizeof *f);
    if (!f)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    f->k = bf_scene_real(sc, "floor", "k");
    *self = f;
    return BF_OK;
}

static int floor_accel(const void *self, const bf_balls *b, double t,
                       const double *x, double *acc)
{
    (void)t;
    bf_floor_accel(self, b, x, acc);
    return 0;
}

static double floor_potential(const void *self, const bf_balls *b, double t,
                              const double *x)
{
    (void)t;
    return bf_floor_potential(self, b, x);
}

const bf_effect_type bf_effect_floor = {
    .name = "floor",
    .kind = BF_EFFECT_FLOOR,
    .doc = "Hertz contact with a rigid floor at x = 0",
    .spec = &floor_spec,
    .create = floor_create,
    .accel = floor_accel,
    .potential = floor_potential,
    .destroy = free,
};
