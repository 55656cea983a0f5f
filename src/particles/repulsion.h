/* repulsion.h: Greenspan's interparticle repulsion (1972, eqs 2.10-2.12).
 *
 * The acceleration of particle j from particle i at distance r < r_c is
 *
 *   a_j += alpha m_i (x_j - x_i) / D(r),
 *   D(r) = (r + xi)^p                       for r >= d,
 *   D(r) = (r + xi)^p ((r + xi)/d)^beta     for r <  d,
 *
 * i.e. a push away from i (eq. 2.11 and the listing; the text's eq. 2.10
 * writes x_i - x_j, a sign slip that would make the "repulsion" an
 * attraction).  p and beta are integers (the listing declares them
 * INTEGER).  The force m_j a_j is symmetric in i and j.  r_c is the
 * optional cutoff (Example 2: r < 2d = 10); 0 means every pair interacts.
 *
 * Units: lengths cm, masses g; alpha m r / r^p is an acceleration, so alpha
 * is in cm^(p-1) g^-1 s^-2 (Greenspan's examples set alpha = 1 and treat
 * the numbers as CGS).
 */
#ifndef BALLFILM_PARTICLES_REPULSION_H
#define BALLFILM_PARTICLES_REPULSION_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"
#include "particles/cells.h"

typedef struct bf_repulsion {
    double alpha;  /* strength */
    double xi;     /* added to r (the text's xi = epsilon) */
    double d;      /* particle width: beta acts for r < d */
    int p, beta;   /* integer exponents */
    double cutoff; /* r_c; 0: no cutoff */
    int use_cells; /* 1: cell list (needs cutoff > 0); 0: all pairs */
    double cell;   /* requested cell side (0: the cutoff) */
    double inv_d;  /* 1/d */
} bf_repulsion;

/* The keys of [repulsion] (bf_repulsion_spec). */
enum { BF_REPULSION_AUTO = 0, BF_REPULSION_CELLS = 1, BF_REPULSION_PAIRS = 2 };
typedef struct bf_repulsion_keys {
    double alpha, xi;
    long p, beta;
    double cutoff;
    int method; /* BF_REPULSION_AUTO, _CELLS, _PAIRS */
    double cell;
} bf_repulsion_keys;

extern const bf_section_spec bf_repulsion_spec; /* [repulsion] */

/* The law from the filled [repulsion] keys; d comes from the model.
 * Refuses (naming the key) a cell list without a cutoff and cell sides
 * above the cutoff or below cutoff/15. */
bf_status bf_repulsion_from_keys(bf_repulsion *r, const bf_repulsion_keys *k,
                                 double d, bf_err *err);

/* Accelerations (cm/s^2), overwriting ax, ay: all pairs, O(N^2).  Returns 0,
 * or 1 if two particles coincide with xi = 0 (the direction is undefined;
 * *bi, *bj name them). */
int bf_repulsion_all_pairs(const bf_repulsion *r, const double *x,
                           const double *y, const double *m, size_t n,
                           double *ax, double *ay, size_t *bi, size_t *bj);

/* Scratch for bf_repulsion_cells: accelerations in slot order (x and y of
 * slot s at sa[2s], sa[2s + 1]) and, per thread, the lists of neighbours
 * of a batch of particles (nb, r2) and where each particle's list starts
 * (bat). */
typedef struct bf_repulsion_work {
    size_t cap;
    int threads; /* OpenMP threads (1 without OpenMP) */
    int wide;    /* 1: the AVX-512 kernels (the same bits; repulsion.c) */
    double *sa, *r2;
    uint32_t *nb, *bat; /* bat: a batch's particles (repulsion.c) */
} bf_repulsion_work;

/* threads <= 0: OpenMP's default. */
bf_status bf_repulsion_work_init(bf_repulsion_work *w, size_t cap, int threads,
                                 bf_err *err);
void bf_repulsion_work_free(bf_repulsion_work *w);

/* The same from a cell list built with the masses as weights (any cell
 * side; the search reaches ceil(cutoff/side) cells).  Pairs within the
 * cutoff only.  The columns of cells are processed in stripes of reach + 1
 * columns, first the even stripes, then the odd ones: a stripe only writes
 * to itself and the next one, so the stripes of a phase run in parallel,
 * and the order of every sum is the same for any number of threads. */
int bf_repulsion_cells(const bf_repulsion *r, const bf_cells *c,
                       bf_repulsion_work *w, double *ax, double *ay,
                       size_t *bi, size_t *bj);

#endif
