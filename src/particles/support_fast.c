/* support_fast.c: the fast method of the support-set gravity (see
 * support.h): the squares entirely below a particle's top band from one
 * sweep in x with a Fenwick tree over levels, the squares cut by that line
 * from lists of the squares each line cuts (by column of the cell list),
 * the empty bands from the gaps between x-sorted squares (support_impl.h).
 */
#ifdef _OPENMP
#include <omp.h>
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "particles/support_impl.h"

/* What first_band and full_level read, held by their caller (through the
 * workspace, every int32 store of the set-up loop might have changed
 * s->kmax and made the compiler load the fields again; the parameters are
 * doubles, which an int32 store cannot change). */
typedef struct band_edges {
    const bf_support_params *p; /* ay, 1/dx (k_of) */
    const double *bz;           /* z_q = bz[q] (band_hi) */
    int kcap;                   /* kmax + 1 */
} band_edges;

/* The lowest level m >= 1 whose line z_m = band_hi(m) is at or above t:
 * exact with respect to band_hi, so that "full below z_m" (the sweep) and
 * "cut by z_m" (t > z_m, the cell query) never disagree. */
HOT int full_level(const band_edges *e, double t)
{
    int m = k_of(e->p, t);
    if (m < 1)
        m = 1;
    while (m > 1 && e->bz[m - 1] >= t)
        m--;
    while (e->bz[m] < t)
        m++;
    return m;
}

/* The lowest band q >= 1 whose top z_q is above b: with full_level, a
 * square reaches (positive height, if t > b) exactly the bands
 * first_band(b) .. full_level(t). */
HOT int first_band(const band_edges *e, double b)
{
    int q = k_of(e->p, b) + 1;
    while (q > 1 && e->bz[q - 1] > b)
        q--;
    while (q <= e->kcap && !(e->bz[q] > b)) /* bounded for NaN */
        q++;
    return q;
}

/* ord[u0..u1) = the slots u0..u1-1 sorted by x[] (ties keep the slot
 * order): counting sort into m = u1 - u0 bins over [xlo, xlo + w) (any
 * binning monotone in x gives the same order), then insertion sort, which
 * moves elements only inside their bins.  Expected O(m). */
static void sort_range(bf_support *s, const double *x, uint32_t u0,
                       uint32_t u1, double xlo, double w)
{
    const size_t m = u1 - u0;
    const double scale = (double)m / w;
    uint32_t *binc = s->binc, *ord = s->ord + u0, *tmp = s->nxt;
    memset(binc, 0, (m + 1) * sizeof *binc);
    for (size_t i = 0; i < m; i++) {
        double f = (x[u0 + i] - xlo) * scale;
        size_t b = f > 0 ? (size_t)f : 0;
        if (b >= m)
            b = m - 1;
        tmp[i] = (uint32_t)b;
        binc[b + 1]++;
    }
    for (size_t b = 0; b < m; b++)
        binc[b + 1] += binc[b];
    for (size_t i = 0; i < m; i++)
        ord[binc[tmp[i]]++] = u0 + (uint32_t)i;
    /* ord is now sorted by bin, stably; one insertion sort over the whole
     * range puts each bin in order (an element never moves past the start
     * of its bin), the same stable order as sorting each bin alone, but
     * without a loop per bin whose length (mostly 0, 1 or 2) is
     * mispredicted at every bin: here the inner loop mostly does not run */
    for (size_t a = 1; a < m; a++) {
        const uint32_t v = ord[a];
        const double xv = x[v];
        size_t c = a;
        while (c > 0 && x[ord[c - 1]] > xv) {
            ord[c] = ord[c - 1];
            c--;
        }
        ord[c] = v;
    }
}

/* The slots of the cell list in x order.  The cell list holds the columns
 * of cells one after the other, and the column of a particle is monotone
 * in x, so the x order is the columns' own x orders one after the other:
 * each column is sorted alone, in bins that stay in the cache. */
static void sort_by_x(bf_support *s, const bf_cells *c)
{
    const size_t ny = (size_t)c->ny;
    for (int col = 0; col < c->nx; col++) {
        const uint32_t u0 = c->start[(size_t)col * ny],
                       u1 = c->start[(size_t)(col + 1) * ny];
        if (u1 > u0)
            sort_range(s, c->sx, u0, u1, c->x0 + (double)col * c->h, c->h);
    }
}

/* The sweep's two prefix sums over levels (A = sum h, B = sum h e of the
 * squares entered so far at each level), kept as a Fenwick tree laid out
 * by depth: block j of depth t holds the levels j 2^t + 1 .. (j + 1) 2^t
 * (at fen + 2 (foff[t] + j), A and B side by side).  An update of level L
 * adds to the block of depth t that holds L, for every depth t < depth; a
 * prefix sum over the levels 1..K adds, for every bit t set in K from the
 * lowest up, the block of depth t that ends at level (K >> t) 2^t.  These
 * are the nodes of a Fenwick tree (node k is block k / 2^t - 1 of depth t,
 * 2^t the lowest bit of k), visited in the Fenwick tree's order, and the
 * blocks that are not nodes of it (j + 1 even) are never read: the same
 * additions in the same order, so the same bits.  Unlike the Fenwick loops
 * (k += k & -k), whose trip counts change with every level, both loops run
 * `depth` times, the same number for every update and query of a chunk:
 * no mispredicted branches; a bit that is not set adds +0.0 (the sum
 * starts at +0.0 and is never -0.0, so adding +0.0 changes nothing).  With
 * SSE2 A and B share one register (the same additions). */
#if defined(__SSE2__)
/* The update with (a, b) in one register (lane 0: a). */
static inline void fen_add_v(const bf_support *s, double *fen, int depth,
                             int level, __m128d ab)
{
    const unsigned i = (unsigned)level - 1u;
    for (int t = 0; t < depth; t++) {
        double *nd = fen + 2 * (s->foff[t] + (i >> t));
        _mm_storeu_pd(nd, _mm_add_pd(_mm_loadu_pd(nd), ab));
    }
}
#endif

static inline void fen_add(const bf_support *s, double *fen, int depth,
                           int level, double a, double b)
{
#if defined(__SSE2__)
    fen_add_v(s, fen, depth, level, _mm_set_pd(b, a));
#else
    const unsigned i = (unsigned)level - 1u;
    for (int t = 0; t < depth; t++) {
        double *nd = fen + 2 * (s->foff[t] + (i >> t));
        nd[0] += a;
        nd[1] += b;
    }
#endif
}

/* The square at sorted position p, with its left (sigma = +1) or right
 * (sigma = -1) edge at local coordinate e, enters the sweep.  It counts
 * with its full height h at every level m whose line z_m = ay + m dx is at
 * or above its top (m >= sl[p]; a square clipped by the ceiling never
 * counts); squares cut by the line z_m are added by the cell-list query of
 * the particle asking (cut_band).  Levels above mq are never asked. */
static inline void sweep_add(const bf_support *s, double *fen, int depth,
                             int mq, size_t p, double sigma, double e)
{
    const int mt = s->sl[p];
    if (mt <= mq) {
        double h = sigma * (s->ts[p] - s->bs[p]);
        fen_add(s, fen, depth, mt, h, h * e);
    }
}

/* G(x) = x A - B over the levels 1..m (local coordinates). */
static inline double sweep_eval(const bf_support *s, const double *fen,
                                int depth, double x, int m)
{
    const unsigned P = (unsigned)m;
#if defined(__SSE2__)
    __m128d ab = _mm_setzero_pd();
    for (int t = 0; t < depth; t++) {
        const unsigned q = P >> t;
        const __m128d on =
            _mm_castsi128_pd(_mm_set1_epi64x(-(long long)(q & 1u)));
        ab = _mm_add_pd(ab, _mm_and_pd(on, _mm_loadu_pd(
                                               fen + 2 * (s->foff[t] +
                                                          (q & ~1u)))));
    }
    return x * _mm_cvtsd_f64(ab) - _mm_cvtsd_f64(_mm_unpackhi_pd(ab, ab));
#else
    double a = 0, b = 0;
    for (int t = 0; t < depth; t++) {
        const unsigned q = P >> t;
        if (q & 1u) {
            const double *nd = fen + 2 * (s->foff[t] + q - 1u);
            a += nd[0];
            b += nd[1];
        }
    }
    return x * a - b;
#endif
}

/* The square edges as one sequence of updates of the sweep, in the order
 * in which the sweep meets them: the left edges (+h) and right edges (-h)
 * merged by x, a left edge first on ties (the order of the sums in every
 * chunk).  Squares clipped by the ceiling never enter (sweep level
 * INT32_MAX).  Returns their number; uv[nu] = +inf ends the sequence.
 * Which stream comes next is random, so the merge must not branch on it:
 * gcc turns the selects of the scalar code into a branch, and the SSE2
 * code selects with masks (+h or -h: the sign flipped, as the product with
 * -1.0).  In either, a ceiling square's entry is written and then written
 * over by the next. */
static size_t sweep_updates(bf_support *s, size_t n)
{
    const double *ls = s->ls, *rs = s->rs, *ts = s->ts, *bs = s->bs;
    const int32_t *sl = s->sl;
    double *uv = s->uv, *uh = s->uh;
    int32_t *ul = s->ul;
    size_t a = 0, b = 0, u = 0;
#if defined(__SSE2__)
    const __m128d SIGN = _mm_set_sd(-0.0), INF = _mm_set_sd(INFINITY);
    while (b < n) {
        const __m128d la = a < n ? _mm_load_sd(ls + a) : INF,
                      rb = _mm_load_sd(rs + b);
        const __m128d left = _mm_cmple_sd(la, rb);
        const size_t l = (size_t)(_mm_movemask_pd(left) & 1);
        const size_t p = b ^ ((a ^ b) & (0 - l));
        _mm_store_sd(uv + u, _mm_or_pd(_mm_and_pd(left, la),
                                       _mm_andnot_pd(left, rb)));
        _mm_store_sd(uh + u, _mm_xor_pd(_mm_sub_sd(_mm_load_sd(ts + p),
                                                   _mm_load_sd(bs + p)),
                                        _mm_andnot_pd(left, SIGN)));
        ul[u] = sl[p];
        u += sl[p] != INT32_MAX;
        a += l;
        b += 1 - l;
    }
#else
    while (b < n) {
        const int left = a < n && ls[a] <= rs[b];
        const size_t p = left ? a : b;
        uv[u] = left ? ls[a] : rs[b];
        uh[u] = (left ? 1.0 : -1.0) * (ts[p] - bs[p]);
        ul[u] = sl[p];
        u += sl[p] != INT32_MAX;
        a += (size_t)left;
        b += (size_t)!left;
    }
#endif
    uv[u] = INFINITY; /* with a level and a height that sweep_chunk reads */
    uh[u] = 0.0;
    ul[u] = 1;
    return u;
}

/* Lower-band areas of the asking particles (the query list qk, with their
 * strip edges qg, qd, in x order) whose strips start in the chunk
 * [X0, X1): a sweep over the square edges in (X0, X1 + dx], in coordinates
 * relative to X0 so that the sums stay small (their round-off does not
 * grow with the box).  Squares straddling X0 enter with their left edge at
 * X0: G(x) = integral from X0 to x of the filled height.  Each query at x
 * sees the updates at or before x, in the order of sweep_updates.  The
 * tree keeps only the depths that the highest K asked in the chunk reads,
 * and only squares of levels up to that K enter at X0: a block it does
 * not read may hold anything, and every block it reads gets the same
 * additions in the same order as in a taller tree, so the areas are the
 * same bits.  qd[i] is replaced by F(delta_i) once read. */
static void sweep_chunk(bf_support *s, double *fen, size_t n, size_t nu,
                        size_t nq, double X0, double X1, int last)
{
    const double *ls = s->ls, *rs = s->rs, *qg = s->qg;
    const double *uv = s->uv, *uh = s->uh;
    const int32_t *ul = s->ul;
    double *qd = s->qd, *fg = s->fgam;
    const uint32_t *qk = s->qk;
    const int32_t *qK = s->qK;
    size_t q0 = bsearch_pos(qg, 0, nq, X0, 1);
    size_t q1 = last ? nq : bsearch_pos(qg, q0, nq, X1, 1);
    if (q0 == q1)
        return;
    int mq = s->exhaustive ? s->kmax + 1 : 1;
    for (size_t i = q0; i < q1; i++)
        mq = qK[i] > mq ? qK[i] : mq;
    /* the depths that a query of a level <= mq reads (its highest bit);
     * updates of higher levels go into blocks that no query reads */
    int depth = 1;
    while ((mq >> depth) > 0)
        depth++;
    memset(fen, 0, 2 * s->foff[depth] * sizeof *fen);
    /* squares with l <= X0 < r enter at X0 */
    size_t pr = bsearch_pos(rs, 0, n, X0, 0);
    size_t pl = bsearch_pos(ls, 0, n, X0, 0);
    for (size_t p = pr; p < pl; p++)
        sweep_add(s, fen, depth, mq, p, 1.0, 0.0);
    /* then the edges beyond X0 */
    size_t u = bsearch_pos(uv, 0, nu, X0, 0);
    size_t pg = q0, pd = q0;
    while (pd < q1) {
        /* the next query: gamma of pg or delta of pd (gamma first on
         * ties; the order of the reads does not matter).  Which one is
         * random: selected with masks (with SSE2; gcc makes a branch of
         * the scalar selects) */
#if defined(__SSE2__)
        const __m128d g = _mm_load_sd(qg + pg), dd = _mm_load_sd(qd + pd);
        const size_t isg = (size_t)(_mm_movemask_pd(_mm_cmple_sd(g, dd)) &
                                    (pg < q1)); /* qg[nq] exists */
        const __m128d m = _mm_castsi128_pd(_mm_set1_epi64x(-(long long)isg));
        const double v = _mm_cvtsd_f64(
            _mm_or_pd(_mm_and_pd(m, g), _mm_andnot_pd(m, dd)));
        const uintptr_t og = (uintptr_t)(fg + pg), od = (uintptr_t)(qd + pd);
        double *dst = (double *)(od ^ ((og ^ od) & (0 - (uintptr_t)isg)));
#else
        const size_t isg = (pg < q1) & (qg[pg] <= qd[pd]);
        const double v = isg ? qg[pg] : qd[pd];
        double *dst = isg ? fg + pg : qd + pd;
#endif
        const size_t i = pd ^ ((pg ^ pd) & (0 - isg));
#if defined(__SSE2__)
        /* the first update before the query, taken or not without a
         * branch (a query is preceded by 0, 1, 2 ... updates at random;
         * most by at most one): not taken, it adds +0.0 to the blocks of
         * the next update's level, which changes none of them (a block's
         * sum starts at +0.0 and is never -0.0) */
        {
            const __m128d e = _mm_load_sd(uv + u);
            const __m128d mk = _mm_cmple_sd(e, _mm_set_sd(v));
            const size_t take = (size_t)(_mm_movemask_pd(mk) & 1);
            const __m128d h = _mm_and_pd(mk, _mm_load_sd(uh + u)),
                          x = _mm_and_pd(mk, _mm_sub_sd(e, _mm_set_sd(X0)));
            fen_add_v(s, fen, depth, ul[u],
                      _mm_unpacklo_pd(h, _mm_mul_sd(h, x)));
            u += take;
        }
#endif
        for (; uv[u] <= v; u++)
            fen_add(s, fen, depth, ul[u], uh[u], uh[u] * (uv[u] - X0));
        *dst = sweep_eval(s, fen, depth, v - X0, qK[i]);
        pg += isg;
        pd += 1 - isg;
    }
    for (size_t i = q0; i < q1; i++)
        s->lower[qk[i]] = qd[i] - fg[i];
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

/* Grows *v to hold `want` elements of `size` bytes (*v keeps its size
 * if that fails). */
static int grow(void **v, size_t want, size_t size)
{
    void *w = realloc(*v, want * size);
    if (!w)
        return 0;
    *v = w;
    return 1;
}

/* The squares that cut_band adds for particles of top band m, listed once
 * per line m = 1..kmax: those with csl > m and min(t, z_m) - b > 0, that
 * is, b < z_m < t (the lines first_band(b) .. csl - 1), or, clipped by the
 * ceiling (csl = INT32_MAX) with t > b, z_m > b (the lines from
 * first_band(b) on): the lines cmb[u] .. cme[u] of slot u (fast_to_slots).
 * Bucket (m, col) = (m - 1) nx + col holds those of column col of the
 * cell list in slot order, so that the buckets of line m in the columns
 * c0..c1 are one run of entries in slot order: the order in which
 * cut_band adds them (its window holds all of them: the rows from
 * hi_m - d/2 to min(y_j, hi_m + d/2) with a margin far above round-off,
 * and the same columns c0..c1).  A query reads only the squares that its
 * line cuts in those columns, not every square of the window's cells, and
 * reads them from one run of memory: each entry holds what the query
 * needs, the height min(t, z_m) - b below the line already formed (the
 * same expression cut_band forms).  Returns 0 if out of memory (cut_band
 * is used instead). */
static int cut_lists(bf_support *s, const bf_cells *c)
{
    const int L = s->kmax, nx = c->nx;
    const size_t ny = (size_t)c->ny, nb = (size_t)L * (size_t)nx;
    if (L < 1)
        return 0;
    if (nb + 2 > s->cutst_cap) {
        if (!grow((void **)&s->cutst, nb + 2, sizeof *s->cutst))
            return 0;
        s->cutst_cap = nb + 2;
    }
    uint32_t *st = s->cutst;
    const int32_t *cmb = s->cmb, *cme = s->cme;
    const double *cl = s->cl, *cr = s->cr, *cb = s->cb, *ct = s->ct,
                 *sy = c->sy, *bz = s->bz;
    memset(st, 0, (nb + 2) * sizeof *st);
    /* bucket (m, col) counted at st[(m - 1) nx + col + 2] */
    for (int col = 0; col < nx; col++) {
        const uint32_t u0 = c->start[(size_t)col * ny],
                       u1 = c->start[(size_t)(col + 1) * ny];
        uint32_t *sc = st + col + 2 - nx; /* line m at m nx */
        for (uint32_t u = u0; u < u1; u++)
            for (int m = cmb[u]; m <= cme[u]; m++)
                sc[(size_t)m * (size_t)nx]++;
    }
    /* st[k + 1]: the start of bucket k, the end after the filling */
    for (size_t k = 0; k < nb; k++)
        st[k + 2] += st[k + 1];
    const size_t ne = st[nb + 1] ? st[nb + 1] : 1;
    if (ne > s->cutv_cap) {
        if (!grow((void **)&s->cutv, ne, sizeof *s->cutv) ||
            !grow((void **)&s->cutl, ne, sizeof *s->cutl) ||
            !grow((void **)&s->cutr, ne, sizeof *s->cutr) ||
            !grow((void **)&s->cuth, ne, sizeof *s->cuth) ||
            !grow((void **)&s->cuty, ne, sizeof *s->cuty))
            return 0;
        s->cutv_cap = ne;
    }
    for (int col = 0; col < nx; col++) {
        const uint32_t u0 = c->start[(size_t)col * ny],
                       u1 = c->start[(size_t)(col + 1) * ny];
        uint32_t *sc = st + col + 1 - nx;
        for (uint32_t u = u0; u < u1; u++)
            for (int m = cmb[u]; m <= cme[u]; m++) {
                const uint32_t e = sc[(size_t)m * (size_t)nx]++;
                s->cutv[e] = u;
                s->cutl[e] = cl[u];
                s->cutr[e] = cr[u];
                s->cuth[e] = dmin(ct[u], bz[m]) - cb[u];
                s->cuty[e] = sy[u];
            }
    }
    return 1; /* bucket k is st[k] .. st[k + 1] - 1 */
}

/* cut_band from the cut lists: the same squares, added in the same order
 * with the same expressions, so the same bits.  Every entry has positive
 * height (b < z_K), so its term is positive or, where it does not count,
 * +0.0 (the sum starts at +0.0): the select is a mask, not a branch. */
static inline double cut_list_band(const bf_support *s, const bf_cells *c,
                                   const stripq *q, uint32_t tj,
                                   uint32_t *count)
{
    const double hd = s->hd;
    const double *restrict el = s->cutl, *restrict er = s->cutr,
                           *restrict eh = s->cuth, *restrict ey = s->cuty;
    const uint32_t *restrict ev = s->cutv;
    const int c0 = bf_cells_col(c, q->gam - hd),
              c1 = bf_cells_col(c, q->del + hd);
    const uint32_t *st =
        s->cutst + (size_t)(q->K - 1) * (size_t)c->nx;
    const uint32_t k1 = st[c1 + 1];
    double acc = 0.0;
    uint32_t cnt = 0;
    for (uint32_t k = st[c0]; k < k1; k++) {
        double f2 = dmin(er[k], q->del) - dmax(el[k], q->gam);
        int ok = (f2 > 0) & (ey[k] <= q->ytop) & (ev[k] != tj);
        acc += (double)ok * (f2 * eh[k]);
        cnt += (uint32_t)ok;
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

/* The squares, strips and levels of the particles at sorted positions
 * [k0, k1) (slots ord[k] of the cell list, positions sx, sy); returns the
 * largest K among them (0 if none).  The workspace's pointers and
 * constants are held in locals (see band_edges). */
static int fast_setup(bf_support *s, const double *sx, const double *sy,
                      size_t k0, size_t k1)
{
    const bf_support_params *p = &s->p;
    const uint32_t *restrict ord = s->ord;
    double *restrict ls = s->ls, *restrict rs = s->rs, *restrict bs = s->bs,
                     *restrict ts = s->ts, *restrict gs = s->gs,
                     *restrict ds = s->ds, *restrict lower = s->lower;
    int32_t *restrict ks = s->ks, *restrict mb = s->mb, *restrict mt = s->mt,
                      *restrict sl = s->sl, *restrict lowe = s->lowe;
    const band_edges e = {p, s->bz, s->kmax + 1};
    const double hd = s->hd, hdx = s->hdx, ax = p->box.ax, bx = p->box.bx,
                 ay = p->box.ay, by = p->box.by;
    int kmax = 0;
    for (size_t k = k0; k < k1; k++) {
        const uint32_t i = ord[k];
        const double xi = sx[i], yi = sy[i];
        const double b = dmax(yi - hd, ay), t = dmin(yi + hd, by);
        ls[k] = dmax(xi - hd, ax);
        rs[k] = dmin(xi + hd, bx);
        bs[k] = b;
        ts[k] = t;
        gs[k] = dmax(xi - hdx, ax);
        ds[k] = dmin(xi + hdx, bx);
        const int K = k_of(p, yi);
        ks[k] = K;
        kmax = K > kmax ? K : kmax;
        mb[k] = first_band(&e, b);
        const int m = full_level(&e, t);
        mt[k] = m;
        sl[k] = yi + hd > by ? INT32_MAX : m;
        lower[k] = 0.0;
        lowe[k] = INT32_MAX;
    }
    return kmax;
}

/* The results of sorted position k into the order of the cell list. */
static inline void fast_to_slots(bf_support *s, size_t k)
{
    uint32_t t = s->ord[k];
    s->fgam[t] = s->lower[k];
    s->ks[t] = s->lowe[k];
    s->csl[t] = s->sl[k];
    /* the lines whose cut lists hold the square (cut_lists) */
    const int cap = s->kmax;
    s->cmb[t] = s->mb[k];
    s->cme[t] = !(s->ts[k] > s->bs[k]) ? 0
                : s->sl[k] == INT32_MAX || s->sl[k] > cap ? cap
                                                          : s->sl[k] - 1;
}

/* g of particle j in slot t with K >= 1 and no empty band below its top
 * band, or with K = 0 and not resting: the K = 0 rectangle, or the squares
 * that the sweep at level K leaves out and the test of band K.  lower (the
 * sweep) is in the order of the cell list.  Not inlined: most particles
 * rest or fall freely (fast_g), and their loop should not pay for this
 * one's registers. */
static __attribute__((noinline)) void
fast_strip(const bf_support *s, const bf_cells *c, const double *lower,
           int lists, size_t t, uint32_t j, double yj, int K, double *g,
           uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    const double xj = c->sx[t];
    uint8_t kd;
    double gj;
    double gam = dmax(xj - s->hdx, p->box.ax);
    double del = dmin(xj + s->hdx, p->box.bx);
    double area = 0.0;
    uint32_t cnt = 0;
    if (K == 0) {
        bf_sup_column(s, c, j, yj, gam, del, 0, 0, 0, &area, &cnt);
    } else {
        const stripq q =
            stripq_of(gam, del, band_hi(s, K), band_lo(s, K),
                      p->tie ? yj : nextafter(yj, -INFINITY), K);
        area = lists ? cut_list_band(s, c, &q, (uint32_t)t, &cnt)
                     : cut_band(s, c, &q, (uint32_t)t, yj, &cnt);
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
    g[j] = gj;
    if (kind)
        kind[j] = kd;
}

/* g of the particles in slots [t0, t1): lowe (the lowest empty band) in
 * the order of the cell list. */
static void fast_g(const bf_support *s, const bf_cells *c,
                   const double *lower, const int32_t *lowe, int lists,
                   size_t t0, size_t t1, double *g, uint8_t *kind)
{
    const bf_support_params *p = &s->p;
    const double g0 = p->g0;
    for (size_t t = t0; t < t1; t++) {
        const uint32_t j = c->idx[t];
        const double yj = c->sy[t];
        const int K = k_of(p, yj);
        if (resting(s, yj, K)) {
            g[j] = 0.0;
            if (kind)
                kind[j] = BF_SUP_REST;
        } else if (K >= 2 && lowe[t] <= K - 1) {
            g[j] = -g0;
            if (kind)
                kind[j] = BF_SUP_FREE;
        } else {
            fast_strip(s, c, lower, lists, t, j, yj, K, g, kind);
        }
    }
}

/* (The positions come from the cell list, which holds them in its order.) */
void bf_sup_eval_fast(bf_support *s, size_t n, const bf_cells *c, double *g,
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
    sort_by_x(s, c);
    int kmax = 0;
    if (pr) {
#ifdef _OPENMP
        /* four blocks a thread, of at least 1024 particles */
        size_t blk = (n + 4 * (size_t)nt - 1) / (4 * (size_t)nt);
        blk = blk < 1024 ? 1024 : blk;
        const size_t nblk = (n + blk - 1) / blk;
#pragma omp parallel for schedule(static) num_threads(nt) reduction(max : kmax)
        for (size_t b = 0; b < nblk; b++) {
            const size_t k1 = (b + 1) * blk < n ? (b + 1) * blk : n;
            int K = fast_setup(s, c->sx, c->sy, b * blk, k1);
            kmax = K > kmax ? K : kmax;
        }
#endif
    } else {
        kmax = fast_setup(s, c->sx, c->sy, 0, n);
    }
    /* the empty bands first: a particle that falls freely through one
     * asks the sweep nothing */
    if (kmax >= 2) /* bands 1..kmax - 1, below every top band */
        bf_sup_empty_bands(s, n, kmax - 1);
    size_t nq = 0;
    for (size_t k = 0; k < n; k++) {
        const int K = s->ks[k];
        s->qk[nq] = (uint32_t)k;
        s->qK[nq] = K;
        s->qg[nq] = s->gs[k];
        s->qd[nq] = s->ds[k];
        nq += K >= 1 && (s->exhaustive ||
                         !(K >= 2 && s->lowe[k] <= K - 1)); /* fast_g */
    }
    s->qg[nq] = INFINITY; /* read, not used, at the end of the last chunk */
    const size_t nu = nq > 0 ? sweep_updates(s, n) : 0;
    if (nq > 0) {
        /* the chunks are independent (each has its own tree), so they run
         * in parallel with results independent of the thread count */
        const double w = p->box.bx - p->box.ax, chunk = SUP_CHUNK_BANDS * p->dx;
        long nch = (long)ceil(w / chunk);
        if (nch < 1)
            nch = 1;
        const size_t fsz = s->fsz;
        if (pr) {
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
            for (long ch = 0; ch < nch; ch++)
                sweep_chunk(s, s->fen + (size_t)omp_get_thread_num() * fsz, n,
                            nu, nq, p->box.ax + (double)ch * chunk,
                            p->box.ax + (double)(ch + 1) * chunk,
                            ch == nch - 1);
#endif
        } else {
            for (long ch = 0; ch < nch; ch++)
                sweep_chunk(s, s->fen, n, nu, nq,
                            p->box.ax + (double)ch * chunk,
                            p->box.ax + (double)(ch + 1) * chunk,
                            ch == nch - 1);
        }
    }
    /* the sweep's results and the square edges in the order of the cell
     * list; then g in that order (neighbouring queries read neighbouring
     * cells) */
    bf_sup_slot_edges(s, c, n, 0);
    if (pr) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt)
        for (size_t k = 0; k < n; k++)
            fast_to_slots(s, k);
#endif
    } else {
        for (size_t k = 0; k < n; k++)
            fast_to_slots(s, k);
    }
    /* the cut squares by line (the exhaustive mode asks the cell list's
     * window, as before the lists) */
    const int lists = !s->exhaustive && cut_lists(s, c);
    if (pr) {
#ifdef _OPENMP
        const size_t nb = (n + 255) / 256;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
        for (size_t b = 0; b < nb; b++)
            fast_g(s, c, s->fgam, s->ks, lists, 256 * b,
                   256 * (b + 1) < n ? 256 * (b + 1) : n, g, kind);
#endif
    } else {
        fast_g(s, c, s->fgam, s->ks, lists, 0, n, g, kind);
    }
}
