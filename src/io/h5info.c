/* h5info.c: what an HDF5 file holds, without h5dump: every dataset with
 * its shape, type, unit and description (h5out.h, bf_h5_list; the
 * program's `ballfilm info`). */
#include <hdf5.h>
#include <signal.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "io/h5check.h"
#include "io/h5part.h"

typedef struct lister {
    bf_h5_dataset *list;
    size_t n, cap;
    bf_h5_flushed *flushed; /* a run's .part: rows of its last flush */
    const char *file;       /* for messages */
    bf_err *err;
    bf_status st;           /* why the listing stopped */
    const volatile sig_atomic_t *stop_flag;
} lister;

/* The string attribute `name` of dataset `obj` (fixed or variable length,
 * checked as h5check.h says) into buf; "" when it has none.  One that is
 * there but cannot be read is an error, not an absent attribute. */
static bf_status attr_text(hid_t obj, const char *file, const char *path,
                           const char *name, char *buf, size_t cap,
                           bf_err *err)
{
    buf[0] = '\0';
    htri_t e = H5Aexists(obj, name);
    if (e < 0)
        return bf_fail(err, BF_EIO, "%s: cannot look up attribute %s of %s",
                       file, name, path);
    if (!e)
        return BF_OK;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0)
        return bf_fail(err, BF_EIO, "%s: cannot open attribute %s of %s",
                       file, name, path);
    char *v = NULL;
    bf_status st = bf_h5_attr_string(a, file, path, name, &v, err);
    H5Aclose(a);
    if (!st)
        snprintf(buf, cap, "%s", v);
    free(v);
    return st;
}

static herr_t visit(hid_t root, const char *name, const H5O_info_t *info,
                    void *ctx)
{
    lister *l = ctx;
    /* the flush log of a run still written (h5part.h) is not its data */
    if (l->stop_flag && *l->stop_flag) {
        l->st = bf_fail(l->err, BF_INTERRUPTED, "%s: interrupted", l->file);
        return 1;
    }
    if (info->type != H5O_TYPE_DATASET || !strcmp(name, BF_H5_FLUSH_LOG + 1))
        return 0;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        bf_h5_dataset *nl = realloc(l->list, cap * sizeof *nl);
        if (!nl) {
            l->st = bf_fail(l->err, BF_EINTERNAL, "out of memory");
            return 1;
        }
        l->list = nl;
        l->cap = cap;
    }
    bf_h5_dataset *d = &l->list[l->n];
    memset(d, 0, sizeof *d);
    snprintf(d->path, sizeof d->path, "/%s", name);
    hid_t ds = H5Dopen2(root, name, H5P_DEFAULT);
    if (ds < 0)
        return 0;
    hid_t sp = H5Dget_space(ds), ty = H5Dget_type(ds);
    int rank = H5Sget_simple_extent_ndims(sp);
    hsize_t dims[H5S_MAX_RANK] = {0};
    H5Sget_simple_extent_dims(sp, dims, NULL);
    d->rank = rank;
    if (rank >= 1)
        dims[0] = bf_h5_flushed_rows(l->flushed, name, dims[0]);
    for (int k = 0; k < rank && k < 2; k++)
        d->dims[k] = (size_t)dims[k];
    H5T_class_t c = H5Tget_class(ty);
    d->kind = c == H5T_INTEGER ? 'i' : c == H5T_FLOAT ? 'f'
              : c == H5T_STRING ? 's' : '?';
    l->st = attr_text(ds, l->file, d->path, "unit", d->unit, sizeof d->unit,
                      l->err);
    /* the attributes of its series spec (series.h) */
    static const struct {
        const char *name;
        size_t off, cap;
    } text[] = {
        {"description", offsetof(bf_h5_dataset, description),
         sizeof d->description},
        {"kind", offsetof(bf_h5_dataset, series_kind), sizeof d->series_kind},
        {"role", offsetof(bf_h5_dataset, role), sizeof d->role},
    };
    for (size_t k = 0; k < sizeof text / sizeof *text && !l->st; k++)
        l->st = attr_text(ds, l->file, d->path, text[k].name,
                          (char *)d + text[k].off, text[k].cap, l->err);
    H5Tclose(ty);
    H5Sclose(sp);
    H5Dclose(ds);
    l->n++;
    return l->st ? 1 : 0;
}

static int by_path(const void *a, const void *b)
{
    return strcmp(((const bf_h5_dataset *)a)->path,
                  ((const bf_h5_dataset *)b)->path);
}

bf_status bf_h5_list_until(const char *file, bf_h5_dataset **list,
                           size_t *n, const volatile sig_atomic_t *stop_flag,
                           bf_err *err)
{
    *list = NULL;
    *n = 0;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = bf_h5_open_read(file);
    if (f < 0)
        return bf_fail(err, BF_EIO, "%s: cannot open HDF5 file%s", file,
                       bf_h5_open_hint(file));
    lister l = {0};
    l.file = file;
    l.err = err;
    l.stop_flag = stop_flag;
    l.st = bf_h5_flushed_load(f, file, &l.flushed, err);
    herr_t r = l.st ? 0 : H5Ovisit(f, H5_INDEX_NAME, H5_ITER_NATIVE, visit,
                                   &l);
    bf_h5_flushed_free(l.flushed);
    H5Fclose(f);
    if (!l.st && r < 0)
        l.st = bf_fail(err, BF_EINPUT, "%s: cannot list its datasets "
                       "(damaged, or not an HDF5 file of ballfilm)", file);
    if (l.st) {
        free(l.list);
        return l.st;
    }
    qsort(l.list, l.n, sizeof *l.list, by_path);
    *list = l.list;
    *n = l.n;
    return BF_OK;
}

bf_status bf_h5_list(const char *file, bf_h5_dataset **list, size_t *n,
                     bf_err *err)
{
    return bf_h5_list_until(file, list, n, NULL, err);
}
