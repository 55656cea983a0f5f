/* test_events.c: contact events and the energy-conserving scheme for the
 * balls (issue 19, docs/accuracy-balls.md).
 *
 *   orders      with [integrator] events = yes (each step split at the
 *               contact onsets and releases, graded substeps near them),
 *               MV2M and RK4 show their nominal orders 3 and 4 on the
 *               bouncing ball (runs/bouncing_ball.ini, T = 1 s, 35
 *               bounces, final position against the ARKODE reference with
 *               rootfinding at the contacts, rtol 1e-14/1e-15, estimated
 *               error 1.6e-11 cm, below the errors compared by 100x).
 *               dt = 2.5e-5 and 1.25e-5 s: the observed orders of
 *               successive halvings there are 3.04-3.10 (MV2M) and
 *               4.01-4.21 (RK4); the error constants still move with the
 *               position of the onsets in the step grid, by up to 2^0.11,
 *               so +-0.15 is the tolerance (2^0.15 = 1.11).  Without the
 *               events the same runs give orders between -7 and 10; with
 *               splitting but no grading (events_zone -> 0), RK4 falls
 *               towards 5/2 and the test fails.
 *   greenspan73 on runs/two_balls_A.ini for 10 s (10^5 steps of 1e-4 s,
 *               about 300 contacts): the relative energy error stays
 *               below 1e-12 at every step.  Round-off per step is a few
 *               eps E (eps = 1.1e-16) and adds up like a random walk,
 *               sqrt(10^5) * 4 eps = 1.4e-13; measured 5e-14.  The
 *               implicit mid-point rule on the same run: 1e-6.  A
 *               step that cannot converge in max_iter iterations fails
 *               with BF_ENOCONV and a message, state unchanged.
 *   simultaneous two impacts at the same instant (three balls in mirror
 *               image: the two gaps are the same bits) are located once;
 *               the run ends (it used to loop for ever in the search for
 *               an earlier crossing), stays mirror-symmetric to the bit,
 *               and conserves energy as a split RK4 step does.
 *   hertz_dd    the divided difference of the Hertz energy is the
 *               quotient (E(a) - E(b))/(a - b) where that has no
 *               cancellation, symmetric to the bit, and the force at
 *               a = b. */
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/converge.h"
#include "ballfilm/run.h"
#include "ballfilm/scene.h"
#include "contact/hertz.h"
#include "models/ballsys.h"
#include "testutil.h"

START_TEST(orders_with_event_splitting)
{
    const char *methods[] = {"mv2m:events=yes", "rk4:events=yes"};
    const int nominal[] = {3, 4};
    double dts[] = {2.5e-5, 1.25e-5};
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load(&sc, tu_repo("runs/bouncing_ball.ini"), &err) ==
              BF_OK);
    bf_converge_opts o = {.methods = methods,
                          .nmethods = 2,
                          .dts = dts,
                          .ndts = 2,
                          .t_end = 1.0,
                          .repeats = 1,
                          .ref_rtol = 1e-14};
    bf_converge_result *r;
    ck_assert_msg(bf_converge_run(sc, &o, &r, &err) == BF_OK, "%s", err.msg);
    ck_assert_msg(r->ref_err[0] < 1e-10, "reference error %g", r->ref_err[0]);
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(w->status == BF_OK, "%s: %s", w->label, w->msg);
        ck_assert(w->err[0] > 100 * r->ref_err[0]);
        if (isnan(w->order_obs[0]))
            continue;
        ck_assert_msg(fabs(w->order_obs[0] - nominal[w->method]) < 0.15,
                      "%s: observed order %.3f, nominal %d (error %g)",
                      methods[w->method], w->order_obs[0], nominal[w->method],
                      w->err[0]);
    }
    bf_converge_free(r);
    bf_scene_free(sc);
}
END_TEST

static bf_ballsys *two_balls(const char *integrator, const char *tol)
{
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load(&sc, tu_repo("runs/two_balls_A.ini"), &err) ==
              BF_OK);
    ck_assert(bf_scene_set(sc, integrator, "test", &err) == BF_OK);
    if (tol)
        ck_assert(bf_scene_set(sc, tol, "test", &err) == BF_OK);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK);
    bf_ballsys *s;
    ck_assert_msg(bf_ballsys_from_scene(&s, bf_catalog_builtin(), sc, &err) ==
                      BF_OK,
                  "%s", err.msg);
    bf_scene_free(sc);
    return s;
}

/* max relative energy error over n steps of dt */
static double energy_drift(bf_ballsys *s, long n, double dt)
{
    bf_err err = {0};
    double k, p;
    bf_ballsys_energy(s, 0, &k, &p);
    const double e0 = k + p;
    double worst = 0;
    for (long j = 0; j < n; j++) {
        ck_assert_msg(bf_ballsys_step(s, j * dt, dt, &err) == BF_OK,
                      "step %ld: %s", j, err.msg);
        bf_ballsys_energy(s, (j + 1) * dt, &k, &p);
        worst = fmax(worst, fabs(k + p - e0) / fabs(e0));
    }
    return worst;
}

START_TEST(simultaneous_events_are_located_once)
{
    alarm(60); /* a loop for ever fails the test, not the suite's timeout */
    bf_sim *sim = tu_run_scene(
        "[scene]\nmodel = balls\nintegrator = rk4\neffects = contact\n"
        "dt = 1e-5\nt_end = 0.05\n[integrator]\nevents = yes\n"
        "[contact]\nk = 1e7\n"
        "[ball.1]\nposition = -3\nvelocity = 100\nradius = 1\n"
        "[ball.2]\nposition = 0\nradius = 1\n"
        "[ball.3]\nposition = 3\nvelocity = -100\nradius = 1\n",
        NULL);
    alarm(0);
    size_t n;
    const double *x = bf_sim_get(sim, "balls/position", &n);
    const double *v = bf_sim_get(sim, "balls/velocity", &n);
    ck_assert_uint_eq(n, 3);
    /* the balls met (1 cm apart at 100 cm/s: after 0.01 s) and parted */
    ck_assert_msg(v[0] < 0 && v[2] > 0, "v %g %g %g", v[0], v[1], v[2]);
    ck_assert_msg(x[0] == -x[2] && v[0] == -v[2] && x[1] == 0 && v[1] == 0,
                  "x %.17g %.17g %.17g, v %.17g %.17g %.17g", x[0], x[1],
                  x[2], v[0], v[1], v[2]);
    /* 2 m v^2 / 2 = 10^4 erg before and after the contacts: a split RK4
     * run at 1e-5 s keeps it to about 1e-10 (rk4's local error, 100s of
     * graded substeps); a missed or doubled event costs O(1) */
    const double ke = 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    ck_assert_msg(fabs(ke - 1e4) < 1e-6 * 1e4, "kinetic energy %.12g", ke);
    bf_sim_free(sim);
}
END_TEST

START_TEST(greenspan73_conserves_energy)
{
    bf_ballsys *s = two_balls("scene.integrator=greenspan73", NULL);
    const double e = energy_drift(s, 100000, 1e-4);
    ck_assert_msg(e < 1e-12, "greenspan73: relative energy error %g", e);
    /* 4-7 iterations per step (contraction dt^2/4 |da/dx| ~ 6e-3) */
    ck_assert(s->it->count.iterations > 100000 &&
              s->it->count.iterations < 8 * 100000ULL);
    bf_ballsys_free(s);
    s = two_balls("scene.integrator=impmid", NULL);
    const double em = energy_drift(s, 100000, 1e-4);
    ck_assert_msg(em > 1e4 * e, "implicit mid-point %g vs greenspan73 %g", em,
                  e);
    bf_ballsys_free(s);
}
END_TEST

START_TEST(greenspan73_refuses_to_continue_unconverged)
{
    bf_ballsys *s =
        two_balls("scene.integrator=greenspan73", "integrator.max_iter=2");
    /* in a contact (0.01 cm deep) two iterations leave a change of
     * ~(dt^2/4 |da/dx|)^2 ~ 1e-5 of the first */
    s->b.x[0] = 0.09;
    const double x0 = s->b.x[0], v0 = s->b.v[0];
    bf_err err = {0};
    ck_assert(bf_ballsys_step(s, 0, 1e-4, &err) == BF_ENOCONV);
    ck_assert(strstr(err.msg, "did not converge"));
    ck_assert(s->b.x[0] == x0 && s->b.v[0] == v0);
    bf_ballsys_free(s);
}
END_TEST

START_TEST(hertz_dd)
{
    const double k = 1e7;
    for (double a = 1e-6; a < 0.05; a *= 1.9)
        for (double b = -0.01; b < 0.05; b += 0.0037) {
            double q = bf_hertz_energy_dd(k, a, b);
            ck_assert(q == bf_hertz_energy_dd(k, b, a));
            if (fabs(a - b) > 0.1 * fmax(a, b)) {
                double ref = (bf_hertz_energy(k, a) - bf_hertz_energy(k, b)) /
                             (a - b);
                ck_assert_msg(fabs(q - ref) <= 1e-13 * fabs(ref),
                              "a %g b %g: %.17g vs %.17g", a, b, q, ref);
            }
        }
    for (double a = 1e-8; a < 0.05; a *= 3)
        ck_assert(fabs(bf_hertz_energy_dd(k, a, a) - bf_hertz_force(k, a)) <=
                  4e-16 * bf_hertz_force(k, a));
    ck_assert(bf_hertz_energy_dd(k, -1e-3, -2e-3) == 0.0);
}
END_TEST

Suite *suite_events(void)
{
    Suite *s = suite_create("events");
    TCase *tc = tu_tcase("events");
    tcase_add_test(tc, orders_with_event_splitting);
    tcase_add_test(tc, greenspan73_conserves_energy);
    tcase_add_test(tc, greenspan73_refuses_to_continue_unconverged);
    tcase_add_test(tc, hertz_dd);
    tcase_add_test(tc, simultaneous_events_are_located_once);
    suite_add_tcase(s, tc);
    return s;
}
