/* floor.c: Hertz contact with a rigid floor at x = 0, Yasuda eq. 2.5:
 * f = k x^{3/2}, x = max(R - z, 0), potential (2/5) k x^{5/2} (eq. 2.8,
 * exact for the floor).  Only the lowest ball can reach the floor while the
 * balls keep their order, but every ball is checked: it costs nothing and
 * stays right if a scene starts with balls out of order. */
#include "effect_kernels.h"

static const bf_param floor_params[] = {
    {"k", BF_AT(bf_floor, k, BF_REAL), "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-floor contact", BF_POS, 0, 0, NULL},
    {0},
};

static const bf_section_spec floor_spec = BF_SECTION(
    "floor", "rigid floor at x = 0 with Hertz contact (Yasuda eq. 2.5)",
    floor_params, bf_floor);

static bf_status floor_create(void **self, const void *params,
                              const bf_balls *b, bf_err *err)
{
    for (size_t i = 0; i < b->n; i++) {
        if (b->x[i] < b->R[i]) {
            char sec[32];
            snprintf(sec, sizeof sec, "ball.%zu", i + 1);
            return bf_fail_key(err, BF_EINPUT, sec, "position",
                               "ball %zu at %g cm penetrates the floor "
                               "(radius %g cm): start with position >= "
                               "radius",
                               i + 1, b->x[i], b->R[i]);
        }
    }
    return bf_effect_copy_params(self, params, sizeof(bf_floor), err);
}

BF_EFFECT_KERNEL_WRAPPERS(floor)

const bf_effect_type bf_effect_floor = {
    .name = "floor",
    .doc = "Hertz contact with a rigid floor at x = 0",
    .spec = &floor_spec,
    .flags = BF_EFFECT_FLOOR | BF_EFFECT_CONSERVATIVE,
    .create = floor_create,
    .accel = floor_accel,
    .potential = floor_potential,
    .destroy = free,
};
