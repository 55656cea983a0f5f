/* support.h: Greenspan's support-set gravity (1972, eqs 2.8-2.9).
 *
 * Gravity on particle j is an acceleration g_j (cm/s^2, along y) that
 * depends on how much of the container below j is filled by the other
 * particles.  Each particle i is a square Q_i of side d centred on it and
 * clipped to the box.  With
 *
 *   [gamma_j, delta_j] = [x_j - dx/2, x_j + dx/2] clipped,  W_j = delta - gamma,
 *   K_j = floor((y_j - ay)/dx),   band q = [ay + (q-1) dx, ay + q dx],
 *   S(P_j) = { i != j : y_i <= y_j }      (tie = le; y_i < y_j for tie = lt),
 *   A(R)   = sum over i in S(P_j) of |Q_i n R|   (overlaps count repeatedly),
 *
 *   K_j = 0, y_j - ay <= d:  g_j = 0                           (resting)
 *   K_j = 0, y_j - ay >  d:  g_j = -g0 (1 - A(R)/(W (y_j - ay) + eps)),
 *                            R = [gamma, delta] x [ay, y_j]     (2.8)
 *   K_j >= 1: if some band q = 1..K_j has no square of S(P_j) overlapping
 *             [gamma, delta] x band_q with positive area, g_j = -g0 (free
 *             fall); otherwise
 *             g_j = -g0 (1 - sum_q A(band_q)/(W K_j dx + eps))   (2.9)
 *
 * g_j > 0 ("antigravity") when the squares below overfill the region.  eps
 * is 0 in the text and 1e-3 in Schubert's listing.  There is no potential
 * and no reaction force, so the model does not conserve energy.
 *
 * Three exact methods give the same decisions and the same g to round-off:
 *   naive  O(N^2): every particle against every other (the reference);
 *   cell   O(N * particles in the column below): a cell list.  With
 *          K <= 64 the area of bands 1..K is sum f2 (min(t, hi_K) - b) and
 *          the empty-band test is a 64-bit mask of the bands each counted
 *          square reaches; cheapest for small boxes (Example 2: K <= 16);
 *   fast   O(N log N), needs d <= 2 dx.  For K_j >= 1 every square that
 *          lies entirely below the line z_K = ay + K_j dx (top t_i <= z_K)
 *          belongs to a particle with y_i <= z_K - d/2 < y_j, so those
 *          squares need no support-set test.  Their area in the strip,
 *            S_j = sum_i H_i(K_j) |[l_i, r_i] n [gamma_j, delta_j]|
 *          (H_i(m): the height of Q_i if it lies below z_m, else 0), is
 *          F(delta_j) - F(gamma_j) with
 *          F(x) = sum_{l_i<=x} H_i (x - l_i) - sum_{r_i<=x} H_i (x - r_i),
 *          evaluated by one sweep in x over the sorted square edges with a
 *          Fenwick tree over levels (each edge is one tree update).  The
 *          squares that line z_K cuts (and those clipped by the ceiling) come
 *          from a list of them per line and column of the cell list (the
 *          squares of a window of height d around z_K, in the same order),
 *          with the support-set test.  "Some band q <= K_j - 1 is empty" is
 *          decided exactly from the gaps between consecutive x-sorted squares
 *          of each band: a strip fits a gap iff no square of that band
 *          overlaps it; the strips that fit a gap are a contiguous range of
 *          the x order, and a skip list assigns each particle its lowest empty
 *          band once.  Band K_j is non-empty if a cut square of S(P_j)
 *          overlaps the strip, else the cell list is asked (rare).  The K = 0
 *          rectangle uses the cell list.  The empty bands are found first: a
 *          particle that falls freely through one asks the sweep nothing, and
 *          each chunk's tree keeps only the levels up to the highest one asked
 *          (the same bits as the exhaustive path, bf_support_set_exhaustive;
 *          tested).
 */
#ifndef BALLFILM_PARTICLES_SUPPORT_H
#define BALLFILM_PARTICLES_SUPPORT_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"
#include "particles/cells.h"
#include "particles/walls.h"

typedef enum bf_support_method {
    BF_SUPPORT_FAST = 0,
    BF_SUPPORT_CELL = 1,
    BF_SUPPORT_NAIVE = 2,
    BF_SUPPORT_AUTO = 3 /* cell if the box has <= 64 bands, else fast */
} bf_support_method;

/* What g_j is for each particle (diagnostics; eval's `kind` output). */
enum {
    BF_SUP_REST = 0,    /* K = 0 and y - ay <= d: g = 0 */
    BF_SUP_PARTIAL = 1, /* -g0 < g <= 0 from (2.8)/(2.9) */
    BF_SUP_FREE = 2,    /* an empty band (or no area at all): g = -g0 */
    BF_SUP_ANTI = 3     /* g > 0: the region below is overfull */
};

typedef struct bf_support_params {
    bf_box box;
    double g0;  /* cm/s^2 (980) */
    double dx;  /* band height and strip width, cm */
    double d;   /* side of a particle's square, cm */
    double eps; /* added to the denominators (listing: 1e-3), cm^2 */
    int tie;    /* 1: y_i = y_j counts in S(P_j) (listing); 0: strict */
    bf_support_method method;
    int threads;   /* OpenMP threads for method fast (<= 0: the default) */
    double inv_dx; /* 1/dx (set by bf_support_create) */
} bf_support_params;

/* The keys of [support] (bf_support_spec). */
typedef struct bf_support_keys {
    double g, dx;
    int method; /* bf_support_method */
    int tie;    /* 0: le (y_i <= y_j counts), 1: lt */
    double eps;
} bf_support_keys;

extern const bf_section_spec bf_support_spec; /* [support] */

/* The parameters from the filled [support] keys; box and d come from the
 * model.  Resolves method auto; refuses (naming the key) dx larger than
 * the box and method fast with d > 2 dx. */
bf_status bf_support_params_from_keys(bf_support_params *p,
                                      const bf_support_keys *k, bf_box box,
                                      double d, bf_err *err);

typedef struct bf_support bf_support;

/* Workspace for up to `cap` particles.  Refuses method fast with d > 2 dx. */
bf_status bf_support_create(bf_support **out, const bf_support_params *p,
                            size_t cap, bf_err *err);
void bf_support_free(bf_support *s);

/* g[j] for j < n.  `cells` must be built on (x, y) for methods cell and
 * fast (NULL is fine for naive).  kind[j] (may be NULL) gets BF_SUP_*.
 * Positions must lie in the box. */
void bf_support_eval(bf_support *s, const double *x, const double *y,
                     size_t n, const bf_cells *cells, double *g,
                     uint8_t *kind);

/* How far from a particle at x the squares lie on which its g depends
 * (cm): x - *left < x_i < x + *right for the centre x_i of every
 * square that the evaluation reads for it (a run split over ranks needs
 * them as a halo; slabs.h).  The strip with the squares that overlap it
 * is dx/2 + d/2 each way; the fast method's sweep starts at the left end
 * of the chunk of the strip, up to SUP_CHUNK_BANDS dx further left
 * (support_impl.h); the naive method reads every particle (INFINITY). */
void bf_support_reach(const bf_support *s, double *left, double *right);

/* The parameters the workspace was created with. */
const bf_support_params *bf_support_params_of(const bf_support *s);

/* The same with another method on the same workspace (tests, benchmarks);
 * fast with d > 2 dx falls back to cell. */
void bf_support_eval_with(bf_support *s, bf_support_method m, const double *x,
                          const double *y, size_t n, const bf_cells *cells,
                          double *g, uint8_t *kind);

/* Method fast, for tests and benchmarks: with `on`, every particle with
 * K >= 1 asks the sweep, free falling or not, every chunk's tree holds
 * every level of the box, and the cut squares come from the cell list's
 * window, not from the lists of each line, as before issue 21 item 5; the
 * results must be the same bits either way. */
void bf_support_set_exhaustive(bf_support *s, int on);

#endif
