/* h5swmr.c: an output file in HDF5's SWMR mode while its run steps (see
 * h5out.h, bf_out_start_appending).
 *
 * Why.  Outside SWMR mode HDF5 writes the metadata of a flush (the
 * datasets' lengths, their chunk indices, the superblock's end of the
 * allocated space) in no fixed order.  A kill among those writes left, at
 * about a third of the writes of a flush (tests/killwrite.c, preloaded
 * into a run, kills it at a chosen write): files that did not open ("addr
 * overflow": the superblock's end of file older than objects it points
 * to), or datasets of different lengths, whose last rows read as zeros (a
 * length that reached the disk before its chunk's index entry).  In SWMR
 * mode HDF5 orders these writes (a chunk index after the chunks, an
 * object's length after its index) so that every state on disk is a file
 * that opens.
 *
 * How.  bf_out_start_appending marks the end of set-up; once the run has
 * stepped SWMR_AFTER, bf_out_maybe_flush calls bf_out_enter_swmr_: a
 * complete flush, the flush log of h5part.h created (a dataset may not be
 * created in SWMR mode), H5Fstart_swmr_write.  From then on each flush,
 * once its H5Fflush has returned (the kernel holds every write of it, and
 * a kill loses none), appends its row to the log and flushes again;
 * readers take the rows of the last complete row, so that every series
 * ends at the same flush.  Writing anything other than rows (an attribute,
 * an array, a new series or a shorter one) calls bf_out_before_metadata_,
 * which closes the file and opens it again without SWMR.  A run's end
 * (its status and counters) is therefore written outside SWMR mode, as
 * set-up is, and a kill there is not covered (docs/reliability.md).  SWMR
 * mode needs HDF5's 1.10 file format (superblock 3, bf_out_fapl_). */
#include "base/clock.h"
#include "h5out_impl.h"
#include "h5part.h"

#include <stdlib.h>
#include <string.h>

void bf_out_close_series_(bf_out *out)
{
    for (size_t k = 0; k < out->nseries; k++) {
        H5Dclose(out->series[k]->dset);
        out->series[k]->dset = -1;
    }
}

/* Every series' dataset opened again with its chunk cache
 * (bf_out_series_dapl_); 0, or -1 if one does not open. */
static int series_open_all(bf_out *out)
{
    int rc = 0;
    for (size_t k = 0; k < out->nseries; k++) {
        bf_series *s = out->series[k];
        hid_t dapl = bf_out_series_dapl_(s->rpc, s->ncols);
        s->dset = H5Dopen2(out->file, s->path, dapl);
        H5Pclose(dapl);
        if (s->dset < 0)
            rc = -1;
    }
    return rc;
}

/* After a flush has reached the file (its H5Fflush returned: a kill no
 * longer loses a write of it), its row of the log (h5part.h): its number
 * and the rows of every series. */
bf_status bf_out_log_flush_(bf_out *out, bf_err *err)
{
    size_t w = out->nseries + 1;
    int64_t *row = malloc(w * sizeof *row);
    if (!row)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    row[0] = out->flushes + 1;
    for (size_t k = 0; k < out->nseries; k++)
        row[k + 1] = (int64_t)out->series[k]->written;
    hsize_t dims[2] = {(hsize_t)out->flushes + 1, w};
    herr_t rc = H5Dset_extent(out->log, dims);
    if (rc >= 0) {
        hid_t fsp = H5Dget_space(out->log);
        hsize_t start[2] = {(hsize_t)out->flushes, 0}, count[2] = {1, w};
        H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, count, NULL);
        hid_t msp = H5Screate_simple(2, count, NULL);
        rc = H5Dwrite(out->log, H5T_NATIVE_INT64, msp, fsp, H5P_DEFAULT, row);
        H5Sclose(msp);
        H5Sclose(fsp);
    }
    free(row);
    if (rc < 0 || H5Fflush(out->file, H5F_SCOPE_GLOBAL) < 0)
        return bf_fail(err, BF_EIO, "%s: writing the flush log failed (disk "
                       "full?)", out->path);
    out->flushes++;
    return BF_OK;
}

/* The log's attribute "series": the paths of the series, one per line. */
static char *series_paths(const bf_out *out)
{
    size_t len = 1;
    for (size_t k = 0; k < out->nseries; k++)
        len += strlen(out->series[k]->path) + 1;
    char *text = malloc(len), *p = text;
    if (!text)
        return NULL;
    for (size_t k = 0; k < out->nseries; k++) {
        size_t n = strlen(out->series[k]->path);
        memcpy(p, out->series[k]->path, n);
        p[n] = '\n';
        p += n + 1;
    }
    *p = '\0';
    return text;
}

/* Into SWMR mode (see the top), after a complete flush, with the log of
 * these series (created, or the one the file has).  A file that cannot
 * enter it (one of an older format, continued by this version) stays as
 * it was and is written as before. */
bf_status bf_out_enter_swmr_(bf_out *out, bf_err *err)
{
    bf_status st = bf_out_flush(out, err);
    if (st)
        return st;
    size_t w = out->nseries + 1;
    /* a log of the same series (this writer's, left by bf_out_leave_swmr_,
     * or that of the killed run this one continues) goes on: its rows stay
     * valid, rows are only added to a series; another one goes */
    out->flushes = 0;
    if (H5Lexists(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT) > 0) {
        hid_t log = H5Dopen2(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT);
        hid_t sp = log >= 0 ? H5Dget_space(log) : -1;
        hsize_t have[2] = {0, 0};
        if (sp >= 0 && H5Sget_simple_extent_ndims(sp) == 2)
            H5Sget_simple_extent_dims(sp, have, NULL);
        if (sp >= 0)
            H5Sclose(sp);
        if (have[1] == w) {
            out->log = log;
            out->flushes = (int64_t)have[0];
        } else {
            if (log >= 0)
                H5Dclose(log);
            H5Ldelete(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT);
        }
    }
    if (out->log >= 0)
        goto start;
    hsize_t dims[2] = {0, w}, maxdims[2] = {H5S_UNLIMITED, w},
            chunk[2] = {64, w};
    hid_t sp = H5Screate_simple(2, dims, maxdims);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 2, chunk);
    out->log = H5Dcreate2(out->file, BF_H5_FLUSH_LOG, H5T_STD_I64LE, sp,
                          H5P_DEFAULT, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Sclose(sp);
    char *paths = series_paths(out);
    if (out->log < 0 || !paths ||
        bf_out_str_attr_(out->log, "series", paths) ||
        bf_out_str_attr_(out->log, "unit", "1") ||
        bf_out_str_attr_(out->log, "description",
                         "while the run is written: row g holds g and the "
                         "rows of every series (attribute series, one path "
                         "a line) that flush g had written when it reached "
                         "the file; a reader of a killed run's file takes "
                         "the last row whose first value is its number; "
                         "deleted when the run ends") ||
        H5Fflush(out->file, H5F_SCOPE_GLOBAL) < 0) {
        free(paths);
        out->failed = 1;
        return bf_fail(err, BF_EIO, "%s: cannot write the flush log (disk "
                       "full?)", out->path);
    }
    free(paths);
start:
    out->dirty = 1; /* the log's dataset or its deletion, until flushed */
    /* SWMR mode wants no open object but datasets; and it gives the open
     * datasets HDF5's default chunk cache (1 MiB each, which made the
     * memory of a run grow with its length), so they are opened again
     * with theirs */
    if (out->root >= 0)
        H5Oclose(out->root);
    out->root = -1;
    bf_out_close_series_(out);
    herr_t rc = H5Fstart_swmr_write(out->file);
    if (series_open_all(out) < 0) {
        out->failed = 1;
        return bf_fail(err, BF_EIO, "%s: cannot open the datasets of %s "
                       "again", out->path, out->part);
    }
    if (rc < 0) {
        H5Dclose(out->log);
        out->log = -1;
        H5Ldelete(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT);
        out->root = H5Oopen(out->file, "/", H5P_DEFAULT);
        out->appending = 0; /* not again */
        return BF_OK;
    }
    out->swmr = 1;
    return BF_OK;
}

bf_status bf_out_before_metadata_(bf_out *out, bf_err *err)
{
    if (out->swmr && bf_out_leave_swmr_(out, err))
        return BF_EIO;
    out->dirty = 1;
    return BF_OK;
}

/* Out of SWMR mode, to write what it does not allow (an attribute, an
 * array, a new series, a shorter series): the rows flushed, the file
 * closed and opened again.  The log stays until the run ends (finish):
 * a kill before that leaves a file whose readers take the rows of the
 * last flush in SWMR mode. */
bf_status bf_out_leave_swmr_(bf_out *out, bf_err *err)
{
    bf_status st = bf_out_flush(out, err);
    if (st)
        return st;
    out->swmr = 0;
    /* SWMR mode again only once the run has stepped as long as at its
     * start: a library user who writes an attribute every few rows does
     * not close and open the file at every flush */
    out->appending_since = bf_coarse_time();
    H5Dclose(out->log);
    out->log = -1;
    bf_out_close_series_(out);
    herr_t rc = H5Fclose(out->file);
    hid_t fapl = bf_out_fapl_(0);
    out->file = rc < 0 ? -1 : H5Fopen(out->h5name, H5F_ACC_RDWR, fapl);
    H5Pclose(fapl);
    if (out->file >= 0) {
        rc = series_open_all(out);
        out->root = H5Oopen(out->file, "/", H5P_DEFAULT);
    }
    if (out->file < 0 || rc < 0 || out->root < 0) {
        out->failed = 1;
        return bf_fail(err, BF_EIO, "%s: cannot open %s again after its "
                       "rows were written", out->path, out->part);
    }
    return BF_OK;
}

