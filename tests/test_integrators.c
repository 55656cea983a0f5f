/* test_integrators.c: Verlet and MV2M against analysis on the harmonic
 * oscillator x'' = -x (omega = 1, Yasuda sec. 2.3).
 *
 *  - one MV2M step is the matrix of eq. 2.25 (to round-off);
 *  - the quadratic form Q that eq. 2.25 multiplies by exactly
 *    det = 1 - dt^6/72 decays as det^n (the amplitude as det^{n/2});
 *  - the observed global orders are 2 (Verlet) and 3 (MV2M).
 */
#include <math.h>
#include <stdlib.h>

#include "ballfilm/integrator.h"
#include "testutil.h"

static int harmonic(void *ctx, double t, const double *x, const double *v,
                    double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = -x[0];
    return 0;
}

static const bf_ode osc = {1, harmonic, NULL, 0, 0};

static bf_integrator *make(const char *name)
{
    bf_integrator *it;
    bf_err err = {0};
    ck_assert_msg(bf_integrator_create(&it, name, 1, NULL, &err) == BF_OK, "%s",
                  err.msg);
    return it;
}

START_TEST(mv2m_step_is_matrix_2_25)
{
    bf_integrator *it = make("mv2m");
    bf_err err = {0};
    const double dt = 0.3;
    const double M[2][2] = {
        {1 - dt * dt / 2 + pow(dt, 4) / 12, dt - pow(dt, 3) / 6},
        {-dt + pow(dt, 3) / 6, 1 - dt * dt / 2},
    };
    const double e[2][2] = {{1, 0}, {0, 1}};
    for (int c = 0; c < 2; c++) {
        double x = e[c][0], v = e[c][1];
        ck_assert(bf_integrator_step(it, &osc, 0, dt, &x, &v, &err) == BF_OK);
        ck_assert_msg(fabs(x - M[0][c]) < 4e-16 && fabs(v - M[1][c]) < 4e-16,
                      "column %d: (%.17g, %.17g) vs (%.17g, %.17g)", c, x, v,
                      M[0][c], M[1][c]);
    }
    ck_assert(it->count.evals == 6 && it->count.steps == 2);
    bf_integrator_free(it);
}
END_TEST

START_TEST(mv2m_amplitude_decays_as_det_power)
{
    bf_integrator *it = make("mv2m");
    bf_err err = {0};
    const double dt = 0.1;
    const long n = 20000;
    /* eq. 2.25 = [[a b] [c d]]; Q(x,v) = -c x^2 + (a-d) x v + b v^2 obeys
     * Q(M y) = det(M) Q(y) for any 2x2 M. */
    const double a = 1 - dt * dt / 2 + pow(dt, 4) / 12, b = dt - pow(dt, 3) / 6,
                 c = -b, d = 1 - dt * dt / 2;
    const double det = a * d - b * c;
    ck_assert(fabs(det - (1 - pow(dt, 6) / 72)) < 1e-15);
    double x = 1, v = 0;
    double q0 = -c * x * x + (a - d) * x * v + b * v * v;
    for (long k = 0; k < n; k++)
        ck_assert(bf_integrator_step(it, &osc, k * dt, dt, &x, &v, &err) == BF_OK);
    double q = -c * x * x + (a - d) * x * v + b * v * v;
    double want = pow(det, (double)n);
    /* 1 - want = 2.8e-4: the decay is resolved to 1e-10 relative, far above
     * the round-off of 2e4 steps (~1e-12) */
    ck_assert_msg(fabs(q / q0 - want) < 1e-10, "Q ratio %.15g, det^n %.15g",
                  q / q0, want);
    /* the amplitude decays as det^(n/2) */
    ck_assert(fabs(sqrt(q / q0) - pow(det, n / 2.0)) < 1e-10);
    bf_integrator_free(it);
}
END_TEST

/* Error at T = 10 against the exact solution x = cos t, v = -sin t. */
static double final_error(const char *name, double dt)
{
    bf_integrator *it = make(name);
    bf_err err = {0};
    const double T = 10.0;
    long n = lround(T / dt);
    double x = 1, v = 0;
    for (long k = 0; k < n; k++)
        ck_assert(bf_integrator_step(it, &osc, k * dt, dt, &x, &v, &err) == BF_OK);
    bf_integrator_free(it);
    return hypot(x - cos(n * dt), v + sin(n * dt));
}

static void check_order(const char *name, double expect)
{
    double dts[] = {0.04, 0.02, 0.01, 0.005};
    double e[4];
    for (int k = 0; k < 4; k++)
        e[k] = final_error(name, dts[k]);
    for (int k = 0; k + 1 < 4; k++) {
        double p = log2(e[k] / e[k + 1]);
        ck_assert_msg(fabs(p - expect) < 0.1,
                      "%s: observed order %.4f between dt=%g and %g (errors "
                      "%.3e, %.3e), expected %g",
                      name, p, dts[k], dts[k + 1], e[k], e[k + 1], expect);
    }
}

START_TEST(verlet_order_2) { check_order("verlet", 2.0); }
END_TEST

START_TEST(mv2m_order_3) { check_order("mv2m", 3.0); }
END_TEST

/* Verlet reuses its end-of-step force: one evaluation per step, and the
 * cache notices when the caller moves x or bumps the epoch. */
START_TEST(verlet_force_cache)
{
    bf_integrator *it = make("verlet");
    bf_err err = {0};
    double x = 1, v = 0;
    bf_ode o = osc;
    for (int k = 0; k < 10; k++)
        bf_integrator_step(it, &o, k * 0.1, 0.1, &x, &v, &err);
    ck_assert_uint_eq(it->count.evals, 11);
    x += 0.5; /* moved by the caller: must re-evaluate */
    bf_integrator_step(it, &o, 1.0, 0.1, &x, &v, &err);
    ck_assert_uint_eq(it->count.evals, 13);
    o.epoch++; /* force field changed: must re-evaluate */
    bf_integrator_step(it, &o, 1.1, 0.1, &x, &v, &err);
    ck_assert_uint_eq(it->count.evals, 15);
    bf_integrator_free(it);
}
END_TEST

Suite *suite_integrators(void)
{
    Suite *s = suite_create("integrators");
    TCase *tc = tu_tcase("oscillator");
    tcase_add_test(tc, mv2m_step_is_matrix_2_25);
    tcase_add_test(tc, mv2m_amplitude_decays_as_det_power);
    tcase_add_test(tc, verlet_order_2);
    tcase_add_test(tc, mv2m_order_3);
    tcase_add_test(tc, verlet_force_cache);
    suite_add_tcase(s, tc);
    return s;
}
