/* repulsion.c: Greenspan 1972 eqs 2.11-2.12, the repulsion between
 * particles (see repulsion.h).  Every pair is visited once and both
 * accelerations are updated (the listing's ACX(J) += AM(I) TX,
 * ACX(I) -= AM(J) TX). */
#include "repulsion.h"

#include "particles/ipow.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define BF_REP_AVX512 1
#endif

/* Small kernels that must be inlined with constant arguments. */
#define HOT static inline __attribute__((always_inline))

/* Entries of room past the end of a list of neighbours (the AVX-512 copy
 * of neighbours writes up to 7 past it). */
enum { NB_PAD = 8 };

/* At most NRUN columns in a neighbourhood: reach <= NRUN - 1, i.e. cells
 * of at least cutoff / (NRUN - 1) (bf_repulsion_from_keys refuses smaller
 * ones; bf_repulsion_cells falls back to all pairs). */
enum { NRUN = 16 };

static const bf_param repulsion_params[] = {
    {"alpha", BF_AT(bf_repulsion_keys, alpha, BF_REAL), "1", "1",
     "strength alpha of eqs 2.11-2.12", BF_NONNEG, 0, 0, NULL},
    {"xi", BF_AT(bf_repulsion_keys, xi, BF_REAL), "cm", "0",
     "xi: added to the distance (how close centres may come)", BF_NONNEG, 0,
     0, NULL},
    {"p", BF_AT(bf_repulsion_keys, p, BF_INT), "1", "2",
     "exponent p of (r + xi)^p", BF_MIN | BF_MAX, 0, 30, NULL},
    {"beta", BF_AT(bf_repulsion_keys, beta, BF_INT), "1", "5",
     "exponent beta of ((r + xi)/d)^beta, applied only for r < d",
     BF_MIN | BF_MAX, 0, 30, NULL},
    {"cutoff", BF_AT(bf_repulsion_keys, cutoff, BF_REAL), "cm", "0",
     "only pairs with r < cutoff interact (Example 2: 2d = 10); 0: all pairs",
     BF_NONNEG, 0, 0, NULL},
    {"method", BF_AT(bf_repulsion_keys, method, BF_ENUM), "", "auto",
     "cells: cell list (needs a cutoff); pairs: all pairs; auto: cells when "
     "there is a cutoff",
     0, 0, 0, "auto|cells|pairs"},
    {"cell", BF_AT(bf_repulsion_keys, cell, BF_REAL), "cm", "0",
     "side of the cell-list cells (0: the cutoff); smaller cells test "
     "fewer pairs but visit more cells",
     BF_NONNEG | BF_HIDDEN, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_repulsion_spec = BF_SECTION(
    "repulsion", "repulsion between particles (Greenspan 1972 eqs 2.10-2.12)",
    repulsion_params, bf_repulsion_keys);

bf_status bf_repulsion_from_keys(bf_repulsion *r, const bf_repulsion_keys *k,
                                 double d, bf_err *err)
{
    r->alpha = k->alpha;
    r->xi = k->xi;
    r->p = (int)k->p;
    r->beta = (int)k->beta;
    r->cutoff = k->cutoff;
    r->cell = k->cell;
    r->d = d;
    r->inv_d = 1.0 / d;
    int m = k->method;
    r->use_cells = m == BF_REPULSION_CELLS ||
                   (m == BF_REPULSION_AUTO && r->cutoff > 0);
    if (r->use_cells && !(r->cutoff > 0))
        return bf_fail_key(err, BF_EINPUT, "repulsion", "method",
                           "the cell list needs a cutoff > 0");
    if (r->cell > 0 && r->cutoff > 0 && r->cell > r->cutoff)
        return bf_fail_key(err, BF_EINPUT, "repulsion", "cell",
                           "cell side %g is above the cutoff %g", r->cell,
                           r->cutoff);
    if (r->cell > 0 && r->cell * (NRUN - 1) < r->cutoff)
        return bf_fail_key(err, BF_EINPUT, "repulsion", "cell",
                           "cell side %g is below cutoff/%d (the search "
                           "reaches at most %d cells)",
                           r->cell, NRUN - 1, NRUN - 1);
    return BF_OK;
}

/* The force law with its constants in locals: the stores to the
 * accelerations (double *) could otherwise alias the struct's doubles and
 * force a reload of every constant for every pair. */
typedef struct law {
    double alpha, xi, d, inv_d;
    int p, beta;
} law;

/* D(r) for r^2 = r2: D (s/d)^beta for r < d, else D, written as
 * arithmetic: (double)(r < d) is 0 or 1, so in B + (1 - in) is exactly B
 * or 1 (B is finite), which is what the SSE2 path selects with a mask.
 * p and beta are constants in the specialised copies of law_factors. */
static inline double law_D(const law *L, double r2, int p, int beta)
{
    double d = sqrt(r2);
    double s = d + L->xi;
    double D = bf_ipow(s, p), B = bf_ipow(s * L->inv_d, beta);
    double in = (double)(d < L->d);
    return D * (in * B + (1.0 - in));
}

/* alpha / D(r), or -1 if D = 0. */
static inline double law_factor(const law *L, double r2)
{
    double D = law_D(L, r2, L->p, L->beta);
    return D > 0 ? L->alpha / D : -1.0;
}

int bf_repulsion_all_pairs(const bf_repulsion *r, const double *x,
                           const double *y, const double *m, size_t n,
                           double *ax, double *ay, size_t *bi, size_t *bj)
{
    const law L = {r->alpha, r->xi, r->d, r->inv_d, r->p, r->beta};
    const double rc2 = r->cutoff > 0 ? r->cutoff * r->cutoff : INFINITY;
    memset(ax, 0, n * sizeof *ax);
    memset(ay, 0, n * sizeof *ay);
    for (size_t j = 0; j < n; j++)
        for (size_t i = j + 1; i < n; i++) {
            double dx = x[j] - x[i], dy = y[j] - y[i];
            double r2 = dx * dx + dy * dy;
            if (!(r2 < rc2))
                continue;
            double f = law_factor(&L, r2);
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

static int have_avx512(void);

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
    w->wide = have_avx512();
    w->sa = malloc(2 * k * sizeof *w->sa);
    w->r2 = malloc(nt * (k + NB_PAD) * sizeof *w->r2);
    w->nb = malloc(nt * (k + NB_PAD) * sizeof *w->nb);
    w->bat = malloc(nt * 2 * (k + 1) * sizeof *w->bat);
    if (!w->sa || !w->r2 || !w->nb || !w->bat) {
        bf_repulsion_work_free(w);
        return bf_fail(err, BF_EINTERNAL, "out of memory (repulsion)");
    }
    return BF_OK;
}

void bf_repulsion_work_free(bf_repulsion_work *w)
{
    free(w->sa);
    free(w->r2);
    free(w->nb);
    free(w->bat);
    w->sa = w->r2 = NULL;
    w->nb = w->bat = NULL;
}

#if defined(__SSE2__)
/* bf_ipow on two lanes, with the same multiplications in the same order
 * (so the same bits); e is a constant where it is inlined. */
HOT __m128d ipow_pd(__m128d b, int e)
{
    switch (e) {
    case 0:
        return _mm_set1_pd(1.0);
    case 1:
        return b;
    case 2:
        return _mm_mul_pd(b, b);
    case 3:
        return _mm_mul_pd(_mm_mul_pd(b, b), b);
    case 4: {
        __m128d b2 = _mm_mul_pd(b, b);
        return _mm_mul_pd(b2, b2);
    }
    case 5: {
        __m128d b2 = _mm_mul_pd(b, b);
        return _mm_mul_pd(_mm_mul_pd(b2, b2), b);
    }
    default: {
        __m128d r = _mm_set1_pd(1.0);
        while (e) {
            if (e & 1)
                r = _mm_mul_pd(r, b);
            b = _mm_mul_pd(b, b);
            e >>= 1;
        }
        return r;
    }
    }
}
#endif

/* law_factors with the exponents p, beta (constants where inlined).  With
 * SSE2 two pairs at a time: sqrt, +, *, / are the same IEEE operations and
 * the select of B or 1 gives what in B + (1 - in) gives, so the same bits
 * as law_D. */
HOT int law_factors_pb(const law *L, double *restrict v, size_t m, int p,
                       int beta)
{
    int zero = 0;
    size_t k = 0;
#if defined(__SSE2__)
    const __m128d XI = _mm_set1_pd(L->xi), ID = _mm_set1_pd(L->inv_d),
                  DD = _mm_set1_pd(L->d), A = _mm_set1_pd(L->alpha),
                  ONE = _mm_set1_pd(1.0), Z = _mm_setzero_pd();
    for (; k < m; k += 2) {
        /* a last odd one in lane 0 (lane 1 computes on 0 and is dropped):
         * no scalar tail, whose branches would mispredict */
        const int two = k + 2 <= m;
        __m128d r2 = two ? _mm_loadu_pd(v + k) : _mm_load_sd(v + k);
        __m128d d = _mm_sqrt_pd(r2);
        __m128d s = _mm_add_pd(d, XI);
        __m128d D = ipow_pd(s, p), B = ipow_pd(_mm_mul_pd(s, ID), beta);
        __m128d in = _mm_cmplt_pd(d, DD);
        D = _mm_mul_pd(D, _mm_or_pd(_mm_and_pd(in, B), _mm_andnot_pd(in, ONE)));
        __m128d f = _mm_div_pd(A, D);
        zero |= _mm_movemask_pd(_mm_cmpngt_pd(D, Z)) & (two ? 3 : 1);
        if (two)
            _mm_storeu_pd(v + k, f);
        else
            _mm_store_sd(v + k, f);
    }
#endif
    for (; k < m; k++) {
        double D = law_D(L, v[k], p, beta);
        zero |= !(D > 0);
        v[k] = L->alpha / D;
    }
    return zero != 0;
}

/* v[k] = alpha / D for the m squared distances v[k], in place; returns 1
 * if some D = 0 (their v[k] are not finite).  The exponent pairs of
 * Greenspan's examples (Example 1: p = 2, beta = 5; Example 2: p = 2,
 * beta = 2) get copies in which the powers are a few multiplications
 * without a switch. */
static int law_factors(const law *L, double *restrict v, size_t m)
{
    if (L->p == 2 && L->beta == 2)
        return law_factors_pb(L, v, m, 2, 2);
    if (L->p == 2 && L->beta == 5)
        return law_factors_pb(L, v, m, 2, 5);
    return law_factors_pb(L, v, m, L->p, L->beta);
}

/* The particles t in the slot runs [t0[k], t1[k]) within the cutoff of the
 * particle at (xs, ys): their slots in nb and squared distances in r2;
 * returns their number.  Branch-free: about half of the candidates are
 * beyond the cutoff, at random, which a branch would mispredict. */
static size_t neighbours(const double *restrict sx, const double *restrict sy,
                         double xs, double ys, double rc2, const uint32_t *t0,
                         const uint32_t *t1, int nrun, uint32_t *restrict nb,
                         double *restrict r2)
{
    size_t m = 0;
#if defined(__SSE2__)
    const __m128d XS = _mm_set1_pd(xs), YS = _mm_set1_pd(ys),
                  RC = _mm_set1_pd(rc2);
#endif
    for (int k = 0; k < nrun; k++) {
        const uint32_t e = t1[k];
        uint32_t t = t0[k];
#if defined(__SSE2__)
        /* two candidates at a time (the same operations, so the same r2) */
        for (; t + 2 <= e; t += 2) {
            __m128d dx = _mm_sub_pd(XS, _mm_loadu_pd(sx + t)),
                    dy = _mm_sub_pd(YS, _mm_loadu_pd(sy + t));
            __m128d q = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
            const int in = _mm_movemask_pd(_mm_cmplt_pd(q, RC));
            nb[m] = t;
            _mm_storel_pd(r2 + m, q);
            m += (size_t)(in & 1);
            nb[m] = t + 1;
            _mm_storeh_pd(r2 + m, q);
            m += (size_t)(in >> 1);
        }
#endif
        for (; t < e; t++) {
            double dx = xs - sx[t], dy = ys - sy[t];
            double q = dx * dx + dy * dy;
            nb[m] = t;
            r2[m] = q;
            m += q < rc2;
        }
    }
    return m;
}

/* Particle s (at xs, ys, mass ws) and its m neighbours nb with the factors
 * f: both accelerations of each pair, in the order of the list, into sa
 * (x and y of slot t at 2t, 2t + 1).  With SSE2 the x and y components
 * share one register: the same operations per component, in the same
 * order, so the same bits. */
static void pair_forces(const double *restrict sx, const double *restrict sy,
                        const double *restrict sw, uint32_t s, double xs,
                        double ys, double ws, const uint32_t *restrict nb,
                        const double *restrict f, size_t m,
                        double *restrict sa)
{
#if defined(__SSE2__)
    const __m128d P = _mm_set_pd(ys, xs), W = _mm_set1_pd(ws);
    __m128d acc = _mm_setzero_pd();
    for (size_t k = 0; k < m; k++) {
        const uint32_t t = nb[k];
        __m128d q = _mm_loadh_pd(_mm_load_sd(sx + t), sy + t);
        __m128d txy = _mm_mul_pd(_mm_sub_pd(P, q), _mm_set1_pd(f[k]));
        acc = _mm_add_pd(acc, _mm_mul_pd(_mm_set1_pd(sw[t]), txy));
        double *at = sa + 2 * (size_t)t;
        _mm_storeu_pd(at, _mm_sub_pd(_mm_loadu_pd(at), _mm_mul_pd(W, txy)));
    }
    double *as = sa + 2 * (size_t)s;
    _mm_storeu_pd(as, _mm_add_pd(_mm_loadu_pd(as), acc));
#else
    double axs = 0, ays = 0;
    for (size_t k = 0; k < m; k++) {
        const uint32_t t = nb[k];
        double tx = (xs - sx[t]) * f[k], ty = (ys - sy[t]) * f[k];
        axs += sw[t] * tx;
        ays += sw[t] * ty;
        sa[2 * (size_t)t] -= ws * tx;
        sa[2 * (size_t)t + 1] -= ws * ty;
    }
    sa[2 * (size_t)s] += axs;
    sa[2 * (size_t)s + 1] += ays;
#endif
}

#if defined(BF_REP_AVX512)
/* AVX-512 copies of neighbours and law_factors (eight lanes instead of
 * two), chosen at run time on processors that have AVX-512F and VL.  Each
 * lane does the same IEEE operations in the same order as the scalar and
 * SSE2 code (no fused multiply-adds: the intrinsics name every operation),
 * and the compress stores keep the candidates in their order, so the
 * lists, the factors and the sums are the same bits. */
#define AVX512 __attribute__((target("avx512f,avx512vl")))

AVX512 static inline __m512d ipow_512(__m512d b, int e)
{
    switch (e) {
    case 0:
        return _mm512_set1_pd(1.0);
    case 1:
        return b;
    case 2:
        return _mm512_mul_pd(b, b);
    case 3:
        return _mm512_mul_pd(_mm512_mul_pd(b, b), b);
    case 4: {
        __m512d b2 = _mm512_mul_pd(b, b);
        return _mm512_mul_pd(b2, b2);
    }
    case 5: {
        __m512d b2 = _mm512_mul_pd(b, b);
        return _mm512_mul_pd(_mm512_mul_pd(b2, b2), b);
    }
    default: {
        __m512d r = _mm512_set1_pd(1.0);
        while (e) {
            if (e & 1)
                r = _mm512_mul_pd(r, b);
            b = _mm512_mul_pd(b, b);
            e >>= 1;
        }
        return r;
    }
    }
}

/* law_factors_pb, eight pairs at a time; the lanes past m compute on 0
 * and are neither stored nor tested. */
AVX512 static inline int law_factors_512_pb(const law *L, double *restrict v,
                                            size_t m, int p, int beta)
{
    const __m512d XI = _mm512_set1_pd(L->xi), ID = _mm512_set1_pd(L->inv_d),
                  DD = _mm512_set1_pd(L->d), A = _mm512_set1_pd(L->alpha),
                  ONE = _mm512_set1_pd(1.0), Z = _mm512_setzero_pd();
    __mmask8 zero = 0;
    for (size_t k = 0; k < m; k += 8) {
        const __mmask8 lanes =
            m - k >= 8 ? (__mmask8)0xff : (__mmask8)((1u << (m - k)) - 1u);
        __m512d r2 = _mm512_maskz_loadu_pd(lanes, v + k);
        __m512d d = _mm512_sqrt_pd(r2);
        __m512d s = _mm512_add_pd(d, XI);
        __m512d D = ipow_512(s, p), B = ipow_512(_mm512_mul_pd(s, ID), beta);
        const __mmask8 in = _mm512_cmp_pd_mask(d, DD, _CMP_LT_OQ);
        D = _mm512_mul_pd(D, _mm512_mask_blend_pd(in, ONE, B));
        __m512d f = _mm512_div_pd(A, D);
        zero |= _mm512_mask_cmp_pd_mask(lanes, D, Z, _CMP_NGT_UQ);
        _mm512_mask_storeu_pd(v + k, lanes, f);
    }
    return zero != 0;
}

AVX512 static int law_factors_512(const law *L, double *restrict v, size_t m)
{
    if (L->p == 2 && L->beta == 2)
        return law_factors_512_pb(L, v, m, 2, 2);
    if (L->p == 2 && L->beta == 5)
        return law_factors_512_pb(L, v, m, 2, 5);
    return law_factors_512_pb(L, v, m, L->p, L->beta);
}

/* neighbours, eight candidates at a time. */
AVX512 static size_t neighbours_512(const double *restrict sx,
                                    const double *restrict sy, double xs,
                                    double ys, double rc2, const uint32_t *t0,
                                    const uint32_t *t1, int nrun,
                                    uint32_t *restrict nb,
                                    double *restrict r2)
{
    size_t m = 0;
    const __m512d XS = _mm512_set1_pd(xs), YS = _mm512_set1_pd(ys),
                  RC = _mm512_set1_pd(rc2);
    const __m512i STEP = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
    for (int k = 0; k < nrun; k++) {
        const uint32_t e = t1[k];
        for (uint32_t t = t0[k]; t < e; t += 8) {
            const __mmask8 lanes = e - t >= 8
                                       ? (__mmask8)0xff
                                       : (__mmask8)((1u << (e - t)) - 1u);
            __m512d dx = _mm512_sub_pd(XS, _mm512_maskz_loadu_pd(lanes, sx + t)),
                    dy = _mm512_sub_pd(YS, _mm512_maskz_loadu_pd(lanes, sy + t));
            __m512d q = _mm512_add_pd(_mm512_mul_pd(dx, dx),
                                      _mm512_mul_pd(dy, dy));
            const __mmask8 in =
                _mm512_mask_cmp_pd_mask(lanes, q, RC, _CMP_LT_OQ);
            const unsigned cnt = (unsigned)__builtin_popcount((unsigned)in);
            /* compressed in registers and stored whole (a compressing
             * store to memory is slow on some processors): up to 7
             * entries past the list are written, which the buffers have
             * room for (NB_PAD) */
            _mm512_storeu_pd(r2 + m, _mm512_maskz_compress_pd(in, q));
            __m256i idx = _mm512_cvtepi64_epi32(
                _mm512_add_epi64(_mm512_set1_epi64((long long)t), STEP));
            _mm256_storeu_si256((__m256i *)(void *)(nb + m),
                                _mm256_maskz_compress_epi32(in, idx));
            m += cnt;
        }
    }
    return m;
}
#endif

/* 1 if the AVX-512 copies can run here. */
static int have_avx512(void)
{
#if defined(BF_REP_AVX512)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512vl");
#else
    return 0;
#endif
}

/* The pairs of a batch of particles: the factors of all their pairs in
 * one loop (so that the square roots and divisions of many particles
 * overlap: one particle has only a few neighbours), then, particle by
 * particle in their order, both accelerations of each pair.  bat[2b] is
 * the slot of the batch's particle b, bat[2b + 1] where its pairs start
 * in nb and f (bat[2 nbat + 1] = m, their end).  A coincident pair (law
 * D = 0) gets factor 0; the first in the order of the pairs is reported
 * through bad. */
static void batch_forces(const law *L, const double *restrict sx,
                         const double *restrict sy, const double *restrict sw,
                         const uint32_t *restrict bat, size_t nbat,
                         const uint32_t *restrict nb, double *restrict f,
                         size_t m, int wide, double *restrict sa,
                         uint32_t bad[2], int *found)
{
    int zero;
#if defined(BF_REP_AVX512)
    if (wide)
        zero = law_factors_512(L, f, m);
    else
#endif
        zero = law_factors(L, f, m);
    (void)wide;
    for (size_t b = 0; b < nbat; b++) {
        const uint32_t s = bat[2 * b], k0 = bat[2 * b + 1],
                       k1 = bat[2 * b + 3];
        const double xs = sx[s], ys = sy[s];
        if (zero)
            /* rare (r = 0 with xi = 0): which pairs */
            for (uint32_t k = k0; k < k1; k++) {
                const uint32_t t = nb[k];
                double dx = xs - sx[t], dy = ys - sy[t];
                if (law_D(L, dx * dx + dy * dy, L->p, L->beta) > 0)
                    continue;
                if (!*found) {
                    *found = 1;
                    bad[0] = s;
                    bad[1] = t;
                }
                f[k] = 0.0;
            }
        pair_forces(sx, sy, sw, s, xs, ys, sw[s], nb + k0, f + k0, k1 - k0,
                    sa);
    }
}

/* Columns [x0, x1) of the cell list; the first coincident pair found is
 * reported through bad (slots).  For each particle s, in slot order: the
 * neighbours in half of its neighbourhood (its own column: the slots after
 * s up to row cy + reach; the columns to the right: rows cy - reach ..
 * cy + reach); the particles of a column of cells are one batch
 * (batch_forces), cut where their lists would not fit in the cap entries
 * of nb and f.  The sums run in the order of one loop over the pairs, as
 * if each particle's pairs were done before the next one's: a pair's
 * factor depends on its distance only. */
static void cols_pairs(const bf_repulsion *r, const bf_cells *c, int reach,
                       int x0, int x1, double *restrict f,
                       uint32_t *restrict nb, uint32_t *restrict bat,
                       size_t cap, double *restrict sa, uint32_t bad[2],
                       int *found, int wide)
{
    const law L = {r->alpha, r->xi, r->d, r->inv_d, r->p, r->beta};
    const double rc2 = r->cutoff * r->cutoff;
    const int nx = c->nx, ny = c->ny;
    const double *restrict sx = c->sx, *restrict sy = c->sy,
                           *restrict sw = c->sw;
    uint32_t t0[NRUN], t1[NRUN];
    for (int cx = x0; cx < x1; cx++) {
        const int nrun = cx + reach < nx ? reach + 1 : nx - cx;
        size_t m = 0, nbat = 0;
        for (int cy = 0; cy < ny; cy++) {
            uint32_t a0, a1;
            bf_cells_run(c, cx, cy, cy, &a0, &a1);
            if (a0 == a1)
                continue;
            const int ylo = cy - reach < 0 ? 0 : cy - reach,
                      yhi = cy + reach >= ny ? ny - 1 : cy + reach;
            /* the same runs for every particle of the cell, but for the
             * start of the first (s + 1) */
            size_t others = 0; /* the candidates of the other columns */
            for (int ox = 0; ox < nrun; ox++) {
                bf_cells_run(c, cx + ox, ox == 0 ? cy : ylo, yhi, &t0[ox],
                             &t1[ox]);
                others += ox > 0 ? t1[ox] - t0[ox] : 0;
            }
            for (uint32_t s = a0; s < a1; s++) {
                t0[0] = s + 1;
                if (m + others + (t1[0] - t0[0]) > cap) {
                    bat[2 * nbat + 1] = (uint32_t)m;
                    batch_forces(&L, sx, sy, sw, bat, nbat, nb, f, m, wide,
                                 sa, bad, found);
                    m = nbat = 0;
                }
                bat[2 * nbat] = s;
                bat[2 * nbat + 1] = (uint32_t)m;
                nbat++;
#if defined(BF_REP_AVX512)
                if (wide)
                    m += neighbours_512(sx, sy, sx[s], sy[s], rc2, t0, t1,
                                        nrun, nb + m, f + m);
                else
#endif
                    m += neighbours(sx, sy, sx[s], sy[s], rc2, t0, t1, nrun,
                                    nb + m, f + m);
            }
        }
        if (nbat) {
            bat[2 * nbat + 1] = (uint32_t)m;
            batch_forces(&L, sx, sy, sw, bat, nbat, nb, f, m, wide, sa, bad,
                         found);
        }
    }
}

/* OpenMP only pays from a few thousand particles on, and only with more
 * than one thread; otherwise no parallel region is entered (libgomp
 * allocates a team for every region, even for one with if (0)). */
static inline int par(const bf_repulsion_work *w, size_t n)
{
    return w->threads > 1 && n >= 4096;
}

/* ax, ay in particle order from the sums in slot order. */
static void to_index_order(const bf_cells *c, const bf_repulsion_work *w,
                           double *ax, double *ay)
{
    const size_t n = c->n;
    if (par(w, n)) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(w->threads)
        for (size_t s = 0; s < n; s++) {
            ax[c->idx[s]] = w->sa[2 * s];
            ay[c->idx[s]] = w->sa[2 * s + 1];
        }
#endif
    } else {
        for (size_t s = 0; s < n; s++) {
            ax[c->idx[s]] = w->sa[2 * s];
            ay[c->idx[s]] = w->sa[2 * s + 1];
        }
    }
}

int bf_repulsion_cells(const bf_repulsion *r, const bf_cells *c,
                       bf_repulsion_work *w, double *ax, double *ay,
                       size_t *bi, size_t *bj)
{
    const int reach = (int)ceil(r->cutoff * c->inv_h * (1.0 - 1e-12));
    const size_t n = c->n;
    if (reach >= NRUN) {
        /* cells far below the cutoff (a direct call; scenes refuse them):
         * all pairs, in slot order */
        double *tx = w->sa, *ty = w->sa + n;
        if (bf_repulsion_all_pairs(r, c->sx, c->sy, c->sw, n, tx, ty, bi,
                                   bj)) {
            *bi = c->idx[*bi];
            *bj = c->idx[*bj];
            return 1;
        }
        for (size_t s = 0; s < n; s++) {
            ax[c->idx[s]] = tx[s];
            ay[c->idx[s]] = ty[s];
        }
        return 0;
    }
    const int nx = c->nx, width = reach + 1;
    const int nstripes = (nx + width - 1) / width;
    const int wide = w->wide;
    memset(w->sa, 0, 2 * n * sizeof *w->sa);
    /* the first coincident pair in stripe order (thread-count independent) */
    uint32_t bad[2] = {0, 0};
    int found = 0;
    if (par(w, n)) {
        for (int phase = 0; phase < 2; phase++) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(w->threads)
            for (int k = phase; k < nstripes; k += 2) {
                int tid = omp_get_thread_num();
                uint32_t b[2];
                int f = 0;
                int x1 = (k + 1) * width < nx ? (k + 1) * width : nx;
                cols_pairs(r, c, reach, k * width, x1,
                           w->r2 + (size_t)tid * (n + NB_PAD),
                           w->nb + (size_t)tid * (n + NB_PAD),
                           w->bat + (size_t)tid * 2 * (n + 1), n, w->sa, b,
                           &f, wide);
                if (f) {
#pragma omp critical(bf_repulsion_bad)
                    if (!found || b[0] < bad[0]) {
                        found = 1;
                        bad[0] = b[0];
                        bad[1] = b[1];
                    }
                }
            }
#endif
        }
    } else {
        /* the stripes in the same order as above: every stripe of a phase
         * writes only to itself and the next one */
        for (int phase = 0; phase < 2; phase++)
            for (int k = phase; k < nstripes; k += 2) {
                int x1 = (k + 1) * width < nx ? (k + 1) * width : nx;
                uint32_t b[2];
                int f = 0;
                cols_pairs(r, c, reach, k * width, x1, w->r2, w->nb, w->bat,
                           n, w->sa, b, &f, wide);
                if (f && (!found || b[0] < bad[0])) {
                    found = 1;
                    bad[0] = b[0];
                    bad[1] = b[1];
                }
            }
    }
    if (found) {
        *bi = c->idx[bad[0]];
        *bj = c->idx[bad[1]];
        return 1;
    }
    to_index_order(c, w, ax, ay);
    return 0;
}
