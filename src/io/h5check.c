/* h5check.c: checks before every read of an HDF5 file (see h5check.h). */
#include "io/h5check.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

double bf_h5_file_bytes(const char *file)
{
    struct stat sb;
    return stat(file, &sb) ? -1.0 : (double)sb.st_size;
}

/* 1 if the dataspace of attribute a holds exactly one value. */
static int one_value(hid_t a)
{
    hid_t sp = H5Aget_space(a);
    if (sp < 0)
        return 0;
    H5S_class_t c = H5Sget_simple_extent_type(sp);
    hssize_t n = H5Sget_simple_extent_npoints(sp);
    H5Sclose(sp);
    return c == H5S_SCALAR || (c == H5S_SIMPLE && n == 1);
}

/* The class of the type of attribute a, or H5T_NO_CLASS. */
static H5T_class_t attr_class(hid_t a, hid_t *type)
{
    *type = H5Aget_type(a);
    return *type < 0 ? H5T_NO_CLASS : H5Tget_class(*type);
}

bf_status bf_h5_attr_number(hid_t a, const char *file, const char *obj,
                            const char *name, double *value, bf_err *err)
{
    hid_t t;
    H5T_class_t c = attr_class(a, &t);
    int one = one_value(a);
    if (t >= 0)
        H5Tclose(t);
    if ((c != H5T_INTEGER && c != H5T_FLOAT) || !one)
        return bf_fail(err, BF_EINPUT, "%s: attribute %s of %s is not one "
                       "number (damaged, or not a ballfilm file)", file, name,
                       obj);
    double v;
    if (H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0)
        return bf_fail(err, BF_EIO, "%s: cannot read attribute %s of %s",
                       file, name, obj);
    *value = v;
    return BF_OK;
}

bf_status bf_h5_root_number(hid_t f, const char *fname, const char *name,
                            double fallback, double *value, bf_err *err)
{
    *value = fallback;
    htri_t e = H5Aexists(f, name);
    if (!e)
        return BF_OK;
    hid_t a = e > 0 ? H5Aopen(f, name, H5P_DEFAULT) : -1;
    if (a < 0)
        return bf_fail(err, BF_EIO, "%s: cannot open attribute %s", fname,
                       name);
    bf_status st = bf_h5_attr_number(a, fname, "/", name, value, err);
    H5Aclose(a);
    return st;
}

/* A fixed-length string of len bytes, NUL-terminated. */
static char *read_fixed(hid_t a, size_t len)
{
    char *v = calloc(len + 1, 1);
    hid_t t = H5Tcopy(H5T_C_S1);
    if (!v || t < 0 || H5Tset_size(t, len + 1) < 0 || H5Aread(a, t, v) < 0) {
        free(v);
        v = NULL;
    }
    if (t >= 0)
        H5Tclose(t);
    return v;
}

/* A variable-length string in the character set cset, copied. */
static char *read_variable(hid_t a, H5T_cset_t cset, int *too_long)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    char *v = NULL, *copy = NULL;
    if (t >= 0 && H5Tset_size(t, H5T_VARIABLE) >= 0 &&
        H5Tset_cset(t, cset) >= 0 && H5Aread(a, t, &v) >= 0 && v) {
        size_t len = strnlen(v, BF_H5_MAX_TEXT + 1);
        *too_long = len > BF_H5_MAX_TEXT;
        if (!*too_long && (copy = malloc(len + 1))) {
            memcpy(copy, v, len);
            copy[len] = '\0';
        }
        H5free_memory(v);
    }
    if (t >= 0)
        H5Tclose(t);
    return copy;
}

bf_status bf_h5_attr_string(hid_t a, const char *file, const char *obj,
                            const char *name, char **value, bf_err *err)
{
    *value = NULL;
    hid_t t;
    H5T_class_t c = attr_class(a, &t);
    int one = one_value(a);
    int variable = c == H5T_STRING && H5Tis_variable_str(t) > 0;
    size_t len = c == H5T_STRING && !variable ? H5Tget_size(t) : 0;
    H5T_cset_t cset = c == H5T_STRING ? H5Tget_cset(t) : H5T_CSET_ASCII;
    if (t >= 0)
        H5Tclose(t);
    if (c != H5T_STRING || !one)
        return bf_fail(err, BF_EINPUT, "%s: attribute %s of %s is not one "
                       "string (damaged, or not a ballfilm file)", file, name,
                       obj);
    if (!variable && (len < 1 || len > BF_H5_MAX_TEXT))
        return bf_fail(err, BF_EINPUT, "%s: attribute %s of %s is a string "
                       "of %zu bytes (at most %zu are read)", file, name, obj,
                       len, BF_H5_MAX_TEXT);
    int too_long = 0;
    *value = variable ? read_variable(a, cset, &too_long) : read_fixed(a, len);
    if (too_long)
        return bf_fail(err, BF_EINPUT, "%s: attribute %s of %s is a string "
                       "of more than %zu bytes", file, name, obj,
                       BF_H5_MAX_TEXT);
    if (!*value)
        return bf_fail(err, BF_EIO, "%s: cannot read attribute %s of %s",
                       file, name, obj);
    return BF_OK;
}

bf_status bf_h5_dataset_shape(hid_t d, const char *file, const char *path,
                              int *rank, hsize_t dims[2], bf_err *err)
{
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
    H5T_class_t c = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
    int simple = sp >= 0 && H5Sget_simple_extent_type(sp) == H5S_SIMPLE;
    int r = simple ? H5Sget_simple_extent_ndims(sp) : -1;
    dims[0] = dims[1] = 0;
    if (r >= 1 && r <= 2 && H5Sget_simple_extent_dims(sp, dims, NULL) < 0)
        r = -1;
    if (t >= 0)
        H5Tclose(t);
    if (sp >= 0)
        H5Sclose(sp);
    if (c != H5T_INTEGER && c != H5T_FLOAT)
        return bf_fail(err, BF_EINPUT, "%s: dataset %s does not hold numbers "
                       "(damaged, or not a ballfilm file)", file, path);
    if (r < 1 || r > 2)
        return bf_fail(err, BF_EINPUT, "%s: dataset %s has rank %d (want 1 "
                       "or 2)", file, path, r);
    *rank = r;
    return BF_OK;
}

bf_status bf_h5_dataset_fits(hid_t d, const char *file, const char *path,
                             hsize_t rows, hsize_t width, double file_bytes,
                             size_t *count, bf_err *err)
{
    hid_t t = H5Dget_type(d), dcpl = H5Dget_create_plist(d);
    size_t elsize = t >= 0 ? H5Tget_size(t) : 0;
    int filtered = dcpl >= 0 && H5Pget_nfilters(dcpl) > 0;
    if (t >= 0)
        H5Tclose(t);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    const double bound = file_bytes * (filtered ? BF_H5_MAX_RATIO : 1.0);
    /* counted in doubles as read into memory, then as stored */
    /* a row's width is checked even when no row is read: callers size
     * their row buffers from it */
    if (!elsize || file_bytes < 0 ||
        (width && rows > SIZE_MAX / sizeof(double) / width) ||
        (double)rows * (double)width * (double)elsize > bound ||
        (double)width * (double)elsize > bound)
        return bf_fail(err, BF_EINPUT, "%s: dataset %s claims %llu x %llu "
                       "values, more than the file (%.0f bytes) can hold "
                       "(damaged, or not a ballfilm file)", file, path,
                       (unsigned long long)rows, (unsigned long long)width,
                       file_bytes);
    *count = (size_t)rows * (size_t)width;
    return BF_OK;
}
