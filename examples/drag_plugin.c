/* drag_plugin.c: a force that depends on velocity, written here against
 * the installed headers: linear air drag a = -gamma v on every ball, with
 * its own section [my_drag] (gamma in 1/s), added to the program's
 * catalog next to the built-in gravity.
 *
 * What makes it work: `accel` reads the velocities it is given (v, the
 * integrator's stage values), never b->v (the state at the step's start),
 * and the descriptor declares BF_EFFECT_VELOCITY.  Integrators that take
 * such forces then evaluate them at each stage's velocity and keep their
 * order; those made for a = a(x) (mv2m, alpha, rkn6, greenspan73) refuse
 * the scene with status 2, naming [scene] integrator and the effect.
 *
 * The known answer: a ball falling from rest, v' = -g - gamma v, has
 *     v(t) = -(g/gamma) (1 - e^{-gamma t}).
 * Trust numbers: the observed order of rk4 (4) and of verlet (2, its last
 * half-kick solved for v^{n+1}) from the velocity error at T = 2 s with dt
 * = 0.04 and 0.02 s (within 0.15: the error's next term is relatively
 * O(gamma dt) = 0.02), and mv2m refused with status 2.  Exit status 1 if
 * any is off.
 *
 * Build and run: make -C examples drag_plugin && examples/drag_plugin
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ballfilm/run.h>
#include <ballfilm/sim.h>

/* ---- the effect ---- */

typedef struct my_drag {
    double gamma; /* 1/s */
} my_drag;

static const bf_param my_drag_params[] = {
    {"gamma", BF_AT(my_drag, gamma, BF_REAL), "1/s", "0.5",
     "linear drag rate: a = -gamma v", BF_NONNEG, 0, 0, NULL},
    {0},
};

static const bf_section_spec my_drag_spec = BF_SECTION(
    "my_drag", "linear air drag a = -gamma v", my_drag_params, my_drag);

static bf_status my_drag_create(void **self, const void *params,
                                const bf_balls *b, bf_err *err)
{
    (void)b;
    my_drag *d = malloc(sizeof *d);
    if (!d)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    *d = *(const my_drag *)params;
    *self = d;
    return BF_OK;
}

/* a_i = -gamma v_i at the stage's velocities v (cm/s^2) */
static int my_drag_accel(const void *self, const bf_balls *b, double t,
                         const double *x, const double *v, double *acc)
{
    (void)t;
    (void)x;
    const my_drag *d = self;
    for (size_t i = 0; i < b->n; i++)
        acc[i] -= d->gamma * v[i];
    return 0;
}

static const bf_effect_type my_drag_effect = {
    .name = "my_drag",
    .doc = "linear air drag a = -gamma v",
    .spec = &my_drag_spec,
    .flags = BF_EFFECT_VELOCITY, /* no potential: not conservative */
    .create = my_drag_create,
    .accel = my_drag_accel,
    .destroy = free,
};

/* ---- runs ---- */

static const char scene[] =
    "[scene]\n"
    "model = balls\n"
    "effects = gravity my_drag\n"
    "t_end = 2\n"
    "[gravity]\ng = 980\n"
    "[my_drag]\ngamma = 0.5\n"
    "[ball.1]\nposition = 0\nvelocity = 0\nmass = 1\n";

/* the velocity error at T against the exact v(T); the run's status */
static bf_status run(const bf_catalog *cat, const char *integrator,
                     double dt, double *err_v, bf_err *err)
{
    char set_it[64], set_dt[64];
    snprintf(set_it, sizeof set_it, "scene.integrator=%s", integrator);
    snprintf(set_dt, sizeof set_dt, "scene.dt=%.17g", dt);
    const char *sets[] = {set_it, set_dt};
    bf_run *r;
    bf_status st = bf_run_from_text(&r, cat, "drag_plugin", scene, sets, 2,
                                    NULL, err);
    if (st)
        return st;
    bf_sim *sim = bf_run_sim(r);
    st = bf_sim_run(sim, err);
    if (!st) {
        const double g = 980.0, gamma = 0.5, t = bf_sim_time(sim);
        const double v = bf_sim_get(sim, "balls/velocity", NULL)[0];
        *err_v = fabs(v + (g / gamma) * (1.0 - exp(-gamma * t)));
    }
    bf_run_free(r);
    return st;
}

/* the observed order of `integrator` between dt and dt/2; 1 if it is
 * not `nominal` within 0.15 */
static int order_check(const bf_catalog *cat, const char *integrator,
                       int nominal)
{
    bf_err err = {0};
    double e1 = 0, e2 = 0;
    if (run(cat, integrator, 0.04, &e1, &err) ||
        run(cat, integrator, 0.02, &e2, &err)) {
        printf("%s: failed: %s\n", integrator, err.msg);
        return 1;
    }
    const double p = log2(e1 / e2);
    const int ok = fabs(p - nominal) < 0.15;
    printf("%-7s |v - v(T)| = %.3e, %.3e cm/s at dt = 0.04, 0.02 s: "
           "observed order %.3f (nominal %d)%s\n",
           integrator, e1, e2, p, nominal, ok ? "" : "  << off");
    return !ok;
}

int main(void)
{
    bf_err err = {0};
    bf_catalog *cat = bf_catalog_new(bf_catalog_builtin());
    if (!cat || bf_catalog_add_effect(cat, &my_drag_effect, &err)) {
        fprintf(stderr, "drag_plugin: %s\n", err.msg);
        return 1;
    }
    int bad = order_check(cat, "rk4", 4);
    bad |= order_check(cat, "verlet", 2);
    /* a method for a = a(x) refuses, naming the key and the effect */
    double e = 0;
    bf_status st = run(cat, "mv2m", 0.02, &e, &err);
    const int refused = st == BF_EINPUT &&
                        strstr(err.msg, "[scene] integrator") &&
                        strstr(err.msg, "'my_drag'");
    printf("mv2m    %s (status %d): %s\n",
           refused ? "refused" : "NOT refused", (int)st, err.msg);
    bad |= !refused;
    bf_catalog_free(cat);
    return bad;
}
