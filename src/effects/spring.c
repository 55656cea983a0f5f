/* spring.c: a linear restoring force f = -s (x - x_rest) on every ball,
 * for the harmonic-oscillator checks of Yasuda sec. 2.3 (omega^2 = s/m).
 * Potential (1/2) s (x - x_rest)^2. */
#include "effect_kernels.h"

static const bf_param spring_params[] = {
    {"stiffness", BF_AT(bf_spring, s, BF_REAL), "g/s^2", "1",
     "spring constant s (dyn/cm); omega = sqrt(s/m)", BF_POS, 0, 0, NULL},
    {"rest", BF_AT(bf_spring, rest, BF_REAL), "cm", "0",
     "rest position x_rest", 0, 0, 0, NULL},
    {0},
};

static const bf_section_spec spring_spec = BF_SECTION(
    "spring", "linear restoring force towards x_rest (harmonic oscillator)",
    spring_params, bf_spring);

static bf_status spring_create(void **self, const void *params,
                               const bf_balls *b, bf_err *err)
{
    (void)b;
    return bf_effect_copy_params(self, params, sizeof(bf_spring), err);
}

BF_EFFECT_KERNEL_WRAPPERS(spring)

const bf_effect_type bf_effect_spring = {
    .name = "spring",
    .doc = "linear restoring force (harmonic oscillator)",
    .spec = &spring_spec,
    .flags = BF_EFFECT_CONSERVATIVE,
    .create = spring_create,
    .accel = spring_accel,
    .potential = spring_potential,
    .destroy = free,
};
