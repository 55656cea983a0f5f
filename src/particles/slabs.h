/* slabs.h: x-slabs of the columns of a cell list, for a particle run split
 * over ranks.
 *
 * Rank r owns the particles whose cell column is in cut[r] .. cut[r+1]-1
 * and reads, besides them, the particles of hl columns to the left and hr
 * to the right (its halo): every force its own particles get depends only
 * on particles within those columns (the callers give the widths).  The
 * cuts are placed by particle counts (bf_slabs_balance), so that every
 * rank owns about n/size particles whatever the density; any cuts give the
 * same forces, so rebalancing changes no result.
 */
#ifndef BALLFILM_PARTICLES_SLABS_H
#define BALLFILM_PARTICLES_SLABS_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"

typedef struct bf_slabs {
    int size;       /* ranks */
    int nx;         /* columns */
    int hl, hr;     /* halo columns left and right */
    int *cut;       /* [size + 1]: rank r owns columns cut[r] .. cut[r+1]-1 */
    int *rank_of;   /* [nx]: the owner of each column */
    size_t *cnt;    /* [nx]: particles per column (bf_slabs_balance) */
    size_t *own;    /* [size]: particles each rank owns */
} bf_slabs;

bf_status bf_slabs_init(bf_slabs *s, int size, int nx, int hl, int hr,
                        bf_err *err);
void bf_slabs_free(bf_slabs *s);

/* Cuts such that rank r owns the columns from the first whose cumulative
 * count reaches r n / size (col[i]: the column of particle i, in 0..nx-1);
 * fills rank_of, cnt and own. */
void bf_slabs_balance(bf_slabs *s, const int32_t *col, size_t n);
/* The same cuts from the particles per column already in cnt (a sum over
 * ranks of their counts), n in all. */
void bf_slabs_cut(bf_slabs *s, size_t n);

/* The columns [*c0, *c1) that rank r reads: its own and its halo. */
static inline void bf_slabs_reads(const bf_slabs *s, int r, int *c0, int *c1)
{
    int a = s->cut[r] - s->hl, b = s->cut[r + 1] + s->hr;
    *c0 = a < 0 ? 0 : a;
    *c1 = b > s->nx ? s->nx : b;
}

#endif
