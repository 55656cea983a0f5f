/* test_stability.c: energy behaviour and the stability limits.
 *
 * Drift on the harmonic oscillator x'' = -x, dt = 0.2, 10^4 steps, where
 * everything is known in closed form: the RK methods multiply the energy
 * by |R(i dt)|^2 per step exactly (their step is a function of the skew
 * matrix, hence normal), RK3 |R|^2 = 1 - dt^4/12 + dt^6/36, RK4
 * 1 - dt^6/72 + dt^8/576; MV2M scales the quadratic form of eq. 2.25 by
 * det = 1 - dt^6/72, so its energy drifts at RK4's leading rate (it is not
 * symplectic, whatever its good behaviour at contacts); Verlet's energy
 * oscillates (by about dt^2/4) without drift and the implicit mid-point
 * rule conserves it to its iteration tolerance.
 *
 * Drift on the bouncing ball (k = 1e7, dt = 1e-4): measured in free flight
 * (where every method here integrates exactly), so that the per-contact
 * error does not mask the trend; Verlet and the implicit mid-point rule
 * stay bounded, RK3 loses energy bounce after bounce; the alpha-family
 * with Verlet's position update gains energy for alpha = 0 and 1/8 (see
 * alpha.c), the trapezoid update with alpha = 1/8 loses it.
 *
 * Beyond a method's stable step a run stops with a clear message and keeps
 * a readable output file; a non-finite state is reported naming the ball.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/ballsys.h"
#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "testutil.h"

static double energy(const bf_ballsys *s)
{
    double k, p;
    bf_ballsys_energy(s, 0, &k, &p);
    return k + p;
}

/* E_n/E_0 on the oscillator after n steps, and the max/min over the first
 * and the last quarter of the run */
static void oscillator(const char *method, double dt, long n, double *ratio,
                       double *q1max, double *q4max)
{
    char text[512];
    snprintf(text, sizeof text,
             "[scene]\nintegrator = %s\neffects = spring\ndt = %g\n"
             "t_end = 1\n[spring]\nstiffness = 1\n[ball.1]\nposition = 1\n",
             method, dt);
    bf_ballsys *s = tu_ballsys(text);
    bf_err err = {0};
    const double e0 = energy(s);
    *q1max = *q4max = 0;
    for (long k = 0; k < n; k++) {
        ck_assert(bf_ballsys_step(s, k * dt, dt, &err) == BF_OK);
        double d = fabs(energy(s) / e0 - 1);
        if (k < n / 4 && d > *q1max)
            *q1max = d;
        if (k >= 3 * n / 4 && d > *q4max)
            *q4max = d;
    }
    *ratio = energy(s) / e0;
    bf_ballsys_free(s);
}

START_TEST(oscillator_drift_rates)
{
    const double h = 0.2;
    const long n = 10000;
    double r, a, b;
    /* RK: exactly |R|^(2n) (to round-off of 1e4 steps) */
    oscillator("rk3", h, n, &r, &a, &b);
    double want = pow(1 - pow(h, 4) / 12 + pow(h, 6) / 36, (double)n);
    ck_assert_msg(fabs(r / want - 1) < 1e-9, "rk3: E/E0 %.12g, |R|^2n %.12g",
                  r, want);
    ck_assert(r < 0.3); /* RK3 loses 70% in 1e4 steps */
    oscillator("rk4", h, n, &r, &a, &b);
    want = pow(1 - pow(h, 6) / 72 + pow(h, 8) / 576, (double)n);
    ck_assert_msg(fabs(r / want - 1) < 1e-9, "rk4: E/E0 %.12g, |R|^2n %.12g",
                  r, want);
    ck_assert(r < 0.992);
    /* MV2M: det^n up to the O(dt^3) oscillation of E about its quadratic
     * form (7e-4 here), against a drift of 9e-3 */
    oscillator("mv2m", h, n, &r, &a, &b);
    want = pow(1 - pow(h, 6) / 72, (double)n);
    ck_assert_msg(fabs(r / want - 1) < 2e-3, "mv2m: E/E0 %.8g, det^n %.8g", r,
                  want);
    ck_assert(b > 5e-3 && b > 3 * a);
    /* Verlet: bounded, the same band in the first and last quarter */
    oscillator("verlet", h, n, &r, &a, &b);
    ck_assert_msg(a > 1e-3 && a < 0.011 && fabs(b / a - 1) < 0.01,
                  "verlet: %g then %g", a, b);
    /* implicit mid-point: conserved to the iteration tolerance */
    oscillator("impmid", h, n, &r, &a, &b);
    ck_assert_msg(fabs(r - 1) < 1e-10 && b < 1e-10, "impmid: %g", r - 1);
}
END_TEST

/* Energy error in free flight at the end of each eighth of 5 s. */
static void flight_energy(const char *method, const char *keys, double e8[8])
{
    char text[512];
    snprintf(text, sizeof text,
             "[scene]\nintegrator = %s\neffects = gravity floor\ndt = 1e-4\n"
             "t_end = 1\n%s\n[ball.1]\nposition = 0.2\n",
             method, keys);
    bf_ballsys *s = tu_ballsys(text);
    bf_err err = {0};
    const double e0 = energy(s), dt = 1e-4;
    const long n = 50000;
    for (int q = 0; q < 8; q++)
        e8[q] = NAN;
    for (long k = 0; k < n; k++) {
        ck_assert(bf_ballsys_step(s, k * dt, dt, &err) == BF_OK);
        if (s->b.x[0] >= 0.1)
            e8[8 * k / n] = energy(s) / e0 - 1;
    }
    bf_ballsys_free(s);
}

static int monotone(const double e[8], int sign)
{
    for (int q = 1; q < 8; q++)
        if (sign * (e[q] - e[q - 1]) <= 0)
            return 0;
    return 1;
}

static double absmax(const double *e, int a, int b)
{
    double m = 0;
    for (int q = a; q < b; q++)
        m = fmax(m, fabs(e[q]));
    return m;
}

START_TEST(bouncing_ball_drift)
{
    double e[8];
    /* bounded: no growth from the first half to the second (measured
     * 2.6e-4 then 2.2e-4 for Verlet, 2.0e-4 then 1.1e-4 for impmid) */
    const char *bounded[] = {"verlet", "impmid"};
    for (int k = 0; k < 2; k++) {
        flight_energy(bounded[k], "", e);
        ck_assert_msg(absmax(e, 0, 8) < 1e-3 &&
                          absmax(e, 4, 8) < 2 * absmax(e, 0, 4),
                      "%s: %g then %g", bounded[k], absmax(e, 0, 4),
                      absmax(e, 4, 8));
    }
    /* RK3 loses energy at every bounce: monotone, 3.3% in 5 s */
    flight_energy("rk3", "", e);
    ck_assert_msg(monotone(e, -1) && e[7] < -0.02, "rk3: %g", e[7]);
    /* the alpha-family (dt = 1e-4): Verlet position update with alpha = 0
     * and 1/8 gains (+12% and +5% in 5 s), trapezoid with 1/8 loses */
    flight_energy("alpha", "[integrator]\nalpha = 0", e);
    ck_assert_msg(monotone(e, 1) && e[7] > 0.05, "alpha 0: %g", e[7]);
    flight_energy("alpha", "[integrator]\nalpha = 0.125", e);
    ck_assert_msg(monotone(e, 1) && e[7] > 0.02, "alpha 1/8: %g", e[7]);
    flight_energy("alpha", "[integrator]\nalpha = 0.125\nposition = trapezoid",
                  e);
    ck_assert_msg(monotone(e, -1) && e[7] < -0.01, "alpha 1/8 trap: %g", e[7]);
}
END_TEST

/* Verlet at dt = 2e-3 is far beyond its limit on the bouncing ball
 * (bench_stability: 7e-4): the scene's energy bound stops the run with
 * exit 3 and a message; the file holds the rows before, status unstable. */
START_TEST(beyond_the_limit_stops)
{
    const char *out = tu_tmp("unstable.h5");
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/bouncing_ball.ini"), "-o",
                    out, "-q", "--set", "scene.integrator=verlet", "--set",
                    "scene.dt=2e-3", NULL);
    ck_assert_int_eq(rc, 3);
    ck_assert_msg(strstr(err, "max_energy_error") && strstr(err, "too large"),
                  "%s", err);
    free(err);
    char *status = NULL;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_str(out, "/", "status", &status, &e) == BF_OK);
    ck_assert_str_eq(status, "unstable");
    free(status);
    double *t;
    size_t n0, n1;
    ck_assert(bf_h5_read(out, "/time", &t, &n0, &n1, &e) == BF_OK);
    ck_assert(n0 >= 1 && t[n0 - 1] < 100);
    free(t);
}
END_TEST

static int overflow(void *ctx, double t, const double *x, const double *v,
                    double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = 1e300 * 1e300 * x[0]; /* inf */
    a[1] = 0;
    return 0;
}

/* A non-finite state stops the step with BF_EUNSTABLE naming the ball. */
START_TEST(non_finite_state_named)
{
    bf_ballsys *s = tu_ballsys("[scene]\nintegrator = mv2m\ndt = 1e-3\n"
                             "t_end = 1\n[ball.1]\nposition = 1\n"
                             "[ball.2]\nposition = 2\n");
    s->ode.accel = overflow;
    bf_err err = {0};
    ck_assert_int_eq(bf_ballsys_step(s, 0, 1e-3, &err), BF_EUNSTABLE);
    ck_assert_msg(strstr(err.msg, "ball 1") && strstr(err.msg, "non-finite"),
                  "%s", err.msg);
    bf_ballsys_free(s);
}
END_TEST

Suite *suite_stability(void)
{
    Suite *s = suite_create("stability");
    TCase *tc = tu_tcase("stability");
    tcase_add_test(tc, oscillator_drift_rates);
    tcase_add_test(tc, bouncing_ball_drift);
    tcase_add_test(tc, beyond_the_limit_stops);
    tcase_add_test(tc, non_finite_state_named);
    suite_add_tcase(s, tc);
    return s;
}
