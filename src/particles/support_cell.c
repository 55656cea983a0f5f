/* support_cell.c: the cell method of the support-set gravity (see
 * support.h): for 1 <= K <= 64 one pass over the column below a particle
 * sums the areas of bands 1..K and ORs the 64-bit masks of the bands each
 * counted square reaches (support_impl.h).
 */
#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>

#include "particles/support_impl.h"

/* Square edges in cell-list order, and (masks) the bands 1..64 in which
 * each square has positive height: bit q-1 is set iff b < hi_q and
 * t > lo_q, the exact condition f1 > 0 of add_square. */
static inline void slot_edge(bf_support *s, const bf_cells *c, size_t t,
                             int masks)
{
    const bf_support_params *p = &s->p;
    double xi = c->sx[t], yi = c->sy[t];
    double b = dmax(yi - s->hd, p->box.ay), tp = dmin(yi + s->hd, p->box.by);
    s->cl[t] = dmax(xi - s->hd, p->box.ax);
    s->cr[t] = dmin(xi + s->hd, p->box.bx);
    s->cb[t] = b;
    s->ct[t] = tp;
    if (masks) {
        /* bands qa..qb, with qa, qb moved by one if rounding put them
         * beyond the exact edges */
        int qa = k_of(p, b) + 1, qb = k_of(p, tp) + 1;
        if (qa > 1 && b < band_hi(s, qa - 1))
            qa--;
        if (!(b < band_hi(s, qa)))
            qa++;
        if (!(tp > band_lo(s, qb)))
            qb--;
        if (tp > band_lo(s, qb + 1))
            qb++;
        if (qb > 64)
            qb = 64;
        s->bm[t] = qa > qb ? 0
                           : (((uint64_t)2 << (qb - 1)) - 1) &
                                 ~(((uint64_t)1 << (qa - 1)) - 1);
    }
}

void bf_sup_slot_edges(bf_support *s, const bf_cells *c, size_t n,
                       int masks)
{
    if (par(s, n)) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(s->threads)
#endif
        for (size_t t = 0; t < n; t++)
            slot_edge(s, c, t, masks);
    } else {
        for (size_t t = 0; t < n; t++)
            slot_edge(s, c, t, masks);
    }
}

/* The cell method, g of the particle in slot t (thread tid's scratch): for
 * 1 <= K <= 64 the area of bands 1..K is sum f2 (min(t, hi_K) - b) over
 * the squares of S(P_j) below, and a band is empty iff no counted square
 * has its bit; the other cases (K = 0, K > 64) go band by band
 * (bf_sup_one_particle). */
static inline void cell_one(bf_support *s, const double *x, const double *y,
                            size_t n, const bf_cells *c, size_t t, int tid,
                            double *g, uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    const size_t nbands = (size_t)s->kmax + 3;
    const uint32_t j = c->idx[t];
    const double xj = c->sx[t], yj = c->sy[t];
    const int K = k_of(p, yj);
    uint8_t kd;
    double gj;
    if (K == 0 || K > 64) {
        gj = bf_sup_one_particle(s, c, x, y, n, j,
                                 s->area + (size_t)tid * nbands,
                                 s->cnt + (size_t)tid * nbands, &kd);
    } else {
        const double gam = dmax(xj - s->hdx, p->box.ax);
        const double del = dmin(xj + s->hdx, p->box.bx);
        const double hd = s->hd;
        const stripq q =
            stripq_of(gam, del, band_hi(s, K), band_lo(s, K),
                      p->tie ? yj : nextafter(yj, -INFINITY), K);
        uint32_t cnt = 0;
        int c0 = bf_cells_col(c, gam - hd), c1 = bf_cells_col(c, del + hd);
        int r1 = bf_cells_row(c, yj);
        double area = 0.0;
        uint64_t mask = 0;
        for (int col = c0; col <= c1; col++) {
            /* rows 0..r1 of the column, j itself skipped */
            uint32_t u0, u1;
            bf_cells_run(c, col, 0, r1, &u0, &u1);
            if (t >= u0 && t < u1) {
                strip_range(s, c->sy, &q, u0, (uint32_t)t, 0, &area, &mask,
                            &cnt);
                strip_range(s, c->sy, &q, (uint32_t)t + 1, u1, 0, &area,
                            &mask, &cnt);
            } else {
                strip_range(s, c->sy, &q, u0, u1, 0, &area, &mask, &cnt);
            }
        }
        const uint64_t need = K == 64 ? ~(uint64_t)0
                                      : ((uint64_t)1 << K) - 1;
        if ((mask & need) != need) {
            gj = -p->g0;
            kd = BF_SUP_FREE;
        } else {
            gj = -p->g0 * (1.0 - area / ((del - gam) * ((double)K * p->dx) +
                                         p->eps));
            kd = gj > 0 ? BF_SUP_ANTI : BF_SUP_PARTIAL;
        }
    }
    g[j] = gj;
    if (kind)
        kind[j] = kd;
}

void bf_sup_eval_cell(bf_support *s, const double *x, const double *y,
                      size_t n, const bf_cells *c, double *g, uint8_t *kind)
{
    bf_sup_slot_edges(s, c, n, 1);
    if (par(s, n)) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 64) num_threads(s->threads)
        for (size_t t = 0; t < n; t++)
            cell_one(s, x, y, n, c, t, omp_get_thread_num(), g, kind);
#endif
    } else {
        for (size_t t = 0; t < n; t++)
            cell_one(s, x, y, n, c, t, 0, g, kind);
    }
}
