/* test_coupled_lyapunov.c: the largest Lyapunov exponent of the coupled
 * model (coupled.c, lyapunov.h): the shadow coupled system, its
 * renormalisation of the whole state, its checkpoint.  All runs use a
 * 10 cm film (101 nodes) and at most 2 s of simulated time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/coupled.h"
#include "models/coupled_impl.h"
#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "diag/lyapsum.h"
#include "testutil.h"

/* Two balls falling on a floor (runs/two_balls_A.ini: lower 1.2 g, a
 * chaotic case), MV2M at dt = 1e-4 s, as a "balls" scene ... */
#define TWO_BALLS                                                              \
    "[ball.1]\nposition = 0.2\nmass = 1.2\nradius = 0.1\n"                    \
    "[ball.2]\nposition = 0.5\nmass = 1\nradius = 0.1\n"                      \
    "[gravity]\ng = 980\n[floor]\nk = 1e7\n[contact]\nk = 1e7\n"              \
    "[lyapunov]\nenabled = yes\nrenormalise_every = 0.1 s\n"

static const char *balls_scene =
    "[scene]\nmodel = balls\nintegrator = mv2m\n"
    "effects = gravity floor contact\ndt = 1e-4\nt_end = 2\n"
    "output_every = 1000\n" TWO_BALLS;

/* ... and the same balls in a dynamic film that does not push them:
 * V0 = 0 makes the coupling force -M dF/dr = -4 pi R^2 V0 M dI/dr (eq.
 * 3.10, 3.12) and mu_cpl (3.11) exactly zero. */
static const char *film_scene =
    "[scene]\nmodel = coupled\nintegrator = mv2m\n"
    "effects = gravity floor contact coupling\ndt = 1e-4\nt_end = 2\n"
    "output_every = 1000\n"
    "[coupled]\nfilm = dynamic\n"
    "[film]\nlength = 10\ndx = 0.1\ninitial = kink\n"
    "[coupling]\nV0 = 0\nr0 = 0.5\nmobility = 1e5\n" TWO_BALLS;

static double lyapunov_of(bf_sim *sim)
{
    bf_results a;
    bf_sim_results(sim, &a);
    ck_assert(a.has_lyapunov);
    return a.lyapunov_exponent;
}

/* With V0 = 0 the balls of the coupled model and their shadow do exactly
 * what the balls model's do: the zero coupling force adds +-0 to each
 * acceleration (no bit changes), both films see mu_cpl = 0 and evolve
 * identically, so their difference is exactly 0 and the pull-back leaves
 * the shadow film equal to the run's; the ball parts use the same
 * displacement, distance and pull-back code (bf_lyap_sum), and MV2M's
 * specialised step (coupled run and shadow) gives the bits of the generic
 * step (the balls model's shadow, test_advance.c).  So lambda must agree
 * bit for bit, single rate and multirate, fixed or film_every = auto: the
 * shadow must take the run's film steps (choosing its own, from its own
 * ball velocities, its film would step at other times than the run's). */
START_TEST(without_film_force_equals_balls_model)
{
    bf_sim *b = tu_run_scene(balls_scene, NULL);
    double lb = lyapunov_of(b);
    bf_sim_free(b);
    ck_assert_msg(isfinite(lb) && lb > 5, "balls model lambda %g", lb);
    const char *every[] = {"coupled.film_every=1", "coupled.film_every=3",
                           "coupled.film_every=auto"};
    for (int k = 0; k < 3; k++) {
        bf_sim *c = tu_run_scene(film_scene, every[k], NULL);
        double lc = lyapunov_of(c);
        bf_coupled_parts run, sh;
        ck_assert(bf_coupled_sim_parts(c, &run, &sh) == BF_OK);
        ck_assert(sh.film != NULL);
        /* the film evolved (it is not a static test) and the shadow film
         * stayed the run's */
        double *fr[BF_FILM_NSTATE], *fs[BF_FILM_NSTATE];
        size_t nodes = bf_film_state(run.film, fr);
        bf_film_state(sh.film, fs);
        for (int q = 0; q < BF_FILM_NSTATE; q++)
            ck_assert(memcmp(fr[q], fs[q], nodes * sizeof(double)) == 0);
        ck_assert(bf_film_max_speed(run.film) > 0);
        bf_sim_free(c);
        ck_assert_msg(lc == lb, "%s: coupled lambda %.17g, balls %.17g",
                      every[k], lc, lb);
    }
}
END_TEST

/* Four balls in the interface of a 10 cm film (Fig. 8 set-up, smaller),
 * the film pushing the balls and the balls the film. */
static const char *fig8_small =
    "[scene]\nmodel = coupled\nintegrator = mv2m\n"
    "effects = coupling contact\ndt = 1e-5\nt_end = 0.02\n"
    "output_every = 100\n"
    "[coupled]\nfilm = dynamic\nfilm_every = 10\nprobe = 0.3\n"
    "[film]\nlength = 10\ndx = 0.1\ninitial = kink\nprofile_every = 0.01 s\n"
    "[coupling]\nV0 = 0.01\nr0 = 0.5\nmobility = 1e5\npsi_s = 0\n"
    "[contact]\nk = 1e7\n"
    "[lyapunov]\nenabled = yes\n"
    "[ball.1]\nposition = -0.5\n[ball.2]\nposition = -0.2\n"
    "[ball.3]\nposition = 0.2\n[ball.4]\nposition = 0.5\n";

static double ball_distance(const bf_coupled_parts *a,
                            const bf_coupled_parts *b, double tau)
{
    double d2 = 0;
    for (size_t i = 0; i < a->sys->b.n; i++) {
        double dx = b->sys->b.x[i] - a->sys->b.x[i];
        double dv = tau * (b->sys->b.v[i] - a->sys->b.v[i]);
        d2 += dx * dx + dv * dv;
    }
    return sqrt(d2);
}

/* N steps with renormalise_every = N (one pull-back, at the last step)
 * against renormalise_every = N + 1 (none): the runs are the same, and
 * the pulled shadow must be run + (d0/d)(unpulled shadow - run) in every
 * component (balls, all film arrays, mu_cpl), at distance d0 in the ball
 * norm, with a physical film.  N = 2000 ends a multirate window
 * (film_every = 10: the film has just stepped); N = 1995 stops inside one,
 * where mu_cpl (computed at step 1990 from the balls then) is state that
 * the film step at 2000 will use. */
static void check_pull(const char *tend, const char *every_pulled,
                       const char *every_not)
{
    bf_sim *p = tu_run_scene(fig8_small, tend, every_pulled, NULL);
    bf_sim *u = tu_run_scene(fig8_small, tend, every_not, NULL);
    bf_coupled_parts pr, ps, ur, us;
    ck_assert(bf_coupled_sim_parts(p, &pr, &ps) == BF_OK);
    ck_assert(bf_coupled_sim_parts(u, &ur, &us) == BF_OK);
    const double d0 = 1e-8, tau = 0.01; /* the defaults */
    double d = ball_distance(&ur, &us, tau);
    ck_assert_msg(d > d0, "the separation did not grow: %g", d);
    double f = d0 / d;
    /* the pulled shadow at d0, to round-off of x ~ 0.5 cm (1e-16) */
    double dp = ball_distance(&pr, &ps, tau);
    ck_assert_msg(fabs(dp / d0 - 1) < 1e-6, "distance after the pull %g",
                  dp / d0);
    /* every component scaled by the same factor */
    size_t nb = pr.sys->b.n;
    for (size_t i = 0; i < nb; i++) {
        ck_assert(pr.sys->b.x[i] == ur.sys->b.x[i]);
        ck_assert(ps.sys->b.x[i] ==
                  pr.sys->b.x[i] + (us.sys->b.x[i] - ur.sys->b.x[i]) * f);
        ck_assert(ps.sys->b.v[i] ==
                  pr.sys->b.v[i] + (us.sys->b.v[i] - ur.sys->b.v[i]) * f);
    }
    double *a_pr[BF_FILM_NSTATE], *a_ps[BF_FILM_NSTATE];
    double *a_ur[BF_FILM_NSTATE], *a_us[BF_FILM_NSTATE];
    size_t nodes = bf_film_state(pr.film, a_pr);
    bf_film_state(ps.film, a_ps);
    bf_film_state(ur.film, a_ur);
    bf_film_state(us.film, a_us);
    double film_diff = 0;
    for (int q = 0; q < BF_FILM_NSTATE; q++)
        for (size_t i = 0; i < nodes; i++) {
            ck_assert(a_pr[q][i] == a_ur[q][i]);
            ck_assert_msg(a_ps[q][i] ==
                              a_pr[q][i] + (a_us[q][i] - a_ur[q][i]) * f,
                          "film array %d node %zu not pulled", q, i);
            if (q < 4)
                film_diff = fmax(film_diff, fabs(a_us[q][i] - a_ur[q][i]));
        }
    /* the film did take part: the shadow film had moved away */
    ck_assert_msg(film_diff > 0, "the shadow film equals the run's");
    for (size_t i = 0; i < nodes; i++)
        ck_assert(ps.mu_cpl[i] ==
                  pr.mu_cpl[i] + (us.mu_cpl[i] - ur.mu_cpl[i]) * f);
    /* physical: alpha_k h >= 0, h > 0, |psi| <= 1 */
    const double *h = bf_film_h(ps.film), *psi = bf_film_psi(ps.film);
    for (size_t i = 0; i < nodes; i++) {
        ck_assert(a_ps[0][i] >= 0 && a_ps[1][i] >= 0);
        ck_assert(h[i] > 0 && fabs(psi[i]) <= 1);
    }
    ck_assert(bf_film_min_alpha(ps.film) >= 0);
    bf_sim_free(p);
    bf_sim_free(u);
}

START_TEST(pull_back_scales_whole_state_and_keeps_film_physical)
{
    check_pull("scene.t_end=0.02", "lyapunov.renormalise_every=2000",
               "lyapunov.renormalise_every=2001");
    check_pull("scene.t_end=0.01995", "lyapunov.renormalise_every=1995",
               "lyapunov.renormalise_every=1996");
}
END_TEST

/* A separation that shrank is left alone and the sum telescopes: d = d0/2
 * then d = 2 d0 gives log 2 in total and one pull-back by 1/2; one that
 * shrank below BF_LYAP_RESEED_BELOW d0 is re-seeded. */
START_TEST(shrunken_separation_is_not_pushed_out)
{
    bf_lyap_sum ls = {.n = 1, .d0 = 1, .tau = 1, .every = 1, .d_start = 1};
    double x = 0, v = 0, xs = 0.5, vs = 0, f;
    bf_err err = {0};
    ck_assert(bf_lyap_measure(&ls, &x, &v, &xs, &vs, 1.0, &f, &err) == BF_OK);
    ck_assert(f == 1.0);
    ck_assert(ls.d_start == 0.5);
    xs = 2;
    ck_assert(bf_lyap_measure(&ls, &x, &v, &xs, &vs, 2.0, &f, &err) == BF_OK);
    ck_assert(f == 0.5);
    ck_assert(ls.d_start == 1);
    double t;
    ck_assert(fabs(bf_lyap_sum_estimate(&ls, &t) - log(2.0) / 2) < 1e-15);
    ck_assert(t == 2.0);
    /* shrunk below BF_LYAP_RESEED_BELOW d0: re-seed (factor 0), the next
     * interval starts at d0 again, and the shrink is still counted */
    xs = 0.5 * BF_LYAP_RESEED_BELOW;
    ck_assert(bf_lyap_measure(&ls, &x, &v, &xs, &vs, 3.0, &f, &err) == BF_OK);
    ck_assert(f == 0.0);
    ck_assert(ls.d_start == 1);
    ck_assert(fabs(bf_lyap_sum_estimate(&ls, &t) -
                   log(BF_LYAP_RESEED_BELOW) / 3) < 1e-15);
    /* just above the threshold: left alone */
    xs = 2 * BF_LYAP_RESEED_BELOW;
    ck_assert(bf_lyap_measure(&ls, &x, &v, &xs, &vs, 4.0, &f, &err) == BF_OK);
    ck_assert(f == 1.0);
    ck_assert(ls.d_start == xs);
    xs = 0;
    ck_assert(bf_lyap_measure(&ls, &x, &v, &xs, &vs, 5.0, &f, &err) ==
              BF_EUNSTABLE);
}
END_TEST

/* Stopped at an odd step inside a multirate window and between
 * renormalisations, continued with --restart: the same bits in every
 * dataset (/lyapunov/estimate included) and the same lambda. Plain,
 * with symmetrize = yes (the mirror-odd displacement) and with film_every
 * = auto (the run's and the shadow's film steps are state). */
static void restart_case(const char *tag, const char *sym)
{
    char scene[600], full[600], part[600];
    snprintf(scene, sizeof scene, "%s", tu_write(tag, fig8_small));
    snprintf(full, sizeof full, "%s.full.h5", tu_tmp(tag));
    snprintf(part, sizeof part, "%s.part.h5", tu_tmp(tag));
    const char *every = "lyapunov.renormalise_every=70";
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", scene, "-o", full, "-q", "--set",
                    every, "--set", sym, NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    const char *args[] = {"--set", every, "--set", sym, NULL};
    tu_stop_restart_same(scene, full, part, "1237", args);
    double lf, lp;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_real(full, "/", "lyapunov_exponent", &lf, &e) ==
              BF_OK);
    ck_assert(bf_h5_read_attr_real(part, "/", "lyapunov_exponent", &lp, &e) ==
              BF_OK);
    ck_assert_msg(isfinite(lf) && lf == lp, "lambda %.17g vs %.17g", lf, lp);
    double *est;
    size_t n0, n1;
    ck_assert(bf_h5_read(full, "/lyapunov/estimate", &est, &n0, &n1, &e) ==
              BF_OK);
    ck_assert_int_eq(n0, 28); /* 2000 steps / 70 */
    free(est);
}

START_TEST(restart_bit_identical_with_estimate)
{
    restart_case("lyap_plain.ini", "coupled.symmetrize=no");
    restart_case("lyap_sym.ini", "coupled.symmetrize=yes");
    restart_case("lyap_auto.ini", "coupled.film_every=auto");
}
END_TEST


/* film_every = auto with the shadow: after every step the shadow's film
 * step under way is the run's (the same start, the same K), and K did
 * change; choosing its own from its own balls, the shadow would step its
 * film at other times (its lag and velocities differ from the run's). */
START_TEST(adaptive_shadow_takes_the_runs_film_steps)
{
    bf_scene *sc = tu_scene(fig8_small);
    bf_err err = {0};
    ck_assert(bf_scene_set(sc, "coupled.film_every=auto", "test", &err) ==
              BF_OK);
    ck_assert(bf_scene_set(sc, "coupled.multirate_tol=1e-7", "test", &err) ==
              BF_OK);
    /* a shadow far from the run (1e-3 cm), whose own choices would differ */
    ck_assert(bf_scene_set(sc, "lyapunov.d0=1e-3", "test", &err) == BF_OK);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK);
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL,
                                    &err) == BF_OK,
                  "%s", err.msg);
    const coupled_model *m = bf_sim_model(sim);
    ck_assert(m->adaptive && m->shadow && m->shadow->leader == m);
    long kmin = m->win_k, kmax = m->win_k;
    for (long n = 0; n < bf_sim_steps_total(sim); n++) {
        ck_assert_msg(bf_sim_steps(sim, 1, &err) == BF_OK, "%s", err.msg);
        ck_assert_msg(m->shadow->win_start == m->win_start &&
                          m->shadow->win_k == m->win_k,
                      "step %ld: shadow window %ld + %ld, run's %ld + %ld", n,
                      m->shadow->win_start, m->shadow->win_k, m->win_start,
                      m->win_k);
        kmin = m->win_k < kmin ? m->win_k : kmin;
        kmax = m->win_k > kmax ? m->win_k : kmax;
    }
    ck_assert_msg(kmax > kmin, "K stayed %ld", kmin);
    bf_sim_free(sim);
    bf_scene_free(sc);
}
END_TEST

Suite *suite_coupled_lyapunov(void)
{
    Suite *s = suite_create("coupled_lyapunov");
    TCase *tc = tu_tcase("shadow");
    tcase_add_test(tc, without_film_force_equals_balls_model);
    tcase_add_test(tc, pull_back_scales_whole_state_and_keeps_film_physical);
    tcase_add_test(tc, shrunken_separation_is_not_pushed_out);
    tcase_add_test(tc, restart_bit_identical_with_estimate);
    tcase_add_test(tc, adaptive_shadow_takes_the_runs_film_steps);
    suite_add_tcase(s, tc);
    return s;
}
