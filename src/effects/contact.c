/* contact.c: Hertz contact between neighbouring balls, Yasuda eqs 2.6 and
 * 3.13-3.14: f = k x^{3/2}, x = max((R_i + R_{i+1} - (x_{i+1} - x_i))/2, 0),
 * pushing ball i down/left and ball i+1 up/right.  Potential (4/5) k x^{5/2}
 * per pair (see src/contact/hertz.h for why the paper's 2/5 is not the
 * potential of this force).  Optionally damped (restitution, viscosity:
 * damped.c). */
#include "effect_kernels.h"

static const bf_param contact_params[] = {
    {"k", BF_AT(bf_contact, k, BF_REAL), "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-ball contact", BF_POS, 0, 0, NULL},
    {"restitution", BF_AT(bf_contact, e, BF_REAL), "1", "1",
     "coefficient of restitution at any impact speed (damping c delta^1/4 "
     "ddelta; 1: elastic)", BF_POS | BF_MAX, 0, 1, NULL},
    {"viscosity", BF_AT(bf_contact, A, BF_REAL), "s", "0",
     "Kuwabara-Kono damping (3/2) A k delta^1/2 ddelta", BF_NONNEG, 0, 0,
     NULL},
    {0},
};

static const bf_section_spec contact_spec = BF_SECTION(
    "contact", "Hertz contact between neighbouring balls (Yasuda eq. 2.6)",
    contact_params, bf_contact);

static bf_status contact_create(void **self, const void *params,
                                const bf_balls *b, bf_err *err)
{
    (void)b;
    bf_status st =
        bf_effect_copy_params(self, params, sizeof(bf_contact), err);
    if (!st) {
        bf_contact *p = *self;
        p->alpha = bf_damping_alpha(p->e);
        p->law = bf_contact_law(p->e, p->A, 0.0);
        p->branch = NULL;
    }
    return st;
}

static int contact_accel(const void *self, const bf_balls *b, double t,
                         const double *x, const double *v, double *acc)
{
    (void)t;
    const bf_contact *p = self;
    if (p->law)
        bf_contact_accel_general(p, b, x, v, acc, NULL);
    else
        bf_contact_accel(p, b, x, acc);
    return 0;
}

static double contact_potential(const void *self, const bf_balls *b, double t,
                                const double *x)
{
    (void)t;
    return bf_contact_potential(self, b, x);
}

const bf_effect_type bf_effect_contact = {
    .name = "contact",
    .doc = "Hertz contact between neighbouring balls",
    .spec = &contact_spec,
    .flags = BF_EFFECT_MIRROR_ODD | BF_EFFECT_CONSERVATIVE,
    .create = contact_create,
    .accel = contact_accel,
    .potential = contact_potential,
    .destroy = free,
};
