/* force.c: the effect "coupling": the force of the film on the balls,
 * -M dF_p/dr_p with F_p of eq. 3.10 (coupling.h), and the potential
 * energy sum_p m_p M F_p; the keys of [coupling].  The coupling itself
 * belongs to the model that couples balls and film: it creates it from
 * these keys and the film and hands it to its ball system as this
 * effect's instance (bf_ballsys_create's `given`). */
#include "coupling/force.h"

static const double PI = 3.14159265358979323846;

static const bf_param coupling_params[] = {
    {"V0", BF_AT(bf_coupling_keys, V0, BF_REAL), "g/(cm^3 s^2)", "0.01",
     "strength V0 of V(s) = V0 exp(-|s|/r0) (eq. 3.10)", BF_NONNEG, 0, 0,
     NULL},
    {"r0", BF_AT(bf_coupling_keys, r0, BF_REAL), "cm", "0.5",
     "range r0 of V(s)", BF_POS, 0, 0, NULL},
    {"mobility", BF_AT(bf_coupling_keys, mobility, BF_REAL), "1/g", "1e5",
     "ball mobility M (eq. 3.12)", BF_NONNEG, 0, 0, NULL},
    {"psi_s", BF_AT(bf_coupling_keys, psi_s, BF_REAL), "1", "0",
     "order parameter of the ball surface", BF_MIN | BF_MAX, -1, 1, NULL},
    {"quadrature", BF_AT(bf_coupling_keys, quadrature, BF_ENUM), "", "spline",
     "interpolation of g = h (psi - psi_s)^2 for the integral (3.10): "
     "spline (natural cubic, the paper's) or linear; nodes: the integral "
     "summed at the nodes, F_i = sum_j h_j V(x_j - x_i) (psi_j - psi_s)^2 dx, "
     "and the natural cubic spline through the F_i",
     0, 0, 0, "spline|linear|nodes"},
    {"taylor", BF_AT(bf_coupling_keys, taylor, BF_BOOL), "", "true",
     "reuse a 5th-order expansion of the integral around each ball's first "
     "position per film level (exact to 1e-17 within 2e-3 r0)",
     0, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_coupling_spec = BF_SECTION(
    "coupling",
    "balls coupled to the film by the free energy F (Yasuda eqs 3.10-3.12)",
    coupling_params, bf_coupling_keys);

bf_coupling_params bf_coupling_params_from_keys(const bf_coupling_keys *k)
{
    bf_coupling_params p = {
        .V0 = k->V0,
        .r0 = k->r0,
        .M = k->mobility,
        .psi_s = k->psi_s,
        .quad = (bf_coupling_quad)k->quadrature,
    };
    p.taylor_radius = k->taylor ? 2e-3 * p.r0 : 0.0;
    return p;
}

/* The coupling itself belongs to the model that couples balls and film
 * (it creates it from this effect's keys and the film, and hands it over
 * as the instance); created by any other model, the effect has no film. */
static bf_status coupling_effect_create(void **self, const void *params,
                                        const bf_balls *b, bf_err *err)
{
    (void)self;
    (void)params;
    (void)b;
    return bf_fail_key(err, BF_EINPUT, "scene", "effects",
                       "the coupling effect needs a film: use model = "
                       "coupled (with film = static for a fixed kink)");
}

/* a = -M dF/dr (eq. 3.12): a function of x and of the film (whose changes
 * bump the ode's epoch), not of v */
static int coupling_accel(const void *self, const bf_balls *b, double t,
                          const double *x, const double *v, double *acc)
{
    (void)t;
    (void)v;
    bf_coupling *c = (bf_coupling *)self; /* caches are not state */
    const bf_coupling_params *p = bf_coupling_params_of(c);
    const double k = 4.0 * PI * p->V0 * p->M;
    for (size_t i = 0; i < b->n; i++) {
        double I, dI;
        bf_coupling_integral_ball(c, i, x[i], &I, &dI);
        acc[i] -= k * b->R[i] * b->R[i] * dI;
    }
    return 0;
}

static double coupling_potential(const void *self, const bf_balls *b,
                                 double t, const double *x)
{
    (void)t;
    bf_coupling *c = (bf_coupling *)self;
    const bf_coupling_params *p = bf_coupling_params_of(c);
    const double k = 4.0 * PI * p->V0 * p->M;
    double u = 0.0;
    for (size_t i = 0; i < b->n; i++) {
        double I, dI;
        bf_coupling_integral(c, x[i], &I, &dI);
        u += b->m[i] * k * b->R[i] * b->R[i] * I;
    }
    return u;
}

const bf_effect_type bf_effect_coupling = {
    .name = "coupling",
    .doc = "ball-film coupling: -M dF/dr with F of eq. 3.10 (model coupled)",
    .spec = &bf_coupling_spec,
    .flags = BF_EFFECT_MIRROR_ODD,
    .create = coupling_effect_create,
    .accel = coupling_accel,
    .potential = coupling_potential,
};
