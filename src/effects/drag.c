/* drag.c: air drag on every ball, linear and quadratic in its velocity,
 *
 *   a_i = -gamma v_i - c |v_i| v_i                                (cm/s^2)
 *
 * [drag] gamma (1/s): linear (Stokes) drag, the force -m gamma v;
 * [drag] quadratic (1/cm): c of the quadratic (Newton) drag, the force
 *   -m c |v| v (c = rho_air C_d A / (2 m) for a ball of cross-section A).
 * Both default to 0.  The force depends on the velocity, so the effect
 * declares BF_EFFECT_VELOCITY: it is evaluated at each stage's velocity,
 * and integrators for a = a(x) refuse it (docs/forces.md).  It has no
 * potential and is not conservative: dE/dt = -sum_i m_i (gamma v_i^2 +
 * c |v_i|^3) <= 0, so the energy check of all-conservative scenes does not
 * apply (the ball system's energy bound is 0 with it).  Its kernel,
 * bf_drag_accel (effect_kernels.h), sums the dissipated power from the
 * same evaluation when the ball system tracks the work. */
#include <math.h>

#include "effect_kernels.h"

static const bf_param drag_params[] = {
    {"gamma", BF_AT(bf_drag, gamma, BF_REAL), "1/s", "0",
     "linear drag: a = -gamma v", BF_NONNEG, 0, 0, NULL},
    {"quadratic", BF_AT(bf_drag, c, BF_REAL), "1/cm", "0",
     "quadratic drag: a = -quadratic |v| v", BF_NONNEG, 0, 0, NULL},
    {0},
};

static const bf_section_spec drag_spec = BF_SECTION(
    "drag", "air drag a = -gamma v - quadratic |v| v on every ball",
    drag_params, bf_drag);

static bf_status drag_create(void **self, const void *params,
                             const bf_balls *b, bf_err *err)
{
    (void)b;
    return bf_effect_copy_params(self, params, sizeof(bf_drag), err);
}

static int drag_accel(const void *self, const bf_balls *b, double t,
                      const double *x, const double *v, double *acc)
{
    (void)t;
    (void)x;
    bf_drag_accel(self, b, v, acc, NULL);
    return 0;
}

const bf_effect_type bf_effect_drag = {
    .name = "drag",
    .doc = "air drag a = -gamma v - quadratic |v| v (not conservative)",
    .spec = &drag_spec,
    .flags = BF_EFFECT_VELOCITY,
    .create = drag_create,
    .accel = drag_accel,
    .destroy = free,
};
