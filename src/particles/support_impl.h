/* support_impl.h: the workspace of the support-set gravity and what its
 * three methods share (private to src/particles/support_*.c; see
 * support.h for the definitions and the methods).
 *
 *   support_setup.c parameters, workspace, the naive method and the
 *                   per-band sums of one particle (also the cell method's
 *                   fallback), the dispatch;
 *   support_cell.c  the cell method (one 64-bit mask of bands per square);
 *   support_fast.c  the fast method (the x order, the sweep, the cut
 *                   squares, g);
 *   support_gaps.c  its empty bands (the gaps between the squares of each
 *                   band).
 *
 * Every method decides "square i overlaps strip j in band q with positive
 * area" with the same two floating-point expressions,
 *   f2 = min(r_i, delta_j) - max(l_i, gamma_j) > 0,
 *   f1 = min(t_i, hi_q) - max(b_i, lo_q) > 0,
 * and the same band edges lo_q = ay + (q-1) dx, hi_q = ay + q dx, so the
 * free-fall decisions are identical; only the order of the area sums (and,
 * in the fast method, their form) differs, which changes g by round-off.
 */
#ifndef BALLFILM_PARTICLES_SUPPORT_IMPL_H
#define BALLFILM_PARTICLES_SUPPORT_IMPL_H

#include <stddef.h>
#include <stdint.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "particles/support.h"

/* Small kernels that must be inlined with constant arguments. */
#define HOT static inline __attribute__((always_inline))

struct bf_support {
    bf_support_params p;
    size_t cap;
    int kmax;        /* largest K of a particle in the box */
    double *bz;      /* [kmax + 3]: the band edges z_q (line_z) */
    int threads;     /* OpenMP threads */
    int exhaustive;  /* bf_support_set_exhaustive */
    double hd, hdx;  /* d/2, dx/2 */
    /* x-sorted order and geometry in that order (fast method) */
    uint32_t *ord, *binc; /* x order, bin counts */
    double *ls, *rs, *bs, *ts, *gs, *ds;
    uint32_t *qk;     /* the sorted positions that ask the sweep (x order) */
    int32_t *qK;      /* their K */
    double *qg, *qd;  /* their strip edges gamma, delta ([cap + 1]) */
    double *uv, *uh;  /* the sweep's updates in order: x, signed height */
    int32_t *ul;      /* and level (sweep_updates) */
    int32_t *ks, *mb, *mt; /* K; the first and last band with positive
                              height of the square (first_band, full_level) */
    int32_t *sl, *csl; /* sweep level: mt, or INT32_MAX for a square clipped
                          by the ceiling (never in the sweep); x order, cell
                          order */
    double *lower; /* area of the squares entirely below z_K (the sweep) */
    double *cl, *cr, *cb, *ct; /* square edges in cell-list order */
    uint64_t *bm;              /* bands 1..64 each square reaches */
    double *fgam;  /* F(gamma) while sweeping (by query) */
    int32_t *lowe; /* lowest empty band below the top band */
    uint32_t *nxt; /* skip list of particles without a lowest empty band */
    /* the sweep's prefix sums over levels (support_fast.c, fen_add): the
     * blocks of 2^t levels of depth t start at foff[t], as many depths as
     * kmax + 3 has bits; fsz doubles per thread */
    double *fen;
    size_t foff[34], fsz;
    /* the bands' gaps (bf_sup_empty_bands): per band the right edge of
     * its last square so far (gr, [kmax + 4]) and its number of gaps
     * (gcnt); per gap ([3 cap + kmax + 3]: a square reaches at most 3
     * bands, and each band has a last gap) its left end glo, the end p1 of
     * the strips that fit it (gp1), its band gq, and the gaps in order of
     * band (gord) */
    double *gr, *glo;
    uint32_t *gcnt, *gp1, *gord;
    int32_t *gq;
    /* the squares that the sweep at level m leaves out and that reach band
     * m, by line m and column of the cell list (support_fast.c,
     * cut_lists): the lines cmb..cme of each slot's square; per entry of a
     * bucket the slot (cutv), the square's edges l, r (cutl, cutr), its
     * height below z_m (cuth) and its centre's y (cuty); where the buckets
     * start (cutst).  Allocated on first use (their sizes depend on the
     * cell list) */
    int32_t *cmb, *cme;
    uint32_t *cutv, *cutst;
    double *cutl, *cutr, *cuth, *cuty;
    size_t cutv_cap, cutst_cap;
    /* per-band sums for one particle (naive and cell) */
    double *area;
    uint32_t *cnt;
};

/* The fast method's sweep runs in independent chunks of this many band
 * heights dx in x, from the left wall (support_fast.c); a query reads the
 * squares from the start of its chunk on (bf_support_reach). */
#define SUP_CHUNK_BANDS 8.0

/* ---------------------------------------------------------- geometry */

static inline double dmax(double a, double b) { return a > b ? a : b; }
static inline double dmin(double a, double b) { return a < b ? a : b; }

static inline double band_lo(const bf_support *s, int q)
{
    return s->bz[q - 1];
}

static inline double band_hi(const bf_support *s, int q) { return s->bz[q]; }

/* K(y) = floor((y - ay)/dx) >= 0, with the reciprocal of dx (one
 * definition for every method; at an exact band edge it may differ from a
 * division by one ulp's worth, which only moves the edge by round-off). */
static inline int k_of(const bf_support_params *p, double y)
{
    double k = (y - p->box.ay) * p->inv_dx;
    return k > 0 ? (int)k : 0;
}

/* Particle j is resting on the floor band. */
static inline int resting(const bf_support *s, double yj, int K)
{
    return K == 0 && yj - s->p.box.ay <= s->p.d;
}

/* --------------------------------------------- sorted searches */

/* First sorted position p in [lo, hi) with v[p] > key (or >= if ge). */
static inline size_t bsearch_pos(const double *v, size_t lo, size_t hi,
                                 double key, int ge)
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

/* The same answer as bsearch_pos(v, 0, n, key, ge), found by galloping
 * from `hint` (v is sorted): O(log distance) when the answer is near the
 * hint, as it is for the strips that fit a gap (support_gaps.c). */
static inline size_t gallop_pos(const double *v, size_t n, size_t hint,
                                double key, int ge)
{
#define PAST(p) (ge ? v[p] >= key : v[p] > key)
    if (hint > n)
        hint = n;
    size_t step = 1;
    if (hint > 0 && PAST(hint - 1)) {
        /* the answer is at or before hint - 1: gallop down */
        size_t hi = hint - 1; /* PAST(hi) */
        while (hi >= step && PAST(hi - step)) {
            hi -= step;
            step *= 2;
        }
        return bsearch_pos(v, hi >= step ? hi - step + 1 : 0, hi, key, ge);
    }
    /* the answer is at or after hint: gallop up */
    size_t lo = hint; /* !PAST(p) for every p < lo */
    while (lo + step - 1 < n && !PAST(lo + step - 1)) {
        lo += step;
        step *= 2;
    }
    return bsearch_pos(v, lo, lo + step - 1 < n ? lo + step - 1 : n, key, ge);
#undef PAST
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

/* ------------------------------------- the cell list, cell and fast */

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

/* ------------------------------------------ across the method files */

/* support_setup.c: the bands q0..K (or the K = 0 rectangle) of particle j from
 * the cell list, band q at index q - base; g of particle j from per-band
 * sums (the naive method with c == NULL, the cell method's fallback). */
void bf_sup_column(const bf_support *s, const bf_cells *c, size_t j,
                   double yj, double gam, double del, int K, int q0, int base,
                   double *area, uint32_t *cnt);
double bf_sup_one_particle(const bf_support *s, const bf_cells *c,
                           const double *x, const double *y, size_t n,
                           size_t j, double *area, uint32_t *cnt,
                           uint8_t *kind);

/* The lowest empty band of every strip (support_gaps.c, the fast
 * method): lowe[k] for sorted position k, the lowest band q <= mq in which
 * no square overlaps strip k with positive area, or a value > mq; nxt is
 * its scratch. */
void bf_sup_empty_bands(bf_support *s, size_t n, int mq);

/* support_cell.c: the square edges in cell-list order (and, with masks,
 * the bands 1..64 each reaches); the cell method. */
void bf_sup_slot_edges(bf_support *s, const bf_cells *c, size_t n,
                       int masks);
void bf_sup_eval_cell(bf_support *s, const double *x, const double *y,
                      size_t n, const bf_cells *c, double *g, uint8_t *kind);

/* support_fast.c: the fast method (positions from the cell list). */
void bf_sup_eval_fast(bf_support *s, size_t n, const bf_cells *c, double *g,
                      uint8_t *kind);

#endif
