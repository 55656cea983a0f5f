/* test_converge_coupled.c: `ballfilm converge` on balls in the dynamic
 * film (src/models/study_coupled.c) against ARKODE on the whole system,
 * the balls and the film in method-of-lines form as one ODE
 * (src/models/coupled_whole.c, [coupled] scheme = arkode).
 *
 *   split      runs/coupled_fig8.ini over T = 0.02 s (the four balls
 *              start at rest; their first contact is at t = 0.106 s, so
 *              the window has no Hertz onset), dt = 4e-5, 2e-5, 1e-5 s:
 *              MV2M, RK4 and MV2M with film_every = 4.  The split scheme
 *              lags the film one step behind the balls and its film
 *              scheme is first order in dt, so every ball integrator
 *              converges to the whole-system solution at order 1
 *              (measured 0.97-1.01 for x, v, psi and h; with film_every
 *              = 4 h gives 0.93-0.98, the dt^2 term being larger at 4
 *              dt).  +-0.15 is wide for the dt^2 term at these steps and
 *              fails an order-2 or order-0 error.  That the split scheme
 *              (the invariant film scheme, the balls' integrators, the
 *              coupling's sums) converges to ARKODE on f_MOL is the
 *              independent check of both.
 *   mri        MRIStep (film slow at the fixed step dt, balls fast, inner
 *              ERK at rtol 1e-10) over T = 0.05 s at dt = 4e-4, 2e-4, 1e-4:
 *              the film converges at MRIStep's order 3 (measured psi
 *              3.02, 3.02, h 2.94, 2.98, q 3.02-3.04); the balls' errors
 *              are at round-off already (not tested for an order).
 *   refusals   what the whole-system schemes do not serve is named.
 *   restart    scheme = arkode and mri stopped and continued: the same
 *              bits and counters. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/converge.h"
#include "testutil.h"

/* the index of group `name` in r (fails the test if absent) */
static size_t group(const bf_converge_result *r, const char *name)
{
    for (size_t g = 0; g < r->ngroups; g++)
        if (!strcmp(r->groups[g].name, name))
            return g;
    ck_abort_msg("no group %s", name);
    return 0;
}

/* the study of runs/coupled_fig8.ini: nm methods at the three steps dts
 * to t_end, 5 rows compared */
static bf_converge_result *study(const char **m, size_t nm,
                                 const double *dts, double t_end)
{
    bf_converge_opts o = {.methods = m, .nmethods = nm, .dts = dts,
                          .ndts = 3, .t_end = t_end, .rows = 5,
                          .repeats = -1};
    bf_err err = {0};
    bf_converge_result *r = NULL;
    ck_assert_msg(bf_converge_file(tu_repo("runs/coupled_fig8.ini"), NULL, 0,
                                   &o, &r, &err) == BF_OK,
                  "%s", err.msg);
    return r;
}

START_TEST(split_first_order_against_the_whole_system)
{
    const char *m[] = {"mv2m", "rk4", "mv2m:film_every=4"};
    const double dts[] = {4e-5, 2e-5, 1e-5};
    bf_converge_result *r = study(m, 3, dts, 0.02);
    ck_assert_uint_eq(r->nrows, 9);
    ck_assert_uint_eq(r->ngroups, 6);
    ck_assert(strstr(r->ref_label, "whole system"));
    ck_assert(strstr(r->notes, "method-of-lines"));
    const char *tested[] = {"x", "v", "psi", "h"};
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(!w->status, "%s: %s", w->label, w->msg);
        ck_assert_int_eq(w->order, 1);
        /* the invariant scheme keeps the phase totals to round-off */
        ck_assert_msg(w->invariant_err < 1e-13, "%s: totals %g", w->label,
                      w->invariant_err);
        for (size_t q = 0; q < 4; q++) {
            size_t g = group(r, tested[q]);
            ck_assert_msg(w->err[g] > 100 * r->ref_err[g],
                          "%s: err %g, reference %g", w->label, w->err[g],
                          r->ref_err[g]);
            if (k % 3 == 0)
                continue;
            ck_assert_msg(fabs(w->order_obs[g] - 1.0) < 0.15,
                          "%s dt %g: observed order %.3f (%s)", w->label,
                          w->dt, w->order_obs[g], tested[q]);
        }
    }
    bf_converge_free(r);
}
END_TEST

START_TEST(mri_third_order_in_the_film)
{
    const char *m[] = {"mri:rtol=1e-10"};
    const double dts[] = {4e-4, 2e-4, 1e-4};
    bf_converge_result *r = study(m, 1, dts, 0.05);
    ck_assert_uint_eq(r->nrows, 3);
    const char *tested[] = {"psi", "h", "q_d"};
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        ck_assert_msg(!w->status, "%s: %s", w->label, w->msg);
        ck_assert_int_eq(w->order, 3);
        for (size_t q = 0; q < 3; q++) {
            size_t g = group(r, tested[q]);
            /* the converge table's own threshold for a meaningful
             * order (measured: psi 1.2e-13 at dt = 1e-4 against the
             * reference's 1.4e-15, which biases the order by < 0.01) */
            ck_assert_msg(w->err[g] > 10 * r->ref_err[g],
                          "dt %g: err %g, reference %g", w->dt, w->err[g],
                          r->ref_err[g]);
            if (k > 0)
                ck_assert_msg(fabs(w->order_obs[g] - 3.0) < 0.15,
                              "dt %g: observed order %.3f (%s)", w->dt,
                              w->order_obs[g], tested[q]);
        }
    }
    bf_converge_free(r);
}
END_TEST

/* a run of the Fig. 8 scene with --set a and b that must fail with exit 2
 * and a message holding want */
static void refused(const char *a, const char *b, const char *want)
{
    char *e = NULL;
    int rc = tu_run(NULL, &e, "run", tu_repo("runs/coupled_fig8.ini"), "-q",
                    "-o", tu_tmp("refused.h5"), "--set", a, "--set", b,
                    NULL);
    ck_assert_msg(rc == 2 && e && strstr(e, want), "%s %s: exit %d: %s", a, b,
                  rc, e ? e : "");
    free(e);
}

START_TEST(whole_system_refusals_name_the_key)
{
    refused("coupled.scheme=arkode", "coupled.film_every=10",
            "[coupled] film_every");
    refused("coupled.scheme=mri", "lyapunov.enabled=yes",
            "[lyapunov] enabled");
    refused("coupled.scheme=arkode", "coupled.film=static",
            "[coupled] scheme");
    refused("coupled.scheme=mri", "film.scheme=arkode", "[film] scheme");
    refused("coupled.scheme=arkode", "coupled.symmetrize=yes",
            "[coupled] symmetrize");
    /* mri's slow step is [scene] dt: the film's explicit stable limit */
    refused("coupled.scheme=mri", "scene.dt=1e-2", "film's stable limit");
}
END_TEST

START_TEST(whole_system_restarts_bit_for_bit)
{
    const char *scene = tu_repo("runs/coupled_fig8.ini");
    const char *ark[] = {"--set", "coupled.scheme=arkode", "--set",
                         "scene.t_end=0.003", NULL};
    const char *mri[] = {"--set", "coupled.scheme=mri", "--set",
                         "scene.dt=1e-4", "--set", "scene.output_every=5",
                         "--set", "scene.t_end=0.006", NULL};
    const char *const *args[2] = {ark, mri};
    const char *tags[2] = {"whole_arkode", "whole_mri"};
    const char *stops[2] = {"170", "33"};
    for (int k = 0; k < 2; k++) {
        char full[600], part[600];
        snprintf(full, sizeof full, "%s.full.h5", tu_tmp(tags[k]));
        snprintf(part, sizeof part, "%s.part.h5", tu_tmp(tags[k]));
        const char *argv[24] = {"run", scene, "-o", full, "-q"};
        size_t n = 5;
        for (const char *const *a = args[k]; *a && n < 23; a++)
            argv[n++] = *a;
        argv[n] = NULL;
        char *e = NULL;
        int rc = tu_runv(NULL, &e, argv);
        ck_assert_msg(rc == 0, "%s: exit %d: %s", tags[k], rc, e ? e : "");
        free(e);
        tu_stop_restart_same(scene, full, part, stops[k], args[k]);
    }
}
END_TEST

Suite *suite_converge_coupled(void)
{
    Suite *s = suite_create("converge_coupled");
    TCase *tc = tu_tcase("converge_coupled");
    tcase_add_test(tc, split_first_order_against_the_whole_system);
    tcase_add_test(tc, mri_third_order_in_the_film);
    tcase_add_test(tc, whole_system_refusals_name_the_key);
    tcase_add_test(tc, whole_system_restarts_bit_for_bit);
    suite_add_tcase(s, tc);
    return s;
}
