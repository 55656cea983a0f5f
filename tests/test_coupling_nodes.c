/* test_coupling_nodes.c: `[coupling] quadrature = nodes` (the integral of
 * eq. 3.10 summed at the nodes, then the natural cubic spline through the
 * node values, src/coupling/nodes.h), against independent references:
 *
 * - at a node, I equals the node sum dx sum_j g_j exp(-|x_j - x_i|/r0)
 *   computed here with one exp() per node (1e-13 relative), at L = 50 cm
 *   (a node at 0) and L = 50.1 cm (nodes at +-0.05);
 * - against the default quadrature (the exact integral of the spline of g,
 *   accurate to dx^4), on a smooth film: the difference is the node sum's
 *   trapezoidal error across the kernel's kink, dx^2 g(r) / (6 r0) to
 *   leading order (Euler-Maclaurin), so it falls as dx^2 (ratio 3.6-4.4
 *   per halving); with that term removed what is left is the spline's
 *   interpolation error, dx^4 in I (ratio > 12) and dx^3 in dI/dr
 *   (ratio > 6);
 * - dI/dr is the derivative of I: a fourth-order finite difference of I
 *   agrees to 1e-8 relative;
 * - a scene runs with the key, and the key's other values are refused.
 * Each check fails for a quadrature that is not this one: the spline of g
 * gives no dx^2 difference, a node sum without the spline gives no dx^4
 * remainder between the nodes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "coupling/coupling.h"
#include "testutil.h"

static const double R0 = 0.5;

/* a smooth film without symmetry: h = 1 + 0.2 sin(x), psi = tanh((x -
 * 0.1)/sqrt 2) */
static double h_of(double x) { return 1.0 + 0.2 * sin(x); }
static double psi_of(double x) { return tanh((x - 0.1) / sqrt(2.0)); }
static double g_of(double x)
{
    double p = psi_of(x);
    return h_of(x) * p * p;
}

static bf_film *smooth_film(double L, double dx)
{
    return tu_film(L, dx, h_of, psi_of);
}

static bf_coupling *make_cpl(const bf_film *f, bf_coupling_quad q)
{
    bf_coupling_params p = {.V0 = 0.01, .r0 = R0, .M = 1e5, .psi_s = 0,
                            .quad = q, .taylor_radius = 2e-3 * R0};
    bf_coupling *c;
    bf_err err = {0};
    ck_assert(bf_coupling_create(&c, &p, f, 4, &err) == BF_OK);
    return c;
}

START_TEST(node_value_equals_direct_sum)
{
    const double lengths[] = {50.0, 50.1};
    for (int l = 0; l < 2; l++) {
        bf_film *f = smooth_film(lengths[l], 0.1);
        bf_coupling *c = make_cpl(f, BF_COUPLING_NODES);
        const size_t n = bf_film_nodes(f);
        const double *x = bf_film_x(f), dx = 0.1;
        const double *h = bf_film_h(f), *psi = bf_film_psi(f);
        double worst = 0;
        for (size_t i = n / 2 - 8; i <= n / 2 + 8; i++) {
            double s = 0;
            for (size_t j = 0; j < n; j++)
                s += h[j] * psi[j] * psi[j] * exp(-fabs(x[j] - x[i]) / R0);
            s *= dx;
            double I, dI;
            bf_coupling_integral(c, x[i], &I, &dI);
            worst = fmax(worst, fabs(I - s) / s);
            /* the ball's path (integral_ball) gives the same */
            double Ib, dIb;
            bf_coupling_integral_ball(c, 0, x[i], &Ib, &dIb);
            ck_assert(Ib == I && dIb == dI);
        }
        printf("coupling_nodes: L = %g cm: node values against the direct "
               "sum, largest relative difference %.2g\n", lengths[l], worst);
        ck_assert_msg(worst < 1e-13, "L = %g: node value differs from the "
                      "direct sum by %g", lengths[l], worst);
        bf_coupling_free(c);
        bf_film_free(f);
    }
}
END_TEST

/* largest |nodes - spline| and the same with dx^2 g / (6 r0) removed, for
 * I (relative to I) and dI/dr (relative to max |dI/dr| of the points) */
static void against_spline(double dx, double *d, double *e, double *dd,
                           double *ed)
{
    bf_film *f = smooth_film(50, dx);
    bf_coupling *cn = make_cpl(f, BF_COUPLING_NODES);
    bf_coupling *cs = make_cpl(f, BF_COUPLING_SPLINE);
    const double rs[] = {0.0137, 0.2, -0.45, 0.777, 1.5, -2.2, 0.5333};
    const double dgs = 0.4; /* about the largest |dI/dr| of the points */
    *d = *e = *dd = *ed = 0;
    for (size_t k = 0; k < sizeof rs / sizeof rs[0]; k++) {
        const double r = rs[k];
        double In, dIn, Is, dIs;
        bf_coupling_integral(cn, r, &In, &dIn);
        bf_coupling_integral(cs, r, &Is, &dIs);
        /* derivative of g for the leading term of dI/dr */
        const double eps = 1e-5,
                     gp = (g_of(r + eps) - g_of(r - eps)) / (2 * eps);
        const double lead = dx * dx * g_of(r) / (6 * R0),
                     leadp = dx * dx * gp / (6 * R0);
        *d = fmax(*d, fabs(In - Is) / Is);
        *e = fmax(*e, fabs(In - Is - lead) / Is);
        *dd = fmax(*dd, fabs(dIn - dIs) / dgs);
        *ed = fmax(*ed, fabs(dIn - dIs - leadp) / dgs);
    }
    bf_coupling_free(cn);
    bf_coupling_free(cs);
    bf_film_free(f);
}

START_TEST(converges_to_spline_quadrature)
{
    double d1, e1, dd1, ed1, d2, e2, dd2, ed2;
    against_spline(0.1, &d1, &e1, &dd1, &ed1);
    against_spline(0.05, &d2, &e2, &dd2, &ed2);
    printf("coupling_nodes: against the spline quadrature, dx 0.1 -> 0.05 cm: "
           "I %.2fx, dI/dr %.2fx; with dx^2 g/(6 r0) removed: I %.2fx, "
           "dI/dr %.2fx\n", d1 / d2, dd1 / dd2, e1 / e2, ed1 / ed2);
    ck_assert_msg(d1 / d2 > 3.6 && d1 / d2 < 4.4 && dd1 / dd2 > 3.6 &&
                      dd1 / dd2 < 4.4,
                  "dx^2 expected: I %g -> %g, dI %g -> %g", d1, d2, dd1, dd2);
    ck_assert_msg(e1 < 0.05 * d1, "the dx^2 term does not explain the "
                  "difference: %g of %g", e1, d1);
    ck_assert_msg(e1 / e2 > 12 && ed1 / ed2 > 6,
                  "after the dx^2 term: dx^4 in I, dx^3 in dI expected: "
                  "I %g -> %g, dI %g -> %g", e1, e2, ed1, ed2);
}
END_TEST

START_TEST(derivative_matches_finite_difference)
{
    bf_film *f = smooth_film(50.1, 0.1);
    bf_coupling *c = make_cpl(f, BF_COUPLING_NODES);
    /* points inside cells (the spline is C2, a finite difference across a
     * node is fine too but less accurate) and beyond the film's end */
    const double rs[] = {0.0137, 0.2, -0.47, 0.777, 26.0};
    const double hh = 1e-3;
    double worst = 0;
    for (size_t k = 0; k < sizeof rs / sizeof rs[0]; k++) {
        double I[4], dI, d;
        const double off[4] = {-2, -1, 1, 2};
        for (int q = 0; q < 4; q++)
            bf_coupling_integral(c, rs[k] + off[q] * hh, &I[q], &d);
        bf_coupling_integral(c, rs[k], &d, &dI);
        const double fd = (I[0] - 8 * I[1] + 8 * I[2] - I[3]) / (12 * hh);
        worst = fmax(worst, fabs(fd - dI));
        ck_assert_msg(fabs(fd - dI) < 1e-8 * fmax(fabs(dI), 1e-3),
                      "r = %g: dI/dr %.15g, finite difference %.15g", rs[k],
                      dI, fd);
    }
    printf("coupling_nodes: dI/dr against a fourth-order finite difference: "
           "largest difference %.2g\n", worst);
    bf_coupling_free(c);
    bf_film_free(f);
}
END_TEST

START_TEST(scene_runs_and_key_checked)
{
    const char *path = tu_repo("runs/coupled_fig9.ini");
    char *errout = NULL;
    int rc = tu_run(NULL, &errout, "run", path, "-o", tu_tmp("nodes.h5"),
                    "-q", "--set", "coupling.quadrature=nodes", "--set",
                    "scene.t_end=0.01", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, errout);
    free(errout);
    errout = NULL;
    rc = tu_run(NULL, &errout, "run", path, "-o", tu_tmp("nodes.h5"), "-q",
                "--set", "coupling.quadrature=node", NULL);
    ck_assert_msg(rc == 2 && strstr(errout, "quadrature"), "exit %d: %s", rc,
                  errout);
    free(errout);
}
END_TEST

Suite *suite_coupling_nodes(void)
{
    Suite *s = suite_create("coupling_nodes");
    TCase *tc = tu_tcase("nodes");
    tcase_add_test(tc, node_value_equals_direct_sum);
    tcase_add_test(tc, converges_to_spline_quadrature);
    tcase_add_test(tc, derivative_matches_finite_difference);
    tcase_add_test(tc, scene_runs_and_key_checked);
    suite_add_tcase(s, tc);
    return s;
}
