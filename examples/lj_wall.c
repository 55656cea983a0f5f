/* lj_wall.c: a user-defined potential next to the built-in effects.
 *
 * A Lennard-Jones wall at x = 0 acts on every ball's centre,
 *     V(x) = 4 eps [ (sigma/x)^12 - (sigma/x)^6 ],
 *     a = -V'(x)/m = (24 eps / (m x)) [ 2 (sigma/x)^12 - (sigma/x)^6 ],
 * with its own section [lj_wall] (eps in erg, sigma in cm).  Two balls
 * stand on it under the built-in gravity; the upper one rests on the lower
 * through the built-in Hertz contact between neighbours.  The lower ball
 * sits in the wall's well (depth eps = 500 erg against m g sigma = 98 erg)
 * and the upper one, dropped from 0.9 cm, makes the pair bounce.
 *
 * The effect gives both the force and the potential, so the library's
 * energy diagnostic sums gravity, contact and wall: the trust number is the
 * largest relative energy error, which for velocity Verlet (order 2)
 * must fall by 4 when dt halves, and stays bounded over the run (a
 * symplectic method), so force and potential agree.
 *
 * Build and run: make -C examples lj_wall && examples/lj_wall
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <ballfilm/run.h>
#include <ballfilm/sim.h>

typedef struct lj_wall {
    double eps;   /* erg */
    double sigma; /* cm */
} lj_wall;

static const bf_param lj_params[] = {
    {"eps", BF_AT(lj_wall, eps, BF_REAL), "erg", "500",
     "depth of the wall's well", BF_POS, 0, 0, NULL},
    {"sigma", BF_AT(lj_wall, sigma, BF_REAL), "cm", "0.1",
     "distance at which V = 0 (the minimum is at 2^(1/6) sigma)", BF_POS, 0,
     0, NULL},
    {0},
};

static const bf_section_spec lj_spec =
    BF_SECTION("lj_wall", "a Lennard-Jones wall at x = 0", lj_params,
               lj_wall);

static bf_status lj_create(void **self, const void *params, const bf_balls *b,
                           bf_err *err)
{
    for (size_t i = 0; i < b->n; i++)
        if (!(b->x[i] > 0)) {
            char sec[32];
            snprintf(sec, sizeof sec, "ball.%zu", i + 1);
            return bf_fail_key(err, BF_EINPUT, sec, "position",
                               "the wall's potential needs x > 0");
        }
    lj_wall *w = malloc(sizeof *w);
    if (!w)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    *w = *(const lj_wall *)params;
    *self = w;
    return BF_OK;
}

/* a force of the positions only: t and v are not read */
static int lj_accel(const void *self, const bf_balls *b, double t,
                    const double *x, const double *v, double *acc)
{
    (void)t;
    (void)v;
    const lj_wall *w = self;
    for (size_t i = 0; i < b->n; i++) {
        if (!(x[i] > 0))
            return 1; /* through the wall: the step fails, naming it */
        const double s2 = (w->sigma / x[i]) * (w->sigma / x[i]);
        const double s6 = s2 * s2 * s2;
        acc[i] += 24.0 * w->eps * b->inv_m[i] / x[i] * (2.0 * s6 * s6 - s6);
    }
    return 0;
}

static double lj_potential(const void *self, const bf_balls *b, double t,
                           const double *x)
{
    (void)t;
    const lj_wall *w = self;
    double V = 0.0;
    for (size_t i = 0; i < b->n; i++) {
        const double s2 = (w->sigma / x[i]) * (w->sigma / x[i]);
        const double s6 = s2 * s2 * s2;
        V += 4.0 * w->eps * (s6 * s6 - s6);
    }
    return V;
}

static const bf_effect_type lj_wall_effect = {
    .name = "lj_wall",
    .doc = "a Lennard-Jones wall at x = 0 acting on the balls' centres",
    .spec = &lj_spec,
    .create = lj_create,
    .accel = lj_accel,
    .potential = lj_potential,
    .destroy = free,
};

/* The scene, written in code: keys and balls (run.h, bf_setf and
 * bf_add_ball), validated like a file when the run is built. */
static int run(const bf_catalog *cat, double dt, double *energy_error)
{
    bf_err err = {0};
    bf_scene *sc;
    bf_run *r;
    if (bf_scene_load_string(&sc, "lj_wall", "", &err) ||
        bf_setf(sc, &err, "scene.title=two balls on a Lennard-Jones wall") ||
        bf_setf(sc, &err, "scene.integrator=verlet") ||
        bf_setf(sc, &err, "scene.effects=gravity contact lj_wall") ||
        bf_setf(sc, &err, "scene.dt=%.17g", dt) ||
        bf_setf(sc, &err, "scene.t_end=2") ||
        bf_setf(sc, &err, "scene.output_every=0.01 s") ||
        bf_setf(sc, &err, "lj_wall.eps=500") ||
        bf_add_ball(sc, 0.1122, 0.0, 1.0, 0.1, NULL, &err) || /* in the well */
        bf_add_ball(sc, 0.9, 0.0, 0.5, 0.1, NULL, &err) ||    /* dropped */
        bf_run_from_scene(&r, cat, sc, NULL, &err) ||
        bf_sim_run(bf_run_sim(r), &err)) {
        fprintf(stderr, "lj_wall: %s\n", err.msg);
        return 1;
    }
    *energy_error = bf_sim_max_energy_error(bf_run_sim(r));
    bf_run_free(r);
    return 0;
}

int main(void)
{
    bf_err err = {0};
    bf_catalog *cat = bf_catalog_new(bf_catalog_builtin());
    if (!cat || bf_catalog_add_effect(cat, &lj_wall_effect, &err)) {
        fprintf(stderr, "lj_wall: %s\n", err.msg);
        return 1;
    }
    double e1, e2;
    if (run(cat, 5e-6, &e1) || run(cat, 2.5e-6, &e2))
        return 1;
    bf_catalog_free(cat);
    const double order = log(e1 / e2) / log(2.0);
    printf("max relative energy error over 2 s (gravity + contact + "
           "lj_wall): %.3e at dt = 5e-6 s, %.3e at 2.5e-6 s\n", e1, e2);
    printf("observed order of the energy error %.2f (velocity Verlet: 2)\n",
           order);
    return fabs(order - 2.0) < 0.3 && e2 < 1e-4 ? 0 : 1;
}
