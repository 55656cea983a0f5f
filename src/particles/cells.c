/* cells.c: cell list by stable counting sort (see cells.h). */
#include "cells.h"

#include <stdlib.h>
#include <string.h>

bf_status bf_cells_init(bf_cells *c, double x0, double y0, double w,
                        double hgt, double h, size_t cap, bf_err *err)
{
    memset(c, 0, sizeof *c);
    if (!(w > 0 && hgt > 0 && h > 0))
        return bf_fail(err, BF_EINTERNAL, "cell list: bad geometry");
    double fx = floor(w / h), fy = floor(hgt / h);
    if (fx < 1)
        fx = 1;
    if (fy < 1)
        fy = 1;
    if (fx * fy > 1e8)
        return bf_fail(err, BF_EINPUT,
                       "cell list: %.0f x %.0f cells is too many (cell side %g "
                       "in a %g x %g box)",
                       fx, fy, h, w, hgt);
    c->nx = (int)fx;
    c->ny = (int)fy;
    /* cells at least h wide: the grid covers the box exactly */
    c->h = fmax(w / fx, hgt / fy);
    c->inv_h = 1.0 / c->h;
    c->x0 = x0;
    c->y0 = y0;
    size_t nc = (size_t)c->nx * (size_t)c->ny, k = cap ? cap : 1;
    c->cap = cap;
    c->start = calloc(nc + 1, sizeof *c->start);
    c->idx = malloc(k * sizeof *c->idx);
    c->cell = malloc(k * sizeof *c->cell);
    c->slot = malloc(k * sizeof *c->slot);
    c->sx = malloc(k * sizeof *c->sx);
    c->sy = malloc(k * sizeof *c->sy);
    c->sw = malloc(k * sizeof *c->sw);
    if (!c->start || !c->idx || !c->cell || !c->slot || !c->sx || !c->sy || !c->sw) {
        bf_cells_free(c);
        return bf_fail(err, BF_EINTERNAL, "out of memory (cell list)");
    }
    return BF_OK;
}

void bf_cells_free(bf_cells *c)
{
    free(c->start);
    free(c->idx);
    free(c->cell);
    free(c->slot);
    free(c->sx);
    free(c->sy);
    free(c->sw);
    memset(c, 0, sizeof *c);
}

void bf_cells_build(bf_cells *c, const double *x, const double *y,
                    const double *w, size_t n)
{
    const size_t nc = (size_t)c->nx * (size_t)c->ny;
    uint32_t *start = c->start;
    c->n = n;
    memset(start, 0, (nc + 1) * sizeof *start);
    for (size_t i = 0; i < n; i++) {
        uint32_t k = (uint32_t)bf_cells_col(c, x[i]) * (uint32_t)c->ny +
                     (uint32_t)bf_cells_row(c, y[i]);
        c->cell[i] = k;
        start[k + 1]++;
    }
    for (size_t k = 0; k < nc; k++)
        start[k + 1] += start[k];
    /* stable scatter of the indices: use start[k] as the running write
     * position, then shift back; then the positions gathered in slot
     * order (one scattered store per particle instead of four: the
     * gathers' loads overlap, scattered stores to arrays larger than the
     * cache do not) */
    for (size_t i = 0; i < n; i++) {
        uint32_t s = start[c->cell[i]]++;
        c->idx[s] = (uint32_t)i;
        c->slot[i] = s;
    }
    for (size_t s = 0; s < n; s++) {
        const uint32_t i = c->idx[s];
        c->sx[s] = x[i];
        c->sy[s] = y[i];
    }
    if (w)
        for (size_t s = 0; s < n; s++)
            c->sw[s] = w[c->idx[s]];
    for (size_t k = nc; k > 0; k--)
        start[k] = start[k - 1];
    start[0] = 0;
}
