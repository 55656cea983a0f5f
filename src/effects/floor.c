/* floor.c: Hertz contact with a rigid floor at x = 0, Yasuda eq. 2.5:
 * f = k x^{3/2}, x = max(R - z, 0), potential (2/5) k x^{5/2} (eq. 2.8,
 * exact for the floor).  Optionally damped (restitution, viscosity) and
 * driven (the floor at height amplitude sin(2 pi frequency t)): damped.c.  Only the lowest ball can reach the floor while the
 * balls keep their order, but every ball is checked: it costs nothing and
 * stays right if a scene starts with balls out of order. */
#include "effect_kernels.h"

static const bf_param floor_params[] = {
    {"k", BF_AT(bf_floor, k, BF_REAL), "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-floor contact", BF_POS, 0, 0, NULL},
    {"restitution", BF_AT(bf_floor, e, BF_REAL), "1", "1",
     "coefficient of restitution at any impact speed (damping c delta^1/4 "
     "ddelta; 1: elastic)", BF_POS | BF_MAX, 0, 1, NULL},
    {"viscosity", BF_AT(bf_floor, A, BF_REAL), "s", "0",
     "Kuwabara-Kono damping (3/2) A k delta^1/2 ddelta", BF_NONNEG, 0, 0,
     NULL},
    {"amplitude", BF_AT(bf_floor, amplitude, BF_REAL), "cm", "0",
     "the floor moves to height amplitude sin(2 pi frequency t)", BF_NONNEG,
     0, 0, NULL},
    {"frequency", BF_AT(bf_floor, frequency, BF_REAL), "Hz", "0",
     "frequency of the floor's motion", BF_NONNEG, 0, 0, NULL},
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
    bf_status st = bf_effect_copy_params(self, params, sizeof(bf_floor), err);
    if (!st) {
        bf_floor *p = *self;
        p->alpha = bf_damping_alpha(p->e);
        p->law = bf_contact_law(p->e, p->A, p->amplitude);
        p->branch = NULL;
    }
    return st;
}

static int floor_accel(const void *self, const bf_balls *b, double t,
                       const double *x, const double *v, double *acc)
{
    const bf_floor *p = self;
    if (p->law)
        bf_floor_accel_general(p, b, t, x, v, acc, NULL);
    else
        bf_floor_accel(p, b, x, acc);
    return 0;
}

static double floor_potential(const void *self, const bf_balls *b, double t,
                              const double *x)
{
    const bf_floor *p = self;
    return p->law ? bf_floor_potential_general(p, b, t, x)
                      : bf_floor_potential(p, b, x);
}

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
