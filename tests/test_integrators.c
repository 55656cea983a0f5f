/* test_integrators.c: the fixed-step integrators against analysis.
 *
 * Harmonic oscillator x'' = -x (omega = 1, Yasuda sec. 2.3):
 *  - one MV2M step is the matrix of eq. 2.25 (to round-off);
 *  - the quadratic form Q that eq. 2.25 multiplies by exactly
 *    det = 1 - dt^6/72 decays as det^n (the amplitude as det^{n/2});
 *  - one alpha-family step has the determinant derived in alpha.c,
 *    1 + (1/4 - alpha) dt^4 (Verlet position update) or 1 - alpha dt^4/2
 *    (trapezoid);
 *  - observed global orders: Verlet 2, MV2M 3, alpha 2, RK3 3, RK4 4,
 *    implicit mid-point 2.
 * The orders are also measured on a nonlinear problem with a known
 * solution, x'' = 2 x^3, x(0) = 1, v(0) = -1, x = 1/(1 + t), because a
 * linear problem can hide order conditions.
 * Implicit mid-point: converged to its tolerance (the step is time
 * reversible to round-off), iterations counted, and a step too large for
 * the fixed-point iteration fails with BF_ENOCONV leaving the state alone.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/integrator.h"
#include "testutil.h"

static const bf_ode osc = {.n = 1, .accel = tu_accel_harmonic};

static int cubic(void *ctx, double t, const double *x, const double *v,
                 double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = 2.0 * x[0] * x[0] * x[0];
    return 0;
}

static const bf_ode nonlin = {.n = 1, .accel = cubic};

static bf_integrator *make(const char *name)
{
    return tu_integrator(name, NULL, 1);
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

/* Error at T against the exact solution: the oscillator x = cos t,
 * v = -sin t to T = 10, or the cubic problem x = 1/(1+t) to T = 1. */
static double final_error(const char *name, const char *keys, int nonlinear,
                          double dt)
{
    bf_integrator *it = tu_integrator(name, keys, 1);
    bf_err err = {0};
    const double T = nonlinear ? 1.0 : 10.0;
    long n = lround(T / dt);
    double x = 1, v = nonlinear ? -1 : 0;
    for (long k = 0; k < n; k++)
        ck_assert_msg(bf_integrator_step(it, nonlinear ? &nonlin : &osc, k * dt,
                                         dt, &x, &v, &err) == BF_OK,
                      "%s", err.msg);
    bf_integrator_free(it);
    double t = n * dt;
    if (nonlinear)
        return hypot(x - 1.0 / (1.0 + t), v + 1.0 / ((1.0 + t) * (1.0 + t)));
    return hypot(x - cos(t), v + sin(t));
}

/* Observed orders between four halvings of dt, each within 0.1 of the
 * nominal order (the errors stay well above round-off: > 1e-11).  On the
 * nonlinear problem the second-order methods start at a smaller dt: the
 * alpha = 1/4 trapezoid variant has a large dt^3 term (observed 1.73, 1.88,
 * 1.94, 1.97, 1.99 from dt = 0.04 down). */
static void check_order_on(const char *name, const char *keys, int nonlinear,
                           double expect)
{
    const double d0 = !nonlinear ? 0.04 : expect > 2.5 ? 0.02 : 0.005;
    double dts[4] = {d0, d0 / 2, d0 / 4, d0 / 8};
    double e[4];
    for (int k = 0; k < 4; k++)
        e[k] = final_error(name, keys, nonlinear, dts[k]);
    for (int k = 0; k + 1 < 4; k++) {
        double p = log2(e[k] / e[k + 1]);
        ck_assert_msg(fabs(p - expect) < 0.1 && e[k + 1] > 1e-11,
                      "%s [%s] %s: observed order %.4f between dt=%g and %g "
                      "(errors %.3e, %.3e), expected %g",
                      name, keys ? keys : "", nonlinear ? "x''=2x^3"
                                                        : "oscillator",
                      p, dts[k], dts[k + 1], e[k], e[k + 1], expect);
    }
}

static void check_order(const char *name, const char *keys, double expect)
{
    check_order_on(name, keys, 0, expect);
    check_order_on(name, keys, 1, expect);
}

START_TEST(verlet_order_2) { check_order("verlet", NULL, 2.0); }
END_TEST

START_TEST(mv2m_order_3) { check_order("mv2m", NULL, 3.0); }
END_TEST

START_TEST(rk3_order_3) { check_order("rk3", NULL, 3.0); }
END_TEST

START_TEST(rk4_order_4) { check_order("rk4", NULL, 4.0); }
END_TEST

START_TEST(impmid_order_2) { check_order("impmid", NULL, 2.0); }
END_TEST

START_TEST(alpha_family_order_2)
{
    const char *keys[] = {"alpha=0", "alpha=0.125", "alpha=0.25",
                          "alpha=0;position=trapezoid",
                          "alpha=0.125;position=trapezoid",
                          "alpha=0.25;position=trapezoid"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        check_order("alpha", keys[k], 2.0);
}
END_TEST

/* One alpha step on x'' = -x: the columns of the step matrix give its
 * determinant, which alpha.c derives as 1 + (1/4 - alpha) dt^4 (Verlet
 * position update) and 1 - alpha dt^4 / 2 (trapezoid). */
START_TEST(alpha_family_determinant)
{
    const double alphas[] = {0.0, 0.125, 0.25}, dt = 0.3;
    for (int pos = 0; pos < 2; pos++)
        for (int k = 0; k < 3; k++) {
            char keys[128];
            snprintf(keys, sizeof keys, "alpha=%g;position=%s", alphas[k],
                     pos ? "trapezoid" : "verlet");
            bf_integrator *it = tu_integrator("alpha", keys, 1);
            bf_err err = {0};
            double x1 = 1, v1 = 0, x2 = 0, v2 = 1;
            ck_assert(bf_integrator_step(it, &osc, 0, dt, &x1, &v1, &err) == 0);
            ck_assert(bf_integrator_step(it, &osc, 0, dt, &x2, &v2, &err) == 0);
            double det = x1 * v2 - x2 * v1;
            double s4 = pow(dt, 4);
            double want = pos ? 1 - alphas[k] * s4 / 2
                              : 1 + (0.25 - alphas[k]) * s4;
            ck_assert_msg(fabs(det - want) < 1e-15, "%s: det %.17g, want %.17g",
                          keys, det, want);
            /* alpha = 0 with the trapezoid update needs no a(x^n) */
            ck_assert_uint_eq(it->count.evals,
                              pos && alphas[k] == 0 ? 2 : 4);
            bf_integrator_free(it);
        }
}
END_TEST

/* The implicit mid-point rule is time-reversible: a step of -dt from the
 * result returns to the start, to the iteration tolerance. */
START_TEST(impmid_reversible_and_counted)
{
    bf_integrator *it = make("impmid");
    bf_err err = {0};
    double x = 0.3, v = -0.7;
    ck_assert(bf_integrator_step(it, &nonlin, 0, 0.1, &x, &v, &err) == BF_OK);
    unsigned long long it1 = it->count.iterations;
    ck_assert(bf_integrator_step(it, &nonlin, 0.1, -0.1, &x, &v, &err) == BF_OK);
    ck_assert_msg(fabs(x - 0.3) < 1e-14 && fabs(v + 0.7) < 1e-14,
                  "back to (%.17g, %.17g)", x, v);
    /* contraction ~ dt^2/4 |da/dx| = 0.0025 * 6 x^2: a few iterations to
     * reach 1e-14, each with one evaluation, plus the predictor's */
    ck_assert(it1 >= 2 && it1 <= 10);
    ck_assert_uint_eq(it->count.evals, it->count.iterations + 2);
    ck_assert_uint_eq(it->count.steps, 2);
    bf_integrator_free(it);
}
END_TEST

static int stiff(void *ctx, double t, const double *x, const double *v,
                 double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = -1e4 * x[0];
    return 0;
}

/* dt^2/4 * 1e4 = 25 > 1: the fixed-point iteration diverges; the step
 * fails with BF_ENOCONV, says why, and leaves the state at t. */
START_TEST(impmid_no_convergence_fails)
{
    const bf_ode o = {.n = 1, .accel = stiff};
    bf_integrator *it = tu_integrator("impmid", "max_iter=20", 1);
    bf_err err = {0};
    double x = 1, v = 0;
    bf_status st = bf_integrator_step(it, &o, 0, 0.1, &x, &v, &err);
    ck_assert_int_eq(st, BF_ENOCONV);
    ck_assert_msg(strstr(err.msg, "did not converge") && strstr(err.msg, "20"),
                  "%s", err.msg);
    ck_assert(x == 1 && v == 0);
    ck_assert_uint_eq(it->count.steps, 0);
    bf_integrator_free(it);
}
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
    tcase_add_test(tc, rk3_order_3);
    tcase_add_test(tc, rk4_order_4);
    tcase_add_test(tc, impmid_order_2);
    tcase_add_test(tc, alpha_family_order_2);
    tcase_add_test(tc, alpha_family_determinant);
    tcase_add_test(tc, impmid_reversible_and_counted);
    tcase_add_test(tc, impmid_no_convergence_fails);
    suite_add_tcase(s, tc);
    return s;
}
