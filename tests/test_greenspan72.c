/* test_greenspan72.c: Greenspan's 1972 two-fluid model.
 *
 * - Support-set gravity (eqs 2.8-2.9): hand-computed areas for the K = 0,
 *   K >= 1, free-fall and antigravity cases (an independent check of the
 *   naive reference); then the cell and fast methods against the naive one
 *   on random configurations built to hit the edge cases (particles on the
 *   walls, on band edges, on the floor, equal heights, clusters, empty
 *   columns, d up to 2 dx, strict and non-strict support sets, the
 *   listing's eps): identical free-fall/resting/antigravity decisions and
 *   g equal to round-off.  Tolerance: g is -g0 (1 - A/(W K dx)); the areas
 *   are sums of at most a few hundred terms of size <= d dx, and the fast
 *   method forms them as differences of sums over one chunk of the sweep,
 *   so the relative error of A is a few hundred ulps at most;
 *   1e-12 (g0 + |g|) is ~5000 ulps and still a million times smaller than
 *   the effect of one missing square (>= 1e-6 of A here).
 * - Repulsion (2.11-2.12): one pair by hand (both sides of r = d, the
 *   symmetric force), the cell list against all pairs.
 * - Walls (2.13): specular reflection with omega by hand, corners, many
 *   bounces in one step, the listing's WALCOL on a hand-computed case, and
 *   particles never leave the box in violent runs (checked after every
 *   step) with both rules.
 * - Leapfrog with the half first step: a lone particle falls freely
 *   (empty bands: g = -g0) and the scheme is exact for constant
 *   acceleration: y_k = y_0 + v_0 t_k - g0 t_k^2 / 2.
 * - Same seed, same bits; another seed, other bits; restart bit-identity;
 *   results independent of the number of threads; the fast method's
 *   skipping of free-falling particles and its cut lists change no bit.
 * - The Hertz contact ([hertz], off by default): two particles colliding
 *   head on, all pairs and through the cell list: momentum conserved to
 *   round-off, K + U during the collision and K after it to the
 *   leapfrog's O(dt^2) (tolerances and their reasons at the test).
 */
#include <float.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/greenspan.h"
#include "ballfilm/h5out.h"
#include "ballfilm/model.h"
#include "ballfilm/run.h"
#include "contact/hertz.h"
#include "particles/repulsion.h"
#include "particles/support.h"
#include "particles/walls.h"
#include "testutil.h"

/* ------------------------------------------------------------ support */

static bf_support_params sup_params(double L, double dx, double d)
{
    bf_support_params p;
    memset(&p, 0, sizeof p);
    p.box = (bf_box){0.0, L, 0.0, L};
    p.g0 = 980.0;
    p.dx = dx;
    p.d = d;
    p.eps = 0.0;
    p.tie = 1;
    p.method = BF_SUPPORT_NAIVE;
    p.threads = 1;
    return p;
}

/* g of every particle with one method (cells of side h). */
static void support_g(const bf_support_params *p, bf_support_method m,
                      const double *x, const double *y, size_t n, double h,
                      double *g, uint8_t *kind)
{
    bf_err err = {0};
    bf_support *s;
    bf_support_params q = *p;
    q.method = m == BF_SUPPORT_FAST && p->d > 2 * p->dx ? BF_SUPPORT_CELL : m;
    ck_assert_msg(bf_support_create(&s, &q, n, &err) == BF_OK, "%s", err.msg);
    bf_cells c;
    ck_assert(bf_cells_init(&c, p->box.ax, p->box.ay, p->box.bx - p->box.ax,
                            p->box.by - p->box.ay, h, n, &err) == BF_OK);
    bf_cells_build(&c, x, y, NULL, n);
    bf_support_eval_with(s, m, x, y, n, &c, g, kind);
    bf_cells_free(&c);
    bf_support_free(s);
}

START_TEST(support_by_hand)
{
    /* box 100, dx 25, d 20: strip of a particle at x = 50 is [37.5, 62.5] */
    bf_support_params p = sup_params(100, 25, 20);
    const bf_support_method ms[] = {BF_SUPPORT_NAIVE, BF_SUPPORT_CELL,
                                    BF_SUPPORT_FAST};
    for (int k = 0; k < 3; k++) {
        double g[3];
        uint8_t kind[3];
        /* K = 1: below it the square [40,60] x [0,20]: area 400 in band 1
         * (W = 25, K dx = 25) */
        double x1[] = {50, 50}, y1[] = {30, 10};
        support_g(&p, ms[k], x1, y1, 2, 10, g, kind);
        ck_assert_double_eq_tol(g[0], -980.0 * (1.0 - 400.0 / 625.0), 1e-12);
        ck_assert_int_eq(kind[0], BF_SUP_PARTIAL);
        ck_assert_int_eq(kind[1], BF_SUP_REST); /* K = 0, y <= d */
        /* K = 2 with band 2 = [25, 50] empty: free fall */
        double y2[] = {60, 10};
        support_g(&p, ms[k], x1, y2, 2, 10, g, kind);
        ck_assert_double_eq(g[0], -980.0);
        ck_assert_int_eq(kind[0], BF_SUP_FREE);
        /* K = 0, d < y < dx: the rectangle [37.5,62.5] x [0,22] holds
         * [40,60] x [0,15] of the square below: area 300 */
        double y3[] = {22, 5};
        support_g(&p, ms[k], x1, y3, 2, 10, g, kind);
        ck_assert_double_eq_tol(g[0], -980.0 * (1.0 - 300.0 / (25.0 * 22.0)),
                                1e-12);
        /* antigravity: three squares on top of each other in band 1 cover
         * 3 x 20 x 20 = 1200 > 625 (overlaps count each time) */
        double x4[] = {50, 50, 50, 50}, y4[] = {30, 10, 10, 10};
        double g4[4];
        uint8_t k4[4];
        support_g(&p, ms[k], x4, y4, 4, 10, g4, k4);
        ck_assert_double_eq_tol(g4[0], -980.0 * (1.0 - 1200.0 / 625.0), 1e-12);
        ck_assert_int_eq(k4[0], BF_SUP_ANTI);
        /* a particle at the wall: strip [0, 12.5] (W = 12.5), square of the
         * one below [0, 10] x [0, 20]: area 200 */
        double x5[] = {0, 0}, y5[] = {30, 10};
        support_g(&p, ms[k], x5, y5, 2, 10, g, kind);
        ck_assert_double_eq_tol(g[0], -980.0 * (1.0 - 200.0 / (12.5 * 25.0)),
                                1e-12);
        /* support set: a particle above j does not hold it (band 1 of j at
         * y = 30 is reached by the square of a particle at y = 34, which
         * is above): free fall with tie = le and the same height counts */
        double x6[] = {50, 50}, y6[] = {30, 34};
        support_g(&p, ms[k], x6, y6, 2, 10, g, kind);
        ck_assert_double_eq(g[0], -980.0);
        double y7[] = {30, 30};
        support_g(&p, ms[k], x6, y7, 2, 10, g, kind);
        /* same height: the other's square [40,60] x [20,40] gives 5 x 20 =
         * 100 in band 1 */
        ck_assert_double_eq_tol(g[0], -980.0 * (1.0 - 100.0 / 625.0), 1e-12);
        bf_support_params lt = p;
        lt.tie = 0;
        support_g(&lt, ms[k], x6, y7, 2, 10, g, kind);
        ck_assert_double_eq(g[0], -980.0);
    }
    /* A strip that exactly fills the gap between two squares touches them
     * with zero area: dx = 6.25, d = 5, j at x = 25.625 (strip [22.5,
     * 28.75], K = 2) above squares [17.5, 22.5] and [28.75, 33.75] in band
     * 1 and one square inside the strip in band 2: band 1 is empty, free
     * fall.  Moving one square by 1e-9 into the strip makes band 1 count. */
    bf_support_params q = sup_params(100, 6.25, 5);
    for (int k = 0; k < 3; k++) {
        double x[] = {25.625, 20, 31.25, 25.625}, y[] = {15, 3, 3, 9};
        double g[4];
        uint8_t kind[4];
        support_g(&q, ms[k], x, y, 4, 5, g, kind);
        ck_assert_int_eq(kind[0], BF_SUP_FREE);
        x[1] = 20 + 1e-9;
        support_g(&q, ms[k], x, y, 4, 5, g, kind);
        ck_assert_int_eq(kind[0], BF_SUP_PARTIAL);
    }
}
END_TEST

/* Random configurations that hit the edge cases. */
static void random_config(gsl_rng *r, size_t n, double L, double dx,
                          double *x, double *y, int style)
{
    for (size_t i = 0; i < n; i++) {
        double u = gsl_rng_uniform(r), v = gsl_rng_uniform(r);
        x[i] = L * u;
        /* style 0: uniform; 1: dense at the bottom; 2: clusters with holes */
        y[i] = style == 1 ? L * v * v : L * v;
        if (style == 2) {
            double cx = floor(u * 6.0) / 6.0 * L + 0.05 * L * v;
            x[i] = cx;
            y[i] = L * gsl_rng_uniform(r) * gsl_rng_uniform(r);
        }
        switch (i % 11) {
        case 1: x[i] = 0.0; break;                  /* left wall */
        case 2: x[i] = L; break;                    /* right wall */
        case 3: y[i] = floor(y[i] / dx) * dx; break; /* on a band edge */
        case 4: y[i] = 0.0; break;                  /* floor */
        case 5: if (i) y[i] = y[i - 1]; break;      /* equal heights */
        case 6: if (i) x[i] = x[i - 1]; break;      /* same column */
        case 7: y[i] = L; break;                    /* ceiling */
        default: break;
        }
    }
}

/* The six arrays of a comparison of two evaluations. */
static void free_arrays(double *x, double *y, double *g0, double *g1,
                        uint8_t *k0, uint8_t *k1)
{
    free(x);
    free(y);
    free(g0);
    free(g1);
    free(k0);
    free(k1);
}

START_TEST(support_fast_and_cell_equal_naive)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 20240611);
    size_t kinds[4] = {0, 0, 0, 0};
    const struct {
        size_t n;
        double L, dx, d, eps;
        int tie, style;
    } cases[] = {
        {16, 100, 25, 20, 0, 1, 0},      /* Example 1 geometry */
        {256, 100, 6.25, 5, 0, 1, 0},    /* Example 2 geometry */
        {256, 100, 6.25, 5, 1e-3, 1, 1}, /* the listing's eps */
        {300, 100, 6.25, 5, 0, 0, 2},    /* strict support set, clusters */
        {1500, 500, 6.25, 5, 0, 1, 1},   /* 80 bands: fast, cell fallback */
        {1500, 500, 6.25, 12.5, 0, 1, 0}, /* d = 2 dx, the fast limit */
        {1200, 400, 5, 1.5, 0, 1, 2},    /* narrow squares: many gaps */
        {800, 300, 6.25, 20, 0, 1, 0},   /* d > 2 dx: cell only */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        for (int rep = 0; rep < 3; rep++) {
            size_t n = cases[c].n;
            double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
            double *g0 = malloc(n * sizeof *g0), *g1 = malloc(n * sizeof *g1);
            uint8_t *k0 = malloc(n), *k1 = malloc(n);
            random_config(r, n, cases[c].L, cases[c].dx, x, y,
                          (cases[c].style + rep) % 3);
            bf_support_params p = sup_params(cases[c].L, cases[c].dx,
                                             cases[c].d);
            p.eps = cases[c].eps;
            p.tie = cases[c].tie;
            support_g(&p, BF_SUPPORT_NAIVE, x, y, n, 5, g0, k0);
            for (size_t i = 0; i < n; i++)
                kinds[k0[i]]++;
            const bf_support_method ms[] = {BF_SUPPORT_CELL, BF_SUPPORT_FAST};
            const double hs[] = {2.5, 5, 10, 30};
            for (int m = 0; m < 2; m++)
                for (int hk = 0; hk < 4; hk++) {
                    support_g(&p, ms[m], x, y, n, hs[hk], g1, k1);
                    for (size_t i = 0; i < n; i++) {
                        ck_assert_msg(k0[i] == k1[i],
                                      "case %zu method %d h %g particle %zu "
                                      "at (%.17g, %.17g): kind %d vs naive %d",
                                      c, m, hs[hk], i, x[i], y[i], k1[i],
                                      k0[i]);
                        double tol = 1e-12 * (980.0 + fabs(g0[i]));
                        ck_assert_msg(fabs(g1[i] - g0[i]) <= tol,
                                      "case %zu method %d particle %zu: g %.17g "
                                      "vs naive %.17g",
                                      c, m, i, g1[i], g0[i]);
                    }
                }
            free_arrays(x, y, g0, g1, k0, k1);
        }
    }
    /* the configurations exercise every case many times */
    for (int k = 0; k < 4; k++)
        ck_assert_msg(kinds[k] > 100, "kind %d seen %zu times", k, kinds[k]);
    gsl_rng_free(r);
}
END_TEST

/* The accelerations (a2, b2) of n particles against (a1, b1), sums of the
 * same terms in another order: equal to a relative tol (what names the
 * case in a failure). */
static void same_sums(const double *a1, const double *b1, const double *a2,
                      const double *b2, size_t n, double tol, const char *what,
                      double value)
{
    for (size_t i = 0; i < n; i++) {
        double s = tol * (1.0 + fabs(a1[i]) + fabs(b1[i]));
        ck_assert_msg(fabs(a1[i] - a2[i]) <= s && fabs(b1[i] - b2[i]) <= s,
                      "%s %g particle %zu: (%g, %g) vs (%g, %g)", what, value,
                      i, a2[i], b2[i], a1[i], b1[i]);
    }
}

/* ------------------------------------------------------------ repulsion */

START_TEST(repulsion_pair_by_hand_and_cells)
{
    bf_repulsion rp = {.alpha = 2.0, .xi = 0.1, .d = 5.0, .p = 2, .beta = 3,
                       .cutoff = 10.0, .inv_d = 0.2};
    /* one pair at r = 3 < d: a_0 = alpha m_1 (x_0 - x_1) / D,
     * D = (r + xi)^p ((r + xi)/d)^beta; a_1 the mirror with m_0 */
    double x[2] = {0.0, 3.0}, y[2] = {0.0, 0.0}, m[2] = {1.5, 0.5};
    double ax[2], ay[2];
    size_t bi, bj;
    ck_assert_int_eq(bf_repulsion_all_pairs(&rp, x, y, m, 2, ax, ay, &bi, &bj), 0);
    double D = pow(3.1, 2) * pow(3.1 / 5.0, 3);
    ck_assert_double_eq_tol(ax[0], 2.0 * 0.5 * (-3.0) / D, 1e-13);
    ck_assert_double_eq_tol(ax[1], 2.0 * 1.5 * 3.0 / D, 1e-13);
    ck_assert(m[0] * ax[0] + m[1] * ax[1] == 0.0); /* symmetric force */
    /* r = 7 >= d: no beta factor; r = 12 >= cutoff: nothing */
    x[1] = 7.0;
    bf_repulsion_all_pairs(&rp, x, y, m, 2, ax, ay, &bi, &bj);
    ck_assert_double_eq_tol(ax[1], 2.0 * 1.5 * 7.0 / pow(7.1, 2), 1e-13);
    x[1] = 12.0;
    bf_repulsion_all_pairs(&rp, x, y, m, 2, ax, ay, &bi, &bj);
    ck_assert(ax[0] == 0.0 && ax[1] == 0.0);
    /* xi = 0 and coinciding particles: an error naming them */
    rp.xi = 0.0;
    x[1] = 0.0;
    ck_assert_int_eq(bf_repulsion_all_pairs(&rp, x, y, m, 2, ax, ay, &bi, &bj), 1);
    ck_assert(bi == 0 && bj == 1);

    /* the cell list against all pairs on a random dense configuration */
    rp.xi = 0.1;
    const size_t n = 3000;
    const double L = 200;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 7);
    double *px = malloc(n * sizeof *px), *py = malloc(n * sizeof *py),
           *pm = malloc(n * sizeof *pm), *a1 = malloc(n * sizeof *a1),
           *b1 = malloc(n * sizeof *b1), *a2 = malloc(n * sizeof *a2),
           *b2 = malloc(n * sizeof *b2);
    for (size_t i = 0; i < n; i++) {
        px[i] = L * gsl_rng_uniform(r);
        py[i] = L * gsl_rng_uniform(r);
        pm[i] = i % 4 ? 0.25 : 1.0;
    }
    px[0] = 0.0;
    px[1] = L;
    bf_repulsion_all_pairs(&rp, px, py, pm, n, a1, b1, &bi, &bj);
    bf_err err = {0};
    /* 0.5: far below cutoff/15, the all-pairs fallback */
    const double hs[] = {10.0, 5.0, 3.0, 0.5};
    for (int k = 0; k < 4; k++) {
        bf_cells c;
        bf_repulsion_work w;
        ck_assert(bf_cells_init(&c, 0, 0, L, L, hs[k], n, &err) == BF_OK);
        ck_assert(bf_repulsion_work_init(&w, n, 1, &err) == BF_OK);
        bf_cells_build(&c, px, py, pm, n);
        ck_assert_int_eq(bf_repulsion_cells(&rp, &c, &w, a2, b2, &bi, &bj), 0);
        same_sums(a1, b1, a2, b2, n, 1e-13, "h", hs[k]);
        bf_repulsion_work_free(&w);
        bf_cells_free(&c);
    }
    gsl_rng_free(r);
    free(px);
    free(py);
    free(pm);
    free(a1);
    free(b1);
    free(a2);
    free(b2);
}
END_TEST

/* The cell list's repulsion in batches (a column of cells, cut where the
 * lists outgrow the buffers) and with the AVX-512 kernels where the
 * processor has them: against all pairs to round-off, and the AVX-512
 * kernels against the SSE2 ones bit for bit.  A dense box (about 150
 * neighbours a particle), so that batches are cut many times, and a
 * sparse one. */
START_TEST(repulsion_batches_and_wide_kernels)
{
    bf_repulsion rp = {.alpha = 2.0, .xi = 0.1, .d = 5.0, .p = 2, .beta = 2,
                       .cutoff = 10.0, .use_cells = 1, .inv_d = 0.2};
    const size_t n = 3000;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 20261204);
    /* positions, masses and three results of n particles in one block */
    double *buf = malloc(9 * n * sizeof *buf);
    ck_assert(buf != NULL);
    double *px = buf, *py = buf + n, *pm = buf + 2 * n, *a1 = buf + 3 * n,
           *b1 = buf + 4 * n, *a2 = buf + 5 * n, *b2 = buf + 6 * n,
           *a3 = buf + 7 * n, *b3 = buf + 8 * n;
    const double sides[] = {40.0, 300.0};
    for (int k = 0; k < 2; k++) {
        const double L = sides[k];
        for (size_t i = 0; i < n; i++) {
            px[i] = L * gsl_rng_uniform(r);
            py[i] = L * gsl_rng_uniform(r);
            pm[i] = i % 4 ? 0.25 : 1.0;
        }
        size_t bi, bj;
        bf_repulsion_all_pairs(&rp, px, py, pm, n, a1, b1, &bi, &bj);
        bf_err err = {0};
        bf_cells c;
        bf_repulsion_work w;
        ck_assert(bf_cells_init(&c, 0, 0, L, L, 10.0, n, &err) == BF_OK);
        ck_assert(bf_repulsion_work_init(&w, n, 1, &err) == BF_OK);
        bf_cells_build(&c, px, py, pm, n);
        ck_assert_int_eq(bf_repulsion_cells(&rp, &c, &w, a2, b2, &bi, &bj), 0);
        same_sums(a1, b1, a2, b2, n, 1e-13, "L", L);
        if (w.wide) {
            /* the SSE2 kernels on the same box */
            w.wide = 0;
            ck_assert_int_eq(
                bf_repulsion_cells(&rp, &c, &w, a3, b3, &bi, &bj), 0);
            ck_assert(memcmp(a2, a3, n * sizeof *a2) == 0 &&
                      memcmp(b2, b3, n * sizeof *b2) == 0);
        } else {
            /* the AVX-512 kernels cannot run on this processor */
            fprintf(stderr, "repulsion: no AVX-512 here, the SSE2 kernels "
                            "only\n");
        }
        bf_repulsion_work_free(&w);
        bf_cells_free(&c);
    }
    gsl_rng_free(r);
    free(buf);
}
END_TEST

/* ---------------------------------------------------------------- walls */

static void one_particle(bf_particles *p, double x, double y, double vx,
                         double vy)
{
    bf_err err = {0};
    ck_assert(bf_particles_init(p, 1, &err) == BF_OK);
    p->x[0] = x;
    p->y[0] = y;
    p->vx[0] = vx;
    p->vy[0] = vy;
}

START_TEST(walls_by_hand)
{
    bf_walls w = {{0, 100, 0, 100}, 0.5, BF_WALL_CLEAN, 1e-3};
    bf_particles p;
    bf_err err = {0};
    unsigned long long hits = 0;
    /* from (90, 50) to (110, 60): impact at (100, 55); the remaining
     * (10, 5) is mirrored and halved: (95, 57.5); v (200, 100) -> (-100, 50) */
    one_particle(&p, 110, 60, 200, 100);
    double x0 = 90, y0 = 50;
    ck_assert(bf_walls_apply(&w, &p, &x0, &y0, &hits, &err) == BF_OK);
    ck_assert_double_eq_tol(p.x[0], 95.0, 1e-12);
    ck_assert_double_eq_tol(p.y[0], 57.5, 1e-12);
    ck_assert_double_eq(p.vx[0], -100.0);
    ck_assert_double_eq(p.vy[0], 50.0);
    ck_assert_int_eq(hits, 1);
    bf_particles_free(&p);
    /* exactly into the corner (100, 100) from (90, 90): both components
     * reflect */
    w.omega = 1.0;
    one_particle(&p, 110, 110, 1, 1);
    x0 = y0 = 90;
    ck_assert(bf_walls_apply(&w, &p, &x0, &y0, &hits, &err) == BF_OK);
    ck_assert_double_eq_tol(p.x[0], 90.0, 1e-12);
    ck_assert_double_eq_tol(p.y[0], 90.0, 1e-12);
    ck_assert(p.vx[0] == -1.0 && p.vy[0] == -1.0);
    bf_particles_free(&p);
    /* 350 cm in one step across a 100 cm box, omega = 1: the unfolded
     * path 50 -> 400 meets the walls at 100 (right), 200 (left), 300
     * (right) and ends at 400, i.e. on the left wall x = 0, moving left */
    one_particle(&p, 400, 50, 3500, 0);
    x0 = 50;
    y0 = 50;
    hits = 0;
    ck_assert(bf_walls_apply(&w, &p, &x0, &y0, &hits, &err) == BF_OK);
    ck_assert_double_eq_tol(p.x[0], 0.0, 1e-9);
    ck_assert_int_eq(hits, 3);
    ck_assert(p.vx[0] == -3500.0);
    bf_particles_free(&p);
    /* the listing's WALCOL, omega = 1, EPS = 1e-3: from (90, 50) to
     * (110, 60): TANTH = 10/(20 + EPS); x2 = 90, x1 = 100,
     * y1 = 60 + (90 - 100) TANTH, y2 = y1 - (90 - 100) TANTH = 60;
     * v = |v| (x2 - x1, y2 - y1)/(|.| + EPS) */
    w.rule = BF_WALL_FORTRAN;
    one_particle(&p, 110, 60, 200, 100);
    x0 = 90;
    y0 = 50;
    ck_assert(bf_walls_apply(&w, &p, &x0, &y0, &hits, &err) == BF_OK);
    double t = 10.0 / (20.0 + 1e-3), y1 = 60.0 - 10.0 * t;
    double dxx = -10.0, dyy = 60.0 - y1, len = sqrt(dxx * dxx + dyy * dyy);
    double sp = sqrt(200.0 * 200.0 + 100.0 * 100.0);
    ck_assert_double_eq_tol(p.x[0], 90.0, 1e-12);
    ck_assert_double_eq_tol(p.y[0], 60.0, 1e-12);
    ck_assert_double_eq_tol(p.vx[0], sp * dxx / (len + 1e-3), 1e-9);
    ck_assert_double_eq_tol(p.vy[0], sp * dyy / (len + 1e-3), 1e-9);
    /* the speed is reduced even with omega = 1 */
    ck_assert(hypot(p.vx[0], p.vy[0]) < sp);
    bf_particles_free(&p);
}
END_TEST

static const bf_model_type *g72_type(void)
{
    return bf_catalog_model(bf_catalog_builtin(), "greenspan72");
}

/* The model of a resolved greenspan72 scene, without the time loop (to be
 * driven step by step). */
static void *g72_model(const bf_scene *sc, bf_setup **setup)
{
    bf_err err = {0};
    void *m;
    ck_assert_msg(bf_model_from_scene(bf_catalog_builtin(), sc, setup, &m,
                                      &err) == BF_OK,
                  "%s", err.msg);
    return m;
}

static const char *violent =
    "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 6\n"
    "[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 0.25\nlayout = grid\n"
    "grid_nx = 12\ngrid_ny = 12\nv_random = 5000\nseed = 3\n"
    "output = diagnostics\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\n[walls]\nomega = 0.7\n";

/* Drive the model step by step and look at every particle after every
 * step. */
static void never_leave(const char *rule, const char *omega, long steps)
{
    bf_scene *sc = tu_scene(violent);
    bf_err err = {0};
    char s1[64], s2[64];
    snprintf(s1, sizeof s1, "walls.rule=%s", rule);
    snprintf(s2, sizeof s2, "walls.omega=%s", omega);
    ck_assert(bf_scene_set(sc, s1, "test", &err) == BF_OK);
    ck_assert(bf_scene_set(sc, s2, "test", &err) == BF_OK);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK);
    const bf_model_type *mt = g72_type();
    bf_setup *setup;
    void *m = g72_model(sc, &setup);
    bf_particles *p = bf_greenspan72_particles(m);
    unsigned long long outside = 0;
    for (long k = 0; k < steps; k++) {
        ck_assert_msg(mt->step(m, k, k * 0.01, 0.01, &err) == BF_OK, "%s",
                      err.msg);
        for (size_t i = 0; i < p->n; i++)
            outside += !(p->x[i] >= 0 && p->x[i] <= 100 && p->y[i] >= 0 &&
                         p->y[i] <= 100);
    }
    ck_assert_int_eq(outside, 0);
    bf_counters c;
    mt->counters(m, &c);
    ck_assert_int_eq(c.steps, steps);
    mt->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
}

START_TEST(particles_never_leave_the_box)
{
    /* speeds up to 5000 cm/s: 50 cm per step, several walls per step */
    never_leave("clean", "0.7", 600);
    never_leave("clean", "1", 600);
    never_leave("fortran", "0.7", 600);
    never_leave("fortran", "1", 600);
}
END_TEST

/* ------------------------------------------------------------- leapfrog */

START_TEST(lone_particle_falls_exactly)
{
    /* one particle: every band below it is empty, g = -980; leapfrog with
     * the half first step is exact for constant acceleration */
    bf_sim *sim = tu_run_scene(
        "[scene]\nmodel = greenspan72\ndt = 1e-3\nt_end = 0.3\n"
        "[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 1\nlayout = list\n"
        "positions = 50 90\nvelocities = 3 20\n"
        "[support]\ndx = 6.25\n",
        NULL);
    bf_particles *p = bf_greenspan72_particles(bf_sim_model(sim));
    double t = 0.3;
    ck_assert_double_eq_tol(p->y[0], 90 + 20 * t - 0.5 * 980 * t * t, 1e-10);
    ck_assert_double_eq_tol(p->x[0], 50 + 3 * t, 1e-12);
    /* the half-step velocity v^{k-1/2} = v0 - g (t - dt/2) */
    ck_assert_double_eq_tol(p->vy[0], 20 - 980 * (t - 0.5e-3), 1e-9);
    bf_sim_free(sim);
}
END_TEST

/* ------------------------------------------------------- reproducibility */

static const char *ex2_short =
    "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 3\noutput_every = 7\n"
    "[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 0.25\nlayout = grid\n"
    "v_random = 500\nseed = 1972\nset_velocity = 137 63.0 133.9\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\n[walls]\nomega = 0.9\n";

static int same_file_data(const char *a, const char *b, const char *ds)
{
    bf_err err = {0};
    double *da, *db;
    size_t a0, a1, b0, b1;
    ck_assert_msg(bf_h5_read(a, ds, &da, &a0, &a1, &err) == BF_OK, "%s", err.msg);
    ck_assert_msg(bf_h5_read(b, ds, &db, &b0, &b1, &err) == BF_OK, "%s", err.msg);
    int same = a0 == b0 && a1 == b1 &&
               !memcmp(da, db, a0 * (a1 ? a1 : 1) * sizeof *da);
    free(da);
    free(db);
    return same;
}

START_TEST(same_seed_same_bits)
{
    const char *sc = tu_write("ex2s.ini", ex2_short);
    const char *a = tu_tmp("s1.h5"), *b = tu_tmp("s2.h5"), *c = tu_tmp("s3.h5");
    char pa[512], pb[512], pc[512];
    snprintf(pa, sizeof pa, "%s", a);
    snprintf(pb, sizeof pb, "%s", b);
    snprintf(pc, sizeof pc, "%s", c);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", pa, NULL), 0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", pb, NULL), 0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", pc, "--set",
                            "greenspan72.seed=1973", NULL),
                     0);
    const char *ds[] = {"/particles/x", "/particles/y", "/particles/vx",
                        "/particles/vy", "/diag/kinetic", NULL};
    for (const char **d = ds; *d; d++) {
        ck_assert_msg(same_file_data(pa, pb, *d), "%s differs", *d);
        ck_assert_msg(!same_file_data(pa, pc, *d), "%s same for another seed",
                      *d);
    }
    /* the text's velocity of particle 137 at (53.125, 46.875) */
    double *vx, *x, *y;
    size_t n0, n1;
    bf_err err = {0};
    ck_assert(bf_h5_read(pa, "/particles/vx", &vx, &n0, &n1, &err) == BF_OK);
    ck_assert(bf_h5_read(pa, "/particles/x", &x, &n0, &n1, &err) == BF_OK);
    ck_assert(bf_h5_read(pa, "/particles/y", &y, &n0, &n1, &err) == BF_OK);
    ck_assert(vx[136] == 63.0 && x[136] == 53.125 && y[136] == 46.875);
    free(vx);
    free(x);
    free(y);
}
END_TEST

START_TEST(restart_bit_identical)
{
    const char *sc = tu_write("ex2r.ini", ex2_short);
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("full72.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("part72.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", full, NULL), 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", sc, "-q", "-o", part, "--stop-after",
                    "101", NULL);
    ck_assert_msg(rc == 6, "exit %d: %s", rc, err);
    free(err);
    rc = tu_run(NULL, &err, "run", "--restart", part, "-q", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    const char *ds[] = {"/time", "/particles/x", "/particles/y",
                        "/particles/vx", "/particles/vy", "/diag/kinetic",
                        "/diag/support_kinds", "/diag/settle", NULL};
    for (const char **d = ds; *d; d++)
        ck_assert_msg(same_file_data(full, part, *d), "%s differs", *d);
}
END_TEST

/* The fast method skips the sweep for the particles that fall freely
 * through an empty band, cuts each chunk's tree at the highest level
 * asked and takes the squares cut by a particle's top line from lists per
 * line (support.h); all are claimed to change no bit: a skipped query is
 * a read, a node above the highest level asked is never read, the lists
 * hold the squares of the cell list's window in its order.  Checked
 * against the exhaustive path (every particle asks, every level kept,
 * the cut squares from the window):
 * on random configurations g and the kinds are the same bits, and so are
 * the positions and velocities of two runs of 40 steps of 6400 particles,
 * one with the exhaustive sweep (so any difference in any force would
 * show).  The skipped path must have been taken: free falls with K >= 2
 * are counted. */
static const char *skip_scene =
    "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 1\n"
    "[greenspan72]\nwidth = 500\nheight = 500\ninterface = 375\nd = 5\n"
    "m_heavy = 1\nm_light = 0.25\nlayout = grid\ngrid_nx = 80\n"
    "grid_ny = 80\nv_random = 500\noutput = diagnostics\nthreads = 1\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\nmethod = fast\n[walls]\nomega = 0.9\n";

START_TEST(fast_skipping_changes_no_bit)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 20261202);
    bf_err err = {0};
    size_t skipped = 0;
    const struct {
        size_t n;
        double L, dx, d;
    } cases[] = {{1500, 500, 6.25, 5}, {1500, 500, 6.25, 12.5},
                 {1200, 400, 5, 1.5}, {3000, 300, 6.25, 5}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        for (int style = 0; style < 3; style++) {
            size_t n = cases[c].n;
            double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
            double *g0 = malloc(n * sizeof *g0), *g1 = malloc(n * sizeof *g1);
            uint8_t *k0 = malloc(n), *k1 = malloc(n);
            random_config(r, n, cases[c].L, cases[c].dx, x, y, style);
            bf_support_params p = sup_params(cases[c].L, cases[c].dx,
                                             cases[c].d);
            p.method = BF_SUPPORT_FAST;
            bf_support *s;
            ck_assert(bf_support_create(&s, &p, n, &err) == BF_OK);
            bf_cells cl;
            ck_assert(bf_cells_init(&cl, 0, 0, cases[c].L, cases[c].L, 10, n,
                                    &err) == BF_OK);
            bf_cells_build(&cl, x, y, NULL, n);
            bf_support_eval(s, x, y, n, &cl, g0, k0);
            bf_support_set_exhaustive(s, 1);
            bf_support_eval(s, x, y, n, &cl, g1, k1);
            ck_assert_msg(memcmp(g0, g1, n * sizeof *g0) == 0 &&
                              memcmp(k0, k1, n) == 0,
                          "case %zu style %d: the skipping changed g", c,
                          style);
            for (size_t i = 0; i < n; i++)
                skipped += k0[i] == BF_SUP_FREE &&
                           y[i] >= 2 * cases[c].dx;
            bf_cells_free(&cl);
            bf_support_free(s);
            free_arrays(x, y, g0, g1, k0, k1);
        }
    ck_assert_msg(skipped > 100, "free falls with K >= 2: %zu", skipped);
    gsl_rng_free(r);
    /* two runs, one exhaustive */
    const bf_model_type *mt = g72_type();
    bf_scene *sc = tu_scene(skip_scene);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK);
    bf_setup *sa, *sb;
    void *a = g72_model(sc, &sa), *b = g72_model(sc, &sb);
    bf_support_set_exhaustive(bf_greenspan72_support(b), 1);
    bf_particles *pa = bf_greenspan72_particles(a),
                 *pb = bf_greenspan72_particles(b);
    for (long k = 0; k < 40; k++) {
        ck_assert(mt->step(a, k, k * 0.01, 0.01, &err) == BF_OK);
        ck_assert(mt->step(b, k, k * 0.01, 0.01, &err) == BF_OK);
    }
    const size_t bytes = pa->n * sizeof(double);
    ck_assert(memcmp(pa->x, pb->x, bytes) == 0 &&
              memcmp(pa->y, pb->y, bytes) == 0 &&
              memcmp(pa->vx, pb->vx, bytes) == 0 &&
              memcmp(pa->vy, pb->vy, bytes) == 0);
    mt->destroy(a);
    mt->destroy(b);
    bf_setup_free(sa);
    bf_setup_free(sb);
    bf_scene_free(sc);
}
END_TEST

START_TEST(threads_do_not_change_results)
{
    /* 6400 particles: above the size where the loops run in parallel */
    const char *text =
        "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 0.2\n"
        "output_every = 20\n"
        "[greenspan72]\nwidth = 500\nheight = 500\ninterface = 375\nd = 5\n"
        "m_heavy = 1\nm_light = 0.25\nlayout = grid\ngrid_nx = 80\n"
        "grid_ny = 80\nv_random = 500\noutput = positions\n"
        "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
        "[support]\ndx = 6.25\nmethod = fast\n[walls]\nomega = 0.9\n";
    const char *sc = tu_write("thr.ini", text);
    char a[512], b[512];
    snprintf(a, sizeof a, "%s", tu_tmp("t1.h5"));
    snprintf(b, sizeof b, "%s", tu_tmp("t2.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", a, "--set",
                            "greenspan72.threads=1", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", sc, "-q", "-o", b, "--set",
                            "greenspan72.threads=2", NULL),
                     0);
    ck_assert(same_file_data(a, b, "/particles/x"));
    ck_assert(same_file_data(a, b, "/particles/y"));
}
END_TEST

START_TEST(bad_scenes_are_refused)
{
    char msg[1024];
    const char *base = "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 1\n"
                       "[support]\ndx = 6.25\n";
    char text[2048];
    snprintf(text, sizeof text,
             "%s[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 1\nlayout = "
             "list\npositions = 50 150\n",
             base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "positions") && strstr(msg, "outside"), "%s", msg);
    snprintf(text, sizeof text,
             "%s[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 1\nlayout = "
             "list\npositions = 50 50 60\n",
             base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    snprintf(text, sizeof text,
             "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 1\n"
             "[support]\ndx = 6.25\nmethod = fast\n[greenspan72]\nd = 15\n"
             "m_heavy = 1\nm_light = 1\n");
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "method"), "%s", msg);
    snprintf(text, sizeof text,
             "%s[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 1\n"
             "set_velocity = 300 1 1\n",
             base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "set_velocity"), "%s", msg);
    /* cells so small that the search would reach more than 15 cells */
    snprintf(text, sizeof text,
             "%s[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 1\n"
             "[repulsion]\ncutoff = 10\ncell = 0.5\n",
             base);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "cell"), "%s", msg);
}
END_TEST


/* ------------------------------------------------------------- hertz */

/* A head-on collision of two particles with the Hertz contact ([hertz]),
 * nothing else acting: support gravity g = 0, repulsion alpha = 0 (both
 * contribute exactly zero), walls far.  Particle 1 (light, 0.25 g) at
 * (50, 40) moves up at 100 cm/s, particle 2 (heavy, 1 g) at (50, 60) down
 * at 100 cm/s; R = d/2 = 2.5 cm, so they touch at t = 0.075 s. */
typedef struct collision {
    double dp;        /* largest |P^{k+1/2} - P^0| (g cm/s) */
    double dp_tol;    /* its round-off bound */
    double k0, k1;    /* kinetic energy before and after (erg) */
    double de;        /* largest |K + U - E_0| / E_0 at the steps */
    double v1, v2;    /* y velocities after the collision */
    long ncontact;    /* steps in contact (r < 2R) */
} collision;

static collision collide(double dt, const char *method)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[scene]\nmodel = greenspan72\ndt = %.17g\nt_end = 0.15\n"
             "[greenspan72]\nd = 5\nm_heavy = 1\nm_light = 0.25\n"
             "interface = 50\nlayout = list\npositions = 50 40 50 60\n"
             "velocities = 0 100 0 -100\noutput = diagnostics\n"
             "[repulsion]\nalpha = 0\n%s\n"
             "[support]\ng = 0\ndx = 6.25\nmethod = %s\n"
             "[hertz]\nenabled = yes\nk = 1e7\n",
             dt, strcmp(method, "cells") ? "" : "cutoff = 10",
             strcmp(method, "cells") ? "naive" : "cell");
    bf_scene *sc = tu_scene(text);
    bf_err err = {0};
    const bf_model_type *mt = g72_type();
    bf_setup *setup;
    void *m = g72_model(sc, &setup);
    bf_particles *p = bf_greenspan72_particles(m);
    const double k = 1e7, R = 2.5;
    collision c = {0};
    /* the step leaves x^{n+1} and v^{n+1/2}; the energy at x^n takes
     * v^n = (v^{n-1/2} + v^{n+1/2})/2 (v^0 itself at n = 0) */
    double x0[2], y0[2], vx0[2], vy0[2], vmax = 0;
    const double p0 = p->m[0] * p->vy[0] + p->m[1] * p->vy[1];
    c.k0 = bf_particles_kinetic(p);
    const long nsteps = lround(0.15 / dt);
    for (long n = 0; n < nsteps; n++) {
        for (int i = 0; i < 2; i++) {
            x0[i] = p->x[i];
            y0[i] = p->y[i];
            vx0[i] = p->vx[i];
            vy0[i] = p->vy[i];
        }
        ck_assert_msg(mt->step(m, n, (double)n * dt, dt, &err) == BF_OK,
                      "%s", err.msg);
        double r = hypot(x0[0] - x0[1], y0[0] - y0[1]), kin = 0;
        for (int i = 0; i < 2; i++) {
            double vx = n ? 0.5 * (vx0[i] + p->vx[i]) : vx0[i];
            double vy = n ? 0.5 * (vy0[i] + p->vy[i]) : vy0[i];
            kin += 0.5 * p->m[i] * (vx * vx + vy * vy);
            vmax = fmax(vmax, hypot(p->vx[i], p->vy[i]));
        }
        double e = kin + bf_hertz_pair_energy(k, R, R, r);
        c.de = fmax(c.de, fabs(e - c.k0) / c.k0);
        c.ncontact += r < 2 * R;
        double pn = p->m[0] * p->vy[0] + p->m[1] * p->vy[1];
        c.dp = fmax(c.dp, fmax(fabs(pn - p0), fabs(p->m[0] * p->vx[0] +
                                                   p->m[1] * p->vx[1])));
    }
    /* each contact step adds one rounded increment to every velocity
     * component (relative error <= eps/2 of |v|) from forces that are
     * equal and opposite up to the rounding of f/m_i (<= eps): at most
     * 4 eps (m_1 + m_2) |v|max of momentum per step */
    c.dp_tol = 4.0 * DBL_EPSILON * (p->m[0] + p->m[1]) * vmax *
               (double)c.ncontact;
    c.k1 = bf_particles_kinetic(p);
    c.v1 = p->vy[0];
    c.v2 = p->vy[1];
    mt->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return c;
}

/* Tolerances.  Momentum: the pair forces are equal and opposite, so only
 * round-off changes P (dp_tol above).  Energy: leapfrog conserves the
 * energy of an oscillator of angular frequency w to within (w dt)^2/4
 * (relative, at the steps, with v^n the mean of the half-step velocities:
 * it conserves v^2/2 + w^2 x^2 (1 - (w dt)^2/4)/2 exactly).  A contact of
 * duration t_c is half an oscillation, w = pi/t_c on average, stiffest at
 * the largest compression, where for Hertz w = 4.4/t_c: (w dt)^2/4 =
 * 4.9 (dt/t_c)^2.  The test allows (pi dt/t_c)^2 = 9.9 (dt/t_c)^2 (t_c
 * counted: the steps with r < 2R), for K + U during the collision and for
 * K after it (when U = 0 again), and requires the O(dt^2) order itself:
 * halving dt divides the largest error of K + U by 4 +- 10 %.  (Measured:
 * 0.9 (dt/t_c)^2 and ratios 3.90, 3.94.) */
START_TEST(hertz_collision_conserves)
{
    const char *paths[] = {"pairs", "cells"};
    for (int q = 0; q < 2; q++) {
        collision c[2] = {collide(2e-5, paths[q]), collide(1e-5, paths[q])};
        for (int h = 0; h < 2; h++) {
            const collision *a = &c[h];
            const double dt = h ? 1e-5 : 2e-5;
            ck_assert_msg(a->ncontact > 50, "%s: %ld steps in contact",
                          paths[q], a->ncontact);
            const double pi = 3.14159265358979323846;
            const double tol = pow(pi / (double)a->ncontact, 2);
            ck_assert_msg(a->dp <= a->dp_tol,
                          "%s dt %g: momentum changed by %g (round-off "
                          "bound %g)",
                          paths[q], dt, a->dp, a->dp_tol);
            ck_assert_msg(a->de <= tol,
                          "%s dt %g: K + U off by %.3g of E (allowed %.3g)",
                          paths[q], dt, a->de, tol);
            ck_assert_msg(fabs(a->k1 - a->k0) <= tol * a->k0,
                          "%s dt %g: K %.17g after, %.17g before (allowed "
                          "%.3g relative)",
                          paths[q], dt, a->k1, a->k0, tol);
            /* it did collide: the light particle came back down faster
             * (elastic: -220 and -20 cm/s) */
            ck_assert_msg(a->v1 < -200 && a->v2 > -25 && a->v2 < -15,
                          "%s dt %g: velocities %g, %g after", paths[q], dt,
                          a->v1, a->v2);
        }
        const double ratio = c[0].de / c[1].de;
        ck_assert_msg(ratio > 3.6 && ratio < 4.4,
                      "%s: energy error ratio %g for dt/2 (O(dt^2): 4)",
                      paths[q], ratio);
    }
}
END_TEST

Suite *suite_greenspan72(void)
{
    Suite *s = suite_create("greenspan72");
    TCase *tc = tu_tcase("greenspan72");
    tcase_add_test(tc, support_by_hand);
    tcase_add_test(tc, support_fast_and_cell_equal_naive);
    tcase_add_test(tc, repulsion_pair_by_hand_and_cells);
    tcase_add_test(tc, repulsion_batches_and_wide_kernels);
    tcase_add_test(tc, walls_by_hand);
    tcase_add_test(tc, particles_never_leave_the_box);
    tcase_add_test(tc, lone_particle_falls_exactly);
    tcase_add_test(tc, same_seed_same_bits);
    tcase_add_test(tc, restart_bit_identical);
    tcase_add_test(tc, threads_do_not_change_results);
    tcase_add_test(tc, fast_skipping_changes_no_bit);
    tcase_add_test(tc, bad_scenes_are_refused);
    tcase_add_test(tc, hertz_collision_conserves);
    suite_add_tcase(s, tc);
    return s;
}
