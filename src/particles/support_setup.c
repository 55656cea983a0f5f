/* support_setup.c: support-set gravity, Greenspan 1972 eqs 2.8-2.9 (see
 * support.h for the definitions and the three methods): the parameters,
 * the workspace, the naive method (and the per-band sums the cell method
 * falls back on), the dispatch.  The cell and fast methods are in
 * support_cell.c and support_fast.c; what the three files share is in
 * support_impl.h.
 */
#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "particles/support_impl.h"

static const bf_param support_params[] = {
    {"g", BF_AT(bf_support_keys, g, BF_REAL), "cm/s^2", "980",
     "gravitational acceleration g0 of a particle with nothing below it",
     BF_NONNEG, 0, 0, NULL},
    {"dx", BF_AT(bf_support_keys, dx, BF_REAL), "cm", NULL,
     "Delta x: height of the bands below a particle and width of its strip "
     "(eqs 2.8-2.9)",
     BF_POS, 0, 0, NULL},
    {"method", BF_AT(bf_support_keys, method, BF_ENUM), "", "auto",
     "fast: exact O(N log N) sweep (needs d <= 2 dx); cell: cell list, "
     "O(N * column); naive: all pairs O(N^2); auto: cell for boxes of at "
     "most 64 bands, else fast.  All give the same free-fall decisions and "
     "the same g to round-off",
     0, 0, 0, "fast|cell|naive|auto"},
    {"tie", BF_AT(bf_support_keys, tie, BF_ENUM), "", "le",
     "support set S(P_j): le counts particles with y_i <= y_j (the listing), "
     "lt only y_i < y_j (the text)",
     0, 0, 0, "le|lt"},
    {"eps", BF_AT(bf_support_keys, eps, BF_REAL), "cm^2", "0",
     "added to the denominators of 2.8 and 2.9 (0: the text; 1e-3: the "
     "listing)",
     BF_NONNEG, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_support_spec = BF_SECTION(
    "support", "support-set gravity (Greenspan 1972 eqs 2.8-2.9)",
    support_params, bf_support_keys);

bf_status bf_support_params_from_keys(bf_support_params *p,
                                      const bf_support_keys *k, bf_box box,
                                      double d, bf_err *err)
{
    p->box = box;
    p->d = d;
    p->g0 = k->g;
    p->dx = k->dx;
    p->method = (bf_support_method)k->method;
    p->tie = k->tie == 0;
    p->eps = k->eps;
    if (p->dx > box.bx - box.ax || p->dx > box.by - box.ay)
        return bf_fail_key(err, BF_EINPUT, "support", "dx",
                           "dx = %g is larger than the box", p->dx);
    if (p->method == BF_SUPPORT_AUTO)
        p->method = floor((box.by - box.ay) / p->dx) <= 64 || d > 2 * p->dx
                        ? BF_SUPPORT_CELL
                        : BF_SUPPORT_FAST;
    if (p->method == BF_SUPPORT_FAST && d > 2 * p->dx)
        return bf_fail_key(err, BF_EINPUT, "support", "method",
                           "method fast needs d <= 2 dx (d = %g, dx = %g); "
                           "use method = cell",
                           d, p->dx);
    return BF_OK;
}

/* The lines z_q = ay + q dx, q = 0..kmax + 2, computed once (bf_support
 * create) with this expression: band q is [z_{q-1}, z_q].  Particles in
 * the box never ask beyond kmax + 2 (kmax = K of the ceiling; one level of
 * margin each for rounding in k_of and full_level). */
static inline double line_z(const bf_support_params *p, int q)
{
    return p->box.ay + (double)q * p->dx;
}

bf_status bf_support_create(bf_support **out, const bf_support_params *p,
                            size_t cap, bf_err *err)
{
    *out = NULL;
    if (p->method == BF_SUPPORT_FAST && p->d > 2 * p->dx)
        return bf_fail(err, BF_EINPUT,
                       "support: method fast needs d <= 2 dx (d = %g, dx = %g)",
                       p->d, p->dx);
    bf_support *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->p = *p;
    s->p.inv_dx = 1.0 / p->dx;
    s->cap = cap;
    s->hd = 0.5 * p->d;
    s->hdx = 0.5 * p->dx;
    s->kmax = k_of(&s->p, p->box.by);
#ifdef _OPENMP
    s->threads = p->threads > 0 ? p->threads : omp_get_max_threads();
#else
    s->threads = 1;
#endif
    size_t k = cap ? cap : 1, nb = (size_t)s->kmax + 3;
    s->bz = malloc(nb * sizeof *s->bz);
    s->ord = malloc(k * sizeof *s->ord);
    s->binc = malloc((k + 1) * sizeof *s->binc);
    s->ls = malloc(k * sizeof *s->ls);
    s->rs = malloc(k * sizeof *s->rs);
    s->bs = malloc(k * sizeof *s->bs);
    s->ts = malloc(k * sizeof *s->ts);
    s->gs = malloc(k * sizeof *s->gs);
    s->ds = malloc(k * sizeof *s->ds);
    s->qk = malloc(k * sizeof *s->qk);
    s->qK = malloc(k * sizeof *s->qK);
    s->qg = malloc((k + 1) * sizeof *s->qg);
    s->qd = malloc(k * sizeof *s->qd);
    s->uv = malloc((2 * k + 1) * sizeof *s->uv);
    s->uh = malloc((2 * k + 1) * sizeof *s->uh);
    s->ul = malloc((2 * k + 1) * sizeof *s->ul);
    s->ks = malloc(k * sizeof *s->ks);
    s->mb = malloc(k * sizeof *s->mb);
    s->mt = malloc(k * sizeof *s->mt);
    s->sl = malloc(k * sizeof *s->sl);
    s->csl = malloc(k * sizeof *s->csl);
    s->lower = malloc(k * sizeof *s->lower);
    s->cmb = malloc(k * sizeof *s->cmb);
    s->cme = malloc(k * sizeof *s->cme);
    s->cl = malloc(k * sizeof *s->cl);
    s->cr = malloc(k * sizeof *s->cr);
    s->cb = malloc(k * sizeof *s->cb);
    s->ct = malloc(k * sizeof *s->ct);
    s->bm = malloc(k * sizeof *s->bm);
    s->fgam = malloc(k * sizeof *s->fgam);
    s->lowe = malloc(k * sizeof *s->lowe);
    s->nxt = malloc((k + 1) * sizeof *s->nxt);
    /* depth t has the blocks 0 .. nb >> t of 2^t levels (support_fast.c) */
    size_t fo = 0;
    int t = 0;
    for (; (nb >> t) > 0; t++) {
        s->foff[t] = fo;
        fo += (nb >> t) + 1;
    }
    s->foff[t] = fo;
    s->fsz = 2 * fo;
    s->fen = calloc(s->fsz * (size_t)s->threads, sizeof *s->fen);
    s->gr = malloc((nb + 1) * sizeof *s->gr);
    s->gcnt = malloc((nb + 1) * sizeof *s->gcnt);
    /* a square of height <= 2 dx has positive area in at most 3 bands,
     * and the gap before it in each; every band has a last gap */
    const size_t ngap = 3 * k + nb;
    s->glo = malloc(ngap * sizeof *s->glo);
    s->gp1 = malloc(ngap * sizeof *s->gp1);
    s->gord = malloc(ngap * sizeof *s->gord);
    s->gq = malloc(ngap * sizeof *s->gq);
    s->area = malloc(nb * (size_t)s->threads * sizeof *s->area);
    s->cnt = malloc(nb * (size_t)s->threads * sizeof *s->cnt);
    if (!s->bz || !s->ord || !s->binc || !s->ls || !s->rs || !s->bs ||
        !s->ts || !s->gs || !s->ds || !s->qk || !s->qK || !s->qg ||
        !s->qd || !s->uv || !s->uh || !s->ul || !s->ks || !s->mb || !s->mt ||
        !s->sl || !s->csl || !s->lower || !s->cmb || !s->cme || !s->cl ||
        !s->cr || !s->cb || !s->ct || !s->bm || !s->fgam ||
        !s->lowe || !s->nxt || !s->fen || !s->gr || !s->gcnt ||
        !s->glo || !s->gp1 || !s->gord || !s->gq ||
        !s->area || !s->cnt) {
        bf_support_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory (support, %zu "
                       "particles)", cap);
    }
    for (size_t q = 0; q < nb; q++)
        s->bz[q] = line_z(&s->p, (int)q);
    *out = s;
    return BF_OK;
}

void bf_support_set_exhaustive(bf_support *s, int on)
{
    s->exhaustive = on != 0;
}

void bf_support_reach(const bf_support *s, double *left, double *right)
{
    const double w = s->hdx + s->hd;
    *right = *left = s->p.method == BF_SUPPORT_NAIVE ? INFINITY : w;
    if (s->p.method == BF_SUPPORT_FAST)
        *left = SUP_CHUNK_BANDS * s->p.dx + w;
}

const bf_support_params *bf_support_params_of(const bf_support *s)
{
    return &s->p;
}

void bf_support_free(bf_support *s)
{
    if (!s)
        return;
    free(s->bz);
    free(s->ord);
    free(s->binc);
    free(s->ls);
    free(s->rs);
    free(s->bs);
    free(s->ts);
    free(s->gs);
    free(s->ds);
    free(s->qk);
    free(s->qK);
    free(s->qg);
    free(s->qd);
    free(s->uv);
    free(s->uh);
    free(s->ul);
    free(s->ks);
    free(s->mb);
    free(s->mt);
    free(s->sl);
    free(s->csl);
    free(s->lower);
    free(s->cl);
    free(s->cr);
    free(s->cb);
    free(s->ct);
    free(s->bm);
    free(s->fgam);
    free(s->lowe);
    free(s->nxt);
    free(s->fen);
    free(s->gr);
    free(s->gcnt);
    free(s->glo);
    free(s->gp1);
    free(s->gord);
    free(s->gq);
    free(s->area);
    free(s->cnt);
    free(s->cmb);
    free(s->cme);
    free(s->cutv);
    free(s->cutl);
    free(s->cutr);
    free(s->cuth);
    free(s->cuty);
    free(s->cutst);
    free(s);
}

/* ------------------------------------------- one square, one strip */

/* Add the area of square i (centre xi, yi) in the strip [gam, del] to the
 * bands q0..K (K >= 1) at index q - base, or to the rectangle [ay, yj]
 * (K == 0) at index 0. */
static inline void add_square(const bf_support *s, double xi, double yi,
                              double gam, double del, int K, int q0, int base,
                              double yj, double *area, uint32_t *cnt)
{
    const bf_support_params *p = &s->p;
    double li = dmax(xi - s->hd, p->box.ax), ri = dmin(xi + s->hd, p->box.bx);
    double f2 = dmin(ri, del) - dmax(li, gam);
    if (!(f2 > 0))
        return;
    double bi = dmax(yi - s->hd, p->box.ay), ti = dmin(yi + s->hd, p->box.by);
    if (K == 0) {
        double f1 = dmin(ti, yj) - dmax(bi, p->box.ay);
        if (f1 > 0) {
            area[0] += f1 * f2;
            cnt[0]++;
        }
        return;
    }
    /* the bands the square can reach, with a margin of one for rounding */
    int qa = k_of(p, bi), qb = k_of(p, ti) + 2;
    if (qa < q0)
        qa = q0;
    if (qb > K)
        qb = K;
    for (int q = qa; q <= qb; q++) {
        double f1 = dmin(ti, band_hi(s, q)) - dmax(bi, band_lo(s, q));
        if (f1 > 0) {
            area[q - base] += f1 * f2;
            cnt[q - base]++;
        }
    }
}

/* g from the band sums (K >= 1) or the rectangle (K == 0). */
static inline double finish(const bf_support *s, double yj, double W, int K,
                            const double *area, const uint32_t *cnt,
                            double lower, uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    double g;
    if (K == 0) {
        if (cnt[0] == 0) {
            *kind = BF_SUP_FREE;
            return -p->g0;
        }
        g = -p->g0 * (1.0 - area[0] / (W * (yj - p->box.ay) + p->eps));
    } else {
        double tot = lower;
        for (int q = 1; q <= K; q++)
            tot += area[q];
        g = -p->g0 * (1.0 - tot / (W * ((double)K * p->dx) + p->eps));
    }
    *kind = g > 0 ? BF_SUP_ANTI : BF_SUP_PARTIAL;
    return g;
}

/* Is y_i in the support set of a particle at y_j? */
static inline int below(int tie, double yi, double yj)
{
    return tie ? yi <= yj : yi < yj;
}

/* Bands q0..K (or the K = 0 rectangle) of particle j from the cell list,
 * band q at index q - base. */
void bf_sup_column(const bf_support *s, const bf_cells *c, size_t j,
                   double yj, double gam, double del, int K, int q0, int base,
                   double *area, uint32_t *cnt)
{
    const bf_support_params *p = &s->p;
    const int tie = p->tie;
    double ylo = K == 0 ? p->box.ay : band_lo(s, q0) - s->hd;
    int c0 = bf_cells_col(c, gam - s->hd), c1 = bf_cells_col(c, del + s->hd);
    int r0 = bf_cells_row(c, ylo), r1 = bf_cells_row(c, yj);
    for (int col = c0; col <= c1; col++) {
        uint32_t u0, u1;
        bf_cells_run(c, col, r0, r1, &u0, &u1);
        for (uint32_t t = u0; t < u1; t++) {
            double yi = c->sy[t];
            if (!below(tie, yi, yj) || c->idx[t] == j)
                continue;
            add_square(s, c->sx[t], yi, gam, del, K, q0, base, yj, area, cnt);
        }
    }
}

/* ------------------------------------------------------------ naive */

/* g of particle j from per-band sums: every other particle (cells == NULL,
 * the naive method) or the cell list (the column below j).  area and cnt
 * have room for K + 1 bands. */
double bf_sup_one_particle(const bf_support *s, const bf_cells *c,
                           const double *x, const double *y, size_t n,
                           size_t j, double *area, uint32_t *cnt,
                           uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    double yj = y[j];
    int K = k_of(p, yj);
    if (resting(s, yj, K)) {
        *kind = BF_SUP_REST;
        return 0.0;
    }
    double gam = dmax(x[j] - s->hdx, p->box.ax);
    double del = dmin(x[j] + s->hdx, p->box.bx);
    for (int q = 0; q <= K; q++) {
        area[q] = 0.0;
        cnt[q] = 0;
    }
    if (c) {
        bf_sup_column(s, c, j, yj, gam, del, K, 1, 0, area, cnt);
    } else {
        for (size_t i = 0; i < n; i++)
            if (i != j && below(p->tie, y[i], yj))
                add_square(s, x[i], y[i], gam, del, K, 1, 0, yj, area, cnt);
    }
    for (int q = K == 0 ? 0 : 1; q <= K; q++)
        if (cnt[q] == 0) {
            *kind = BF_SUP_FREE;
            return -p->g0;
        }
    return finish(s, yj, del - gam, K, area, cnt, 0.0, kind);
}

static void eval_naive(bf_support *s, const double *x, const double *y,
                       size_t n, double *g, uint8_t *kind)
{
    for (size_t j = 0; j < n; j++) {
        uint8_t kd;
        g[j] = bf_sup_one_particle(s, NULL, x, y, n, j, s->area, s->cnt, &kd);
        if (kind)
            kind[j] = kd;
    }
}

/* ---------------------------------------------------------- dispatch */

void bf_support_eval_with(bf_support *s, bf_support_method m, const double *x,
                          const double *y, size_t n, const bf_cells *cells,
                          double *g, uint8_t *kind)
{
    if (m == BF_SUPPORT_AUTO)
        m = s->kmax <= 64 ? BF_SUPPORT_CELL : BF_SUPPORT_FAST;
    if (m == BF_SUPPORT_FAST && s->p.d > 2 * s->p.dx)
        m = BF_SUPPORT_CELL;
    switch (m) {
    case BF_SUPPORT_FAST:
        bf_sup_eval_fast(s, n, cells, g, kind);
        break;
    case BF_SUPPORT_CELL:
        bf_sup_eval_cell(s, x, y, n, cells, g, kind);
        break;
    default:
        eval_naive(s, x, y, n, g, kind);
        break;
    }
}

void bf_support_eval(bf_support *s, const double *x, const double *y,
                     size_t n, const bf_cells *cells, double *g, uint8_t *kind)
{
    bf_support_eval_with(s, s->p.method, x, y, n, cells, g, kind);
}
