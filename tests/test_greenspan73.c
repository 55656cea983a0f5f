/* test_greenspan73.c: Greenspan's implicit, energy-conserving scheme (1973).
 *
 * - The discrete force: S_n(a,b) (b^2 - a^2) = 1/a^{n-1} - 1/b^{n-1} (the
 *   identity behind the exact conservation), its limit 2a S_n(a,a) =
 *   (n-1)/a^n, dS/db and the analytic Jacobian against finite differences.
 * - Energy: K + V conserved over the hexagon flows (V = 50, 300 at
 *   dt = 0.02; V = 1000 at dt = 0.1 with omega = 0.2 and at dt = 0.01) to a
 *   relative drift <= 1e-10 with a tight tolerance, also for the internal
 *   energy E - K_cm (10^4 times smaller than E at V = 50); with the
 *   listing's update (inertia 1) and gravity (the penetration example); and
 *   the drift grows when the tolerance is loose (the solve is the only
 *   error).  Momentum is conserved (g = 0, nothing fixed).
 * - Solvers: the listing's fixed point, dense Newton and sparse Newton
 *   (GMRES, with and without a Jacobian cutoff) reach the same solution.
 * - Order 2 on a vibrating pair (observed against a fine reference).
 * - Non-convergence (V = 1000, dt = 0.1, omega = 1): exit 4 with a message
 *   naming the step, the output readable; with on_failure = halve the run
 *   completes, reports the failed solves and still conserves energy.
 * - The penetration example: the listing's reading gives the paper's
 *   (0.40065, -0.05244) to its printed digits, the text's reading rebounds.
 * - Restart bit-identity.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "particles/dforce.h"
#include "models/greenspan.h"
#include "ballfilm/h5out.h"
#include "ballfilm/model.h"
#include "ballfilm/run.h"
#include "particles/pdiag.h"
#include "testutil.h"

START_TEST(s_identity_limit_and_derivative)
{
    const int ns[] = {2, 3, 7, 10, 13};
    for (int k = 0; k < 5; k++) {
        int n = ns[k];
        for (int t = 0; t < 50; t++) {
            double a = 0.5 + 0.03 * t, b = 2.0 - 0.029 * t;
            if (fabs(a - b) < 1e-3)
                continue;
            double s, ds;
            bf_dforce_s(n, a, b, &s, &ds);
            double lhs = s * (b * b - a * a);
            double rhs = 1.0 / pow(a, n - 1) - 1.0 / pow(b, n - 1);
            ck_assert_msg(fabs(lhs - rhs) <= 1e-13 * (1.0 / pow(fmin(a, b), n - 1)),
                          "n %d a %g b %g: %.17g vs %.17g", n, a, b, lhs, rhs);
            double h = 1e-6 * b, sp, sm;
            bf_dforce_s(n, a, b + h, &sp, NULL);
            bf_dforce_s(n, a, b - h, &sm, NULL);
            ck_assert_msg(fabs(ds - (sp - sm) / (2 * h)) <= 1e-6 * fabs(ds),
                          "n %d: dS/db %g vs %g", n, ds, (sp - sm) / (2 * h));
        }
        double a = 1.3, s;
        bf_dforce_s(n, a, a, &s, NULL);
        ck_assert_double_eq_tol(2 * a * s, (n - 1) / pow(a, n), 1e-14 * n);
    }
}
END_TEST

START_TEST(jacobian_matches_finite_differences)
{
    bf_dforce f;
    bf_err err = {0};
    const size_t n = 5;
    ck_assert(bf_dforce_init(&f, n, 7, 10, &err) == BF_OK);
    f.g = 9.8;
    f.gravity[1] = 1;
    f.fixed[4] = 1;
    for (size_t i = 0; i < n; i++)
        f.m[i] = 0.5 + 0.25 * (double)i;
    f.p[0 * n + 2] = f.p[2 * n + 0] = 0.7;
    double x0[5] = {0, 1.1, 2.3, 0.4, 1.7}, y0[5] = {0, 0.2, -0.1, 1.0, 0.9};
    double x1[5], y1[5], r0[25], r1[25], J[100], fx[5], fy[5], gx[5], gy[5];
    for (size_t i = 0; i < n; i++) {
        x1[i] = x0[i] + 0.03 * sin((double)i + 1);
        y1[i] = y0[i] + 0.02 * cos((double)i);
    }
    x1[4] = x0[4];
    y1[4] = y0[4];
    bf_dforce_distances(&f, x0, y0, r0);
    bf_dforce_distances(&f, x1, y1, r1);
    bf_dforce_jacobian(&f, x0, y0, r0, x1, y1, r1, 0.0, J);
    for (size_t j = 0; j < n; j++)
        for (int c = 0; c < 2; c++) {
            double *v = c ? y1 : x1, h = 1e-6, keep = v[j];
            v[j] = keep + h;
            bf_dforce_distances(&f, x1, y1, r1);
            bf_dforce_eval(&f, x0, y0, r0, x1, y1, r1, fx, fy);
            v[j] = keep - h;
            bf_dforce_distances(&f, x1, y1, r1);
            bf_dforce_eval(&f, x0, y0, r0, x1, y1, r1, gx, gy);
            v[j] = keep;
            for (size_t i = 0; i < n; i++)
                for (int a = 0; a < 2; a++) {
                    double fd = ((a ? fy[i] : fx[i]) - (a ? gy[i] : gx[i])) /
                                (2 * h);
                    double an = J[(2 * i + (size_t)a) * 2 * n + 2 * j + (size_t)c];
                    ck_assert_msg(fabs(fd - an) <= 1e-5 * (1.0 + fabs(an)),
                                  "dF%zu%c/dx%zu%c: %g vs %g", i + 1,
                                  "xy"[a], j + 1, "xy"[c], an, fd);
                }
        }
    bf_dforce_free(&f);
}
END_TEST

/* Drive a greenspan73 scene step by step; the largest relative change of
 * E = K + V and of E - K_cm, and of the momentum sum. */
typedef struct drift {
    double e, eint, mom;
    bf_status st;
    char msg[BF_ERR_MSG];
} drift;

static drift run_drift(const char *path, const char *const *sets)
{
    bf_err err = {0};
    bf_scene *sc;
    drift d = {0, 0, 0, BF_OK, ""};
    ck_assert(bf_scene_load(&sc, path, &err) == BF_OK);
    for (; sets && *sets; sets++)
        ck_assert_msg(bf_scene_set(sc, *sets, "test", &err) == BF_OK, "%s",
                      err.msg);
    ck_assert_msg(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK, "%s", err.msg);
    const bf_model_type *mt = bf_catalog_model(bf_catalog_builtin(), "greenspan73");
    void *m;
    bf_setup *setup;
    ck_assert_msg(bf_model_from_scene(bf_catalog_builtin(), sc, &setup, &m,
                                      &err) == BF_OK,
                  "%s", err.msg);
    bf_particles *p = bf_greenspan73_particles(m);
    const double dt = bf_scene_real(sc, "scene", "dt");
    const long steps = lround(bf_scene_real(sc, "scene", "t_end") / dt);
    double K, V, e0, i0, px0 = 0, py0 = 0;
    mt->energy(m, 0, &K, &V);
    e0 = K + V;
    i0 = e0 - bf_pdiag_cm_kinetic(p, NULL);
    for (size_t i = 0; i < p->n; i++) {
        px0 += p->m[i] * p->vx[i];
        py0 += p->m[i] * p->vy[i];
    }
    for (long k = 0; k < steps; k++) {
        d.st = mt->step(m, k, k * dt, dt, &err);
        if (d.st) {
            snprintf(d.msg, sizeof d.msg, "%s", err.msg);
            break;
        }
        mt->energy(m, 0, &K, &V);
        double e = K + V, ei = e - bf_pdiag_cm_kinetic(p, NULL);
        double px = 0, py = 0;
        for (size_t i = 0; i < p->n; i++) {
            px += p->m[i] * p->vx[i];
            py += p->m[i] * p->vy[i];
        }
        d.e = fmax(d.e, fabs(e - e0) / fabs(e0));
        d.eint = fmax(d.eint, fabs(ei - i0) / fabs(i0));
        d.mom = fmax(d.mom, hypot(px - px0, py - py0));
    }
    mt->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return d;
}

START_TEST(energy_conserved_on_hexagon_flows)
{
    const char *tight12[] = {"greenspan73.tol=1e-12", NULL};
    const char *tight11[] = {"greenspan73.tol=1e-11", NULL};
    const char *small[] = {"greenspan73.tol=1e-11", "scene.dt=0.01",
                           "greenspan73.omega=1", NULL};
    const struct {
        const char *scene;
        const char *const *sets;
    } cases[] = {
        {"runs/greenspan73_hex_v50.ini", tight12},
        {"runs/greenspan73_hex_v300.ini", tight12},
        {"runs/greenspan73_hex_v1000.ini", tight11}, /* dt 0.1, omega 0.2 */
        {"runs/greenspan73_hex_v1000.ini", small},
    };
    for (int k = 0; k < 4; k++) {
        drift d = run_drift(tu_repo(cases[k].scene), cases[k].sets);
        ck_assert_msg(d.st == BF_OK, "%s: %s", cases[k].scene, d.msg);
        ck_assert_msg(d.e <= 1e-10 && d.eint <= 1e-10,
                      "%s: relative drift of E %.3g, of E - K_cm %.3g",
                      cases[k].scene, d.e, d.eint);
        /* m = 1: sum v; g = 0 and nothing fixed, so it is conserved */
        ck_assert_msg(d.mom <= 1e-8, "%s: momentum changed by %g",
                      cases[k].scene, d.mom);
    }
    /* the solve is the only error: a loose tolerance drifts visibly */
    const char *loose[] = {"greenspan73.tol=1e-4", NULL};
    drift d = run_drift(tu_repo("runs/greenspan73_hex_v50.ini"), loose);
    ck_assert_msg(d.eint > 1e-8, "tol 1e-4 still conserves E - K_cm to %g",
                  d.eint);
}
END_TEST

START_TEST(energy_conserved_with_walls_and_gravity)
{
    /* the listing's update (inertia 1) conserves its own energy, with
     * gravity on P1 and fixed wall particles; the text's too */
    const char *text[] = {"greenspan73.mass=paper",
                          "greenspan73.wall_mass=10",
                          "greenspan73.gravity=all", NULL};
    drift a = run_drift(tu_repo("runs/greenspan73_penetration.ini"), NULL);
    drift b = run_drift(tu_repo("runs/greenspan73_penetration.ini"), text);
    drift c = run_drift(tu_repo("runs/greenspan73_wall_friction.ini"), NULL);
    ck_assert_msg(a.st == BF_OK && b.st == BF_OK && c.st == BF_OK, "%s %s %s",
                  a.msg, b.msg, c.msg);
    ck_assert_msg(a.e <= 1e-10 && b.e <= 1e-10 && c.e <= 1e-10,
                  "drifts %g %g %g", a.e, b.e, c.e);
}
END_TEST

/* Final positions of a scene run in-process with overrides. */
static void final_state(const char *path, const char *const *sets, double *x,
                        double *y, size_t n)
{
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load(&sc, path, &err) == BF_OK);
    for (; sets && *sets; sets++)
        ck_assert(bf_scene_set(sc, *sets, "test", &err) == BF_OK);
    ck_assert_msg(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK, "%s", err.msg);
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err) == BF_OK, "%s", err.msg);
    ck_assert_msg(bf_sim_run(sim, &err) == BF_OK, "%s", err.msg);
    bf_particles *p = bf_greenspan73_particles(bf_sim_model(sim));
    ck_assert(p->n == n);
    memcpy(x, p->x, n * sizeof *x);
    memcpy(y, p->y, n * sizeof *y);
    bf_sim_free(sim);
    bf_scene_free(sc);
}

START_TEST(fixed_point_and_newton_agree)
{
    const char *path = tu_repo("runs/greenspan73_hex_v300.ini");
    double x[4][34], y[4][34];
    const char *fp[] = {"greenspan73.tol=1e-12", "scene.t_end=0.2", NULL};
    const char *nd[] = {"greenspan73.tol=1e-12", "scene.t_end=0.2",
                        "greenspan73.solver=newton", NULL};
    const char *ns[] = {"greenspan73.tol=1e-12", "scene.t_end=0.2",
                        "greenspan73.solver=newton",
                        "greenspan73.jacobian=sparse", NULL};
    const char *nc[] = {"greenspan73.tol=1e-12", "scene.t_end=0.2",
                        "greenspan73.solver=newton",
                        "greenspan73.jacobian=sparse",
                        "greenspan73.jacobian_cutoff=2.5", NULL};
    final_state(path, fp, x[0], y[0], 34);
    final_state(path, nd, x[1], y[1], 34);
    final_state(path, ns, x[2], y[2], 34);
    final_state(path, nc, x[3], y[3], 34);
    /* the same root to the tolerance (10 steps; differences of ~1e-12 per
     * step, amplified little over t = 0.2) */
    for (int k = 1; k < 4; k++)
        for (int i = 0; i < 34; i++)
            ck_assert_msg(fabs(x[k][i] - x[0][i]) <= 1e-10 &&
                              fabs(y[k][i] - y[0][i]) <= 1e-10,
                          "solver %d particle %d: (%.15g, %.15g) vs (%.15g, "
                          "%.15g)",
                          k, i + 1, x[k][i], y[k][i], x[0][i], y[0][i]);
}
END_TEST

START_TEST(second_order_on_a_vibrating_pair)
{
    /* two unit masses on the x axis, stretched 5 % beyond r0, at rest:
     * the scheme is a consistent, symmetric one-step method, so its error
     * at a fixed time falls as dt^2 */
    const char *text =
        "[scene]\nmodel = greenspan73\ndt = 0.02\nt_end = 1.6\n"
        "[greenspan73]\nlayout = list\npositions = 0 0 1.2019 0\n"
        "tol = 1e-13\n";
    const char *path = tu_write("pair.ini", text);
    double xr[2], yr[2], x[3][2], y[3][2];
    const char *ref[] = {"scene.dt=0.0003125", NULL};
    final_state(path, ref, xr, yr, 2);
    const char *d1[] = {"scene.dt=0.02", NULL};
    const char *d2[] = {"scene.dt=0.01", NULL};
    const char *d3[] = {"scene.dt=0.005", NULL};
    final_state(path, d1, x[0], y[0], 2);
    final_state(path, d2, x[1], y[1], 2);
    final_state(path, d3, x[2], y[2], 2);
    double e[3];
    for (int k = 0; k < 3; k++)
        e[k] = fabs((x[k][1] - x[k][0]) - (xr[1] - xr[0]));
    double o1 = log2(e[0] / e[1]), o2 = log2(e[1] / e[2]);
    ck_assert_msg(fabs(o1 - 2) < 0.15 && fabs(o2 - 2) < 0.15,
                  "observed orders %.3f %.3f (errors %g %g %g)", o1, o2, e[0],
                  e[1], e[2]);
}
END_TEST

START_TEST(non_convergence_is_reported)
{
    const char *scene = tu_repo("runs/greenspan73_hex_v1000.ini");
    char out[512], out2[512];
    snprintf(out, sizeof out, "%s", tu_tmp("nc.h5"));
    snprintf(out2, sizeof out2, "%s", tu_tmp("nc2.h5"));
    char *err = NULL;
    /* omega = 1 at dt = 0.1: the fixed-point iteration diverges */
    int rc = tu_run(NULL, &err, "run", scene, "-q", "-o", out, "--set",
                    "greenspan73.omega=1", NULL);
    ck_assert_msg(rc == 4, "exit %d: %s", rc, err);
    ck_assert_msg(strstr(err, "step 1") && strstr(err, "did not converge") &&
                      strstr(err, "on_failure = stop"),
                  "%s", err);
    free(err);
    char *status = NULL;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_str(out, "/", "status", &status, &e) == BF_OK);
    ck_assert_msg(strcmp(status, "ok") != 0, "status %s", status);
    free(status);
    double *x;
    size_t n0, n1;
    ck_assert(bf_h5_read(out, "/particles/x", &x, &n0, &n1, &e) == BF_OK);
    ck_assert_int_eq(n0, 1); /* the initial row */
    free(x);
    /* Newton at this step does not converge either */
    rc = tu_run(NULL, &err, "run", scene, "-q", "-o", out2, "--set",
                "greenspan73.solver=newton", "--set", "greenspan73.max_iter=60",
                NULL);
    ck_assert_msg(rc == 4 && strstr(err, "Newton"), "exit %d: %s", rc, err);
    free(err);
    /* with halving the run completes and says what it did */
    char *o = NULL;
    rc = tu_run(&o, &err, "run", scene, "-o", out2, "--set",
                "greenspan73.omega=1", "--set", "greenspan73.on_failure=halve",
                NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    ck_assert_msg(strstr(o, "failed solves") && !strstr(o, " 0 failed solves"),
                  "%s", o);
    ck_assert_msg(strstr(o, "most halvings of a step 4"), "%s", o);
    free(o);
    free(err);
    const char *halve[] = {"greenspan73.omega=1",
                           "greenspan73.on_failure=halve",
                           "greenspan73.tol=1e-11", NULL};
    drift d = run_drift(scene, halve);
    ck_assert_msg(d.st == BF_OK && d.e <= 1e-10 && d.eint <= 1e-10,
                  "halved run: %s, drifts %g %g", d.msg, d.e, d.eint);
}
END_TEST

START_TEST(penetration_reproduces_the_paper_in_the_listing_reading)
{
    const char *path = tu_repo("runs/greenspan73_penetration.ini");
    double x[10], y[10];
    final_state(path, NULL, x, y, 10);
    /* the paper prints (.40065, -.05244) */
    ck_assert_msg(fabs(x[0] - 0.40065) <= 5e-6 && fabs(y[0] + 0.05244) <= 5e-5,
                  "P1 at (%.6f, %.6f)", x[0], y[0]);
    const char *all[] = {"greenspan73.gravity=all", NULL};
    final_state(path, all, x, y, 10);
    ck_assert_msg(fabs(y[0] + 0.05244) <= 5e-6, "P1 y %.7f", y[0]);
    /* the text's reading (a = F/m, wall mass 10): P1 bounces back */
    const char *text[] = {"greenspan73.mass=paper", "greenspan73.wall_mass=10",
                          NULL};
    final_state(path, text, x, y, 10);
    ck_assert_msg(y[0] > 0.2, "P1 y %.6f", y[0]);
}
END_TEST

START_TEST(restart_bit_identical)
{
    const char *scene = tu_repo("runs/greenspan73_hex_v300.ini");
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("full73.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("part73.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-q", "-o", full, NULL), 0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-q", "-o", part,
                            "--stop-after", "17", NULL),
                     6);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", part, "-q", NULL), 0);
    const char *ds[] = {"/time", "/particles/x", "/particles/y",
                        "/particles/vx", "/particles/vy", "/diag/energy",
                        "/energy/total", NULL};
    bf_err err = {0};
    for (const char **d = ds; *d; d++) {
        double *a, *b;
        size_t a0, a1, b0, b1;
        ck_assert(bf_h5_read(full, *d, &a, &a0, &a1, &err) == BF_OK);
        ck_assert(bf_h5_read(part, *d, &b, &b0, &b1, &err) == BF_OK);
        ck_assert_msg(a0 == b0 && a1 == b1 &&
                          !memcmp(a, b, a0 * (a1 ? a1 : 1) * sizeof *a),
                      "%s differs", *d);
        free(a);
        free(b);
    }
}
END_TEST

START_TEST(bad_scenes_are_refused)
{
    char msg[1024];
    const char *base = "[scene]\nmodel = greenspan73\ndt = 0.01\nt_end = 1\n";
    char text[1024];
    snprintf(text, sizeof text, "%s[greenspan73]\nfixed = 35\n", base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "fixed"), "%s", msg);
    snprintf(text, sizeof text, "%s[greenspan73]\nalpha = 7\nbeta = 7\n", base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    snprintf(text, sizeof text,
             "%s[greenspan73]\nlayout = list\npositions = 0 0 0 0\n", base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "coincide"), "%s", msg);
}
END_TEST

Suite *suite_greenspan73(void)
{
    Suite *s = suite_create("greenspan73");
    TCase *tc = tu_tcase("greenspan73");
    tcase_add_test(tc, s_identity_limit_and_derivative);
    tcase_add_test(tc, jacobian_matches_finite_differences);
    tcase_add_test(tc, energy_conserved_on_hexagon_flows);
    tcase_add_test(tc, energy_conserved_with_walls_and_gravity);
    tcase_add_test(tc, fixed_point_and_newton_agree);
    tcase_add_test(tc, second_order_on_a_vibrating_pair);
    tcase_add_test(tc, non_convergence_is_reported);
    tcase_add_test(tc, penetration_reproduces_the_paper_in_the_listing_reading);
    tcase_add_test(tc, restart_bit_identical);
    tcase_add_test(tc, bad_scenes_are_refused);
    suite_add_tcase(s, tc);
    return s;
}
