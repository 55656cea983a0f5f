/* test_matrix.c: every integrator of the catalog against every problem, in
 * the manner of GSL's ode-initval2 tests: the harmonic oscillator, the
 * bouncing ball, two falling balls, and a right-hand side that fails.  A
 * new integrator in the catalog is tested here without a line of its own.
 *
 *   oscillator  x'' = -x, x(0) = 1, to T = 2: fixed-step methods show their
 *               nominal order (bf_integrator_order) between dt = 0.02 and
 *               0.01 within +-0.15 (the error constants of these methods
 *               change by far less than 2^0.15 = 1.11 between the two
 *               steps: both are deep in the asymptotic range, w dt <=
 *               0.02); the adaptive method meets its tolerance (error at
 *               T below 100 rtol: the global error of a local-error
 *               control grows with the number of steps, ~100 here).
 *   bouncing    one ball under gravity on the Hertz floor, 2 s (4 floor
 *               contacts), and two balls with a Hertz contact between
 *               them: the maximum relative energy error falls at least by
 *               2 when dt halves.  The Hertz force k x^{3/2} is C^1 but not
 *               C^2 at the onset of a contact, so no method keeps its
 *               nominal order through contacts, but every one converges at
 *               least at first order there (2^1 = 2).
 *   failing     a force that cannot be evaluated beyond t = 0.5 s: the step
 *               that reaches it fails with a message and leaves x and v at
 *               their values at the start of the step.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "models/ballsys.h"
#include "testutil.h"

/* The catalog's integrators, each with its default parameters. */
static const bf_integrator_type *const *all_integrators(size_t *n)
{
    return bf_catalog_integrators(bf_catalog_builtin(), n);
}

static bf_integrator *make(const bf_integrator_type *t, size_t n)
{
    bf_integrator *it;
    bf_err err = {0};
    ck_assert_msg(bf_integrator_create(&it, t, n, NULL, &err) == BF_OK, "%s: %s",
                  t->name, err.msg);
    return it;
}

static const bf_ode osc = {.n = 1, .accel = tu_accel_harmonic};

/* |x(T) - cos T| after T/dt steps */
static double osc_error(const bf_integrator_type *t, double dt)
{
    bf_integrator *it = make(t, 1);
    bf_err err = {0};
    double x = 1, v = 0;
    const double T = 2;
    const long n = lround(T / dt);
    for (long k = 0; k < n; k++)
        ck_assert_msg(bf_integrator_step(it, &osc, k * dt, dt, &x, &v, &err) ==
                          BF_OK,
                      "%s: %s", t->name, err.msg);
    bf_integrator_free(it);
    return fabs(x - cos(T));
}

START_TEST(every_integrator_on_the_oscillator)
{
    size_t n;
    const bf_integrator_type *const *t = all_integrators(&n);
    for (size_t k = 0; k < n; k++) {
        double e1 = osc_error(t[k], 0.02), e2 = osc_error(t[k], 0.01);
        if (!(t[k]->flags & BF_INT_ADAPTIVE) && e2 < 1e-12) {
            /* order 6 (rkn6) is at round-off (1e-15) there: 0.1 and 0.05
             * are its asymptotic range (errors 5e-11, 8e-13) */
            e1 = osc_error(t[k], 0.1);
            e2 = osc_error(t[k], 0.05);
        }
        if (t[k]->flags & BF_INT_ADAPTIVE) {
            /* default rtol 1e-8 */
            ck_assert_msg(e2 < 100 * 1e-8, "%s: error %g", t[k]->name, e2);
            continue;
        }
        bf_integrator *it = make(t[k], 1);
        const int order = bf_integrator_order(it);
        bf_integrator_free(it);
        const double p = log(e1 / e2) / log(2.0);
        ck_assert_msg(fabs(p - order) < 0.15,
                      "%s: observed order %.3f, nominal %d (errors %g, %g)",
                      t[k]->name, p, order, e1, e2);
    }
}
END_TEST

static const char *const bouncing =
    "[scene]\neffects = gravity floor\ndt = 1e-4\nt_end = 2\n"
    "output_every = 1000\n[ball.1]\nposition = 1\nradius = 0.1\n";
static const char *const two =
    "[scene]\neffects = gravity floor contact\ndt = 1e-4\nt_end = 2\n"
    "output_every = 1000\n[ball.1]\nposition = 0.2\nmass = 0.8\n"
    "[ball.2]\nposition = 0.5\n";

/* the run's maximum relative energy error with integrator t and step dt */
static double energy_error(const char *scene, const bf_integrator_type *t,
                           double dt)
{
    char s1[96], s2[64];
    snprintf(s1, sizeof s1, "scene.integrator=%s", t->name);
    snprintf(s2, sizeof s2, "scene.dt=%.17g", dt);
    /* the adaptive method: internal steps of at most dt */
    char s3[64];
    snprintf(s3, sizeof s3, "integrator.max_step=%.17g", dt);
    bf_sim *sim = t->flags & BF_INT_ADAPTIVE
                      ? tu_run_scene(scene, s1, s2, s3, NULL)
                      : tu_run_scene(scene, s1, s2, NULL);
    ck_assert_msg(bf_sim_steps_done(sim) == bf_sim_steps_total(sim), "%s",
                  t->name);
    double e = bf_sim_max_energy_error(sim);
    bf_sim_free(sim);
    return e;
}

static void converges_through_contacts(const char *scene)
{
    size_t n;
    const bf_integrator_type *const *t = all_integrators(&n);
    for (size_t k = 0; k < n; k++) {
        if (t[k]->flags & BF_INT_ADAPTIVE)
            continue; /* its error is set by its tolerance, not by dt */
        double e1 = energy_error(scene, t[k], 2e-4);
        double e2 = energy_error(scene, t[k], 1e-4);
        /* an energy-conserving method (greenspan73) is at round-off at
         * both steps: nothing to halve */
        if (e1 < 1e-12 && e2 < 1e-12)
            continue;
        ck_assert_msg(e2 < 0.05 && e1 / e2 > 2.0,
                      "%s: energy errors %g at dt = 2e-4, %g at 1e-4",
                      t[k]->name, e1, e2);
    }
}

START_TEST(every_integrator_on_the_bouncing_ball)
{
    converges_through_contacts(bouncing);
}
END_TEST

START_TEST(every_integrator_on_two_balls)
{
    converges_through_contacts(two);
}
END_TEST

/* x'' = -x, undefined for t > 0.5 */
static int fails_late(void *ctx, double t, const double *x, const double *v,
                      double *a)
{
    (void)ctx;
    (void)v;
    if (t > 0.5)
        return 1;
    a[0] = -x[0];
    return 0;
}

START_TEST(every_integrator_with_a_failing_force)
{
    const bf_ode ode = {.n = 1, .accel = fails_late};
    size_t n;
    const bf_integrator_type *const *t = all_integrators(&n);
    for (size_t k = 0; k < n; k++) {
        bf_integrator *it = make(t[k], 1);
        bf_err err = {0};
        double x = 1, v = 0;
        const double dt = 0.1;
        long s = 0;
        bf_status st = BF_OK;
        double x0 = x, v0 = v;
        for (; s < 10 && !st; s++) {
            x0 = x;
            v0 = v;
            st = bf_integrator_step(it, &ode, s * dt, dt, &x, &v, &err);
        }
        ck_assert_msg(st != BF_OK, "%s: no failure", t[k]->name);
        /* the failing step is the one that needs a(t) beyond 0.5 s: the
         * fifth (0.4 -> 0.5 evaluates at 0.5 at most) or the sixth */
        ck_assert_msg(s == 5 || s == 6, "%s: failed in step %ld", t[k]->name,
                      s);
        ck_assert_msg(err.msg[0], "%s: no message", t[k]->name);
        ck_assert_msg(x == x0 && v == v0, "%s: the state moved in the failed "
                      "step (%g, %g) -> (%g, %g)", t[k]->name, x0, v0, x, v);
        bf_integrator_free(it);
    }
}
END_TEST

Suite *suite_matrix(void)
{
    Suite *s = suite_create("matrix");
    TCase *tc = tu_tcase("matrix");
    tcase_add_test(tc, every_integrator_on_the_oscillator);
    tcase_add_test(tc, every_integrator_on_the_bouncing_ball);
    tcase_add_test(tc, every_integrator_on_two_balls);
    tcase_add_test(tc, every_integrator_with_a_failing_force);
    suite_add_tcase(s, tc);
    return s;
}
