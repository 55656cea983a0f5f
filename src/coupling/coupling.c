/* coupling.c: the quadrature of the ball-film coupling, F and dF/dr of
 * Yasuda eq. 3.10 (see coupling.h for the formulas); mu_cpl (3.11) is in
 * mu_cpl.c, the force on the balls (3.12) in force.c.
 *
 * Quadrature.  g_i = h_i (psi_i - psi_s)^2 on the nodes; on cell
 * [x_j, x_j+1] (t = (x - x_j)/dx) the natural cubic spline is
 *   S(t) = (1-t) g_j + t g_j+1 + dx^2/6 [((1-t)^3 - (1-t)) M_j + (t^3 - t) M_j+1]
 * (M: second derivatives; M = 0 for quadrature = linear).  With
 * kappa = dx/r0 and m_k = integral_0^1 s^k exp(-kappa s) ds the exact cell
 * moments are
 *   LC_j = integral_cell S exp(-(x_j+1 - x)/r0) dx
 *        = dx [m1 g_j + (m0 - m1) g_j+1 + dx^2/6 ((m3 - m1) M_j
 *              + (3 m2 - 2 m1 - m3) M_j+1)],
 *   RC_j = the same with j and j+1 exchanged (weight exp(-(x - x_j)/r0)),
 * and the node moments ML_j = sum_k<j E^(j-1-k) LC_k, MR_j = sum_k>=j
 * E^(k-j) RC_k (E = exp(-kappa)).  For a ball at t_r in cell j
 *   L(r) = exp(-kappa t_r) ML_j + dx sum_k (-1)^k e_k T^(k+1) m_k(kappa T),
 *          T = t_r,
 *   R(r) = exp(-kappa (1 - t_r)) MR_j+1 + dx sum_k e_k T^(k+1) m_k(kappa T),
 *          T = 1 - t_r,
 * where e_k = S^(k)(t_r)/k! are the spline's Taylor coefficients at t_r and
 * m_k(z) = integral_0^1 s^k exp(-z s) ds (series for z < 0.5, upward
 * recursion above).  All of it is exact integration of the interpolant:
 * dI/dr = (R - L)/r0 is the derivative of I to round-off.
 *
 * Cost.  ML_j, MR_j+1 and the spline's M_j, M_j+1 are linear in g, so
 * each is a dot product W.g with a row W that depends only on the grid,
 * r0 and the quadrature: built once per node (an adjoint spline solve,
 * see build_row) and kept.  Per film level: g (vectorised); lazily, for
 * each cell a ball is in, its four moments as dot products of ~K + 70 and
 * ~70 terms (cached for the level) -- the natural spline of the whole film
 * is never formed (it was ~25% of a coupled step).  A force evaluation is
 * then O(1).  In the coupled
 * run the film is frozen during a ball step and the balls move by ~1e-4 cm
 * per step, so each ball's first evaluation after a refresh anchors a
 * Taylor expansion of L and R to 5th order (L' = g - L/r0, R' = -g + R/r0,
 * higher derivatives likewise; exact within a cell since g''' is constant
 * there), used for later positions in the same cell within taylor_radius
 * (remainder (d/r0)^6/720 < 1e-19 for d <= 2e-3 r0).  bf_coupling_prepare
 * computes these anchors for all balls at once at their positions (where
 * the integrator's first evaluation of the step comes), overlapping the
 * latencies of their serial parts; the numbers are those of the lazy
 * anchor (tested).
 *
 * mu_cpl (mu_cpl.c) takes the table of powers of E (pw, pwr) and the
 * exp() values of the prepared anchors from here (bf_coupling_grid_of,
 * bf_coupling_prepared_exp).
 *
 * Bits.  The anchors prepared ahead and the interleaved series (bf_mk2,
 * bf_mk_series8 of mk.c) give the numbers of the plain sequence of
 * operations bit for bit: work is only interleaved where it is
 * independent (never inside a sum), and values are reused only where they
 * come from the same operands by the same operations; a moment's sum
 * does not depend on which rows are summed with it (dotg4).  The moments
 * by rows are the quantities of the earlier spline-then-cells-then-sums in
 * another order of summation: they differ from those in round-off only
 * (tested against GSL's spline and a quadrature of the interpolant).
 */
#include "coupling/coupling.h"

#include "coupling/mk.h"
#include "coupling/nodes.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { NCACHE = 16, NROW = 96 };
enum { ROW_L, ROW_R, ROW_M }; /* rows of ML_n, MR_n, M_n */
/* nodes beyond which the spline's influence lambda^d (lambda = 2 - sqrt 3)
 * is below 2^-64 * 1e-3: 64 ln 2 / ln(1/lambda) = 33.7, plus margin */
enum { ROW_SPREAD = 40 };

typedef struct cell_moments {
    long j;         /* cell, -1: empty */
    double ml;      /* ML_j */
    double mr;      /* MR_j+1 */
    double m0, m1;  /* the spline's M_j, M_j+1 */
} cell_moments;

typedef struct row_entry {
    int kind;       /* ROW_L, ROW_R, ROW_M; -1: empty */
    long n;         /* node */
    long i0, len;   /* W_i for i = i0 .. i0 + len - 1 in w */
    double *w;
    unsigned long long used; /* when last used (row_clock) */
} row_entry;

typedef struct anchor {
    int valid;   /* set for the current film level */
    int fresh;   /* set by prepare, not yet used (see prepare_anchors) */
    long j;
    double r;
    double L[6], R[6]; /* derivatives 0..5 of L and R at r */
    double lq[6], rq[6]; /* L_k/k!, R_k/k!: the Taylor coefficients */
} anchor;

struct bf_coupling {
    bf_coupling_params p;
    const bf_film *film;
    bf_coupling_grid grid;    /* nodes, kernel reach, powers of E */
    double w_g0, w_g1, w_m0, w_m1; /* LC weights (times dx) */
    double *g, *m, *lc, *rc, *tl, *tw, *tmp;
    row_entry rows[NROW];     /* the rows built (a pool) */
    double *rowmem;           /* their storage, NROW x n8 */
    long n8;                  /* N + 1 rounded up to a multiple of 8 */
    long len_lr, len_m;       /* the rows' windows (see build_row) */
    double *zrow;             /* n8 zeros */
    int *row_of;              /* [kind][node] -> pool entry or -1 */
    unsigned long long row_clock;
    bf_mk_table mk;           /* m_k(z) for z <= min(kappa, 0.5) (mk.h) */
    cell_moments cache[NCACHE];
    int ncache;
    anchor *anc;
    /* exp(-kappa t), exp(-kappa (1 - t)) of each ball at xe (NaN: none),
     * from prepare, for bf_coupling_mu at the same positions */
    double *xe, *ele, *ere;
    size_t nballs;
    bf_coupling_nodes *nodes; /* quadrature = nodes (nodes.h), else NULL */
    unsigned long long n_exact, n_taylor;
};

/* ---------------------------------------------------------------- set-up */

static void *xcalloc(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

/* n doubles, zero, 64-byte aligned */
static double *alloc64(size_t n)
{
    void *p = NULL;
    if (posix_memalign(&p, 64, (n ? n : 1) * sizeof(double)))
        return NULL;
    memset(p, 0, (n ? n : 1) * sizeof(double));
    return p;
}

bf_status bf_coupling_create(bf_coupling **out, const bf_coupling_params *p,
                             const bf_film *film, size_t nballs, bf_err *err)
{
    *out = NULL;
    bf_coupling *c = calloc(1, sizeof *c);
    if (!c)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    c->p = *p;
    c->film = film;
    c->grid.N = (long)bf_film_nodes(film) - 1;
    c->grid.dx = bf_film_params_of(film)->dx;
    c->grid.x0 = bf_film_x(film)[0];
    c->grid.kappa = c->grid.dx / p->r0;
    const size_t n = (size_t)c->grid.N + 1;
    /* g and the rows: 64-byte aligned, zero up to a multiple of 8 (the
     * row sums run over whole blocks of eight, see dotg4) */
    c->n8 = ((long)n + 7) & ~7L;
    c->g = alloc64((size_t)c->n8);
    c->m = xcalloc(n);
    c->lc = xcalloc(n);
    c->rc = xcalloc(n);
    c->grid.pw = xcalloc(n);
    c->grid.pwr = xcalloc(n);
    c->tl = xcalloc(n);
    c->tw = xcalloc(n);
    c->tmp = xcalloc(n);
    c->nballs = nballs;
    c->anc = calloc(nballs ? nballs : 1, sizeof *c->anc);
    c->xe = xcalloc(nballs);
    c->ele = xcalloc(nballs);
    c->ere = xcalloc(nballs);
    c->rowmem = alloc64((size_t)NROW * (size_t)c->n8);
    c->row_of = malloc(3 * n * sizeof *c->row_of);
    c->zrow = alloc64((size_t)c->n8);
    if (p->quad == BF_COUPLING_NODES &&
        !(c->nodes = bf_coupling_nodes_create(c->grid.N, c->grid.dx,
                                              p->r0))) {
        bf_coupling_free(c);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (!c->g || !c->m || !c->lc || !c->rc || !c->grid.pw || !c->grid.pwr ||
        !c->tl || !c->tw || !c->tmp || !c->anc || !c->xe || !c->ele ||
        !c->ere || !c->rowmem || !c->row_of || !c->zrow) {
        bf_coupling_free(c);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    /* powers of E, flushed to zero below 1e-300 (no subnormals):
     * pw[k] = E^k, pwr[k] = E^(N-1-k) */
    for (long k = 0; k <= c->grid.N; k++) {
        double v = exp(-c->grid.kappa * (double)k);
        c->grid.pw[k] = v < 1e-300 ? 0.0 : v;
    }
    for (long k = 0; k < c->grid.N; k++)
        c->grid.pwr[k] = c->grid.pw[c->grid.N - 1 - k];
    /* cell weights */
    c->grid.K = (long)ceil(64.0 * log(2.0) / c->grid.kappa);
    /* the series is used only for z = kappa T <= min(kappa, 0.5), T <= 1 */
    bf_mk_init(&c->mk, fmin(c->grid.kappa, 0.5));
    double m[4];
    bf_mk(&c->mk, c->grid.kappa, m);
    const double h = c->grid.dx, h26 = h * h / 6.0;
    c->w_g0 = h * m[1];
    c->w_g1 = h * (m[0] - m[1]);
    c->w_m0 = h * h26 * (m[3] - m[1]);
    c->w_m1 = h * h26 * (3.0 * m[2] - 2.0 * m[1] - m[3]);
    /* Thomas factors of the natural spline system, rows 1..N-1:
     * M_i-1 + 4 M_i + M_i+1 = d_i, M_0 = M_N = 0 */
    if (c->grid.N >= 2) {
        double w = 4.0;
        c->tw[1] = 1.0 / w;
        for (long i = 2; i < c->grid.N; i++) {
            c->tl[i] = 1.0 / w;
            w = 4.0 - c->tl[i];
            c->tw[i] = 1.0 / w;
        }
    }
    for (size_t p = 0; p < nballs; p++)
        c->xe[p] = NAN;
    /* rows: the kernel's K cells (ML, MR) and ROW_SPREAD nodes on each side
     * for the spline's reach (see build_row); M alone: the spread */
    c->len_lr = c->grid.K + 2 * ROW_SPREAD + 1;
    c->len_m = 2 * ROW_SPREAD + 3;
    if (c->len_lr > c->grid.N + 1)
        c->len_lr = c->grid.N + 1;
    if (c->len_m > c->grid.N + 1)
        c->len_m = c->grid.N + 1;
    for (size_t i = 0; i < 3 * n; i++)
        c->row_of[i] = -1;
    for (int q = 0; q < NROW; q++) {
        c->rows[q].kind = -1;
        c->rows[q].w = c->rowmem + (size_t)q * (size_t)c->n8;
    }
    bf_coupling_refresh(c);
    *out = c;
    return BF_OK;
}

void bf_coupling_free(bf_coupling *c)
{
    if (!c)
        return;
    free(c->g);
    free(c->m);
    free(c->lc);
    free(c->rc);
    free(c->grid.pw);
    free(c->grid.pwr);
    free(c->tl);
    free(c->tw);
    free(c->tmp);
    free(c->anc);
    free(c->xe);
    free(c->ele);
    free(c->ere);
    free(c->rowmem);
    free(c->row_of);
    free(c->zrow);
    bf_coupling_nodes_free(c->nodes);
    free(c);
}

const bf_coupling_params *bf_coupling_params_of(const bf_coupling *c)
{
    return &c->p;
}
const bf_film *bf_coupling_film(const bf_coupling *c) { return c->film; }
const bf_coupling_grid *bf_coupling_grid_of(const bf_coupling *c)
{
    return &c->grid;
}

int bf_coupling_prepared_exp(const bf_coupling *c, size_t p, double x,
                             double *el, double *er)
{
    if (!(p < c->nballs && x == c->xe[p]))
        return 0;
    *el = c->ele[p];
    *er = c->ere[p];
    return 1;
}
const double *bf_coupling_g(const bf_coupling *c) { return c->g; }

void bf_coupling_counts(const bf_coupling *c, unsigned long long *exact,
                        unsigned long long *taylor)
{
    *exact = c->n_exact;
    *taylor = c->n_taylor;
}

/* ---------------------------------------------------------------- refresh */

/* Hot loops: GCC's "cheap" vectoriser cost model (see film.c), and the
 * callers cloned for AVX-512 and AVX2 (element-wise, no reordered
 * reductions: the same bits on every clone).  The helpers are inlined
 * into each clone. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("vect-cost-model=cheap")
#endif
#if defined(__GNUC__) && !defined(__clang__)
#define BF_SPLINE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define BF_SPLINE_CLONES
#endif
#define HOT static inline __attribute__((always_inline))

HOT void g_pass(long n, double psis, const double *restrict h,
                   const double *restrict psi, double *restrict g)
{
    for (long i = 0; i < n; i++) {
        double d = psi[i] - psis;
        g[i] = h[i] * (d * d);
    }
}

/* Four sums r_q = sum_i w_q[i] g[i] over the blocks of eight from lo (a
 * multiple of 8) to hi, each with eight partial sums by i mod 8 (from +0,
 * in increasing i) combined pairwise.  Rows are zero outside their
 * windows, so a range that covers a row's window gives the row's sum bit
 * for bit whatever the range (adding +0 changes no partial sum): the
 * moments do not depend on which rows are summed together.  g is loaded
 * once for the four rows, every load is aligned. */
BF_SPLINE_CLONES
static void dotg4(long lo, long hi, const double *const w[4],
                  const double *restrict g, double r[4])
{
    const double *restrict w0 = w[0], *restrict w1 = w[1], *restrict w2 = w[2],
                           *restrict w3 = w[3];
    double s0[8] = {0}, s1[8] = {0}, s2[8] = {0}, s3[8] = {0};
    for (long k = lo; k <= hi; k += 8)
        for (int l = 0; l < 8; l++) {
            const double gk = g[k + l];
            s0[l] += w0[k + l] * gk;
            s1[l] += w1[k + l] * gk;
            s2[l] += w2[k + l] * gk;
            s3[l] += w3[k + l] * gk;
        }
    const double *sq[4] = {s0, s1, s2, s3};
    for (int q = 0; q < 4; q++) {
        const double *u = sq[q];
        r[q] = ((u[0] + u[1]) + (u[2] + u[3])) + ((u[4] + u[5]) + (u[6] + u[7]));
    }
}

BF_SPLINE_CLONES
void bf_coupling_refresh(bf_coupling *c)
{
    const long N = c->grid.N;
    g_pass(N + 1, c->p.psi_s, bf_film_h(c->film), bf_film_psi(c->film), c->g);
    c->ncache = 0;
    for (size_t p = 0; p < c->nballs; p++)
        c->anc[p].valid = c->anc[p].fresh = 0;
    if (c->nodes)
        bf_coupling_nodes_invalidate(c->nodes);
}

/* ---------------------------------------------------------------- rows */

/* The moments a ball needs are linear in g: ML_n = W.g with a row W that
 * depends only on the grid, r0 and the quadrature (see the file comment).
 * Row of F = sum_k (cL_k LC_k + cR_k RC_k):
 *   alpha_i = w_g0 cL_i + w_g1 cL_(i-1) + w_g1 cR_i + w_g0 cR_(i-1)
 *   beta_i  = w_m0 cL_i + w_m1 cL_(i-1) + w_m1 cR_i + w_m0 cR_(i-1)
 *   F = alpha.g + beta.M, M = A^-1 d (rows 1..N-1 of the natural spline,
 *   d_i = s (g_(i+1) - 2 g_i + g_(i-1)), s = 6/dx^2), so
 *   beta.M = y.d with A y = beta (A symmetric), and
 *   W_k = alpha_k + s (y_(k-1) - 2 y_k + y_(k+1))   (y_0 = y_N = 0).
 * The row of M_n itself has alpha = 0, beta = e_n.  A row is kept on a
 * window of fixed length (len_lr, len_m): alpha's K + 1 nodes (ML, MR) or
 * node n (M) and ROW_SPREAD nodes on each side, shifted inside 0..N at
 * the ends.  Outside it, W is y's tail: |(A^-1)_ik| < lambda^|i-k|, so
 * there W is below 2^-64 of the row's largest (the kernel's cells beyond
 * E^K < 2^-64 are dropped likewise; g is bounded: below the sums'
 * round-off).  The row is stored over all nodes with zeros outside its
 * window (see dotg4). */

/* the row of kind `kind` at node n into the pool entry `e` */
static void build_row(bf_coupling *c, int kind, long n, row_entry *e)
{
    const long N = c->grid.N, K = c->grid.K;
    double *al = c->lc, *be = c->rc, *y = c->tmp; /* scratch, N + 1 each */
    for (long i = 0; i <= N; i++)
        al[i] = be[i] = 0.0;
    if (kind == ROW_M) {
        if (n > 0 && n < N)
            be[n] = 1.0;
    } else {
        /* cell weights: ML_n = sum_(max(0,n-K) <= k < n) E^(n-1-k) LC_k,
         * MR_n = sum_(n <= k < min(n+K,N)) E^(k-n) RC_k */
        const int left = kind == ROW_L;
        const long k0 = left ? (n - K > 0 ? n - K : 0) : n;
        const long k1 = left ? n : (n + K < N ? n + K : N);
        const double g0 = left ? c->w_g0 : c->w_g1, g1 = left ? c->w_g1 : c->w_g0;
        const double m0 = left ? c->w_m0 : c->w_m1, m1 = left ? c->w_m1 : c->w_m0;
        for (long k = k0; k < k1; k++) {
            const double ck = c->grid.pw[left ? n - 1 - k : k - n];
            al[k] += g0 * ck;
            al[k + 1] += g1 * ck;
            be[k] += m0 * ck;
            be[k + 1] += m1 * ck;
        }
    }
    if (c->p.quad == BF_COUPLING_SPLINE && N >= 2) {
        /* A y = beta on rows 1..N-1 by the factors of create */
        const long last = N - 1;
        y[0] = y[N] = 0.0;
        y[1] = be[1];
        for (long i = 2; i <= last; i++)
            y[i] = be[i] - c->tl[i] * y[i - 1];
        y[last] *= c->tw[last];
        for (long i = last - 1; i >= 1; i--)
            y[i] = (y[i] - y[i + 1]) * c->tw[i];
        const double s = 6.0 / (c->grid.dx * c->grid.dx);
        for (long k = 0; k <= N; k++) {
            double ym = k > 0 ? y[k - 1] : 0.0, yp = k < N ? y[k + 1] : 0.0;
            al[k] += s * ((ym - 2.0 * y[k]) + yp);
        }
    }
    const long len = kind == ROW_M ? c->len_m : c->len_lr;
    long i0 = kind == ROW_L   ? n - K - ROW_SPREAD
              : kind == ROW_R ? n - ROW_SPREAD
                              : n - ROW_SPREAD - 1;
    if (i0 > N + 1 - len)
        i0 = N + 1 - len;
    if (i0 < 0)
        i0 = 0;
    e->kind = kind;
    e->n = n;
    e->i0 = i0;
    e->len = len;
    memset(e->w, 0, (size_t)c->n8 * sizeof(double));
    memcpy(e->w + i0, al + i0, (size_t)len * sizeof(double));
}

/* the row of kind at node n, from the pool or built in place of the one
 * used longest ago (so the rows of one evaluation never evict each
 * other) */
static const row_entry *row(bf_coupling *c, int kind, long n)
{
    int *slot = &c->row_of[kind * (c->grid.N + 1) + n];
    if (*slot >= 0) {
        c->rows[*slot].used = ++c->row_clock;
        return &c->rows[*slot];
    }
    int q = 0;
    for (int k = 1; k < NROW; k++)
        if (c->rows[k].used < c->rows[q].used)
            q = k;
    row_entry *e = &c->rows[q];
    if (e->kind >= 0)
        c->row_of[e->kind * (c->grid.N + 1) + e->n] = -1;
    build_row(c, kind, n, e);
    e->used = ++c->row_clock;
    *slot = q;
    return e;
}

/* W.g for a row */
static double row_dot(const bf_coupling *c, const row_entry *e)
{
    const double *w[4] = {e->w, c->zrow, c->zrow, c->zrow};
    double r[4];
    dotg4(e->i0 & ~7L, e->i0 + e->len - 1, w, c->g, r);
    return r[0];
}

/* the spline's M on all nodes (for tests: N + 1 rows) */
const double *bf_coupling_spline_m(bf_coupling *c)
{
    for (long n = 0; n <= c->grid.N; n++)
        c->m[n] = row_dot(c, row(c, ROW_M, n));
    return c->m;
}

/* The moments ML_j, MR_j+1, M_j and M_j+1 of the cells j[0..nc-1] (each
 * 0 <= j < N) into the cache, four cells at a time: each of the four
 * kinds of row of the four cells in one dotg4 over the blocks covering
 * their windows. */
static void moments_batch(bf_coupling *c, const long *j, int nc)
{
    for (int c0 = 0; c0 < nc; c0 += 4) {
        const int m = nc - c0 < 4 ? nc - c0 : 4;
        const double *w[4][4];
        long lo[4], hi[4];
        for (int k = 0; k < 4; k++) {
            lo[k] = c->grid.N;
            hi[k] = 0;
        }
        for (int q = 0; q < 4; q++) {
            if (q >= m) {
                for (int k = 0; k < 4; k++)
                    w[k][q] = c->zrow;
                continue;
            }
            const long jj = j[c0 + q];
            const row_entry *r[4] = {row(c, ROW_L, jj), row(c, ROW_R, jj + 1),
                                     row(c, ROW_M, jj), row(c, ROW_M, jj + 1)};
            for (int k = 0; k < 4; k++) {
                w[k][q] = r[k]->w;
                lo[k] = r[k]->i0 < lo[k] ? r[k]->i0 : lo[k];
                const long e = r[k]->i0 + r[k]->len - 1;
                hi[k] = e > hi[k] ? e : hi[k];
            }
        }
        double v[4][4];
        for (int k = 0; k < 4; k++)
            dotg4(lo[k] & ~7L, hi[k], w[k], c->g, v[k]);
        for (int q = 0; q < m; q++) {
            const long jj = j[c0 + q];
            int k = c->ncache < NCACHE ? c->ncache++ : (int)(jj % NCACHE);
            c->cache[k] = (cell_moments){jj, v[0][q], v[1][q], v[2][q], v[3][q]};
        }
    }
}

static const cell_moments *cached(const bf_coupling *c, long j)
{
    for (int q = 0; q < c->ncache; q++)
        if (c->cache[q].j == j)
            return &c->cache[q];
    return NULL;
}

/* the moments of cell j (0 <= j < N), from the cache or computed */
static const cell_moments *moments(bf_coupling *c, long j)
{
    const cell_moments *cm = cached(c, j);
    if (!cm) {
        moments_batch(c, &j, 1);
        cm = cached(c, j);
    }
    return cm;
}

/* cell of r and its local coordinate t (coupling.h) */
static long locate(const bf_coupling *c, double r, double *t)
{
    return bf_coupling_locate(&c->grid, r, t);
}

/* spline Taylor coefficients e_k = S^(k)(t)/k! (t in cell units) */
static void spline_taylor(const bf_coupling *c, long j, double M0, double M1,
                          double t, double e[4])
{
    const double h26 = c->grid.dx * c->grid.dx / 6.0;
    const double g0 = c->g[j], g1 = c->g[j + 1];
    const double c1 = (g1 - g0) - h26 * (2.0 * M0 + M1);
    const double c2 = 3.0 * h26 * M0;
    const double c3 = h26 * (M1 - M0);
    e[0] = g0 + t * (c1 + t * (c2 + t * c3));
    e[1] = c1 + t * (2.0 * c2 + 3.0 * t * c3);
    e[2] = c2 + 3.0 * c3 * t;
    e[3] = c3;
}

/* An exact evaluation inside the film in three parts, shared by the
 * single evaluation (exact_lr) and the anchors of all balls at once
 * (prepare_anchors): lr_begin (the cell's moments and the spline's Taylor
 * coefficients at t), the m_k series (bf_mk2 or bf_mk_series8), lr_end. */
typedef struct lr_part {
    long j;
    double t, ml, mr, e[4];
} lr_part;

static void lr_begin(bf_coupling *c, long j, double t, lr_part *w)
{
    /* the values, not a pointer: a later moments() may reuse the slot */
    const cell_moments *cm = moments(c, j);
    w->j = j;
    w->t = t;
    w->ml = cm->ml;
    w->mr = cm->mr;
    spline_taylor(c, j, cm->m0, cm->m1, t, w->e);
}

/* L and R from the parts, m_k(kappa t) (mL), m_k(kappa (1 - t)) (mR) and
 * el = exp(-kappa t), er = exp(-kappa (1 - t)) */
static void lr_end(const bf_coupling *c, const lr_part *w, const double mL[4],
                   const double mR[4], double el, double er, double *L,
                   double *R)
{
    const double TL = w->t, TR = 1.0 - w->t;
    const double *e = w->e;
    double pl = 0.0, pr = 0.0, tl = TL, tr = TR;
    for (int k = 0; k < 4; k++) {
        double s = (k & 1) ? -1.0 : 1.0;
        pl += s * e[k] * tl * mL[k];
        pr += e[k] * tr * mR[k];
        tl *= TL;
        tr *= TR;
    }
    *L = el * w->ml + c->grid.dx * pl;
    *R = er * w->mr + c->grid.dx * pr;
}

/* L and R at r (exact for the interpolant); also the cell and t, and the
 * parts (w: set only if r is inside the film, 0 <= t <= 1) */
static void exact_lr(bf_coupling *c, double r, long *jo, double *to, double *L,
                     double *R, lr_part *w)
{
    double t;
    long j = locate(c, r, &t);
    *jo = j;
    *to = t;
    if (t < 0.0 || t > 1.0) {
        /* outside the film: the whole film lies on one side, MR_0 or ML_N
         * seen from the film's end */
        if (t < 0.0) {
            *L = 0.0;
            *R = exp(c->grid.kappa * t) * row_dot(c, row(c, ROW_R, 0));
        } else {
            *L = exp(-c->grid.kappa * (t - 1.0)) *
                 row_dot(c, row(c, ROW_L, c->grid.N));
            *R = 0.0;
        }
        return;
    }
    double mL[4], mR[4];
    lr_begin(c, j, t, w);
    const double TL = t, TR = 1.0 - t;
    bf_mk2(&c->mk, c->grid.kappa * TL, c->grid.kappa * TR, mL, mR);
    double el = exp(-c->grid.kappa * TL), er = exp(-c->grid.kappa * TR);
    lr_end(c, w, mL, mR, el, er, L, R);
}

void bf_coupling_integral(bf_coupling *c, double r, double *I, double *dI)
{
    long j;
    double t, L, R;
    lr_part w;
    c->n_exact++;
    if (c->nodes) {
        j = bf_coupling_locate(&c->grid, r, &t);
        bf_coupling_nodes_eval(c->nodes, c->g, j, t, I, dI);
        return;
    }
    exact_lr(c, r, &j, &t, &L, &R, &w);
    *I = L + R;
    *dI = (R - L) / c->p.r0;
}

/* the anchor at r inside the film from its exact L, R and parts: the
 * derivatives 1..5 and the Taylor coefficients L_k/k!, R_k/k! */
static void anchor_from(bf_coupling *c, anchor *a, double r, const lr_part *w,
                        double L, double R)
{
    a->r = r;
    a->j = w->j;
    a->valid = 1;
    a->L[0] = L;
    a->R[0] = R;
    const double *e = w->e;
    const double h = c->grid.dx, ir = 1.0 / c->p.r0;
    /* g and its x-derivatives at r; g'''' = 0 within the cell */
    const double gd[5] = {e[0], e[1] / h, 2.0 * e[2] / (h * h),
                          6.0 * e[3] / (h * h * h), 0.0};
    for (int k = 1; k < 6; k++) {
        a->L[k] = gd[k - 1] - a->L[k - 1] * ir;
        a->R[k] = -gd[k - 1] + a->R[k - 1] * ir;
    }
    static const double f[5] = {1.0, 1.0, 0.5, 1.0 / 6.0, 1.0 / 24.0};
    for (int k = 0; k < 5; k++) {
        a->lq[k] = a->L[k] * f[k];
        a->rq[k] = a->R[k] * f[k];
    }
    a->lq[5] = a->L[5] / 120.0;
    a->rq[5] = a->R[5] / 120.0;
}

/* anchor ball p at r: L, R and their derivatives 1..5 (x units) */
static void set_anchor(bf_coupling *c, anchor *a, double r)
{
    double t, L, R;
    lr_part w;
    exact_lr(c, r, &a->j, &t, &L, &R, &w);
    a->r = r;
    a->L[0] = L;
    a->R[0] = R;
    a->valid = 0; /* outside the film: always exact */
    a->fresh = 0;
    if (t < 0.0 || t > 1.0)
        return;
    anchor_from(c, a, r, &w, L, R);
}

/* Anchors of the balls at x, computed when the film level is prepared.
 * The first force evaluation of the level comes at the same positions (the
 * integrator starts its step at x); it then takes the anchor as it is
 * (`fresh`) and gets the very numbers the lazy set_anchor would compute
 * there: the same operations in the same order, also for the moments
 * cache.  Done here for all balls at once, the balls' m_k series are the
 * lanes of one vector and their exp() calls overlap, where one ball after
 * the other they were a chain of dependent latencies.  A first evaluation
 * elsewhere (another integrator) drops the fresh anchor and anchors where
 * it is, as before.  Also kept: exp(-kappa t) and exp(-kappa (1 - t)) of
 * each ball, for bf_coupling_mu at the next step's start (same x). */
static void prepare_anchors(bf_coupling *c, size_t nb, const double *x)
{
    enum { G = 4 }; /* balls per group: 8 series */
    if (nb > c->nballs)
        nb = c->nballs;
    for (size_t p0 = 0; p0 < nb; p0 += G) {
        const size_t ng = nb - p0 < G ? nb - p0 : G;
        lr_part w[G];
        int in[G];
        double z[2 * G] = {0}, m[2 * G][4];
        /* the moments of the group's cells at once (moments_batch) */
        long cells[G];
        int nc = 0;
        for (size_t q = 0; q < ng; q++) {
            double t;
            long j = locate(c, x[p0 + q], &t);
            int seen = !(t >= 0.0 && t <= 1.0) || cached(c, j);
            for (int k = 0; k < nc && !seen; k++)
                seen = cells[k] == j;
            if (!seen)
                cells[nc++] = j;
        }
        moments_batch(c, cells, nc);
        for (size_t q = 0; q < ng; q++) {
            double t;
            long j = locate(c, x[p0 + q], &t);
            in[q] = t >= 0.0 && t <= 1.0;
            c->xe[p0 + q] = NAN;
            if (!in[q])
                continue; /* outside the film: always exact */
            lr_begin(c, j, t, &w[q]);
            z[2 * q] = c->grid.kappa * t;
            z[2 * q + 1] = c->grid.kappa * (1.0 - t);
        }
        bf_mk_series8(&c->mk, z, m);
        for (size_t q = 0; q < ng; q++) {
            if (!in[q])
                continue;
            for (int s = 0; s < 2; s++)
                if (!(z[2 * q + s] < 0.5)) /* the recursion, as bf_mk */
                    bf_mk(&c->mk, z[2 * q + s], m[2 * q + s]);
            const size_t p = p0 + q;
            double el = exp(-c->grid.kappa * w[q].t),
                   er = exp(-c->grid.kappa * (1.0 - w[q].t));
            double L, R;
            lr_end(c, &w[q], m[2 * q], m[2 * q + 1], el, er, &L, &R);
            anchor_from(c, &c->anc[p], x[p], &w[q], L, R);
            c->anc[p].fresh = 1;
            c->xe[p] = x[p];
            c->ele[p] = el;
            c->ere[p] = er;
        }
    }
}

void bf_coupling_prepare(bf_coupling *c, size_t nb, const double *x)
{
    if (c->p.taylor_radius > 0 && !c->nodes)
        prepare_anchors(c, nb, x);
}

void bf_coupling_integral_ball(bf_coupling *c, size_t p, double r, double *I,
                               double *dI)
{
    anchor *a = &c->anc[p];
    if (c->p.taylor_radius > 0 && !c->nodes) {
        if (a->fresh) {
            a->fresh = 0;
            if (r == a->r) { /* the anchor of prepare_anchors */
                c->n_exact++;
                *I = a->L[0] + a->R[0];
                *dI = (a->R[0] - a->L[0]) / c->p.r0;
                return;
            }
            a->valid = 0;
        }
        if (!a->valid) {
            set_anchor(c, a, r);
            c->n_exact++;
            *I = a->L[0] + a->R[0];
            *dI = (a->R[0] - a->L[0]) / c->p.r0;
            return;
        }
        double d = r - a->r, t;
        if (fabs(d) <= c->p.taylor_radius && locate(c, r, &t) == a->j &&
            t >= 0.0 && t <= 1.0) {
            /* Horner in d of sum_k (L_k, R_k) d^k / k! */
            double L = a->lq[5], R = a->rq[5];
            for (int k = 4; k >= 0; k--) {
                L = L * d + a->lq[k];
                R = R * d + a->rq[k];
            }
            c->n_taylor++;
            *I = L + R;
            *dI = (R - L) / c->p.r0;
            return;
        }
    }
    bf_coupling_integral(c, r, I, dI);
}

#undef HOT
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif

/* ---------------------------------------------------------------- checkpoint */

/* What a checkpoint keeps (a table of fields, checkpoint.h): the anchor
 * positions and whether each is set, and the two evaluation counters.
 * Nothing else: g, the rows and the cached moments are functions of the
 * film's state and the grid, so a continued run computes the same bits
 * again.  A fresh anchor (prepare_anchors) is saved as none: after a
 * restart the first evaluation computes the same anchor lazily. */
typedef struct coupling_ckpt {
    size_t n;               /* balls */
    double *anchor_r;       /* cm */
    uint8_t *anchor_valid;  /* 1: the anchor at anchor_r is set */
    unsigned long long n_exact, n_taylor;
} coupling_ckpt;

static const bf_field coupling_fields[] = {
    BF_FIELD_PTR(coupling_ckpt, anchor_r, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(coupling_ckpt, anchor_valid, BF_F_U8, n, "1"),
    BF_FIELD(coupling_ckpt, n_exact, BF_F_ULL, "1"),
    BF_FIELD(coupling_ckpt, n_taylor, BF_F_ULL, "1"),
};

/* the table's arrays for n balls (ckpt_free after, also on failure) */
static int ckpt_alloc(coupling_ckpt *k, size_t n)
{
    k->n = n;
    k->anchor_r = calloc(n ? n : 1, sizeof *k->anchor_r);
    k->anchor_valid = calloc(n ? n : 1, sizeof *k->anchor_valid);
    return k->anchor_r && k->anchor_valid;
}

static void ckpt_free(coupling_ckpt *k)
{
    free(k->anchor_r);
    free(k->anchor_valid);
}

bf_status bf_coupling_save(const bf_coupling *c, bf_ckpt *ck,
                           const char *prefix, bf_err *err)
{
    char name[128];
    snprintf(name, sizeof name, "%scoupling", prefix);
    coupling_ckpt k = {.n_exact = c->n_exact, .n_taylor = c->n_taylor};
    if (!ckpt_alloc(&k, c->nballs)) {
        ckpt_free(&k);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t p = 0; p < k.n; p++) {
        k.anchor_r[p] = c->anc[p].r;
        k.anchor_valid[p] = c->anc[p].valid && !c->anc[p].fresh;
    }
    bf_status st = bf_ckpt_put_fields(ck, name, coupling_fields,
                                      BF_NFIELDS(coupling_fields), &k, err);
    ckpt_free(&k);
    return st;
}

bf_status bf_coupling_load(bf_coupling *c, const bf_ckpt *ck,
                           const char *prefix, bf_err *err)
{
    char name[128];
    snprintf(name, sizeof name, "%scoupling", prefix);
    coupling_ckpt k = {0};
    if (!ckpt_alloc(&k, c->nballs)) {
        ckpt_free(&k);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    bf_status st = bf_ckpt_get_fields(ck, name, coupling_fields,
                                      BF_NFIELDS(coupling_fields), &k, err);
    if (!st) {
        /* the film is loaded: g, then the anchors */
        bf_coupling_refresh(c);
        for (size_t p = 0; p < k.n; p++)
            if (k.anchor_valid[p])
                set_anchor(c, &c->anc[p], k.anchor_r[p]);
        c->n_exact = k.n_exact;
        c->n_taylor = k.n_taylor;
    }
    ckpt_free(&k);
    return st;
}
