/* h5part.c: reading a run's file while it is written or after a kill (see
 * h5part.h). */
#include "io/h5part.h"
#include "io/h5check.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct bf_h5_flushed {
    size_t n;
    char **path;
    hsize_t *rows;
};

int bf_h5_fapl_past_mark(hid_t fapl)
{
    hbool_t past = 1;
    return H5Pexist(fapl, "clear_status_flags") > 0 &&
                   H5Pset(fapl, "clear_status_flags", &past) >= 0
               ? 0
               : -1;
}

hid_t bf_h5_open_read(const char *file)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0)
        f = H5Fopen(file, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
    if (f < 0) {
        /* a file whose writer was killed outside SWMR mode keeps HDF5's
         * open-for-writing mark: read it as it is, past the mark (the
         * property that `h5clear -s` sets; on a read-only open it leaves
         * the mark in the file) */
        hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
        if (!bf_h5_fapl_past_mark(fapl))
            f = H5Fopen(file, H5F_ACC_RDONLY, fapl);
        H5Pclose(fapl);
    }
    return f;
}

const char *bf_h5_open_hint(const char *file)
{
    static _Thread_local char hint[4200];
    unsigned char sb[12];
    FILE *f = fopen(file, "rb");
    size_t got = f ? fread(sb, 1, sizeof sb, f) : 0;
    if (f)
        fclose(f);
    /* a superblock of version 2 or 3 at the start: its byte 11 holds the
     * file consistency flags (0x01 open for writing, 0x04 by a SWMR
     * writer); version 0 and 1 have none */
    if (got < sizeof sb || memcmp(sb, "\211HDF\r\n\032\n", 8) || sb[8] < 2 ||
        !(sb[11] & 0x05))
        return "";
    snprintf(hint, sizeof hint, " (HDF5 marks it as open for writing, and "
             "it does not open past the mark either: its writer was killed "
             "in the middle of writing it, outside SWMR mode; `h5clear -s "
             "%s` clears the mark)", file);
    return hint;
}

void bf_h5_flushed_free(bf_h5_flushed *fl)
{
    if (!fl)
        return;
    for (size_t k = 0; k < fl->n; k++)
        free(fl->path[k]);
    free(fl->path);
    free(fl->rows);
    free(fl);
}

/* The log's last complete row (see h5part.h) into a new bf_h5_flushed,
 * with the series named, one per line, in text. */
static bf_h5_flushed *flushed_of(const int64_t *row, size_t width,
                                 const char *text)
{
    bf_h5_flushed *fl = calloc(1, sizeof *fl);
    if (!fl || !(fl->path = calloc(width, sizeof *fl->path)) ||
        !(fl->rows = calloc(width, sizeof *fl->rows))) {
        bf_h5_flushed_free(fl);
        return NULL;
    }
    const char *line = text;
    for (size_t k = 0; k + 1 < width && line && *line; k++) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        fl->path[fl->n] = malloc(len + 1);
        if (!fl->path[fl->n])
            break;
        memcpy(fl->path[fl->n], line, len);
        fl->path[fl->n][len] = '\0';
        fl->rows[fl->n] = row[k + 1] > 0 ? (hsize_t)row[k + 1] : 0;
        fl->n++;
        line = end ? end + 1 : NULL;
    }
    return fl;
}

bf_status bf_h5_flushed_load(hid_t f, const char *file, bf_h5_flushed **out,
                             bf_err *err)
{
    *out = NULL;
    if (H5Lexists(f, BF_H5_FLUSH_LOG, H5P_DEFAULT) <= 0)
        return BF_OK;
    hid_t log = H5Dopen2(f, BF_H5_FLUSH_LOG, H5P_DEFAULT);
    if (log < 0)
        return bf_fail(err, BF_EINPUT, "%s: %s is not a dataset", file,
                       BF_H5_FLUSH_LOG);
    hsize_t dims[2];
    int rank = 0;
    size_t count = 0;
    char *text = NULL;
    int64_t *v = NULL;
    hid_t t = H5Dget_type(log);
    int integer = t >= 0 && H5Tget_class(t) == H5T_INTEGER;
    if (t >= 0)
        H5Tclose(t);
    bf_status st = bf_h5_dataset_shape(log, file, BF_H5_FLUSH_LOG, &rank,
                                       dims, err);
    if (!st && (rank != 2 || dims[1] < 1 || !integer))
        st = bf_fail(err, BF_EINPUT, "%s: %s is not a table of integers "
                     "(damaged, or not a ballfilm file)", file,
                     BF_H5_FLUSH_LOG);
    if (!st)
        st = bf_h5_dataset_fits(log, file, BF_H5_FLUSH_LOG, dims[0], dims[1],
                                bf_h5_file_bytes(file), &count, err);
    /* a log without rows (a kill before its first flush) may not have
     * its attribute yet */
    if (!st && count) {
        hid_t a = H5Aopen(log, "series", H5P_DEFAULT);
        st = a < 0 ? bf_fail(err, BF_EINPUT, "%s: %s names no series", file,
                             BF_H5_FLUSH_LOG)
                   : bf_h5_attr_string(a, file, BF_H5_FLUSH_LOG, "series",
                                       &text, err);
        if (a >= 0)
            H5Aclose(a);
    }
    if (!st && count && !(v = malloc(count * sizeof *v)))
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st && count && H5Dread(log, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL,
                                H5P_DEFAULT, v) < 0)
        st = bf_fail(err, BF_EIO, "%s: cannot read %s", file,
                     BF_H5_FLUSH_LOG);
    if (!st && count) {
        /* the last row that was written whole: its first value is its
         * number */
        size_t width = (size_t)dims[1], r = (size_t)dims[0];
        while (r > 0 && v[(r - 1) * width] != (int64_t)r)
            r--;
        if (r && !(*out = flushed_of(v + (r - 1) * width, width, text)))
            st = bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    free(v);
    free(text);
    H5Dclose(log);
    return st;
}

bf_status bf_h5_dataset_rows(hid_t d, const char *file, const char *path,
                             const bf_h5_flushed *fl, double file_bytes,
                             int *rank, hsize_t dims[2], size_t *count,
                             bf_err *err)
{
    size_t own;
    bf_status st = bf_h5_dataset_shape(d, file, path, rank, dims, err);
    if (st)
        return st;
    dims[0] = bf_h5_flushed_rows(fl, path, dims[0]);
    return bf_h5_dataset_fits(d, file, path, dims[0],
                              *rank == 2 ? dims[1] : 1, file_bytes,
                              count ? count : &own, err);
}

hsize_t bf_h5_flushed_rows(const bf_h5_flushed *fl, const char *path,
                           hsize_t extent)
{
    if (!fl)
        return extent;
    const char *p = path[0] == '/' ? path + 1 : path;
    for (size_t k = 0; k < fl->n; k++) {
        const char *q = fl->path[k][0] == '/' ? fl->path[k] + 1 : fl->path[k];
        if (!strcmp(p, q))
            return fl->rows[k] < extent ? fl->rows[k] : extent;
    }
    return extent;
}
