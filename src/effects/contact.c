/* contact.c: Hertz contact between neighbouring balls, Yasuda eqs 2.6 and
 * 3.13-3.14: f = k x^{3/2}, x = max((R_i + R_{i+1} - (x_{i+1} - x_i))/2, 0),
 * pushing ball i down/left and ball i+1 up/right.  Potential (4/5) k x^{5/2}
 * per pair (see contact.h for why the paper's 2/5 is not the potential of
 * this force). */
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/effect_kernels.h"

typedef bf_contact contact;

static const bf_param contact_params[] = {
    {"k", BF_REAL, 0, "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-ball contact", BF_POS, 0, 0, NULL},
    {0},
};

static const bf_section_spec contact_spec = {
    "contact", "Hertz contact between neighbouring balls (Yasuda eq. 2.6)",
    contact_params, 0};

static bf_status contact_create(void **self, const bf_scene *sc,
                                const bf_balls *b, const bf_effect_env *env,
                                bf_err *err)
{
    (void)env;
    (void)sc;
    (void)b;
    contact *c = malloc(sizeof *c);
    if (!c)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    c->k = bf_scene_real(sc, "contact", "k");
    *self = c;
    return BF_OK;
}

static int contact_accel(const void *self, const bf_balls *b, double t,
                         const double *x, double *acc)
{
    (void)t;
    bf_contact_accel(self, b, x, acc);
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
    .kind = BF_EFFECT_CONTACT,
    .doc = "Hertz contact between neighbouring balls",
    .spec = &contact_spec,
    .create = contact_create,
    .accel = contact_accel,
    .potential = contact_potential,
    .destroy = free,
};
