/* gravity.c: uniform gravity along -x (the line is vertical; x is the
 * height above the floor).  Yasuda eqs 2.3-2.4: the -g term.
 * Potential: sum_i m_i g x_i (erg). */
#include "effect_kernels.h"

static const bf_param gravity_params[] = {
    {"g", BF_AT(bf_gravity, g, BF_REAL), "cm/s^2", "980",
     "gravitational acceleration (downward)", BF_NONNEG, 0, 0, NULL},
    {0},
};

static const bf_section_spec gravity_spec = BF_SECTION(
    "gravity", "uniform gravity pulling balls towards the floor (x decreasing)",
    gravity_params, bf_gravity);

static bf_status gravity_create(void **self, const void *params,
                                const bf_balls *b, bf_err *err)
{
    (void)b;
    return bf_effect_copy_params(self, params, sizeof(bf_gravity), err);
}

BF_EFFECT_KERNEL_WRAPPERS(gravity)

const bf_effect_type bf_effect_gravity = {
    .name = "gravity",
    .doc = "uniform gravity g along -x",
    .spec = &gravity_spec,
    .flags = BF_EFFECT_CONSERVATIVE,
    .create = gravity_create,
    .accel = gravity_accel,
    .potential = gravity_potential,
    .destroy = free,
};
