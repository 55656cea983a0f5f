/* test_forces.c: forces that depend on velocity (the effect `drag`)
 * against exact solutions, through every integrator of the catalog.
 *
 * Known answers (one ball of mass m = 1 g; CGS):
 *   linear drag in free fall, v' = -g - gamma v, x(0) = 0, v(0) = 0:
 *     v(t) = -(g/gamma) (1 - e^{-gamma t}),
 *     x(t) = -(g/gamma) t + (g/gamma^2) (1 - e^{-gamma t});
 *   quadratic drag falling down, v' = -g + c v^2 (v <= 0), from rest:
 *     v(t) = -v_t tanh(g t / v_t),  v_t = sqrt(g / c),
 *     x(t) = -(v_t^2 / g) ln cosh(g t / v_t);
 *   a damped linear spring, x'' = -w0^2 x - gamma x' (spring + drag),
 *     x(0) = 1, v(0) = 0, underdamped, w_d = sqrt(w0^2 - gamma^2/4):
 *     x(t) = e^{-gamma t/2} (cos w_d t + (gamma / (2 w_d)) sin w_d t),
 *     v(t) = -e^{-gamma t/2} (w0^2 / w_d) sin w_d t.
 *
 * Orders: each fixed-step integrator that accepts the scene runs it to T
 * at dt and dt/2; the observed order log2(e(dt)/e(dt/2)) of the position
 * and of the velocity error must be the integrator's nominal order
 * (bf_integrator_order) within 0.15.  Why 0.15: the error is
 * C dt^p (1 + O(lambda dt)), lambda the problem's rate (gamma = 0.5 1/s,
 * g/v_t = 1.4 1/s, w0 = 2 pi 1/s), and lambda dt <= 0.056 at the larger
 * step below, so the observed order is p + O(lambda dt / ln 2) = p +
 * 0.08 at most; a method that evaluates the force with the step's
 * initial velocity (what every method did before the velocity reached the
 * effects) is first order, far outside.  The velocity errors stay at
 * least 100 times above round-off (an ulp of the velocity scale per
 * step), checked.
 * ARKODE (adaptive) at rtol = atol = 1e-12 must agree with the exact
 * solution to 1e-8 of the velocity scale (g/gamma, v_t, w0): the
 * accumulated local errors of 10^2-10^3 steps at 1e-12.
 *
 * Refusals: integrators made for a = a(x) (BF_INT_POSITION_ONLY: mv2m,
 * alpha, rkn6, greenspan73) refuse the scene at creation with status 2,
 * naming [scene] integrator and the effect; so does the program (exit 2,
 * the message on stderr).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "testutil.h"

#define G 980.0
#define PI 3.14159265358979323846

typedef struct problem {
    const char *name;
    const char *text;    /* the scene, without [scene] integrator and dt */
    double T;            /* s */
    double dt;           /* the larger step of the order check, s */
    double vscale;       /* cm/s */
    void (*exact)(double t, double *x, double *v);
} problem;

static const double GAMMA = 0.5, QC = 0.002, W0 = 2 * PI;

static void linear_exact(double t, double *x, double *v)
{
    const double e = exp(-GAMMA * t);
    *v = -(G / GAMMA) * (1 - e);
    *x = -(G / GAMMA) * t + (G / (GAMMA * GAMMA)) * (1 - e);
}

static void quadratic_exact(double t, double *x, double *v)
{
    const double vt = sqrt(G / QC), s = G * t / vt;
    *v = -vt * tanh(s);
    *x = -(vt * vt / G) * log(cosh(s));
}

static void spring_exact(double t, double *x, double *v)
{
    const double wd = sqrt(W0 * W0 - 0.25 * GAMMA * GAMMA),
                 e = exp(-0.5 * GAMMA * t);
    *x = e * (cos(wd * t) + GAMMA / (2 * wd) * sin(wd * t));
    *v = -e * (W0 * W0 / wd) * sin(wd * t);
}

static const problem problems[] = {
    {"linear drag",
     "[scene]\nmodel = balls\neffects = gravity drag\n"
     "[gravity]\ng = 980\n[drag]\ngamma = 0.5\n"
     "[ball.1]\nposition = 0\nvelocity = 0\nmass = 1\n",
     2.0, 0.04, G / 0.5, linear_exact},
    {"quadratic drag",
     "[scene]\nmodel = balls\neffects = gravity drag\n"
     "[gravity]\ng = 980\n[drag]\nquadratic = 0.002\n"
     "[ball.1]\nposition = 0\nvelocity = 0\nmass = 1\n",
     2.0, 0.04, 700.0, quadratic_exact},
    {"damped spring",
     "[scene]\nmodel = balls\neffects = spring drag\n"
     "[spring]\nstiffness = 39.47841760435743\nrest = 0\n"
     "[drag]\ngamma = 0.5\n"
     "[ball.1]\nposition = 1\nvelocity = 0\nmass = 1\n",
     1.28, 0.008, 2 * PI, spring_exact},
};
enum { NPROB = sizeof problems / sizeof problems[0] };

/* the scene of problem p with integrator `it`, dt, T and one more
 * "section.key=value" (or NULL) */
static bf_scene *scene_of(const problem *p, const char *it, double dt,
                          const char *key1)
{
    bf_scene *sc;
    bf_err err = {0};
    ck_assert_msg(bf_scene_load_string(&sc, "forces.ini", p->text, &err) ==
                      BF_OK,
                  "%s", err.msg);
    ck_assert_msg(bf_setf(sc, &err, "scene.integrator=%s", it) == BF_OK &&
                      bf_setf(sc, &err, "scene.dt=%.17g", dt) == BF_OK &&
                      bf_setf(sc, &err, "scene.t_end=%.17g", p->T) ==
                          BF_OK &&
                      (!key1 || bf_setf(sc, &err, "%s", key1) == BF_OK),
                  "%s", err.msg);
    ck_assert_msg(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ==
                      BF_OK,
                  "%s", err.msg);
    return sc;
}

/* run to T; the errors of x and v against the exact solution */
static int run_err(const problem *p, const char *it, double dt,
                   const char *key, double *ex, double *ev, int *order,
                   bf_err *err)
{
    bf_scene *sc = scene_of(p, it, dt, key);
    bf_sim *sim;
    bf_status st = bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL,
                                     err);
    if (st) {
        bf_scene_free(sc);
        return st;
    }
    st = bf_sim_run(sim, err);
    ck_assert_msg(st == BF_OK, "%s %s: %s", p->name, it, err->msg);
    double xe, ve;
    p->exact(bf_sim_time(sim), &xe, &ve);
    ck_assert(fabs(bf_sim_time(sim) - p->T) < 1e-9);
    *ex = fabs(bf_sim_get(sim, "balls/position", NULL)[0] - xe);
    *ev = fabs(bf_sim_get(sim, "balls/velocity", NULL)[0] - ve);
    if (order)
        *order = bf_integrator_order(
            bf_balls_model_system(bf_sim_model(sim))->it);
    bf_sim_free(sim);
    bf_scene_free(sc);
    return BF_OK;
}

/* Every integrator of the catalog on every problem: nominal order,
 * agreement (adaptive) or refusal (a = a(x) only). */
START_TEST(every_integrator_is_exact_to_its_order_or_refuses)
{
    const problem *p = &problems[_i];
    size_t ni;
    const bf_integrator_type *const *its =
        bf_catalog_integrators(bf_catalog_builtin(), &ni);
    int accepted = 0, refused = 0;
    for (size_t k = 0; k < ni; k++) {
        const bf_integrator_type *t = its[k];
        bf_err err = {0};
        double ex1, ev1, ex2, ev2;
        int order = 0;
        if (t->flags & BF_INT_POSITION_ONLY) {
            bf_status st = run_err(p, t->name, p->dt, NULL, &ex1, &ev1, NULL,
                                   &err);
            ck_assert_msg(st == BF_EINPUT, "%s %s: status %d", p->name,
                          t->name, st);
            ck_assert_msg(strstr(err.msg, "[scene] integrator") &&
                              strstr(err.msg, "'drag'") &&
                              strstr(err.msg, t->name),
                          "%s", err.msg);
            printf("forces: %-15s %-12s refused: %s\n", p->name, t->name,
                   err.msg);
            refused++;
            continue;
        }
        if (t->flags & BF_INT_ADAPTIVE) {
            ck_assert_int_eq(run_err(p, t->name, p->dt,
                                     "integrator.rtol=1e-12", &ex1, &ev1,
                                     NULL, &err),
                             BF_OK);
            printf("forces: %-15s %-12s rtol 1e-12: |x - x(T)| %.2e cm, "
                   "|v - v(T)| %.2e cm/s\n",
                   p->name, t->name, ex1, ev1);
            ck_assert_msg(ev1 < 1e-8 * p->vscale &&
                              ex1 < 1e-8 * p->vscale * p->T,
                          "%s %s: %g %g", p->name, t->name, ex1, ev1);
            accepted++;
            continue;
        }
        ck_assert_int_eq(run_err(p, t->name, p->dt, NULL, &ex1, &ev1, &order,
                                 &err),
                         BF_OK);
        ck_assert_int_eq(run_err(p, t->name, p->dt / 2, NULL, &ex2, &ev2,
                                 NULL, &err),
                         BF_OK);
        const double px = log2(ex1 / ex2), pv = log2(ev1 / ev2);
        printf("forces: %-15s %-12s dt %g, %g: |x - x(T)| %.2e, %.2e cm "
               "(order %.2f), |v - v(T)| %.2e, %.2e cm/s (order %.2f); "
               "nominal %d\n",
               p->name, t->name, p->dt, p->dt / 2, ex1, ex2, px, ev1, ev2, pv,
               order);
        ck_assert_msg(fabs(px - order) < 0.15 && fabs(pv - order) < 0.15,
                      "%s %s: observed orders %.3f %.3f, nominal %d",
                      p->name, t->name, px, pv, order);
        /* far above round-off (at most an ulp of the velocity scale per
         * step), so the ratio is truncation's */
        ck_assert(ev2 > 100 * DBL_EPSILON * (2 * p->T / p->dt) * p->vscale);
        accepted++;
    }
    ck_assert_int_ge(accepted, 5); /* rk3 rk4 verlet impmid arkode... */
    ck_assert_int_ge(refused, 4);  /* mv2m alpha rkn6 greenspan73 */
}
END_TEST

/* The program refuses too: exit status 2, the key and the effect named. */
START_TEST(the_program_refuses_with_status_2)
{
    const char *scene = tu_write(
        "drag_mv2m.ini",
        "[scene]\nmodel = balls\nintegrator = mv2m\neffects = gravity drag\n"
        "dt = 1e-3\nt_end = 0.01\n[drag]\ngamma = 0.5\n"
        "[ball.1]\nposition = 10\n");
    char *out = NULL, *errout = NULL;
    int rc = tu_run(&out, &errout, "run", scene, "-q", "-o",
                    tu_tmp("drag_mv2m.h5"), NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(errout, "[scene] integrator") &&
                      strstr(errout, "'drag'") && strstr(errout, "mv2m"),
                  "%s", errout);
    free(out);
    free(errout);
}
END_TEST

/* A scene with drag has no energy bound (the energy is not conserved);
 * every all-conservative scene keeps its bound. */
START_TEST(drag_is_not_conservative)
{
    bf_sim *sim = tu_run_scene(problems[0].text, "scene.integrator=rk4",
                               "scene.dt=0.01", "scene.t_end=0.1", NULL);
    ck_assert(bf_balls_model_system(bf_sim_model(sim)) != NULL);
    ck_assert(bf_ballsys_energy_bound(
                  bf_balls_model_system(bf_sim_model(sim))) == 0.0);
    bf_sim_free(sim);
    sim = tu_run_scene("[scene]\nmodel = balls\neffects = gravity\n"
                       "[ball.1]\nposition = 0\n",
                       "scene.integrator=rk4", "scene.dt=0.01",
                       "scene.t_end=0.1", NULL);
    ck_assert(bf_ballsys_energy_bound(
                  bf_balls_model_system(bf_sim_model(sim))) > 0.0);
    bf_sim_free(sim);
}
END_TEST

/* Event splitting at contact onset and release with a velocity-dependent
 * force: a ball with linear drag dropped on the floor, rk4 with events =
 * yes.  The splitting re-takes steps (rejected > 0) and the result
 * converges at the method's order against a run at dt/8: e(dt)/e(dt/2)
 * >= 2^3.5 (the graded substeps of ballsys_events.c give order p back). */
START_TEST(event_splitting_keeps_working_with_drag)
{
    static const char text[] =
        "[scene]\nmodel = balls\nintegrator = rk4\n"
        "effects = gravity floor drag\nt_end = 0.04\n"
        "[integrator]\nevents = yes\n"
        "[gravity]\ng = 980\n[floor]\nk = 1e7\n[drag]\ngamma = 5\n"
        "[ball.1]\nposition = 1.1\nvelocity = -100\nmass = 1\n"
        "radius = 0.1\n";
    double x[4], v[4];
    const double dts[4] = {2e-4, 1e-4, 5e-5, 2.5e-5};
    unsigned long long rejected = 0;
    for (int k = 0; k < 4; k++) {
        char set[64];
        snprintf(set, sizeof set, "scene.dt=%g", dts[k]);
        bf_sim *sim = tu_run_scene(text, set, NULL);
        x[k] = bf_sim_get(sim, "balls/position", NULL)[0];
        v[k] = bf_sim_get(sim, "balls/velocity", NULL)[0];
        bf_counters c;
        bf_sim_counters(sim, &c);
        rejected += c.rejected;
        bf_sim_free(sim);
    }
    /* it bounced: up again after the contact */
    ck_assert_msg(v[3] > 0, "v(T) = %g", v[3]);
    ck_assert(rejected > 0);
    const double e1 = fabs(v[0] - v[3]), e2 = fabs(v[1] - v[3]),
                 f1 = fabs(x[0] - x[3]), f2 = fabs(x[1] - x[3]);
    printf("forces: bounce with drag, rk4 events: |v - v_ref| %.2e, %.2e "
           "(ratio %.1f), |x - x_ref| %.2e, %.2e (ratio %.1f)\n",
           e1, e2, e1 / e2, f1, f2, f1 / f2);
    ck_assert_msg(e1 / e2 > pow(2, 3.5) && f1 / f2 > pow(2, 3.5),
                  "ratios %g %g", e1 / e2, f1 / f2);
}
END_TEST

Suite *suite_forces(void)
{
    Suite *s = suite_create("forces");
    TCase *tc = tcase_create("forces");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, every_integrator_is_exact_to_its_order_or_refuses,
                        0, NPROB);
    tcase_add_test(tc, the_program_refuses_with_status_2);
    tcase_add_test(tc, drag_is_not_conservative);
    tcase_add_test(tc, event_splitting_keeps_working_with_drag);
    suite_add_tcase(s, tc);
    return s;
}
