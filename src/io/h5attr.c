/* h5attr.c: attributes of the output's objects (h5out.h: bf_out_attr_*),
 * groups created as they are named. */
#include <string.h>

#include "io/h5out_impl.h"

/* The object obj of the file (created as a group if it does not exist)
 * in *o, to be given back with close_obj, once the file may take
 * metadata. */
static bf_status open_obj(bf_out *out, const char *obj, hid_t *o,
                          bf_err *err)
{
    if (out->failed)
        return bf_out_failed_before_(out, err);
    if (bf_out_before_metadata_(out, err))
        return BF_EIO;
    if (!strcmp(obj, "/")) {
        *o = out->root >= 0 ? out->root : H5Oopen(out->file, "/", H5P_DEFAULT);
    } else if (H5Lexists(out->file, obj, H5P_DEFAULT) > 0) {
        *o = H5Oopen(out->file, obj, H5P_DEFAULT);
    } else {
        hid_t lcpl = bf_out_lcpl_();
        *o = H5Gcreate2(out->file, obj, lcpl, H5P_DEFAULT, H5P_DEFAULT);
        H5Pclose(lcpl);
    }
    if (*o < 0)
        return bf_fail(err, BF_EIO, "%s: cannot open %s", out->path, obj);
    return BF_OK;
}

static void close_obj(bf_out *out, hid_t o)
{
    if (o != out->root)
        H5Oclose(o);
}

bf_status bf_out_attr_str(bf_out *out, const char *obj, const char *name,
                          const char *value, bf_err *err)
{
    hid_t o;
    bf_status st = open_obj(out, obj, &o, err);
    if (st)
        return st;
    st = bf_out_str_attr_(o, name, value);
    close_obj(out, o);
    if (st)
        return bf_fail(err, BF_EIO, "%s: cannot write attribute %s of %s",
                       out->path, name, obj);
    return BF_OK;
}

static bf_status num_attr(bf_out *out, const char *obj, const char *name,
                          hid_t ftype, hid_t mtype, const void *v, bf_err *err)
{
    hid_t o;
    bf_status st = open_obj(out, obj, &o, err);
    if (st)
        return st;
    if (H5Aexists(o, name) > 0)
        H5Adelete(o, name);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(o, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT);
    herr_t rc = a >= 0 ? H5Awrite(a, mtype, v) : -1;
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(sp);
    close_obj(out, o);
    if (rc < 0)
        return bf_fail(err, BF_EIO, "%s: cannot write attribute %s of %s",
                       out->path, name, obj);
    return BF_OK;
}

bf_status bf_out_attr_real(bf_out *out, const char *obj, const char *name,
                           double value, bf_err *err)
{
    return num_attr(out, obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value,
                    err);
}

bf_status bf_out_attr_int(bf_out *out, const char *obj, const char *name,
                          int64_t value, bf_err *err)
{
    return num_attr(out, obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value,
                    err);
}
