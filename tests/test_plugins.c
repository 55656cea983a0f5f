/* test_plugins.c: an integrator and an effect written here, outside the
 * library, added to a catalog of the test's own (run.h, bf_catalog_new)
 * with one line each, and named by scenes like the built-in ones.  This
 * is the recipe of docs/architecture.md ("Adding a plug-in"): one file
 * (here, this one) and one table line.
 *
 *   integrator  symplectic Euler, v^{n+1} = v^n + dt a(x^n),
 *               x^{n+1} = x^n + dt v^{n+1}: order 1.  On the harmonic
 *               oscillator x'' = -x, x(0) = 1, to T = 2 its observed order
 *               between dt = 0.02 and 0.01 is 1 within 0.15 (the same
 *               margin as test_matrix.c for the built-in methods: both
 *               steps are deep in the asymptotic range, w dt <= 0.02).
 *   effect      a quartic well V = (q/4) (x - c)^4, a = -(q/m) (x - c)^3,
 *               [quartic] strength q (g/(cm^2 s^2)) and centre c (cm).
 *               From rest at x = c + A the motion is periodic with period
 *               T = 4 sqrt(2 m / q) / A * (varpi / 2), varpi / 2 =
 *               1.311028777146... the integral of (1 - u^4)^(-1/2) over
 *               [0, 1] (half the lemniscate constant).  RK4 run to the
 *               analytic T/4 finds the ball at x = c with speed
 *               A^2 sqrt(q / 2m), with a position error that falls by 2^4
 *               when dt halves (observed order 4 within 0.3, at 100 and
 *               200 steps per quarter period, far above round-off); the
 *               energy diagnostic, which sums the effect's potential,
 *               stays at the method's truncation level (< 1e-7
 *               relative), so force and potential agree.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "testutil.h"

/* ---- the integrator: one step, no keys of its own ---- */

static bf_status euler_init(bf_integrator *it, const void *params,
                            bf_err *err)
{
    (void)params;
    return bf_integrator_alloc_work(it, 1, err); /* a(x^n) */
}

static bf_status euler_step(bf_integrator *it, const bf_ode *ode, double t,
                            double dt, double *x, double *v, bf_err *err)
{
    double *a = it->work;
    bf_status st = bf_ode_eval(it, ode, t, x, v, a, err);
    if (st)
        return st; /* x, v untouched */
    for (size_t i = 0; i < ode->n; i++) {
        v[i] += dt * a[i];
        x[i] += dt * v[i];
    }
    it->count.steps++;
    return BF_OK;
}

static const bf_integrator_type symplectic_euler = {
    .name = "symplectic_euler",
    .doc = "symplectic Euler (kick, then drift), order 1",
    .order = 1,
    .evals_per_step = 1,
    .flags = BF_INT_POSITION_ONLY,
    .init = euler_init,
    .step = euler_step,
};

/* ---- the effect: a quartic well ----
 * The one the Python tests compile into a shared object and load
 * (tests/python/plugin.c): the same source, built into this test too. */
#include "python/plugin.c"

/* ---- the catalog of this file: the library's plus the two ---- */

static bf_catalog *catalog(void)
{
    bf_err err = {0};
    bf_catalog *c = bf_catalog_new(bf_catalog_builtin());
    ck_assert(c != NULL);
    ck_assert_msg(bf_catalog_add_integrator(c, &symplectic_euler, &err) ==
                      BF_OK, "%s", err.msg);
    ck_assert_msg(bf_catalog_add_effect(c, &quartic_well, &err) == BF_OK,
                  "%s", err.msg);
    return c;
}

/* Run scene text against catalog c with the overrides (NULL-terminated);
 * the ball's final position and velocity, the maximum relative energy
 * error. */
static void run(const bf_catalog *c, const char *text, const char *const *sets,
                double *x, double *v, double *energy_err)
{
    bf_scene *sc;
    bf_err err = {0};
    ck_assert_msg(bf_scene_load_string(&sc, "plugins.ini", text, &err) ==
                      BF_OK, "%s", err.msg);
    for (const char *const *s = sets; s && *s; s++)
        ck_assert_msg(bf_scene_set(sc, *s, "--set", &err) == BF_OK, "%s",
                      err.msg);
    ck_assert_msg(bf_catalog_resolve(c, sc, &err) == BF_OK, "%s", err.msg);
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, c, sc, NULL, &err) == BF_OK, "%s",
                  err.msg);
    ck_assert_msg(bf_sim_run(sim, &err) == BF_OK, "%s", err.msg);
    bf_ball_view view;
    const bf_model_type *mt = bf_sim_model_type(sim);
    ck_assert(mt->ball_view && mt->ball_view(bf_sim_model(sim), &view));
    *x = view.x[0];
    *v = view.v[0];
    *energy_err = bf_sim_max_energy_error(sim);
    bf_sim_free(sim);
    bf_scene_free(sc);
}

static const char *const oscillator =
    "[scene]\nintegrator = symplectic_euler\neffects = spring\n"
    "t_end = 2\noutput_every = 10\n[ball.1]\nposition = 1\nmass = 1\n"
    "[spring]\nstiffness = 1\n";

START_TEST(an_integrator_of_the_test_runs_at_its_order)
{
    bf_catalog *c = catalog();
    double x1, v1, e1, x2, v2, e2;
    run(c, oscillator, (const char *const[]){"scene.dt=0.02", NULL}, &x1, &v1,
        &e1);
    run(c, oscillator, (const char *const[]){"scene.dt=0.01", NULL}, &x2, &v2,
        &e2);
    const double err1 = fabs(x1 - cos(2.0)), err2 = fabs(x2 - cos(2.0));
    const double p = log(err1 / err2) / log(2.0);
    ck_assert_msg(fabs(p - 1) < 0.15, "observed order %.3f (errors %g, %g)",
                  p, err1, err2);
    /* symplectic: the energy error is O(dt) and bounded, here below dt */
    ck_assert_msg(e2 < 0.01 && e1 / e2 > 1.8, "energy errors %g, %g", e1, e2);
    bf_catalog_free(c);
}
END_TEST

static const char *const well =
    "[scene]\nintegrator = rk4\neffects = quartic\ndt = 0.01\nt_end = 1\n"
    "output_every = 10\n"
    "[ball.1]\nposition = 1.5\nmass = 2\n[quartic]\nstrength = 8\n"
    "centre = 0.5\n";

START_TEST(an_effect_of_the_test_gives_the_analytic_period)
{
    bf_catalog *c = catalog();
    const double m = 2, q = 8, A = 1.0, half_lemniscate = 1.3110287771460599;
    const double T = 4 * sqrt(2 * m / q) / A * half_lemniscate;
    /* a quarter period from rest at c + A: at the centre, at full speed
     * (q A^4 / 4 = m v^2 / 2); there an error of the period shows in x at
     * first order (at a turning point it would not) */
    const double v_centre = -A * A * sqrt(q / (2 * m));
    char set_t[64];
    snprintf(set_t, sizeof set_t, "scene.t_end=%.17g", T / 4);
    double err[2], eerr[2];
    const long steps[2] = {100, 200}; /* T/4 a whole number of steps */
    for (int k = 0; k < 2; k++) {
        char set_dt[64];
        snprintf(set_dt, sizeof set_dt, "scene.dt=%.17g", T / 4 / steps[k]);
        double x, v;
        run(c, well, (const char *const[]){set_t, set_dt, NULL}, &x, &v,
            &eerr[k]);
        err[k] = fabs(x - 0.5);
        ck_assert_msg(fabs(v - v_centre) < 1e-6, "v(T/4) = %.12g, not %.12g",
                      v, v_centre);
    }
    const double p = log(err[0] / err[1]) / log(2.0);
    ck_assert_msg(fabs(p - 4) < 0.3 && err[1] < 1e-6,
                  "observed order %.3f (errors %g, %g)", p, err[0], err[1]);
    ck_assert_msg(eerr[1] < 1e-7, "energy error %g", eerr[1]);
    bf_catalog_free(c);
}
END_TEST

START_TEST(the_catalog_refuses_what_a_scene_could_not_tell_apart)
{
    bf_err err = {0};
    bf_catalog *c = catalog();
    /* a second descriptor with a name already taken */
    ck_assert(bf_catalog_add_integrator(c, &symplectic_euler, &err) ==
              BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "symplectic_euler"), "%s", err.msg);
    ck_assert(bf_catalog_add_effect(c, &quartic_well, &err) == BF_EINPUT);
    /* the built-in catalog is not changed, and does not know them */
    ck_assert(bf_catalog_add_effect((bf_catalog *)bf_catalog_builtin(),
                                    &quartic_well, &err) == BF_EINPUT);
    ck_assert(bf_catalog_effect(bf_catalog_builtin(), "quartic") == NULL);
    bf_scene *sc;
    ck_assert(bf_scene_load_string(&sc, "plugins.ini", well, &err) == BF_OK);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ==
              BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "plugins.ini:3") && strstr(err.msg,
                                                             "quartic"),
                  "%s", err.msg);
    bf_scene_free(sc);
    /* the effect's keys are checked like the library's: a typo names the
     * file, the line and the key */
    ck_assert(bf_scene_load_string(&sc, "plugins.ini",
                                   "[scene]\neffects = quartic\ndt = 0.01\n"
                                   "t_end = 1\n[ball.1]\nposition = 1\n"
                                   "[quartic]\nstrenght = 2\n",
                                   &err) == BF_OK);
    ck_assert(bf_catalog_resolve(c, sc, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "plugins.ini:8") && strstr(err.msg,
                                                             "strenght"),
                  "%s", err.msg);
    bf_scene_free(sc);
    bf_catalog_free(c);
}
END_TEST

Suite *suite_plugins(void)
{
    Suite *s = suite_create("plugins");
    TCase *tc = tu_tcase("plugins");
    tcase_add_test(tc, an_integrator_of_the_test_runs_at_its_order);
    tcase_add_test(tc, an_effect_of_the_test_gives_the_analytic_period);
    tcase_add_test(tc, the_catalog_refuses_what_a_scene_could_not_tell_apart);
    suite_add_tcase(s, tc);
    return s;
}
