/* repulsion.c: Greenspan 1972 eqs 2.11-2.12, the repulsion between
 * particles (see repulsion.h).  Every pair is visited once and both
 * accelerations are updated (the listing's ACX(J) += AM(I) TX,
 * ACX(I) -= AM(J) TX). */
#include "ballfilm/repulsion.h"

#include "ballfilm/ipow.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const bf_param repulsion_params[] = {
    {"alpha", BF_REAL, "1", "1", "strength alpha of eqs 2.11-2.12",
     BF_NONNEG, 0, 0, NULL},
    {"xi", BF_REAL, "cm", "0",
     "xi: added to the distance (how close centres may come)", BF_NONNEG, 0,
     0, NULL},
    {"p", BF_INT, "1", "2", "exponent p of (r + xi)^p", BF_MIN | BF_MAX, 0, 30,
     NULL},
    {"beta", BF_INT, "1", "5",
     "exponent beta of ((r + xi)/d)^beta, applied only for r < d",
     BF_MIN | BF_MAX, 0, 30, NULL},
    {"cutoff", BF_REAL, "cm", "0",
     "only pairs with r < cutoff interact (Example 2: 2d = 10); 0: all pairs",
     BF_NONNEG, 0, 0, NULL},
    {"method", BF_ENUM, "", "auto",
     "cells: cell list (needs a cutoff); pairs: all pairs; auto: cells when "
     "there is a cutoff",
     0, 0, 0, "auto|cells|pairs"},
    {"cell", BF_REAL, "cm", "0",
     "side of the cell-list cells (0: half the cutoff); smaller cells test "
     "fewer pairs but visit more cells",
     BF_NONNEG | BF_HIDDEN, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_repulsion_spec = {
    "repulsion", "repulsion between particles (Greenspan 1972 eqs 2.10-2.12)",
    repulsion_params};

bf_status bf_repulsion_from_scene(bf_repulsion *r, const bf_scene *sc,
                                  double d, bf_err *err)
{
    r->alpha = bf_scene_real(sc, "repulsion", "alpha");
    r->xi = bf_scene_real(sc, "repulsion", "xi");
    r->p = (int)bf_scene_int(sc, "repulsion", "p");
    r->beta = (int)bf_scene_int(sc, "repulsion", "beta");
    r->cutoff = bf_scene_real(sc, "repulsion", "cutoff");
    r->cell = bf_scene_real(sc, "repulsion", "cell");
    r->d = d;
    r->inv_d = 1.0 / d;
    int m = bf_scene_enum(sc, "repulsion", "method");
    r->use_cells = m == 1 || (m == 0 && r->cutoff > 0);
    if (r->use_cells && !(r->cutoff > 0))
        return bf_scene_fail(sc, err, "repulsion", "method",
                             "the cell list needs a cutoff > 0");
    if (r->cell > 0 && r->cutoff > 0 && r->cell > r->cutoff)
        return bf_scene_fail(sc, err, "repulsion", "cell",
                             "cell side %g is above the cutoff %g", r->cell,
                             r->cutoff);
    return BF_OK;
}

/* alpha / D(r) for r^2 = r2, or -1 if D = 0. */
static inline double factor(const bf_repulsion *r, double r2)
{
    double d = sqrt(r2);
    double s = d + r->xi;
    /* D (s/d)^beta for r < d, else D; as arithmetic (exact: B is finite)
     * because the test is random and a branch would mispredict */
    double D = bf_ipow(s, r->p), B = bf_ipow(s * r->inv_d, r->beta);
    double in = (double)(d < r->d);
    D *= in * B + (1.0 - in);
    return D > 0 ? r->alpha / D : -1.0;
}

int bf_repulsion_all_pairs(const bf_repulsion *r, const double *x,
                           const double *y, const double *m, size_t n,
                           double *ax, double *ay, size_t *bi, size_t *bj)
{
    const double rc2 = r->cutoff > 0 ? r->cutoff * r->cutoff : INFINITY;
    memset(ax, 0, n * sizeof *ax);
    memset(ay, 0, n * sizeof *ay);
    for (size_t j = 0; j < n; j++)
        for (size_t i = j + 1; i < n; i++) {
            double dx = x[j] - x[i], dy = y[j] - y[i];
            double r2 = dx * dx + dy * dy;
            if (!(r2 < rc2))
                continue;
            double f = factor(r, r2);
            if (f < 0) {
                *bi = j;
                *bj = i;
                return 1;
            }
            double tx = dx * f, ty = dy * f;
            ax[j] += m[i] * tx;
            ay[j] += m[i] * ty;
            ax[i] -= m[j] * tx;
            ay[i] -= m[j] * ty;
        }
    return 0;
}

bf_status bf_repulsion_work_init(bf_repulsion_work *w, size_t cap, int threads,
                                 bf_err *err)
{
#ifdef _OPENMP
    w->threads = threads > 0 ? threads : omp_get_max_threads();
#else
    (void)threads;
    w->threads = 1;
#endif
    size_t k = cap ? cap : 1, nt = (size_t)w->threads;
    w->cap = cap;
    w->sax = malloc(k * sizeof *w->sax);
    w->say = malloc(k * sizeof *w->say);
    w->r2 = malloc(nt * k * sizeof *w->r2);
    w->nb = malloc(nt * k * sizeof *w->nb);
    if (!w->sax || !w->say || !w->r2 || !w->nb) {
        bf_repulsion_work_free(w);
        return bf_fail(err, BF_EINTERNAL, "out of memory (repulsion)");
    }
    return BF_OK;
}

void bf_repulsion_work_free(bf_repulsion_work *w)
{
    free(w->sax);
    free(w->say);
    free(w->r2);
    free(w->nb);
    w->sax = w->say = w->r2 = NULL;
    w->nb = NULL;
}

/* Columns [x0, x1) of the cell list; the first coincident pair found is
 * reported through bad (slots). */
static void cols_pairs(const bf_repulsion *r, const bf_cells *c, int reach,
                       int x0, int x1, double *r2b, uint32_t *nb, double *sax,
                       double *say, uint32_t bad[2], int *found)
{
    const double rc2 = r->cutoff * r->cutoff;
    const int nx = c->nx, ny = c->ny;
    const double *sx = c->sx, *sy = c->sy, *sw = c->sw;
    for (int cx = x0; cx < x1; cx++)
        for (int cy = 0; cy < ny; cy++) {
            uint32_t a0, a1;
            bf_cells_run(c, cx, cy, cy, &a0, &a1);
            const int ylo = cy - reach < 0 ? 0 : cy - reach,
                      yhi = cy + reach >= ny ? ny - 1 : cy + reach;
            for (uint32_t s = a0; s < a1; s++) {
                const double xs = sx[s], ys = sy[s], ws = sw[s];
                /* the neighbours in half of the neighbourhood (this column:
                 * the slots after s up to row cy + reach; the columns to
                 * the right: rows cy - reach .. cy + reach), collected
                 * without branches: about half of the candidates are
                 * beyond the cutoff, at random */
                size_t m = 0;
                for (int ox = 0; ox <= reach && cx + ox < nx; ox++) {
                    uint32_t b0, b1;
                    bf_cells_run(c, cx + ox, ox == 0 ? cy : ylo, yhi, &b0, &b1);
                    if (ox == 0)
                        b0 = s + 1;
                    for (uint32_t t = b0; t < b1; t++) {
                        double dx = xs - sx[t], dy = ys - sy[t];
                        double q = dx * dx + dy * dy;
                        nb[m] = t;
                        r2b[m] = q;
                        m += q < rc2;
                    }
                }
                double axs = 0, ays = 0;
                for (size_t k = 0; k < m; k++) {
                    uint32_t t = nb[k];
                    double f = factor(r, r2b[k]);
                    if (f < 0) {
                        if (!*found) {
                            *found = 1;
                            bad[0] = s;
                            bad[1] = t;
                        }
                        f = 0.0;
                    }
                    double tx = (xs - sx[t]) * f, ty = (ys - sy[t]) * f;
                    axs += sw[t] * tx;
                    ays += sw[t] * ty;
                    sax[t] -= ws * tx;
                    say[t] -= ws * ty;
                }
                sax[s] += axs;
                say[s] += ays;
            }
        }
}

int bf_repulsion_cells(const bf_repulsion *r, const bf_cells *c,
                       bf_repulsion_work *w, double *ax, double *ay,
                       size_t *bi, size_t *bj)
{
    const int reach = (int)ceil(r->cutoff * c->inv_h * (1.0 - 1e-12));
    const int nx = c->nx, width = reach + 1;
    const int nstripes = (nx + width - 1) / width;
    const size_t n = c->n;
    double *sax = w->sax, *say = w->say;
    memset(sax, 0, n * sizeof *sax);
    memset(say, 0, n * sizeof *say);
    /* the first coincident pair in stripe order (thread-count independent) */
    uint32_t bad[2] = {0, 0};
    int found = 0;
    for (int phase = 0; phase < 2; phase++) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(w->threads) \
    if (n >= 4096)
#endif
        for (int k = phase; k < nstripes; k += 2) {
            int tid = 0;
#ifdef _OPENMP
            tid = omp_get_thread_num();
#endif
            uint32_t b[2];
            int f = 0;
            int x1 = (k + 1) * width < nx ? (k + 1) * width : nx;
            cols_pairs(r, c, reach, k * width, x1, w->r2 + (size_t)tid * n,
                       w->nb + (size_t)tid * n, sax, say, b, &f);
            if (f) {
#ifdef _OPENMP
#pragma omp critical(bf_repulsion_bad)
#endif
                if (!found || b[0] < bad[0]) {
                    found = 1;
                    bad[0] = b[0];
                    bad[1] = b[1];
                }
            }
        }
    }
    if (found) {
        *bi = c->idx[bad[0]];
        *bj = c->idx[bad[1]];
        return 1;
    }
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(w->threads) \
    if (n >= 4096)
#endif
    for (size_t s = 0; s < n; s++) {
        ax[c->idx[s]] = sax[s];
        ay[c->idx[s]] = say[s];
    }
    return 0;
}
