/* xdmf_rows.c: rows of a series read a block at a time (see xdmf_rows.h). */
#include "io/xdmf_rows.h"

#include <stdlib.h>
#include <string.h>

static int holds(const bf_xdmf_block *b, const char *path, size_t k,
                 size_t n)
{
    return b->path && !strcmp(b->path, path) && b->n == n && k >= b->k0 &&
           (k - b->k0) % b->step == 0 && (k - b->k0) / b->step < b->count;
}

static void drop(bf_xdmf_block *b)
{
    free(b->path);
    free(b->v);
    memset(b, 0, sizeof *b);
}

/* Rows k, k + step, ... (at most what the block may hold, and no row past
 * rows - 1) into b with one read. */
static int load(bf_xdmf_block *b, hid_t h5, const char *path, size_t k,
                size_t n, size_t rows, size_t step)
{
    drop(b);
    size_t most = BF_XDMF_ROW_BLOCK_BYTES / ((n ? n : 1) * sizeof(double));
    size_t count = (rows - 1 - k) / step + 1;
    if (count > most)
        count = most ? most : 1;
    b->v = malloc(count * (n ? n : 1) * sizeof *b->v);
    b->path = strdup(path);
    hid_t id = b->v && b->path ? H5Dopen2(h5, path, H5P_DEFAULT) : -1;
    if (id < 0) {
        drop(b);
        return -1;
    }
    hid_t fsp = H5Dget_space(id);
    hsize_t start[2] = {k, 0}, stride[2] = {step, 1}, cnt[2] = {count, n};
    herr_t rc = H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, stride, cnt,
                                    NULL);
    hid_t msp = H5Screate_simple(2, cnt, NULL);
    if (rc >= 0 && n)
        rc = H5Dread(id, H5T_NATIVE_DOUBLE, msp, fsp, H5P_DEFAULT, b->v);
    H5Sclose(msp);
    H5Sclose(fsp);
    H5Dclose(id);
    if (rc < 0) {
        drop(b);
        return -1;
    }
    b->k0 = k;
    b->step = step;
    b->count = count;
    b->n = n;
    return 0;
}

const double *bf_xdmf_row(bf_xdmf_rows *r, int slot, hid_t h5,
                          const char *path, size_t k, size_t n, size_t rows)
{
    const size_t step = r->step ? r->step : 1;
    if (slot < 0 || slot > 1 || k >= rows)
        return NULL;
    bf_xdmf_block *b = &r->b[slot];
    if (!holds(b, path, k, n) && load(b, h5, path, k, n, rows, step))
        return NULL;
    return b->v + (k - b->k0) / b->step * n;
}

void bf_xdmf_rows_free(bf_xdmf_rows *r)
{
    drop(&r->b[0]);
    drop(&r->b[1]);
}
