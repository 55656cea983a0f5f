/* test_film_imex.c: the film's ARKODE schemes ([film] scheme = arkode,
 * arkode-imex: ARKODE on the film's equations in method-of-lines form on
 * the grid of the invariant scheme, src/film/film_mol.c) and the film's
 * convergence study (src/models/study_film.c).
 *
 *   imex_kink   IMEX (ARKStep, the phase-separation and gravity-wave
 *               terms implicit) on the kink at dx = 0.025 cm relaxes to
 *               the same discrete steady state as the invariant scheme,
 *               with a mean internal step of more than 10x the explicit
 *               stable limit (3.1e-4 s there, the dx^2 phase-separation
 *               limit): max |psi - tanh(x/sqrt 2)| at 20 s within 10 % of
 *               the invariant scheme's (issue 19).  Both converge to the
 *               discrete steady state of the same space discretisation,
 *               so the two errors differ only by what is left of the
 *               transient and by the IMEX time error at rtol 1e-6
 *               (measured: 1.7624e-5 both, 6e-5 relative apart; mean
 *               step 0.1 s = 340x the limit).  Steady: the error changes
 *               by less than 1 % from 15 s to 20 s.
 *   time order  converge on runs/kink_converge.ini without perturbation,
 *               T = 1 s: the invariant scheme against the method-of-lines
 *               reference (time error only) is first order in dt: its
 *               leading time error is the O(dt dx^2) Lax-Wendroff
 *               remainder (docs/models/film.md), the next term O(dt^2)
 *               is below 1/50 of it at these steps (measured orders
 *               0.98-1.00 on psi), so +-0.15 (the tolerance)
 *               leaves room for the rounding of the steps only.  The
 *               second order in dx is checked by test_film.c
 *               (steady_kink_error_is_dx2: error ratio 4 within 5 % for
 *               halved dx, i.e. order 2 +- 0.04).
 *   same system IMEX at rtol 1e-10 agrees with the ERK reference (another
 *               method, the same equations) to 1e-9 in psi at T = 1 s,
 *               its error shrinks with the tolerance, and the phase
 *               totals of both stay constant to 1e-13 (the flux form
 *               telescopes for any integrator).
 *   notes       a study on a start with random noise says that no smooth
 *               limit exists and names --set film.perturbation=0. */
#include <math.h>
#include <string.h>

#include "ballfilm/converge.h"
#include "ballfilm/run.h"
#include "models/filmsys.h"
#include "testutil.h"

/* The kink error of runs/kink_converge.ini at dx = 0.025 cm after t (and
 * after t_mid, if > 0), with scheme `scheme` and [scene] dt; the counters
 * and the invariant scheme's stable limit. */
static double kink_run(const char *scheme, double dt, double t_mid,
                       double *e_mid, bf_counters *c, double *limit)
{
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load(&sc, tu_repo("runs/kink_converge.ini"), &err) ==
              BF_OK);
    char sdt[64], ssch[64];
    snprintf(sdt, sizeof sdt, "scene.dt=%.17g", dt);
    snprintf(ssch, sizeof ssch, "film.scheme=%s", scheme);
    const char *sets[] = {"film.dx=0.025", "scene.t_end=20", sdt, ssch,
                          "scene.output_every=0"};
    for (size_t k = 0; k < 5; k++)
        ck_assert_msg(bf_scene_set(sc, sets[k], "test", &err) == BF_OK, "%s",
                      err.msg);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK);
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL,
                                    &err) == BF_OK,
                  "%s", err.msg);
    bf_filmsys *fs = bf_sim_model(sim);
    if (t_mid > 0) {
        ck_assert_msg(bf_sim_run_until(sim, t_mid, &err) == BF_OK, "%s",
                      err.msg);
        *e_mid = bf_filmsys_kink_error(fs);
    }
    ck_assert_msg(bf_sim_run(sim, &err) == BF_OK, "%s", err.msg);
    double e = bf_filmsys_kink_error(fs);
    bf_filmsys_counters(fs, c);
    if (limit) {
        char why[256];
        *limit = bf_film_stable_dt(bf_filmsys_film(fs), why, sizeof why);
    }
    bf_sim_free(sim);
    bf_scene_free(sc);
    return e;
}

START_TEST(imex_kink_steady_state_at_large_steps)
{
    bf_counters ci, cx;
    double limit, e15;
    const double e_inv = kink_run("invariant", 2.5e-4, 0, NULL, &ci, &limit);
    /* [scene] dt = 1 s: ARKODE chooses its steps inside each second */
    const double e_imex = kink_run("arkode-imex", 1.0, 15.0, &e15, &cx, NULL);
    const double mean_step = 20.0 / (double)cx.steps;
    ck_assert_msg(limit > 2.5e-4 && limit < 4e-4,
                  "explicit limit %g s at dx = 0.025", limit);
    ck_assert_msg(mean_step >= 10 * limit,
                  "IMEX mean step %g s, explicit limit %g s", mean_step,
                  limit);
    ck_assert_msg(fabs(e_imex - e_inv) <= 0.1 * e_inv,
                  "kink error: IMEX %.6e, invariant %.6e", e_imex, e_inv);
    ck_assert_msg(fabs(e_imex - e15) < 0.01 * e_imex,
                  "IMEX not steady: kink error %.6e at 15 s, %.6e at 20 s",
                  e15, e_imex);
    fprintf(stderr, "film imex kink dx=0.025: error %.6e (invariant %.6e), "
            "mean step %.3g s = %.0fx the limit %.3g s\n",
            e_imex, e_inv, mean_step, mean_step / limit, limit);
}
END_TEST

static bf_converge_result *kink_study(const char *const *methods, size_t nm,
                                      int adaptive, const double *h,
                                      size_t nh, const char *pert)
{
    bf_err err = {0};
    const char *sets[] = {pert};
    bf_converge_opts o = {.methods = methods,
                          .nmethods = nm,
                          .t_end = 1.0,
                          .repeats = -1};
    if (adaptive)
        o.tols = h, o.ntols = nh;
    else
        o.dts = h, o.ndts = nh;
    bf_converge_result *r;
    ck_assert_msg(bf_converge_file(tu_repo("runs/kink_converge.ini"), sets, 1,
                                   &o, &r, &err) == BF_OK,
                  "%s", err.msg);
    return r;
}

START_TEST(invariant_scheme_first_order_in_dt)
{
    const char *m[] = {"invariant"};
    const double dts[] = {1e-3, 5e-4, 2.5e-4};
    bf_converge_result *r =
        kink_study(m, 1, 0, dts, 3, "film.perturbation=0");
    ck_assert_uint_eq(r->nrows, 3);
    ck_assert_str_eq(r->groups[0].name, "psi");
    for (size_t k = 0; k < 3; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(!w->status, "%s", w->msg);
        /* the errors compared are far above the reference's */
        ck_assert_msg(w->err[0] > 100 * r->ref_err[0], "err %g, ref %g",
                      w->err[0], r->ref_err[0]);
        ck_assert_msg(w->invariant_err < 1e-13, "totals %g",
                      w->invariant_err);
        if (k)
            ck_assert_msg(fabs(w->order_obs[0] - 1.0) < 0.15,
                          "dt %g: observed order %.3f (errors %g)", w->dt,
                          w->order_obs[0], w->err[0]);
    }
    ck_assert(strstr(r->notes, "same grid"));
    ck_assert(!strstr(r->notes, "perturbation=0"));
    bf_converge_free(r);
}
END_TEST

START_TEST(imex_solves_the_same_system)
{
    const char *m[] = {"arkode-imex"};
    const double tols[] = {1e-8, 1e-10};
    bf_converge_result *r =
        kink_study(m, 1, 1, tols, 2, "film.perturbation=0");
    ck_assert_uint_eq(r->nrows, 2);
    ck_assert_msg(strstr(r->ref_label, "ERK"), "%s", r->ref_label);
    ck_assert(!r->rows[0].status && !r->rows[1].status);
    ck_assert_msg(r->rows[1].err[0] < 1e-9, "psi error %g at rtol 1e-10",
                  r->rows[1].err[0]);
    ck_assert_msg(r->rows[1].err[0] < r->rows[0].err[0] / 10,
                  "errors %g %g", r->rows[0].err[0], r->rows[1].err[0]);
    ck_assert(r->ref_invariant_err < 1e-13 &&
              r->rows[1].invariant_err < 1e-13);
    bf_converge_free(r);
}
END_TEST

START_TEST(perturbed_start_has_no_smooth_limit)
{
    const char *m[] = {"invariant"};
    const double dts[] = {5e-4};
    bf_converge_result *r = kink_study(m, 1, 0, dts, 1, "film.perturbation=1e-4");
    ck_assert_msg(strstr(r->notes, "no smooth limit") &&
                      strstr(r->notes, "--set film.perturbation=0"),
                  "%s", r->notes);
    bf_converge_free(r);
}
END_TEST

Suite *suite_film_imex(void)
{
    Suite *s = suite_create("film_imex");
    TCase *tc = tu_tcase("film_imex");
    tcase_add_test(tc, imex_kink_steady_state_at_large_steps);
    tcase_add_test(tc, invariant_scheme_first_order_in_dt);
    tcase_add_test(tc, imex_solves_the_same_system);
    tcase_add_test(tc, perturbed_start_has_no_smooth_limit);
    suite_add_tcase(s, tc);
    return s;
}
