/* h5read.c: reading back what h5out.c wrote (h5out.h, "reading back"):
 * whole float64 datasets and single attributes, for tests, restarts,
 * initial profiles and sweeps.  Every call opens the file read-only (or
 * reads from a bf_h5_reader, one open for several reads) and reports a
 * missing file, dataset or attribute through err, naming it.  The file of
 * a run still written, or killed, is read as h5part.h says: the rows of
 * its last complete flush.  Nothing is read before its class, shape and
 * size are checked (h5check.h). */
#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "io/h5check.h"
#include "io/h5part.h"

struct bf_h5_reader {
    hid_t file;
    char *name; /* for messages */
    double bytes; /* its size on disk: what its datasets can hold */
    bf_h5_flushed *flushed; /* rows of the last flush of a run's .part */
};

bf_status bf_h5_reader_open(bf_h5_reader **r, const char *file, bf_err *err)
{
    /* errors are reported through err, naming the file and the object,
     * not printed by HDF5 (as in h5out.c, xdmf.c and checkpoint.c) */
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    *r = calloc(1, sizeof **r);
    if (!*r || !((*r)->name = strdup(file))) {
        free(*r);
        *r = NULL;
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    (*r)->file = bf_h5_open_read(file);
    if ((*r)->file < 0) {
        bf_h5_reader_close(*r);
        *r = NULL;
        return bf_fail(err, BF_EIO, "%s: cannot open HDF5 file%s", file,
                       bf_h5_open_hint(file));
    }
    (*r)->bytes = bf_h5_file_bytes(file);
    bf_status st = bf_h5_flushed_load((*r)->file, file, &(*r)->flushed, err);
    if (st) {
        bf_h5_reader_close(*r);
        *r = NULL;
    }
    return st;
}

void bf_h5_reader_close(bf_h5_reader *r)
{
    if (!r)
        return;
    if (r->file >= 0)
        H5Fclose(r->file);
    bf_h5_flushed_free(r->flushed);
    free(r->name);
    free(r);
}

bf_status bf_h5_reader_read(bf_h5_reader *r, const char *path, double **data,
                            size_t *n0, size_t *n1, bf_err *err)
{
    const char *file = r->name;
    *data = NULL;
    hid_t d = H5Dopen2(r->file, path, H5P_DEFAULT);
    if (d < 0)
        return bf_fail(err, BF_EIO, "%s: no dataset %s", file, path);
    int rank = 0;
    hsize_t dims[2];
    size_t total = 0;
    /* the rows of the last complete flush (h5part.h) */
    bf_status st = bf_h5_dataset_rows(d, file, path, r->flushed, r->bytes,
                                      &rank, dims, &total, err);
    double *buf = NULL;
    if (!st && !(buf = malloc((total ? total : 1) * sizeof *buf)))
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st && total) {
        hid_t sp = H5Dget_space(d);
        hsize_t start[2] = {0, 0}, count[2] = {dims[0], dims[1]};
        hid_t msp = H5Screate_simple(rank, count, NULL);
        if (sp < 0 || msp < 0 ||
            H5Sselect_hyperslab(sp, H5S_SELECT_SET, start, NULL, count,
                                NULL) < 0 ||
            H5Dread(d, H5T_NATIVE_DOUBLE, msp, sp, H5P_DEFAULT, buf) < 0)
            st = bf_fail(err, BF_EIO, "%s: cannot read %s", file, path);
        if (msp >= 0)
            H5Sclose(msp);
        if (sp >= 0)
            H5Sclose(sp);
    }
    if (st) {
        free(buf);
    } else {
        *data = buf;
        *n0 = (size_t)dims[0];
        *n1 = rank == 2 ? (size_t)dims[1] : 0;
    }
    H5Dclose(d);
    return st;
}

bf_status bf_h5_reader_attr_real(bf_h5_reader *r, const char *obj,
                                 const char *name, double *value, bf_err *err)
{
    hid_t a = H5Aexists_by_name(r->file, obj, name, H5P_DEFAULT) > 0
                  ? H5Aopen_by_name(r->file, obj, name, H5P_DEFAULT,
                                    H5P_DEFAULT)
                  : -1;
    if (a < 0)
        return bf_fail(err, BF_EIO, "%s: no numeric attribute %s on %s",
                       r->name, name, obj);
    bf_status st = bf_h5_attr_number(a, r->name, obj, name, value, err);
    H5Aclose(a);
    return st;
}

int bf_h5_reader_has_attr(bf_h5_reader *r, const char *obj, const char *name,
                          bf_err *err)
{
    htri_t e = H5Aexists_by_name(r->file, obj, name, H5P_DEFAULT);
    if (e < 0)
        bf_fail(err, BF_EIO, "%s: cannot look up attribute %s of %s",
                r->name, name, obj);
    return e < 0 ? -1 : e > 0;
}

bf_status bf_h5_reader_attr_str(bf_h5_reader *r, const char *obj,
                                const char *name, char **value, bf_err *err)
{
    *value = NULL;
    hid_t a = H5Aexists_by_name(r->file, obj, name, H5P_DEFAULT) > 0
                  ? H5Aopen_by_name(r->file, obj, name, H5P_DEFAULT,
                                    H5P_DEFAULT)
                  : -1;
    if (a < 0)
        return bf_fail(err, BF_EIO, "%s: no attribute %s on %s", r->name,
                       name, obj);
    bf_status st = bf_h5_attr_string(a, r->name, obj, name, value, err);
    H5Aclose(a);
    return st;
}

bf_status bf_h5_read(const char *file, const char *path, double **data,
                     size_t *n0, size_t *n1, bf_err *err)
{
    bf_h5_reader *r;
    *data = NULL;
    bf_status st = bf_h5_reader_open(&r, file, err);
    if (st)
        return st;
    st = bf_h5_reader_read(r, path, data, n0, n1, err);
    bf_h5_reader_close(r);
    return st;
}

bf_status bf_h5_read_attr_real(const char *file, const char *obj,
                               const char *name, double *value, bf_err *err)
{
    bf_h5_reader *r;
    bf_status st = bf_h5_reader_open(&r, file, err);
    if (st)
        return st;
    st = bf_h5_reader_attr_real(r, obj, name, value, err);
    bf_h5_reader_close(r);
    return st;
}

bf_status bf_h5_read_attr_str(const char *file, const char *obj,
                              const char *name, char **value, bf_err *err)
{
    *value = NULL;
    bf_h5_reader *r;
    bf_status st = bf_h5_reader_open(&r, file, err);
    if (st)
        return st;
    st = bf_h5_reader_attr_str(r, obj, name, value, err);
    bf_h5_reader_close(r);
    return st;
}
