/* cells.h: cell list (bin sort) for 2-D particles, the neighbour search
 * shared by the particle models (Greenspan 1972 repulsion and support-set
 * gravity; usable by any model with short-range interactions).
 *
 * The rectangle [x0, x0 + nx h] x [y0, y0 + ny h] is cut into square cells
 * of side h, numbered column by column (cell = col ny + row), so that the
 * cells of one column between two rows hold one contiguous run of slots
 * (bf_cells_run): a query over a block of cells is one loop per column.
 * bf_cells_build() sorts the particles by cell with a stable counting sort
 * (so the order inside a cell is the index order, and every traversal is
 * deterministic), and copies their positions (and optionally a weight such
 * as the mass) into cell order so that pair loops read contiguous memory.  Particles outside the rectangle are put in the
 * nearest edge cell, which keeps every query correct as long as the query
 * ranges are clamped the same way (bf_cells_col, bf_cells_row).
 *
 * Cost: O(N + cells) per build; no allocation after bf_cells_init.
 * Units: whatever the positions are in (cm in the scenes).
 */
#ifndef BALLFILM_PARTICLES_CELLS_H
#define BALLFILM_PARTICLES_CELLS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"

typedef struct bf_cells {
    double x0, y0;  /* lower-left corner */
    double h, inv_h; /* cell side and its inverse */
    int nx, ny;      /* columns and rows of cells */
    size_t n, cap;   /* particles in the last build, capacity */
    uint32_t *start; /* [nx*ny + 1]: slots of cell k = col ny + row are
                        start[k]..start[k+1]-1 */
    uint32_t *idx;   /* [cap]: particle index of each slot */
    uint32_t *cell;  /* [cap]: cell of each particle (scratch) */
    uint32_t *slot;  /* [cap]: slot of each particle (inverse of idx) */
    double *sx, *sy; /* [cap]: positions in slot order */
    double *sw;      /* [cap]: weights in slot order (if built with one) */
} bf_cells;

/* A grid covering [x0, x0 + w] x [y0, y0 + hgt] with cells of side >= h
 * (the side is enlarged so that whole cells fit; at least one cell each
 * way), for up to `cap` particles. */
bf_status bf_cells_init(bf_cells *c, double x0, double y0, double w,
                        double hgt, double h, size_t cap, bf_err *err);
void bf_cells_free(bf_cells *c);

/* Sort n particles by cell; `w` (may be NULL) is copied into sw. */
void bf_cells_build(bf_cells *c, const double *x, const double *y,
                    const double *w, size_t n);

/* Column / row of a coordinate, clamped to the grid: floor((x - x0)/h)
 * with the reciprocal of h.  The conversion truncates, which is the floor
 * for f >= 0 (smaller f clamp to 0 anyway) and, without SSE4.1's round
 * instruction, far cheaper than floor(). */
static inline int bf_cells_index(double f, int n)
{
    if (!(f > 0.0)) /* also NaN */
        return 0;
    return f >= (double)(n - 1) ? n - 1 : (int)f;
}

static inline int bf_cells_col(const bf_cells *c, double x)
{
    return bf_cells_index((x - c->x0) * c->inv_h, c->nx);
}

static inline int bf_cells_row(const bf_cells *c, double y)
{
    return bf_cells_index((y - c->y0) * c->inv_h, c->ny);
}

/* Slots [*u0, *u1) of the cells of column col, rows r0..r1 (r0 <= r1). */
static inline void bf_cells_run(const bf_cells *c, int col, int r0, int r1,
                                uint32_t *u0, uint32_t *u1)
{
    const uint32_t *st = c->start + (size_t)col * (size_t)c->ny;
    *u0 = st[r0];
    *u1 = st[r1 + 1];
}

#endif
