/* h5part.c: reading a run's file while it is written or after a kill (see
 * h5part.h). */
#include "io/h5part.h"

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

char *bf_h5_attr_text(hid_t loc, const char *obj, const char *name)
{
    hid_t a = H5Aopen_by_name(loc, obj, name, H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0)
        return NULL;
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    char *v = NULL, *copy = NULL;
    if (H5Aread(a, t, &v) >= 0 && v) {
        copy = strdup(v);
        H5free_memory(v);
    }
    H5Tclose(t);
    H5Aclose(a);
    return copy;
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

bf_h5_flushed *bf_h5_flushed_load(hid_t f)
{
    if (H5Lexists(f, BF_H5_FLUSH_LOG, H5P_DEFAULT) <= 0)
        return NULL;
    hid_t log = H5Dopen2(f, BF_H5_FLUSH_LOG, H5P_DEFAULT);
    if (log < 0)
        return NULL;
    hid_t sp = H5Dget_space(log);
    hsize_t dims[2] = {0, 0};
    int rank = H5Sget_simple_extent_ndims(sp);
    if (rank == 2)
        H5Sget_simple_extent_dims(sp, dims, NULL);
    H5Sclose(sp);
    char *text = bf_h5_attr_text(log, ".", "series");
    int64_t *v = NULL;
    bf_h5_flushed *fl = NULL;
    size_t width = (size_t)dims[1], nrows = (size_t)dims[0];
    if (rank != 2 || width < 1 || !nrows || !text)
        goto done;
    v = malloc(nrows * width * sizeof *v);
    if (!v || H5Dread(log, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                      v) < 0)
        goto done;
    /* the last row that was written whole: its first value is its number */
    size_t r = nrows;
    while (r > 0 && v[(r - 1) * width] != (int64_t)r)
        r--;
    if (!r)
        goto done;
    const int64_t *row = v + (r - 1) * width;
    fl = calloc(1, sizeof *fl);
    if (!fl || !(fl->path = calloc(width, sizeof *fl->path)) ||
        !(fl->rows = calloc(width, sizeof *fl->rows))) {
        bf_h5_flushed_free(fl);
        fl = NULL;
        goto done;
    }
    char *line = text;
    for (size_t k = 0; k + 1 < width && line && *line; k++) {
        char *end = strchr(line, '\n');
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
done:
    free(v);
    free(text);
    H5Dclose(log);
    return fl;
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
