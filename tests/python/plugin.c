/* plugin.c: an effect written in C outside the library, compiled into a
 * shared object by the Python tests (conftest.py) and added to a catalog
 * from Python (ballfilm.Catalog.add_effect).
 *
 * A quartic well V = (q/4) (x - c)^4, a = -(q/m) (x - c)^3, section
 * [quartic] with strength q (g/(cm^2 s^2)) and centre c (cm): the effect
 * of tests/test_plugins.c, whose motion from rest at c + A has the
 * analytic period T = 4 sqrt(2 m / q) / A * (varpi / 2), varpi / 2 =
 * 1.311028777146... (half the lemniscate constant). */
#include <stdlib.h>

#include <ballfilm/effect.h>

typedef struct quartic {
    double q, centre;
} quartic;

static const bf_param quartic_params[] = {
    {"strength", BF_AT(quartic, q, BF_REAL), "g/(cm^2 s^2)", "1",
     "q of V = (q/4) (x - centre)^4", BF_POS, 0, 0, NULL},
    {"centre", BF_AT(quartic, centre, BF_REAL), "cm", "0",
     "the bottom of the well", 0, 0, 0, NULL},
    {0},
};

static const bf_section_spec quartic_spec =
    BF_SECTION("quartic", "a quartic well", quartic_params, quartic);

static bf_status quartic_create(void **self, const void *params,
                                const bf_balls *b, bf_err *err)
{
    (void)b;
    quartic *w = malloc(sizeof *w);
    if (!w)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    *w = *(const quartic *)params;
    *self = w;
    return BF_OK;
}

static int quartic_accel(const void *self, const bf_balls *b, double t,
                         const double *x, const double *v, double *acc)
{
    (void)t;
    (void)v;
    const quartic *w = self;
    for (size_t i = 0; i < b->n; i++) {
        const double d = x[i] - w->centre;
        acc[i] -= w->q * b->inv_m[i] * d * d * d;
    }
    return 0;
}

static double quartic_potential(const void *self, const bf_balls *b,
                                double t, const double *x)
{
    (void)t;
    const quartic *w = self;
    double V = 0;
    for (size_t i = 0; i < b->n; i++) {
        const double d = x[i] - w->centre;
        V += 0.25 * w->q * d * d * d * d;
    }
    return V;
}

const bf_effect_type quartic_well = {
    .name = "quartic",
    .doc = "a quartic well V = (q/4) (x - centre)^4",
    .spec = &quartic_spec,
    .create = quartic_create,
    .accel = quartic_accel,
    .potential = quartic_potential,
    .destroy = free,
};
