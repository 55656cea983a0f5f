/* xdmf_rows.h: the rows of a series that a sidecar writes inline, read a
 * block at a time (private to the sidecar writer, src/io/xdmf.c).
 *
 * A sidecar writes the point coordinates of every grid inline, row k,
 * k + s, k + 2s, ... of a [rows x n] series.  Read one by one, that was
 * an open and a read of the dataset per grid (2000 of each for the
 * sidecar of a long ball run, about a tenth of such a run's time); a
 * block holds up to BF_XDMF_ROW_BLOCK_BYTES of those rows, read with one
 * strided hyperslab.  Two blocks, for the x and the y of a point set. */
#ifndef BALLFILM_IO_XDMF_ROWS_H
#define BALLFILM_IO_XDMF_ROWS_H

#include <hdf5.h>
#include <stddef.h>

#define BF_XDMF_ROW_BLOCK_BYTES ((size_t)1 << 20)

typedef struct bf_xdmf_block {
    char *path;       /* the series, or NULL */
    size_t k0, step;  /* rows k0, k0 + step, ... */
    size_t count, n;  /* rows held, values per row */
    double *v;        /* count x n */
} bf_xdmf_block;

typedef struct bf_xdmf_rows {
    bf_xdmf_block b[2]; /* 0: a point set's x, 1: its y */
    size_t step;        /* the stride of the collection being written */
} bf_xdmf_rows;

/* Row k (n values) of the [rows x n] series `path` of h5, read into block
 * `slot` (0 or 1) with the rows after it at the stride r->step; a pointer
 * into the block, valid until the next call for that slot, or NULL when
 * it cannot be read.  The series was checked (h5check.h) for the rows
 * given. */
const double *bf_xdmf_row(bf_xdmf_rows *r, int slot, hid_t h5,
                          const char *path, size_t k, size_t n, size_t rows);
void bf_xdmf_rows_free(bf_xdmf_rows *r);

#endif
