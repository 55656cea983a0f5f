/* test_returnmap.c: first-return maps and Lyapunov exponents of the balls
 * model (returnmap.h, lyapunov.h).
 *
 * Return map, against an independent solution: the lower ball falls from
 * rest at z0 = 0.2 cm onto the floor while the upper ball is far above in
 * free fall.  The lower ball touches at t_c = sqrt(2 (z0 - R)/g) with speed
 * v_c = g t_c; in contact (compression x = R - z) energy conservation
 * gives dx/dt = sqrt(v_c^2 + 2 g x - 4k/(5m) x^{5/2}), so the deepest
 * compression x_max is the root of the radicand and the lowest point is
 * reached at t* = t_c + integral_0^{x_max} dx / (dx/dt) (GSL QAGS; the
 * integrand has an integrable 1/sqrt singularity at x_max).  The upper
 * ball then is at z0' - g t*^2/2 with velocity -g t*.
 *
 * Lyapunov: x'' = x has exponent 1 and x'' = -x exponent 0; the estimator
 * must find them.  On the two-ball scenes of Fig. 2 the lower-heavier case
 * (1.2 g) must come out clearly more chaotic than the lower-lighter one.
 */
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "analysis/lyapunov.h"
#include "analysis/returnmap.h"
#include "diag/hermite.h"
#include "ballfilm/run.h"
#include "testutil.h"

static const double G = 980, K = 1e7, R = 0.1, Z0 = 0.2, M1 = 1.0,
                    Z2 = 5.0;

static double rate2(double x, double vc)
{
    return vc * vc + 2 * G * x - 4 * K / (5 * M1) * pow(x, 2.5);
}

static double inv_rate(double x, void *p)
{
    double r = rate2(x, *(double *)p);
    return r > 0 ? 1.0 / sqrt(r) : 0.0;
}

/* exact time and depth of the first lowest point */
static void exact_minimum(double *tstar, double *zmin)
{
    double tc = sqrt(2 * (Z0 - R) / G), vc = G * tc;
    double lo = 0, hi = 0.1; /* rate2(hi) < 0 */
    for (int k = 0; k < 200; k++) {
        double mid = 0.5 * (lo + hi);
        if (rate2(mid, vc) > 0)
            lo = mid;
        else
            hi = mid;
    }
    double xmax = lo;
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function f = {inv_rate, &vc};
    double res, abserr;
    gsl_integration_qags(&f, 0, xmax, 1e-14, 1e-13, 1000, w, &res, &abserr);
    gsl_integration_workspace_free(w);
    *tstar = tc + res;
    *zmin = R - xmax;
}

static const char *scene =
    "[scene]\nintegrator = mv2m\neffects = gravity floor contact\n"
    "dt = 1e-4\nt_end = 0.03\n"
    "[return_map]\nenabled = yes\n"
    "[ball.1]\nposition = 0.2\nmass = 1\n[ball.2]\nposition = 5\nmass = 1\n";

/* first return-map point of `scene` with overrides */
static void first_point(const char *s1, const char *s2, const char *s3,
                        double *t, double *z, double *v, double *zt)
{
    bf_sim *sim = tu_run_scene(scene, s1, s2, s3, NULL);
    const bf_retmap *rm = bf_sim_observer(sim, &bf_retmap_observer);
    ck_assert(rm != NULL);
    const double *ct, *cz, *cv, *czt;
    size_t n = bf_retmap_points(rm, &ct, &cz, &cv, &czt);
    ck_assert_msg(n == 1, "%zu points", n);
    *t = ct[0];
    *z = cz[0];
    *v = cv[0];
    *zt = czt[0];
    bf_sim_free(sim);
}

START_TEST(located_inside_the_step)
{
    double te, zmin;
    exact_minimum(&te, &zmin);
    /* sanity of the exact solution: contact starts at 0.01429 s and lasts
     * about 2.7 ms, so the lowest point is ~1.3 ms later */
    ck_assert(te > 0.0150 && te < 0.0160 && zmin > 0.08 && zmin < 0.1);
    /* The located time differs from the exact one by the integrators'
     * own error of the trajectory (measured at dt = 1e-4: MV2M 8.6e-8 s,
     * RK4 1.7e-9 s; Verlet 1.1e-6 s, so Verlet is run at 1e-5: ~1e-8 s)
     * plus the interpolation error; the bound 2e-3 dt is 250 times below
     * the dt/2 a nearest-step map could be off by. */
    struct {
        const char *integ, *dt, *extra;
        double tol_t;
    } cases[] = {
        {"scene.integrator=mv2m", "scene.dt=1e-4", NULL, 2e-7},
        {"scene.integrator=rk4", "scene.dt=1e-4", NULL, 2e-7},
        {"scene.integrator=verlet", "scene.dt=1e-5", NULL, 2e-8},
        /* ARKODE rootfinding, synchronised every 1 ms */
        {"scene.integrator=arkode", "scene.dt=1e-3", "integrator.rtol=1e-10",
         1e-9},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double t, z, v, zt;
        first_point(cases[k].integ, cases[k].dt, cases[k].extra, &t, &z, &v,
                    &zt);
        ck_assert_msg(fabs(t - te) < cases[k].tol_t,
                      "%s %s: t* = %.12g, exact %.12g (diff %.2e)",
                      cases[k].integ, cases[k].dt, t, te, t - te);
        ck_assert_msg(fabs(zt - zmin) < 1e-6, "%s: depth %.12g vs %.12g",
                      cases[k].integ, zt, zmin);
        /* the upper ball in free fall: interpolated state consistent with
         * the located time (exact for MV2M/Verlet/RK4 in free fall) */
        ck_assert_msg(fabs(z - (Z2 - 0.5 * G * t * t)) < 1e-10 &&
                          fabs(v + G * t) < 1e-8,
                      "%s: (z, v) = (%.12g, %.12g) at t = %.12g", cases[k].integ,
                      z, v, t);
    }
}
END_TEST

/* Every recorded point is a floor contact of the lower ball; times
 * increase; the multi-minimum count matches the stored column; the
 * lower-heavier scene has contacts with more than one minimum. */
START_TEST(two_balls_map_invariants)
{
    bf_sim *sim = tu_run_scene("[scene]\neffects = gravity floor contact\n"
                               "dt = 1e-4\nt_end = 60\noutput_every = 1000\n"
                               "[return_map]\nenabled = yes\n"
                               "[ball.1]\nposition = 0.2\nmass = 1.2\n"
                               "[ball.2]\nposition = 0.5\nmass = 1\n",
                               NULL);
    bf_results a;
    bf_sim_results(sim, &a);
    const bf_retmap *rm = bf_sim_observer(sim, &bf_retmap_observer);
    const double *t, *z, *v, *zt;
    size_t n = bf_retmap_points(rm, &t, &z, &v, &zt);
    ck_assert(a.has_return_map && n == a.map_points && n > 1000);
    for (size_t k = 0; k < n; k++) {
        ck_assert_msg(zt[k] < R, "point %zu: lower ball at %g", k, zt[k]);
        ck_assert(z[k] > zt[k]);
        if (k)
            ck_assert(t[k] > t[k - 1] + 1e-3); /* one per contact */
    }
    ck_assert_msg(a.map_multi_minima > 0, "no multi-minimum contact in 60 s");
    bf_sim_free(sim);
}
END_TEST

/* x'' = s x is not a built-in effect: drive a one-ball system whose force
 * callback is replaced, through the Lyapunov module directly. */
static int inverted(void *ctx, double t, const double *x, const double *v,
                    double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = x[0];
    return 0;
}

static double lyapunov_of(bf_accel_fn f, double T)
{
    /* started away from the equilibrium x = 0, so that the run moves */
    bf_scene *sc = tu_scene("[scene]\nintegrator = verlet\ndt = 0.01\n"
                            "t_end = 1\n[lyapunov]\nenabled = yes\ntau = 1\n"
                            "renormalise_every = 0.1 s\n"
                            "[ball.1]\nposition = 1e-3\nvelocity = 2e-3\n");
    bf_ballsys *sys;
    bf_err err = {0};
    ck_assert(bf_ballsys_from_scene(&sys, bf_catalog_builtin(), sc, &err) == BF_OK);
    sys->ode.accel = f;
    /* the analysis as the time loop drives it, over the ball view */
    bf_lyap_keys keys;
    bf_scene_fill(sc, "lyapunov", &bf_lyap_spec, &keys);
    bf_ball_view view;
    bf_ballsys_view(sys, &view);
    bf_run_ctx run = {0.01, T, lround(T / 0.01), 1, 0};
    bf_analysis_env env = {&view, &run, NULL, NULL};
    void *ly;
    ck_assert(bf_lyap_analysis.create(&ly, &keys, &env, &err) == BF_OK && ly);
    long n = lround(T / 0.01);
    const double x0 = sys->b.x[0];
    for (long s = 0; s < n; s++) {
        ck_assert(bf_ballsys_step(sys, s * 0.01, 0.01, &err) == BF_OK);
        ck_assert(bf_lyap_observer.after_step(ly, s + 1, s * 0.01, 0.01,
                                              &err) == BF_OK);
    }
    bf_results r;
    bf_lyap_observer.results(ly, &r);
    double tr = r.lyapunov_time, l = r.lyapunov_exponent;
    ck_assert(fabs(tr - T) < 1e-9);
    /* the run itself followed the replaced force */
    ck_assert(f == inverted ? sys->b.x[0] > 1e3 * x0 : fabs(sys->b.x[0]) < 0.01);
    bf_lyap_observer.destroy(ly);
    bf_ballsys_free(sys);
    bf_scene_free(sc);
    return l;
}

START_TEST(lyapunov_of_linear_systems)
{
    /* x'' = x: the separation grows as e^t once aligned with the unstable
     * direction (1, 1); the initial direction (1, 1)/sqrt2 in (x, tau v)
     * with tau = 1 is already aligned, so the estimate is 1 up to Verlet's
     * O(dt^2) error of the growth rate.  (10 s: the run itself grows as
     * e^t, and at e^20 its round-off would reach 1% of d0.) */
    double l1 = lyapunov_of(inverted, 10);
    ck_assert_msg(fabs(l1 - 1) < 1e-3, "x'' = x: %g", l1);
    /* x'' = -x with tau = 1/omega: the distance is conserved (Verlet
     * conserves a quadratic form within O(dt^2)) */
    double l0 = lyapunov_of(tu_accel_harmonic, 100);
    ck_assert_msg(fabs(l0) < 1e-3, "x'' = -x: %g", l0);
}
END_TEST

/* The paper's claim in numbers, over 30 s (CI horizon): lower ball 1.2 g
 * (upper lighter) chaotic, 0.8 g (upper heavier) much less so.  The 1000 s
 * values (make fig2) are 23 1/s and 3 1/s at dt = 1e-4. */
START_TEST(fig2_exponents_differ)
{
    double l[2];
    const char *m[2] = {"ball.1.mass=1.2", "ball.1.mass=0.8"};
    for (int k = 0; k < 2; k++) {
        bf_sim *sim = tu_run_scene("[scene]\neffects = gravity floor contact\n"
                                   "dt = 1e-4\nt_end = 30\n"
                                   "output_every = 1000\n"
                                   "[lyapunov]\nenabled = yes\n"
                                   "[ball.1]\nposition = 0.2\n"
                                   "[ball.2]\nposition = 0.5\nmass = 1\n",
                                   m[k], NULL);
        bf_results a;
        bf_sim_results(sim, &a);
        ck_assert(a.has_lyapunov);
        l[k] = a.lyapunov_exponent;
        bf_sim_free(sim);
    }
    ck_assert_msg(l[0] > 10 && l[0] > 4 * l[1],
                  "lower 1.2 g: %g 1/s, lower 0.8 g: %g 1/s", l[0], l[1]);
}
END_TEST

/* [compare] a = verlet, b = alpha (1/8) along MV2M: the difference of the
 * velocity formulas 2.19 and 2.20 is exactly zero while both balls fly
 * freely (both are exact for a constant force) and non-zero in some
 * collision rows (Fig. 4). */
START_TEST(compare_zero_in_free_fall)
{
    const char *out = tu_tmp("compare.h5");
    char *e = NULL;
    int rc = tu_run(NULL, &e, "run", tu_repo("runs/two_balls_B.ini"), "-o", out,
                    "-q", "--set", "scene.t_end=2", "--set",
                    "scene.output_every=1", "--set", "compare.a=verlet", NULL);
    ck_assert_msg(rc == 0, "%s", e);
    free(e);
    bf_err err = {0};
    double *dv, *x;
    size_t n, c, n2, c2;
    ck_assert(bf_h5_read(out, "/compare/dv", &dv, &n, &c, &err) == BF_OK);
    ck_assert(bf_h5_read(out, "/balls/position", &x, &n2, &c2, &err) == BF_OK);
    ck_assert(n == n2 && c == 2 && n == 20001);
    size_t free_rows = 0, nonzero = 0;
    for (size_t k = 0; k < n; k++) {
        /* well clear of floor and each other at the start and end of the
         * step (0.15 cm margin > 1e-4 s * 40 cm/s) */
        int flying = x[2 * k] > 0.105 && x[2 * k + 1] - x[2 * k] > 0.205;
        if (flying) {
            free_rows++;
            ck_assert_msg(dv[2 * k] == 0 && dv[2 * k + 1] == 0,
                          "row %zu: dv = %g, %g in free flight", k, dv[2 * k],
                          dv[2 * k + 1]);
        }
        nonzero += dv[2 * k + 1] != 0;
    }
    ck_assert(free_rows > n / 2 && nonzero > 100);
    free(dv);
    free(x);
}
END_TEST

/* With a damped, driven floor the ball system integrates the work of the
 * non-conservative forces as two more ODE components after the balls
 * (bf_ode.n = balls + 2, docs/forces.md).  The return map's forces, the
 * Lyapunov shadow and the compared steps go through the same callback and
 * integrators, so their buffers must hold every component: a buffer of
 * the balls only was overrun at the first contact (heap corruption, or
 * an AddressSanitizer report).  The run must end normally with its map
 * points, a finite exponent and the compared velocities. */
START_TEST(analyses_hold_the_work_components)
{
    const char *scene = tu_write(
        "work.ini",
        "[scene]\nmodel = balls\nintegrator = rk4\neffects = gravity floor\n"
        "dt = 2e-5\nt_end = 0.5\noutput_every = 100\n"
        "[integrator]\nevents = yes\n"
        "[return_map]\nenabled = yes\ntrigger = 1\nrecord = 1\n"
        "[lyapunov]\nenabled = yes\n"
        "[compare]\na = rk4\nb = rk3\n"
        "[gravity]\ng = 980\n"
        "[floor]\nk = 1e8\nrestitution = 0.5\namplitude = 0.08\n"
        "frequency = 20\n"
        "[ball.1]\nposition = 1\nmass = 1\nradius = 0.1\n");
    const char *out = tu_tmp("work.h5");
    char *e = NULL;
    int rc = tu_run(NULL, &e, "run", scene, "-o", out, "-q", NULL);
    ck_assert_msg(rc == 0, "status %d: %s", rc, e);
    free(e);
    bf_err err = {0};
    double *t, *dv;
    size_t n, c, nr, cr;
    ck_assert(bf_h5_read(out, "/return_map/time", &t, &n, &c, &err) == BF_OK);
    ck_assert(bf_h5_read(out, "/compare/dv", &dv, &nr, &cr, &err) == BF_OK);
    /* dropped from 1 cm: the first impact after 0.043 s */
    ck_assert_msg(n >= 1 && t[0] > 0.04, "%zu points, first at %g s", n,
                  n ? t[0] : 0.0);
    ck_assert(cr == 1 && nr > 200 && isfinite(tu_absmax(dv, nr)));
    free(t);
    free(dv);
}
END_TEST

/* An adaptive integrator cannot feed the two-trajectory estimate. */
START_TEST(lyapunov_refuses_adaptive)
{
    char msg[1024];
    bf_status st = tu_scene_error(
        "[scene]\nintegrator = arkode\neffects = gravity floor\ndt = 1e-3\n"
        "t_end = 1\n[lyapunov]\nenabled = yes\n[ball.1]\nposition = 0.2\n",
        msg, sizeof msg);
    ck_assert_int_eq(st, BF_EINPUT);
    ck_assert_msg(strstr(msg, "fixed-step"), "%s", msg);
}
END_TEST

/* The slope's zero by two halvings per pass after the proved shortcut
 * (diag/hermite.h, bf_hermite_slope_root) is the plain bisection's, one
 * halving at a time from [0, 1], to the bit: on random steps, on zeros
 * near 0 (where the 60-halving cap, not adjacency, ends the search) and
 * near 1, where the slope is 0 at theta = 1, on steps like the balls' and
 * on slopes made to defeat the shortcut. */
static double bisect_one_at_a_time(double D, double d0, double d1)
{
    double lo = 0, hi = 1;
    for (int k = 0; k < 60; k++) {
        double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi)
            break;
        if (bf_hermite_slope_mean(mid, D, d0, d1) < 0)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* xorshift64: a uniform double in [0, 1) */
static double uniform(unsigned long long *seed)
{
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    return (double)(*seed >> 11) * 0x1p-53;
}

/* the zero of one slope both ways, to the bit; 1 if the shortcut of
 * bf_hermite_slope_skip was taken */
static int same_root(double D, double d0, double d1)
{
    double a = bf_hermite_slope_root(D, d0, d1),
           b = bisect_one_at_a_time(D, d0, d1);
    if (memcmp(&a, &b, sizeof a) != 0)
        ck_abort_msg("D = %a, d0 = %a, d1 = %a: %a against %a", D, d0, d1, a,
                     b);
    double lo = 0, hi = 1;
    int k = 0;
    bf_hermite_slope_skip(D, d0, d1, &lo, &hi, &k);
    return k > 0;
}

START_TEST(slope_root_is_the_bisection)
{
    unsigned long long seed = 88172645463325252ull;
    long skipped = 0, cases = 0;
    for (int c = 0; c < 200000; c++) {
        double u1 = uniform(&seed), u2 = uniform(&seed), u3 = uniform(&seed);
        /* d0 < 0 <= d1 over many scales; the mean slope anywhere */
        double d0 = -pow(10.0, 8 * u1 - 6), d1 = pow(10.0, 8 * u2 - 6) - 1e-6;
        double D = (u3 - 0.5) * 2e2;
        if (c % 7 == 0)
            d0 = -1e-300 * (1 + u1); /* the zero right at theta = 0 */
        if (c % 11 == 0)
            d1 = 0.0; /* the zero at theta = 1 */
        if (!(d1 >= 0))
            d1 = 0.0;
        same_root(D, d0, d1);
    }
    /* Steps like the balls' lowest points (q nearly linear from d0 to d1,
     * over many scales): the shortcut must be taken nearly always.  Then
     * slopes made to defeat it: q' nearly 0 at theta = 0 or 1 (either
     * sign), a double zero inside (q = A (th - p)^2 - e), the zero within
     * a few ulps of 0 or 1. */
    for (int c = 0; c < 200000; c++) {
        double u1 = uniform(&seed), u2 = uniform(&seed), u3 = uniform(&seed),
               u4 = uniform(&seed);
        double s = pow(10.0, 12 * u4 - 6);
        double d0 = -s * (0.01 + u1), d1 = s * (0.01 + u2);
        double D = 0.5 * (d0 + d1) + s * 0.1 * (u3 - 0.5);
        cases++;
        skipped += same_root(D, d0, d1);
        double g = s * pow(10.0, -16 * u3) * (u1 < 0.5 ? -1 : 1);
        same_root((2 * d0 + 4 * d1 - g) / 6, d0, d1); /* q'(1) = g */
        same_root((g + 4 * d0 + 2 * d1) / 6, d0, d1); /* q'(0) = g */
        double A = s, p = u3, e = A * p * p * (1 + pow(10.0, -15 * u2));
        /* q = A th^2 - 2Ap th + (Ap^2 - e): d0, d1 and D from A, B, C */
        double C = A * p * p - e, Bq = -2 * A * p;
        double q1 = A + Bq + C;
        if (q1 >= 0)
            same_root((Bq + 4 * C + 2 * q1) / 6, C, q1);
        same_root(D, -s * 0x1p-52 * u1, d1);
        same_root(D, d0, s * 0x1p-52 * u2);
    }
    ck_assert_msg(skipped > cases * 9 / 10,
                  "shortcut taken in %ld of %ld ball-like steps", skipped,
                  cases);
}
END_TEST

Suite *suite_returnmap(void)
{
    Suite *s = suite_create("returnmap");
    TCase *tc = tu_tcase("returnmap");
    tcase_add_test(tc, located_inside_the_step);
    tcase_add_test(tc, slope_root_is_the_bisection);
    tcase_add_test(tc, two_balls_map_invariants);
    tcase_add_test(tc, lyapunov_of_linear_systems);
    tcase_add_test(tc, fig2_exponents_differ);
    tcase_add_test(tc, lyapunov_refuses_adaptive);
    tcase_add_test(tc, compare_zero_in_free_fall);
    tcase_add_test(tc, analyses_hold_the_work_components);
    suite_add_tcase(s, tc);
    return s;
}
