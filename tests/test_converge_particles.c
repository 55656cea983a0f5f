/* test_converge_particles.c: `ballfilm converge` on Greenspan's 1973
 * particles (src/models/study_g73.c) against the ARKODE reference
 * on the particles' ODE (src/models/g73_ode.c), and on the 1972 ones
 * (study_g72.c, g72_ode.c).
 *
 *   orders     runs/greenspan73_hex_v50.ini (34 particles, V = 50) over
 *              the short window T = 0.2 s (10 steps of the scene's dt =
 *              0.02 s), dt = 0.02, 0.01, 0.005 s: the paper's implicit
 *              scheme and the 1972 leapfrog are both second order (the
 *              implicit scheme is the discrete-gradient mid-point rule,
 *              symmetric, so its error expansion is in dt^2; the
 *              leapfrog likewise).  Measured orders 1.99-2.01 for x and v;
 *              the next term of the expansion is O(dt^4), below 1 % of the
 *              leading one at these steps, and the reference's estimated
 *              error (3.6e-14 cm) is 1e-7 of the smallest error compared,
 *              so +-0.15 (the tolerance) is wide; the window is
 *              short enough that chaos (the errors grow like exp(lambda
 *              T)) does not bend the orders.
 *   energy     the implicit scheme keeps K + V to 1e-13 relative (its
 *              solver tolerance 1e-10 on x, v), the leapfrog only to
 *              O(dt^2) (above 1e-10 here), ARKODE's error falls with its
 *              tolerance.
 *   restart    leapfrog and arkode on the hexagon, IMEX on the film:
 *              stopped and continued, the same bits and counters.
 *   adaptive   ARKODE at rtol 1e-6 and 1e-10: errors below 1e-6 and 1e-10
 *              cm and falling by over 100x (measured 7.7e-10, 7.0e-13: 20x
 *              the reference's estimated error). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/converge.h"
#include "testutil.h"

START_TEST(greenspan73_and_leapfrog_second_order)
{
    const char *m[] = {"greenspan73", "leapfrog", "arkode"};
    const double dts[] = {0.02, 0.01, 0.005};
    const double tols[] = {1e-6, 1e-10};
    bf_converge_opts o = {.methods = m,
                          .nmethods = 3,
                          .dts = dts,
                          .ndts = 3,
                          .tols = tols,
                          .ntols = 2,
                          .t_end = 0.2,
                          .rows = 5,
                          .repeats = -1};
    bf_err err = {0};
    bf_converge_result *r;
    ck_assert_msg(bf_converge_file(tu_repo("runs/greenspan73_hex_v50.ini"),
                                   NULL, 0, &o, &r, &err) == BF_OK,
                  "%s", err.msg);
    ck_assert_uint_eq(r->nrows, 8);
    ck_assert_str_eq(r->groups[0].name, "x");
    ck_assert_msg(r->ref_err[0] < 1e-12, "reference error %g", r->ref_err[0]);
    ck_assert(strstr(r->notes, "chaotic"));
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(!w->status, "%s: %s", w->label, w->msg);
        ck_assert_msg(w->err[0] > (w->method < 2 ? 1e3 : 10) * r->ref_err[0],
                      "%s: err %g", w->label, w->err[0]);
        if (w->method == 0)
            ck_assert_msg(w->invariant_err < 1e-13, "energy %g",
                          w->invariant_err);
        if (w->method == 1)
            ck_assert_msg(w->invariant_err > 1e-10, "leapfrog energy %g",
                          w->invariant_err);
        if (w->method == 2)
            ck_assert_msg(w->err[0] < w->tol, "arkode rtol %g: err %g",
                          w->tol, w->err[0]);
        if (w->method < 2 && !isnan(w->order_obs[0]))
            for (size_t g = 0; g < 2; g++)
                ck_assert_msg(fabs(w->order_obs[g] - 2.0) < 0.15,
                              "%s dt %g: observed order %.3f (%s)", w->label,
                              w->dt, w->order_obs[g], r->groups[g].name);
    }
    ck_assert(r->rows[7].err[0] < r->rows[6].err[0] / 100);
    bf_converge_free(r);
}
END_TEST

/* Greenspan 1972, Example 1 (runs/greenspan72_ex1.ini, 16 particles,
 * V = 100 cm/s) over the window T = 0.01 s: the leapfrog against ARKODE
 * on the same forces (src/models/study_g72.c).  The window is chosen
 * free of events: a run at dt = 1e-5 s to 0.02 s has no wall hit, no
 * change of any particle's support kind, and its accelerations (from the
 * velocity differences) have no jump and no kink before t = 0.0126 s
 * (the overlap area of particles 2 and 6 starts changing there); over T
 * = 0.02 s the observed orders are 2.49, 1.16, 2.99.  Inside the window
 * the right-hand side is smooth and the leapfrog, symmetric, has an
 * error expansion in dt^2: measured orders 2.00 and 2.00 at dt = 1e-3,
 * 5e-4, 2.5e-4 s, the dt^4 term below 1 % of the leading one, the
 * reference's estimated error (4e-14 cm) 5e-6 of the smallest error
 * compared; so +-0.15 is wide, and a kink inside the window (the orders
 * above) would fail it. */
START_TEST(greenspan72_leapfrog_second_order_without_events)
{
    const char *m[] = {"leapfrog", "arkode"};
    const double dts[] = {1e-3, 5e-4, 2.5e-4};
    const double tols[] = {1e-6};
    bf_converge_opts o = {.methods = m,
                          .nmethods = 2,
                          .dts = dts,
                          .ndts = 3,
                          .tols = tols,
                          .ntols = 1,
                          .t_end = 0.01,
                          .rows = 5,
                          .repeats = -1};
    bf_err err = {0};
    bf_converge_result *r;
    ck_assert_msg(bf_converge_file(tu_repo("runs/greenspan72_ex1.ini"),
                                   NULL, 0, &o, &r, &err) == BF_OK,
                  "%s", err.msg);
    ck_assert_uint_eq(r->nrows, 4);
    ck_assert_str_eq(r->groups[0].name, "x");
    ck_assert_msg(r->ref_err[0] < 1e-12, "reference error %g", r->ref_err[0]);
    ck_assert(strstr(r->notes, "not smooth"));
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(!w->status, "%s: %s", w->label, w->msg);
        if (w->method == 0) {
            ck_assert_msg(w->err[0] > 1e3 * r->ref_err[0], "err %g",
                          w->err[0]);
            if (!isnan(w->order_obs[0]))
                ck_assert_msg(fabs(w->order_obs[0] - 2.0) < 0.15,
                              "dt %g: observed order %.3f", w->dt,
                              w->order_obs[0]);
        } else {
            /* rtol 1e-6 on positions below 100 cm */
            ck_assert_msg(w->err[0] < 1e-4, "arkode: err %g", w->err[0]);
        }
    }
    ck_assert(!isnan(r->rows[2].order_obs[0]));
    bf_converge_free(r);
}
END_TEST

/* A run with args, then the same stopped at step `stop` and continued:
 * the same datasets and counters (tu_stop_restart_same). */
static void restart_case(const char *tag, const char *scene, const char *stop,
                         const char *const *args)
{
    char full[600], part[600];
    snprintf(full, sizeof full, "%s.full.h5", tu_tmp(tag));
    snprintf(part, sizeof part, "%s.part.h5", tu_tmp(tag));
    const char *argv[24] = {"run", scene, "-o", full, "-q"};
    size_t n = 5;
    for (const char *const *a = args; *a && n < 23; a++)
        argv[n++] = *a;
    argv[n] = NULL;
    char *err = NULL;
    int rc = tu_runv(NULL, &err, argv);
    ck_assert_msg(rc == 0, "%s: exit %d: %s", tag, rc, err ? err : "");
    free(err);
    tu_stop_restart_same(scene, full, part, stop, args);
}

START_TEST(new_integrators_restart_bit_for_bit)
{
    /* the checkpoints keep ARKODE's next initial step and its counters,
     * the leapfrog's counters (its kept force is recomputed, not
     * counted), the film's time */
    const char *hex = tu_repo("runs/greenspan73_hex_v50.ini");
    const char *lf[] = {"--set", "greenspan73.integrator=leapfrog", NULL};
    const char *ark[] = {"--set", "greenspan73.integrator=arkode", NULL};
    const char *imex[] = {"--set", "scene.t_end=1",   "--set",
                          "scene.dt=0.05", "--set", "film.perturbation=0",
                          "--set", "film.scheme=arkode-imex", NULL};
    restart_case("g73_leapfrog", hex, "17", lf);
    restart_case("g73_arkode", hex, "17", ark);
    const char *g72[] = {"--set", "greenspan72.integrator=arkode", "--set",
                         "scene.t_end=0.3", NULL};
    restart_case("g72_arkode", tu_repo("runs/greenspan72_ex1.ini"), "170",
                 g72);
    restart_case("film_imex", tu_repo("runs/kink_converge.ini"), "7", imex);
}
END_TEST

Suite *suite_converge_particles(void)
{
    Suite *s = suite_create("converge_particles");
    TCase *tc = tu_tcase("converge_particles");
    tcase_add_test(tc, greenspan73_and_leapfrog_second_order);
    tcase_add_test(tc, greenspan72_leapfrog_second_order_without_events);
    tcase_add_test(tc, new_integrators_restart_bit_for_bit);
    suite_add_tcase(s, tc);
    return s;
}
