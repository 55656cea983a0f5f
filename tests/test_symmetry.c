/* test_symmetry.c: [coupled] symmetrize (forced mirror symmetry of the
 * four-ball film set-up, src/models/coupled.c) and bf_film_mirror.
 *
 * - bf_film_mirror on an arbitrary film state: the result is exactly
 *   mirror symmetric (A_d(i) = A_c(N-i), u_d(i) = -u_c(N-i), psi odd, h
 *   even), a second projection changes nothing, the sum of the phase
 *   totals is kept to round-off, and the reported correction equals the
 *   one computed here from the definition.
 * - The symmetric subspace is invariant: with symmetrize = yes the
 *   symmetry errors of balls and film stay exactly 0 over 0.5 s while the
 *   projection never changes anything by more than 1e-12 relative (round-
 *   off; a wrong mirror map, e.g. u even or h odd, would change O(1)); the
 *   same run without it is asymmetric by then (the control that the
 *   errors are measured at all).
 * - A set-up that is not mirror symmetric is refused naming FILE:LINE and
 *   the key (exit status 2 from the program).
 * - A restarted symmetrized run gives the bits of the uninterrupted one.
 */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/film.h"
#include "ballfilm/h5out.h"
#include "testutil.h"

START_TEST(film_mirror_projects)
{
    bf_film_params p = {.length = 2.0, .dx = 0.1, .rho_d = 1, .rho_c = 1,
                        .nu = 0.01, .g = 980, .a = 1, .b = 1, .gamma = 1};
    bf_film *f;
    bf_err err = {0};
    ck_assert(bf_film_create(&f, &p, &err) == 0);
    const size_t n = bf_film_nodes(f), N = n - 1;
    double h[32], psi[32], ud[32], uc[32];
    ck_assert(n <= 32);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 7);
    for (size_t i = 0; i < n; i++) {
        h[i] = 0.5 + gsl_rng_uniform(r);
        psi[i] = 2 * gsl_rng_uniform(r) - 1;
        ud[i] = gsl_rng_uniform(r) - 0.5;
        uc[i] = gsl_rng_uniform(r) - 0.5;
    }
    gsl_rng_free(r);
    ck_assert(bf_film_set_state(f, h, psi, ud, uc, &err) == 0);
    /* the expected correction from the definition (u at the walls is 0) */
    const double *Ad = bf_film_ah_d(f), *Ac = bf_film_ah_c(f);
    const double *Ud = bf_film_u_d(f), *Uc = bf_film_u_c(f);
    double ea = 0, eu = 0, hmax = 0, umax = 0, tot0 = 0;
    for (size_t i = 0; i < n; i++) {
        ea = fmax(ea, fabs(Ad[i] - Ac[N - i]) / 2);
        eu = fmax(eu, fabs(Ud[i] + Uc[N - i]) / 2);
        hmax = fmax(hmax, h[i]);
        umax = fmax(umax, fmax(fabs(Ud[i]), fabs(Uc[i])));
    }
    double md, mc;
    bf_film_totals(f, &md, &mc);
    tot0 = md + mc;
    double c[2];
    bf_film_mirror(f, 0, c); /* measure only: nothing changes */
    ck_assert(c[0] == ea / hmax && c[1] == eu / umax);
    ck_assert(bf_film_ah_d(f)[3] == Ad[3] && bf_film_u_c(f)[5] == Uc[5]);
    bf_film_mirror(f, 1, c);
    ck_assert(c[0] == ea / hmax && c[1] == eu / umax);
    ck_assert(c[0] > 0.01 && c[1] > 0.01); /* the state was far from it */
    Ad = bf_film_ah_d(f);
    Ac = bf_film_ah_c(f);
    Ud = bf_film_u_d(f);
    Uc = bf_film_u_c(f);
    const double *H = bf_film_h(f), *Psi = bf_film_psi(f);
    for (size_t i = 0; i < n; i++) {
        ck_assert(Ad[i] == Ac[N - i]);
        ck_assert(Ud[i] == -Uc[N - i]);
        ck_assert(H[i] == H[N - i]);
        ck_assert(Psi[i] == -Psi[N - i]);
        ck_assert(H[i] == Ad[i] + Ac[i]);
        /* the bits the step's own derivation gives (also the sign of 0) */
        double ps = (Ad[i] - Ac[i]) / H[i];
        ck_assert(memcmp(&ps, &Psi[i], sizeof ps) == 0);
    }
    ck_assert(Ud[0] == 0 && Uc[0] == 0 && Ud[N] == 0 && Uc[N] == 0);
    bf_film_totals(f, &md, &mc);
    /* each total becomes the mean of the two (trapezoid weights are
     * symmetric); their sum is kept up to the rounding of the sums */
    ck_assert_msg(fabs(md - mc) <= 4e-16 * md, "%g vs %g", md, mc);
    ck_assert_msg(fabs(md + mc - tot0) <= 4e-16 * tot0, "%g", md + mc - tot0);
    bf_film_mirror(f, 1, c);
    ck_assert(c[0] == 0 && c[1] == 0);
    bf_film_free(f);
}
END_TEST

/* the largest of a dataset (rows x cols, cols 0 = 1) */
static double h5max(const char *file, const char *name, size_t *rows)
{
    double *d;
    size_t n0, n1;
    bf_err err = {0};
    ck_assert_msg(bf_h5_read(file, name, &d, &n0, &n1, &err) == 0, "%s",
                  err.msg);
    double m = tu_absmax(d, n0 * (n1 ? n1 : 1));
    free(d);
    if (rows)
        *rows = n0;
    return m;
}

START_TEST(symmetric_subspace_is_invariant)
{
    const char *sym = tu_tmp("sym05.h5"), *plain = tu_tmp("plain05.h5");
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/coupled_fig8_sym.ini"),
                    "-q", "-o", sym, "--set", "scene.t_end=0.5", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    rc = tu_run(NULL, &err, "run", tu_repo("runs/coupled_fig8_sym.ini"), "-q",
                "-o", plain, "--set", "scene.t_end=0.5", "--set",
                "coupled.symmetrize=no", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    size_t rows;
    ck_assert(h5max(sym, "/coupled/sym_balls", &rows) == 0);
    ck_assert_int_eq(rows, 501);
    ck_assert(h5max(sym, "/coupled/sym_film", NULL) == 0);
    /* the plain run has left the subspace by 0.5 s (first at ~0.015 s) */
    ck_assert(h5max(plain, "/coupled/sym_balls", NULL) > 0);
    /* each projection removes round-off only: film u and ball v are
     * differences of terms much larger than themselves, so their rounding
     * is ~1e-15 of max|u|; 1e-12 leaves room and is far below the O(1)
     * change a wrong mirror map would make */
    double *c;
    size_t n0, n1;
    bf_err e2 = {0};
    ck_assert(bf_h5_read(sym, "/coupled/sym_correction_max", &c, &n0, &n1,
                         &e2) == 0);
    ck_assert_int_eq(n0, 4);
    for (int k = 0; k < 4; k++)
        ck_assert_msg(c[k] >= 0 && c[k] <= 1e-12, "correction %d: %g", k, c[k]);
    free(c);
    ck_assert(h5max(sym, "/coupled/sym_correction", &rows) <= 1e-12);
    ck_assert_int_eq(rows, 501);
    /* the phase totals: conserved, and equal (symmetric state) */
    double *md, *mc;
    ck_assert(bf_h5_read(sym, "/film/mass_d", &md, &n0, &n1, &e2) == 0);
    ck_assert(bf_h5_read(sym, "/film/mass_c", &mc, &n0, &n1, &e2) == 0);
    for (size_t i = 0; i < n0; i++) {
        ck_assert_msg(fabs(md[i] - md[0]) <= 1e-14 * md[0], "%g",
                      md[i] - md[0]);
        ck_assert(md[i] == mc[i]);
    }
    free(md);
    free(mc);
}
END_TEST

/* a symmetric four-ball scene; line k of the text is lines[k - 1] */
static const char *lines[] = {
    "[scene]",                     /* 1 */
    "model = coupled",             /* 2 */
    "effects = coupling contact",  /* 3 */
    "dt = 1e-5",                   /* 4 */
    "t_end = 0.01",                /* 5 */
    "[coupled]",                   /* 6 */
    "symmetrize = yes",            /* 7 */
    "[film]",                      /* 8 */
    "length = 10",                 /* 9 */
    "perturbation = 0",            /* 10 */
    "[coupling]",                  /* 11 */
    "psi_s = 0",                   /* 12 */
    "[ball.1]",                    /* 13 */
    "position = -0.5",             /* 14 */
    "[ball.2]",                    /* 15 */
    "position = -0.2",             /* 16 */
    "[ball.3]",                    /* 17 */
    "position = 0.2",              /* 18 */
    "[ball.4]",                    /* 19 */
    "position = 0.5",              /* 20 */
    NULL};

/* the scene with line k replaced (k = 0: unchanged) */
static const char *scene_with(int k, const char *repl)
{
    static char text[2048];
    text[0] = 0;
    for (int i = 0; lines[i]; i++) {
        strcat(text, i + 1 == k ? repl : lines[i]);
        strcat(text, "\n");
    }
    return text;
}

START_TEST(asymmetric_setups_refused)
{
    char msg[2048];
    ck_assert_msg(tu_scene_error(scene_with(0, ""), msg, sizeof msg) == 0,
                  "%s", msg);
    static const struct {
        int line;
        const char *repl, *where, *key;
    } cases[] = {
        {20, "position = 0.51", "test.ini:20:", "[ball.4] position"},
        {18, "position = 0.2\nvelocity = 1", "test.ini:19:",
         "[ball.3] velocity"},
        {20, "position = 0.5\nmass = 2", "test.ini:21:", "[ball.4] mass"},
        {20, "position = 0.5\nradius = 0.12", "test.ini:21:",
         "[ball.4] radius"},
        {10, "perturbation = 1e-6", "test.ini:10:", "[film] perturbation"},
        {10, "center = 0.1", "test.ini:10:", "[film] center"},
        {10, "rho_c = 1.1", "test.ini:10:", "[film] rho_c"},
        {12, "psi_s = 0.1", "test.ini:12:", "[coupling] psi_s"},
        {3, "effects = coupling contact gravity", "test.ini:3:",
         "[scene] effects"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        bf_status st = tu_scene_error(scene_with(cases[k].line, cases[k].repl),
                                      msg, sizeof msg);
        ck_assert_msg(st == BF_EINPUT && strstr(msg, cases[k].where) &&
                          strstr(msg, cases[k].key) &&
                          strstr(msg, "symmetrize"),
                      "case %zu: status %d: %s", k, st, msg);
        /* without symmetrize the same set-up runs */
        char text[2048];
        snprintf(text, sizeof text, "%s",
                 scene_with(cases[k].line, cases[k].repl));
        memcpy(strstr(text, "symmetrize = yes"), "symmetrize = no ", 16);
        ck_assert_msg(tu_scene_error(text, msg, sizeof msg) == 0,
                      "case %zu without symmetrize: %s", k, msg);
    }
    /* the program: exit status 2, no output file */
    const char *out = tu_tmp("refused.h5");
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/coupled_fig9_sym.ini"),
                    "-q", "-o", out, "--set", "ball.2.position=-0.25", NULL);
    ck_assert_msg(rc == 2 && strstr(err, "[ball.3] position"), "exit %d: %s",
                  rc, err);
    free(err);
    FILE *fp = fopen(out, "r");
    ck_assert(fp == NULL);
}
END_TEST

START_TEST(symmetrized_restart_bit_identical)
{
    const char *full = tu_tmp("symrs.h5"), *part = tu_tmp("symrs.part.h5");
    const char *scene = tu_repo("runs/coupled_fig9_sym.ini");
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q",
                            "--set", "scene.t_end=0.1", NULL),
                     0);
    const char *args[] = {"--set", "scene.t_end=0.1", NULL};
    tu_stop_restart_same(scene, full, part, "4321", args);
}
END_TEST

Suite *suite_symmetry(void)
{
    Suite *s = suite_create("symmetry");
    TCase *tc = tu_tcase("mirror");
    tcase_add_test(tc, film_mirror_projects);
    tcase_add_test(tc, symmetric_subspace_is_invariant);
    tcase_add_test(tc, asymmetric_setups_refused);
    tcase_add_test(tc, symmetrized_restart_bit_identical);
    suite_add_tcase(s, tc);
    return s;
}
