/* h5info.c: what an HDF5 file holds, without h5dump: every dataset with
 * its shape, type, unit and description (h5out.h, bf_h5_list; the
 * program's `ballfilm info`). */
#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "io/h5part.h"

typedef struct lister {
    bf_h5_dataset *list;
    size_t n, cap;
    int oom;
    bf_h5_flushed *flushed; /* a run's .part: rows of its last flush */
} lister;

/* A string attribute of object `obj` (fixed or variable length) into
 * buf; "" when it has none. */
static void attr_text(hid_t obj, const char *name, char *buf, size_t cap)
{
    buf[0] = '\0';
    if (H5Aexists(obj, name) <= 0)
        return;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    hid_t ft = a < 0 ? -1 : H5Aget_type(a);
    if (ft >= 0 && H5Tget_class(ft) == H5T_STRING) {
        hid_t t = H5Tcopy(H5T_C_S1);
        if (H5Tis_variable_str(ft) > 0) {
            char *v = NULL;
            H5Tset_size(t, H5T_VARIABLE);
            H5Tset_cset(t, H5Tget_cset(ft));
            if (H5Aread(a, t, &v) >= 0 && v) {
                snprintf(buf, cap, "%s", v);
                H5free_memory(v);
            }
        } else {
            size_t len = H5Tget_size(ft);
            char *v = calloc(len + 1, 1);
            H5Tset_size(t, len + 1);
            if (v && H5Aread(a, t, v) >= 0)
                snprintf(buf, cap, "%s", v);
            free(v);
        }
        H5Tclose(t);
    }
    if (ft >= 0)
        H5Tclose(ft);
    if (a >= 0)
        H5Aclose(a);
}

static herr_t visit(hid_t root, const char *name, const H5O_info_t *info,
                    void *ctx)
{
    lister *l = ctx;
    /* the flush log of a run still written (h5part.h) is not its data */
    if (info->type != H5O_TYPE_DATASET || !strcmp(name, BF_H5_FLUSH_LOG + 1))
        return 0;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        bf_h5_dataset *nl = realloc(l->list, cap * sizeof *nl);
        if (!nl) {
            l->oom = 1;
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
    attr_text(ds, "unit", d->unit, sizeof d->unit);
    attr_text(ds, "description", d->description, sizeof d->description);
    H5Tclose(ty);
    H5Sclose(sp);
    H5Dclose(ds);
    l->n++;
    return 0;
}

static int by_path(const void *a, const void *b)
{
    return strcmp(((const bf_h5_dataset *)a)->path,
                  ((const bf_h5_dataset *)b)->path);
}

bf_status bf_h5_list(const char *file, bf_h5_dataset **list, size_t *n,
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
    l.flushed = bf_h5_flushed_load(f);
    herr_t r = H5Ovisit(f, H5_INDEX_NAME, H5_ITER_NATIVE, visit, &l);
    bf_h5_flushed_free(l.flushed);
    H5Fclose(f);
    if (l.oom || r < 0) {
        free(l.list);
        return l.oom ? bf_fail(err, BF_EINTERNAL, "out of memory")
                     : bf_fail(err, BF_EIO, "%s: cannot list its datasets",
                               file);
    }
    qsort(l.list, l.n, sizeof *l.list, by_path);
    *list = l.list;
    *n = l.n;
    return BF_OK;
}
