/* support.c: support-set gravity, Greenspan 1972 eqs 2.8-2.9 (see
 * support.h for the definitions and the three methods).
 *
 * Every method decides "square i overlaps strip j in band q with positive
 * area" with the same two floating-point expressions,
 *   f2 = min(r_i, delta_j) - max(l_i, gamma_j) > 0,
 *   f1 = min(t_i, hi_q) - max(b_i, lo_q) > 0,
 * and the same band edges lo_q = ay + (q-1) dx, hi_q = ay + q dx, so the
 * free-fall decisions are identical; only the order of the area sums (and,
 * in the fast method, their form) differs, which changes g by round-off.
 */
#include "support.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Small kernels that must be inlined with constant arguments. */
#define HOT static inline __attribute__((always_inline))

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

struct bf_support {
    bf_support_params p;
    size_t cap;
    int kmax;        /* largest K of a particle in the box */
    double *bz;      /* [kmax + 3]: the band edges z_q (line_z) */
    int threads;     /* OpenMP threads */
    double hd, hdx;  /* d/2, dx/2 */
    /* x-sorted order and geometry in that order (fast method) */
    uint32_t *ord, *binc; /* x order, bin counts */
    double *ls, *rs, *bs, *ts, *gs, *ds, *ys;
    int32_t *ks, *mb, *mt; /* K; the first and last band with positive
                              height of the square (first_band, full_level) */
    int32_t *sl, *csl; /* sweep level: mt, or INT32_MAX for a square clipped
                          by the ceiling (never in the sweep); x order, cell
                          order */
    double *lower; /* area of the squares entirely below z_K (the sweep) */
    double *cl, *cr, *cb, *ct; /* square edges in cell-list order */
    uint64_t *bm;              /* bands 1..64 each square reaches */
    double *fgam;  /* F(gamma) while sweeping */
    int32_t *lowe; /* lowest empty band below the top band */
    uint32_t *nxt; /* skip list of particles without a lowest empty band */
    double *fen;   /* Fenwick tree over levels: 4 sums per node */
    uint32_t *bstart, *bfill, *blist;
    /* per-band sums for one particle (naive and cell) */
    double *area;
    uint32_t *cnt;
};

/* ---------------------------------------------------------- geometry */

static inline double dmax(double a, double b) { return a > b ? a : b; }
static inline double dmin(double a, double b) { return a < b ? a : b; }

/* The lines z_q = ay + q dx, q = 0..kmax + 2, computed once (bf_support
 * create) with this expression: band q is [z_{q-1}, z_q].  Particles in
 * the box never ask beyond kmax + 2 (kmax = K of the ceiling; one level of
 * margin each for rounding in k_of and full_level). */
static inline double line_z(const bf_support_params *p, int q)
{
    return p->box.ay + (double)q * p->dx;
}

static inline double band_lo(const bf_support *s, int q) { return s->bz[q - 1]; }

static inline double band_hi(const bf_support *s, int q) { return s->bz[q]; }

/* K(y) = floor((y - ay)/dx) >= 0, with the reciprocal of dx (one
 * definition for every method; at an exact band edge it may differ from a
 * division by one ulp's worth, which only moves the edge by round-off). */
static inline int k_of(const bf_support_params *p, double y)
{
    double k = (y - p->box.ay) * p->inv_dx;
    return k > 0 ? (int)k : 0;
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
    s->ys = malloc(k * sizeof *s->ys);
    s->ks = malloc(k * sizeof *s->ks);
    s->mb = malloc(k * sizeof *s->mb);
    s->mt = malloc(k * sizeof *s->mt);
    s->sl = malloc(k * sizeof *s->sl);
    s->csl = malloc(k * sizeof *s->csl);
    s->lower = malloc(k * sizeof *s->lower);
    s->cl = malloc(k * sizeof *s->cl);
    s->cr = malloc(k * sizeof *s->cr);
    s->cb = malloc(k * sizeof *s->cb);
    s->ct = malloc(k * sizeof *s->ct);
    s->bm = malloc(k * sizeof *s->bm);
    s->fgam = malloc(k * sizeof *s->fgam);
    s->lowe = malloc(k * sizeof *s->lowe);
    s->nxt = malloc((k + 1) * sizeof *s->nxt);
    s->fen = malloc(2 * nb * (size_t)s->threads * sizeof *s->fen);
    s->bstart = malloc((nb + 1) * sizeof *s->bstart);
    s->bfill = malloc((nb + 1) * sizeof *s->bfill);
    /* a square of height <= 2 dx has positive area in at most 3 bands */
    s->blist = malloc(3 * k * sizeof *s->blist);
    s->area = malloc(nb * (size_t)s->threads * sizeof *s->area);
    s->cnt = malloc(nb * (size_t)s->threads * sizeof *s->cnt);
    if (!s->bz || !s->ord || !s->binc || !s->ls || !s->rs || !s->bs ||
        !s->ts || !s->gs || !s->ds || !s->ys || !s->ks || !s->mb || !s->mt ||
        !s->sl || !s->csl || !s->lower || !s->cl || !s->cr || !s->cb ||
        !s->ct || !s->bm || !s->fgam ||
        !s->lowe || !s->nxt || !s->fen || !s->bstart || !s->bfill ||
        !s->blist || !s->area || !s->cnt) {
        bf_support_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory (support, %zu "
                       "particles)", cap);
    }
    for (size_t q = 0; q < nb; q++)
        s->bz[q] = line_z(&s->p, (int)q);
    *out = s;
    return BF_OK;
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
    free(s->ys);
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
    free(s->bstart);
    free(s->bfill);
    free(s->blist);
    free(s->area);
    free(s->cnt);
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

/* The lowest level m >= 1 whose line z_m = band_hi(m) is at or above t:
 * exact with respect to band_hi, so that "full below z_m" (the sweep) and
 * "cut by z_m" (t > z_m, the cell query) never disagree. */
static inline int full_level(const bf_support *s, double t)
{
    int m = k_of(&s->p, t);
    if (m < 1)
        m = 1;
    while (m > 1 && band_hi(s, m - 1) >= t)
        m--;
    while (band_hi(s, m) < t)
        m++;
    return m;
}

/* The lowest band q >= 1 whose top z_q is above b: with full_level, a
 * square reaches (positive height, if t > b) exactly the bands
 * first_band(b) .. full_level(t). */
static inline int first_band(const bf_support *s, double b)
{
    int q = k_of(&s->p, b) + 1;
    while (q > 1 && band_hi(s, q - 1) > b)
        q--;
    while (q <= s->kmax + 1 && !(band_hi(s, q) > b)) /* bounded for NaN */
        q++;
    return q;
}

/* Particle j is resting on the floor band. */
static inline int resting(const bf_support *s, double yj, int K)
{
    return K == 0 && yj - s->p.box.ay <= s->p.d;
}

/* Is y_i in the support set of a particle at y_j? */
static inline int below(int tie, double yi, double yj)
{
    return tie ? yi <= yj : yi < yj;
}

/* Bands q0..K (or the K = 0 rectangle) of particle j from the cell list,
 * band q at index q - base. */
static void column_from_cells(const bf_support *s, const bf_cells *c,
                              size_t j, double yj, double gam, double del,
                              int K, int q0, int base, double *area,
                              uint32_t *cnt)
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

/* ------------------------------------------------------ naive, cell */

/* g of particle j from per-band sums: every other particle (cells == NULL,
 * the naive method) or the cell list (the column below j).  area and cnt
 * have room for K + 1 bands. */
static double one_particle(const bf_support *s, const bf_cells *c,
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
        column_from_cells(s, c, j, yj, gam, del, K, 1, 0, area, cnt);
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
        g[j] = one_particle(s, NULL, x, y, n, j, s->area, s->cnt, &kd);
        if (kind)
            kind[j] = kd;
    }
}

/* OpenMP only pays from a few thousand particles on, and only with more
 * than one thread.  Otherwise the loops run without entering a parallel
 * region at all: libgomp allocates a team for every region, even for one
 * with if (0). */
#define PAR_MIN 4096

static inline int par(const bf_support *s, size_t n)
{
    return s->threads > 1 && n >= PAR_MIN;
}

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

static void slot_edges(bf_support *s, const bf_cells *c, size_t n, int masks)
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

/* The constants of one particle j's queries of the cell list. */
typedef struct stripq {
    double gam, del; /* its strip */
    double hi, lo;   /* its band K */
    double ytop;     /* S(P_j): y_i <= ytop */
    int K;
#if defined(__SSE2__)
    __m128d G, D, H, Y; /* gam, del, hi, ytop in both lanes */
    __m128i KK;         /* K in every 32-bit lane */
#endif
} stripq;

static inline stripq stripq_of(double gam, double del, double hi, double lo,
                               double ytop, int K)
{
    stripq q = {gam, del, hi, lo, ytop, K
#if defined(__SSE2__)
                ,
                _mm_set1_pd(gam), _mm_set1_pd(del), _mm_set1_pd(hi),
                _mm_set1_pd(ytop), _mm_set1_epi32(K)
#endif
    };
    return q;
}

/* The squares of slots [u, u1) (not j itself) that count for particle j:
 * y <= ytop, f2 > 0 (the strip) and hh = min(t, hi_K) - b > 0, and if
 * `cut` only those the sweep at level K leaves out (sweep level csl > K).
 * Adds the sum of f2 hh to *area and, if `cut`, their number to *cnt,
 * else the OR of their band masks to *mask.  (The height test only
 * matters in j's row: the rows below hold only squares below j.)
 * Branch-free, the tests fail at random; with SSE2 two squares at a time:
 * min/max/sub/mul are the same IEEE operations, the masked term is f2 hh
 * or +0 and the sum runs in slot order, so the same bits as the scalar
 * loop.  `cut` is a constant where this is inlined. */
HOT void strip_range(const bf_support *s, const double *restrict sy,
                     const stripq *q, uint32_t u, uint32_t u1, int cut,
                     double *area, uint64_t *mask, uint32_t *cnt)
{
    const double *restrict cl = s->cl, *restrict cr = s->cr,
                           *restrict cb = s->cb, *restrict ct = s->ct;
    const uint64_t *restrict bm = s->bm;
    const int32_t *restrict csl = s->csl;
    double a = *area;
    uint64_t m = *mask;
    uint32_t n = *cnt;
#if defined(__SSE2__)
    const __m128d Z = _mm_setzero_pd();
    __m128i M = _mm_setzero_si128();
    for (; u + 2 <= u1; u += 2) {
        __m128d f2 = _mm_sub_pd(_mm_min_pd(_mm_loadu_pd(cr + u), q->D),
                                _mm_max_pd(_mm_loadu_pd(cl + u), q->G));
        __m128d hh = _mm_sub_pd(_mm_min_pd(_mm_loadu_pd(ct + u), q->H),
                                _mm_loadu_pd(cb + u));
        __m128d ok = _mm_and_pd(_mm_cmpgt_pd(f2, Z), _mm_cmpgt_pd(hh, Z));
        ok = _mm_and_pd(ok, _mm_cmple_pd(_mm_loadu_pd(sy + u), q->Y));
        if (cut) {
            /* csl > K, widened from two 32-bit lanes to two 64-bit ones */
            __m128i o = _mm_cmpgt_epi32(
                _mm_loadl_epi64((const void *)(csl + u)), q->KK);
            ok = _mm_and_pd(ok, _mm_castsi128_pd(_mm_unpacklo_epi32(o, o)));
        }
        __m128d term = _mm_and_pd(ok, _mm_mul_pd(f2, hh));
        a += _mm_cvtsd_f64(term);
        a += _mm_cvtsd_f64(_mm_unpackhi_pd(term, term));
        if (cut) {
            const int bits = _mm_movemask_pd(ok);
            n += (uint32_t)((bits & 1) + (bits >> 1));
        } else {
            /* ok is all ones or zeros in each 64-bit lane */
            M = _mm_or_si128(
                M, _mm_and_si128(_mm_castpd_si128(ok),
                                 _mm_loadu_si128((const void *)(bm + u))));
        }
    }
    if (!cut) {
        uint64_t mv[2];
        _mm_storeu_si128((void *)mv, M);
        m |= mv[0] | mv[1];
    }
#endif
    for (; u < u1; u++) {
        double f2 = dmin(cr[u], q->del) - dmax(cl[u], q->gam);
        double hh = dmin(ct[u], q->hi) - cb[u];
        int ok = (f2 > 0) & (hh > 0) & (sy[u] <= q->ytop) &
                 (!cut | (csl[u] > q->K));
        a += (double)ok * (f2 * hh);
        if (cut)
            n += (uint32_t)ok;
        else
            m |= bm[u] & (0 - (uint64_t)ok);
    }
    *area = a;
    *mask = m;
    *cnt = n;
}

/* The cell method, g of the particle in slot t (thread tid's scratch): for
 * 1 <= K <= 64 the area of bands 1..K is sum f2 (min(t, hi_K) - b) over
 * the squares of S(P_j) below, and a band is empty iff no counted square
 * has its bit; the other cases (K = 0, K > 64) go band by band
 * (one_particle). */
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
        gj = one_particle(s, c, x, y, n, j, s->area + (size_t)tid * nbands,
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

static void eval_cell(bf_support *s, const double *x, const double *y,
                      size_t n, const bf_cells *c, double *g, uint8_t *kind)
{
    slot_edges(s, c, n, 1);
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

/* ------------------------------------------------------------- fast */

/* Sort the indices 0..n-1 of x[] by x: counting sort into n bins, then
 * insertion sort inside each bin (ties keep the index order).  Expected
 * O(n). */
static void sort_by_x(bf_support *s, const double *x, size_t n)
{
    const double ax = s->p.box.ax, w = s->p.box.bx - s->p.box.ax;
    const double scale = (double)n / w;
    uint32_t *binc = s->binc, *ord = s->ord, *tmp = s->nxt;
    memset(binc, 0, (n + 1) * sizeof *binc);
    for (size_t i = 0; i < n; i++) {
        double f = (x[i] - ax) * scale;
        size_t b = f > 0 ? (size_t)f : 0;
        if (b >= n)
            b = n - 1;
        tmp[i] = (uint32_t)b;
        binc[b + 1]++;
    }
    for (size_t b = 0; b < n; b++)
        binc[b + 1] += binc[b];
    for (size_t i = 0; i < n; i++)
        ord[binc[tmp[i]]++] = (uint32_t)i;
    /* binc[b] is now the end of bin b; insertion sort each bin */
    size_t lo = 0;
    for (size_t b = 0; b < n; b++) {
        size_t hi = binc[b];
        for (size_t a = lo + 1; a < hi; a++) {
            uint32_t v = ord[a];
            double xv = x[v];
            size_t c = a;
            while (c > lo && x[ord[c - 1]] > xv) {
                ord[c] = ord[c - 1];
                c--;
            }
            ord[c] = v;
        }
        lo = hi;
    }
}

/* Fenwick tree over levels 1..m of 2 sums (A, B), stored side by side
 * (with SSE2 both in one register: the same additions, the same bits). */
static inline void fen_add(double *fen, int m, int level, double a, double b)
{
#if defined(__SSE2__)
    const __m128d ab = _mm_set_pd(b, a);
    for (int k = level; k <= m; k += k & -k)
        _mm_storeu_pd(fen + 2 * k, _mm_add_pd(_mm_loadu_pd(fen + 2 * k), ab));
#else
    for (int k = level; k <= m; k += k & -k) {
        fen[2 * k] += a;
        fen[2 * k + 1] += b;
    }
#endif
}

/* The square at sorted position p, with its left (sigma = +1) or right
 * (sigma = -1) edge at local coordinate e, enters the sweep.  It counts
 * with its full height h at every level m whose line z_m = ay + m dx is at
 * or above its top (m >= sl[p]; a square clipped by the ceiling never
 * counts); squares cut by the line z_m are added by the cell-list query of
 * the particle asking (cut_band). */
static inline void sweep_add(const bf_support *s, double *fen, int mq,
                             size_t p, double sigma, double e)
{
    const int mt = s->sl[p];
    if (mt <= mq) {
        double h = sigma * (s->ts[p] - s->bs[p]);
        fen_add(fen, mq, mt, h, h * e);
    }
}

/* G(x) = x A - B at level m (local coordinates). */
static inline double sweep_eval(const double *fen, double x, int m)
{
#if defined(__SSE2__)
    __m128d ab = _mm_setzero_pd();
    for (int k = m; k > 0; k -= k & -k)
        ab = _mm_add_pd(ab, _mm_loadu_pd(fen + 2 * k));
    return x * _mm_cvtsd_f64(ab) - _mm_cvtsd_f64(_mm_unpackhi_pd(ab, ab));
#else
    double a = 0, b = 0;
    for (int k = m; k > 0; k -= k & -k) {
        a += fen[2 * k];
        b += fen[2 * k + 1];
    }
    return x * a - b;
#endif
}

/* First sorted position p in [lo, hi) with v[p] > key (or >= if ge). */
static size_t bsearch_pos(const double *v, size_t lo, size_t hi, double key,
                          int ge)
{
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (ge ? v[mid] >= key : v[mid] > key)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* Lower-band areas of the particles whose strips start in the chunk
 * [X0, X1): a sweep over the square edges in (X0, X1 + dx], in coordinates
 * relative to X0 so that the sums stay small (their round-off does not
 * grow with the box).  Squares straddling X0 enter with their left edge at
 * X0: G(x) = integral from X0 to x of the filled height. */
static void sweep_chunk(bf_support *s, double *fen, size_t n, int mq,
                        double X0, double X1, int last)
{
    const double *ls = s->ls, *rs = s->rs, *gs = s->gs, *ds = s->ds;
    size_t q0 = bsearch_pos(gs, 0, n, X0, 1);
    size_t q1 = last ? n : bsearch_pos(gs, q0, n, X1, 1);
    if (q0 == q1)
        return;
    memset(fen, 0, 2 * (size_t)(mq + 1) * sizeof *fen);
    /* squares with l <= X0 < r enter at X0 */
    size_t pr = bsearch_pos(rs, 0, n, X0, 0);
    size_t pl = bsearch_pos(ls, 0, n, X0, 0);
    for (size_t p = pr; p < pl; p++)
        sweep_add(s, fen, mq, p, 1.0, 0.0);
    size_t pg = q0, pd = q0;
    const double inf = INFINITY;
    while (pd < q1) {
        double vl = pl < n ? ls[pl] : inf, vr = pr < n ? rs[pr] : inf;
        double vg = pg < q1 ? gs[pg] : inf, vd = ds[pd];
        if (vl <= vr && vl <= vg && vl <= vd) {
            sweep_add(s, fen, mq, pl, 1.0, vl - X0);
            pl++;
        } else if (vr <= vg && vr <= vd) {
            sweep_add(s, fen, mq, pr, -1.0, vr - X0);
            pr++;
        } else if (vg <= vd) {
            if (s->ks[pg] >= 1)
                s->fgam[pg] = sweep_eval(fen, vg - X0, s->ks[pg]);
            pg++;
        } else {
            if (s->ks[pd] >= 1)
                s->lower[pd] = sweep_eval(fen, vd - X0, s->ks[pd]) -
                               s->fgam[pd];
            pd++;
        }
    }
}

static inline uint32_t skip_find(uint32_t *nxt, uint32_t p)
{
    while (nxt[p] != p) {
        nxt[p] = nxt[nxt[p]];
        p = nxt[p];
    }
    return p;
}

/* For every sorted position, the lowest band q <= mq in which no square
 * overlaps its strip with positive area (lowe), or a value > mq. */
static void empty_bands(bf_support *s, size_t n, int mq)
{
    uint32_t *bstart = s->bstart, *bfill = s->bfill, *blist = s->blist;
    uint32_t *nxt = s->nxt;
    memset(bstart, 0, (size_t)(mq + 2) * sizeof *bstart);
    /* squares per band, in x order */
    for (int pass = 0; pass < 2; pass++) {
        for (size_t k = 0; k < n; k++) {
            /* f1 > 0 exactly in the bands mb..mt (z_{q-1} < t and
             * z_q > b), unless the square has no height */
            if (!(s->ts[k] > s->bs[k]))
                continue;
            const int qa = s->mb[k], qb = s->mt[k] < mq ? s->mt[k] : mq;
            for (int q = qa; q <= qb; q++) {
                if (pass == 0)
                    bstart[q + 1]++;
                else
                    blist[bfill[q]++] = (uint32_t)k;
            }
        }
        if (pass == 0) {
            for (int q = 1; q <= mq; q++)
                bstart[q + 1] += bstart[q];
            memcpy(bfill, bstart, (size_t)(mq + 2) * sizeof *bfill);
        }
    }
    double wmin = INFINITY;
    for (size_t k = 0; k < n; k++) {
        double w = s->ds[k] - s->gs[k];
        if (w < wmin)
            wmin = w;
        s->lowe[k] = mq + 1;
        nxt[k] = (uint32_t)k;
    }
    nxt[n] = (uint32_t)n;
    size_t left = n;
    for (int q = 1; q <= mq && left; q++) {
        uint32_t a = bstart[q], e = bstart[q + 1];
        /* gaps: (-inf, l_first], [r_k, l_{k+1}], [r_last, +inf) */
        for (uint32_t k = a; k <= e; k++) {
            double lo = k == a ? -INFINITY : s->rs[blist[k - 1]];
            double hi = k == e ? INFINITY : s->ls[blist[k]];
            /* rounding is monotone: a strip of width w fits only if the
             * rounded gap width is >= w */
            if (!(hi - lo >= wmin))
                continue;
            size_t p0 = bsearch_pos(s->gs, 0, n, lo, 1);
            size_t p1 = bsearch_pos(s->ds, 0, n, hi, 0);
            for (uint32_t j = skip_find(nxt, (uint32_t)p0); j < p1;
                 j = skip_find(nxt, j + 1)) {
                s->lowe[j] = q;
                nxt[j] = j + 1;
                left--;
            }
        }
    }
}

/* Slots [u, u1): is there a square of S(P_j) with positive area in the
 * strip in band K (f2 > 0, f1 > 0 as in add_square)? */
static inline int band_range(const bf_support *s, const double *sy,
                             const stripq *q, uint32_t u, uint32_t u1)
{
    for (; u < u1; u++) {
        double f2 = dmin(s->cr[u], q->del) - dmax(s->cl[u], q->gam);
        double f1 = dmin(s->ct[u], q->hi) - dmax(s->cb[u], q->lo);
        if (sy[u] <= q->ytop && f2 > 0 && f1 > 0)
            return 1;
    }
    return 0;
}

/* The slots [u0, u1) of column col, rows r0..r1, without tj. */
static inline void run_without(const bf_cells *c, int col, int r0, int r1,
                               uint32_t tj, uint32_t u[4])
{
    bf_cells_run(c, col, r0, r1, &u[0], &u[3]);
    if (tj >= u[0] && tj < u[3]) {
        u[1] = tj;
        u[2] = tj + 1;
    } else {
        u[1] = u[2] = u[3];
    }
}

/* Particle j (slot tj of the cell list, height yj, strip [gam, del],
 * K >= 1): the area in bands 1..K of the squares of S(P_j) that the sweep
 * at level K leaves out (sweep level csl > K: the squares cut by the line
 * z_K = hi_K, and those clipped by the ceiling), area min(t, hi_K) - b
 * times f2.  Each of them has positive area in band K (b < hi_K <= t or
 * the ceiling); *count is how many, with f2 > 0 as in add_square.  They
 * lie in hi_K - d/2 < y < hi_K + d/2 (with a margin for rounding), a
 * window about half as tall as band K with the squares that reach it.
 * j itself is skipped. */
static inline double cut_band(const bf_support *s, const bf_cells *c,
                              const stripq *q, uint32_t tj, double yj,
                              uint32_t *count)
{
    const double hd = s->hd, eps = 1e-12 * (fabs(q->hi) + hd);
    int c0 = bf_cells_col(c, q->gam - hd), c1 = bf_cells_col(c, q->del + hd);
    int r0 = bf_cells_row(c, q->hi - hd - eps),
        r1 = bf_cells_row(c, dmin(yj, q->hi + hd + eps));
    double acc = 0.0;
    uint64_t mask = 0; /* not used by a cut query */
    uint32_t cnt = 0;
    for (int col = c0; col <= c1; col++) {
        uint32_t u0, u1;
        bf_cells_run(c, col, r0, r1, &u0, &u1);
        if (tj >= u0 && tj < u1) {
            strip_range(s, c->sy, q, u0, tj, 1, &acc, &mask, &cnt);
            strip_range(s, c->sy, q, tj + 1, u1, 1, &acc, &mask, &cnt);
        } else {
            strip_range(s, c->sy, q, u0, u1, 1, &acc, &mask, &cnt);
        }
    }
    *count = cnt;
    return acc;
}

/* Is band K of particle j non-empty: a square of S(P_j) with positive area
 * in it (those cut by z_K are not enough when cut_band counted none: the
 * squares of sweep level K count too)?  Only asked when cut_band found
 * none, so rarely. */
static int band_filled(const bf_support *s, const bf_cells *c, const stripq *q,
                       uint32_t tj, double yj)
{
    const double hd = s->hd, eps = 1e-12 * (fabs(q->lo) + hd);
    int c0 = bf_cells_col(c, q->gam - hd), c1 = bf_cells_col(c, q->del + hd);
    int r0 = bf_cells_row(c, q->lo - hd - eps), r1 = bf_cells_row(c, yj);
    for (int col = c0; col <= c1; col++) {
        uint32_t u[4];
        run_without(c, col, r0, r1, tj, u);
        if (band_range(s, c->sy, q, u[0], u[1]) ||
            band_range(s, c->sy, q, u[2], u[3]))
            return 1;
    }
    return 0;
}

/* The square, strip and levels of the particle at sorted position k (slot
 * ord[k] of the cell list, positions sx, sy); returns its K. */
static inline int fast_setup(bf_support *s, const double *sx,
                             const double *sy, size_t k)
{
    const bf_support_params *p = &s->p;
    uint32_t i = s->ord[k];
    double xi = sx[i], yi = sy[i];
    s->ys[k] = yi;
    s->ls[k] = dmax(xi - s->hd, p->box.ax);
    s->rs[k] = dmin(xi + s->hd, p->box.bx);
    s->bs[k] = dmax(yi - s->hd, p->box.ay);
    s->ts[k] = dmin(yi + s->hd, p->box.by);
    s->gs[k] = dmax(xi - s->hdx, p->box.ax);
    s->ds[k] = dmin(xi + s->hdx, p->box.bx);
    int K = k_of(p, yi);
    s->ks[k] = K;
    s->mb[k] = first_band(s, s->bs[k]);
    s->mt[k] = full_level(s, s->ts[k]);
    s->sl[k] = yi + s->hd > p->box.by ? INT32_MAX : s->mt[k];
    s->lower[k] = 0.0;
    s->lowe[k] = INT32_MAX;
    return K;
}

/* The results of sorted position k into the order of the cell list. */
static inline void fast_to_slots(bf_support *s, size_t k)
{
    uint32_t t = s->ord[k];
    s->fgam[t] = s->lower[k];
    s->ks[t] = s->lowe[k];
    s->csl[t] = s->sl[k];
}

/* g of the particle in slot t: lower (the sweep) and lowe (the lowest
 * empty band) are in the order of the cell list. */
static inline void fast_one(const bf_support *s, const bf_cells *c,
                            const double *lower, const int32_t *lowe,
                            size_t t, double *g, uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    uint32_t j = c->idx[t];
    const double xj = c->sx[t], yj = c->sy[t];
    const int K = k_of(p, yj);
    uint8_t kd = BF_SUP_REST;
    double gj;
    if (resting(s, yj, K)) {
        gj = 0.0;
    } else if (K >= 2 && lowe[t] <= K - 1) {
        gj = -p->g0;
        kd = BF_SUP_FREE;
    } else {
        /* the K = 0 rectangle, or the squares that the sweep at level K
         * leaves out and the test of band K */
        double gam = dmax(xj - s->hdx, p->box.ax);
        double del = dmin(xj + s->hdx, p->box.bx);
        double area = 0.0;
        uint32_t cnt = 0;
        if (K == 0) {
            column_from_cells(s, c, j, yj, gam, del, 0, 0, 0, &area, &cnt);
        } else {
            const stripq q =
                stripq_of(gam, del, band_hi(s, K), band_lo(s, K),
                          p->tie ? yj : nextafter(yj, -INFINITY), K);
            area = cut_band(s, c, &q, (uint32_t)t, yj, &cnt);
            if (cnt == 0 && band_filled(s, c, &q, (uint32_t)t, yj))
                cnt = 1;
        }
        if (cnt == 0) {
            gj = -p->g0;
            kd = BF_SUP_FREE;
        } else {
            double tot = (K >= 1 ? lower[t] : 0.0) + area;
            double den = K == 0 ? (del - gam) * (yj - p->box.ay)
                                : (del - gam) * ((double)K * p->dx);
            gj = -p->g0 * (1.0 - tot / (den + p->eps));
            kd = gj > 0 ? BF_SUP_ANTI : BF_SUP_PARTIAL;
        }
    }
    g[j] = gj;
    if (kind)
        kind[j] = kd;
}

/* (The positions come from the cell list, which holds them in its order.) */
static void eval_fast(bf_support *s, size_t n, const bf_cells *c, double *g,
                      uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    const int nt = s->threads, pr = par(s, n);
    (void)nt;
    if (n == 0)
        return;
    /* the slots of the cell list in x order: the cell list is already
     * sorted by columns of cells, so the reads and writes through ord stay
     * within a column's block of slots (in the cache) */
    sort_by_x(s, c->sx, n);
    int kmax = 0;
    if (pr) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt) reduction(max : kmax)
        for (size_t k = 0; k < n; k++) {
            int K = fast_setup(s, c->sx, c->sy, k);
            kmax = K > kmax ? K : kmax;
        }
#endif
    } else {
        for (size_t k = 0; k < n; k++) {
            int K = fast_setup(s, c->sx, c->sy, k);
            kmax = K > kmax ? K : kmax;
        }
    }
    if (kmax >= 1) {
        /* the chunks are independent (each has its own tree), so they run
         * in parallel with results independent of the thread count */
        const double w = p->box.bx - p->box.ax, chunk = 8.0 * p->dx;
        long nch = (long)ceil(w / chunk);
        if (nch < 1)
            nch = 1;
        const size_t fsz = 2 * ((size_t)s->kmax + 3);
        if (pr) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
            for (long ch = 0; ch < nch; ch++)
                sweep_chunk(s, s->fen + (size_t)omp_get_thread_num() * fsz, n,
                            kmax, p->box.ax + (double)ch * chunk,
                            p->box.ax + (double)(ch + 1) * chunk,
                            ch == nch - 1);
#endif
        } else {
            for (long ch = 0; ch < nch; ch++)
                sweep_chunk(s, s->fen, n, kmax,
                            p->box.ax + (double)ch * chunk,
                            p->box.ax + (double)(ch + 1) * chunk,
                            ch == nch - 1);
        }
        if (kmax >= 2) /* bands 1..kmax - 1, below every top band */
            empty_bands(s, n, kmax - 1);
    }
    /* the sweep's results and the square edges in the order of the cell
     * list; then g in that order (neighbouring queries read neighbouring
     * cells) */
    slot_edges(s, c, n, 0);
    if (pr) {
#ifdef _OPENMP
#pragma omp parallel num_threads(nt)
        {
#pragma omp for schedule(static)
            for (size_t k = 0; k < n; k++)
                fast_to_slots(s, k);
#pragma omp for schedule(dynamic, 256)
            for (size_t t = 0; t < n; t++)
                fast_one(s, c, s->fgam, s->ks, t, g, kind);
        }
#endif
    } else {
        for (size_t k = 0; k < n; k++)
            fast_to_slots(s, k);
        for (size_t t = 0; t < n; t++)
            fast_one(s, c, s->fgam, s->ks, t, g, kind);
    }
}

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
        eval_fast(s, n, cells, g, kind);
        break;
    case BF_SUPPORT_CELL:
        eval_cell(s, x, y, n, cells, g, kind);
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
