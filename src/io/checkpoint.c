/* checkpoint.c: in-memory store of named arrays and its atomic HDF5 file
 * (see checkpoint.h).  File layout: one 1-D dataset per entry at the root,
 * float64, int64 or uint8, with an attribute "kind" ("real", "int",
 * "bytes", "str").
 *
 * Two seals.  The entry "checksum" sums a hash of every entry (a file
 * whose entries were edited and re-sealed by hand still parses).  The
 * HDF5 user block (the first SEAL_BYTES of the file, which HDF5 skips)
 * holds the length of the rest of the file and its FNV-1a hash: a file
 * that was cut short, had a bit flipped or was written by something else
 * is refused before HDF5 parses a byte of it (HDF5 is not robust against
 * damaged files), and no dataset may claim more bytes than the file has,
 * so no stored length sizes an allocation. */
#include "ballfilm/checkpoint.h"

#include "base/hash.h"
#include "io/h5check.h"
#include "io/outpath.h"

#include <fcntl.h>
#include <hdf5.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef enum { K_REAL, K_INT, K_BYTES, K_STR } kind;
static const char *kind_name[] = {"real", "int", "bytes", "str"};

typedef struct item {
    char *name;
    kind k;
    size_t n;    /* elements */
    void *data;  /* n * elsize bytes (+1 NUL for strings) */
} item;

struct bf_ckpt {
    item *items;
    size_t n, cap;
};

static size_t elsize(kind k) { return k == K_REAL || k == K_INT ? 8 : 1; }

bf_ckpt *bf_ckpt_new(void) { return calloc(1, sizeof(bf_ckpt)); }

void bf_ckpt_free(bf_ckpt *ck)
{
    if (!ck)
        return;
    for (size_t k = 0; k < ck->n; k++) {
        free(ck->items[k].name);
        free(ck->items[k].data);
    }
    free(ck->items);
    free(ck);
}

static const item *find(const bf_ckpt *ck, const char *name)
{
    for (size_t k = 0; k < ck->n; k++)
        if (!strcmp(ck->items[k].name, name))
            return &ck->items[k];
    return NULL;
}

static bf_status put(bf_ckpt *ck, const char *name, kind k, const void *p,
                     size_t n, bf_err *err)
{
    if (!*name || strchr(name, '/'))
        return bf_fail(err, BF_EINTERNAL, "checkpoint entry name '%s' is "
                       "invalid", name);
    if (find(ck, name))
        return bf_fail(err, BF_EINTERNAL, "checkpoint entry '%s' stored twice",
                       name);
    if (ck->n == ck->cap) {
        size_t cap = ck->cap ? 2 * ck->cap : 32;
        item *ni = realloc(ck->items, cap * sizeof *ni);
        if (!ni)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        ck->items = ni;
        ck->cap = cap;
    }
    item *it = &ck->items[ck->n];
    it->name = strdup(name);
    it->k = k;
    it->n = n;
    it->data = malloc(n * elsize(k) + 1);
    if (!it->name || !it->data) {
        free(it->name);
        free(it->data);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (n)
        memcpy(it->data, p, n * elsize(k));
    ((char *)it->data)[n * elsize(k)] = '\0';
    ck->n++;
    return BF_OK;
}

bf_status bf_ckpt_put(bf_ckpt *ck, const char *name, const double *v, size_t n,
                      bf_err *err)
{
    return put(ck, name, K_REAL, v, n, err);
}

bf_status bf_ckpt_put_i64(bf_ckpt *ck, const char *name, const int64_t *v,
                          size_t n, bf_err *err)
{
    return put(ck, name, K_INT, v, n, err);
}

bf_status bf_ckpt_put_bytes(bf_ckpt *ck, const char *name, const void *p,
                            size_t n, bf_err *err)
{
    return put(ck, name, K_BYTES, p, n, err);
}

bf_status bf_ckpt_put_real(bf_ckpt *ck, const char *name, double v,
                           bf_err *err)
{
    return put(ck, name, K_REAL, &v, 1, err);
}

bf_status bf_ckpt_put_int(bf_ckpt *ck, const char *name, int64_t v, bf_err *err)
{
    return put(ck, name, K_INT, &v, 1, err);
}

bf_status bf_ckpt_put_str(bf_ckpt *ck, const char *name, const char *s,
                          bf_err *err)
{
    return put(ck, name, K_STR, s, strlen(s), err);
}

static bf_status get(const bf_ckpt *ck, const char *name, kind k, void *p,
                     size_t n, bf_err *err)
{
    const item *it = find(ck, name);
    if (!it)
        return bf_fail(err, BF_EINPUT, "checkpoint has no entry '%s' (written "
                       "by another version or another scene?)", name);
    if (it->k != k || it->n != n)
        return bf_fail(err, BF_EINPUT, "checkpoint entry '%s' holds %zu %s "
                       "values, expected %zu %s (the scene changed?)",
                       name, it->n, kind_name[it->k], n, kind_name[k]);
    if (n)
        memcpy(p, it->data, n * elsize(k));
    return BF_OK;
}

bf_status bf_ckpt_get(const bf_ckpt *ck, const char *name, double *v, size_t n,
                      bf_err *err)
{
    return get(ck, name, K_REAL, v, n, err);
}

bf_status bf_ckpt_get_i64(const bf_ckpt *ck, const char *name, int64_t *v,
                          size_t n, bf_err *err)
{
    return get(ck, name, K_INT, v, n, err);
}

bf_status bf_ckpt_get_bytes(const bf_ckpt *ck, const char *name, void *p,
                            size_t n, bf_err *err)
{
    return get(ck, name, K_BYTES, p, n, err);
}

bf_status bf_ckpt_get_real(const bf_ckpt *ck, const char *name, double *v,
                           bf_err *err)
{
    return get(ck, name, K_REAL, v, 1, err);
}

bf_status bf_ckpt_get_int(const bf_ckpt *ck, const char *name, int64_t *v,
                          bf_err *err)
{
    return get(ck, name, K_INT, v, 1, err);
}

const double *bf_ckpt_data(const bf_ckpt *ck, const char *name, size_t *n)
{
    const item *it = find(ck, name);
    if (!it || it->k != K_REAL)
        return NULL;
    *n = it->n;
    return it->data;
}

const int64_t *bf_ckpt_data_i64(const bf_ckpt *ck, const char *name, size_t *n)
{
    const item *it = find(ck, name);
    if (!it || it->k != K_INT)
        return NULL;
    *n = it->n;
    return it->data;
}

const char *bf_ckpt_str(const bf_ckpt *ck, const char *name)
{
    const item *it = find(ck, name);
    return it && it->k == K_STR ? it->data : NULL;
}

int bf_ckpt_has(const bf_ckpt *ck, const char *name)
{
    return find(ck, name) != NULL;
}

size_t bf_ckpt_count(const bf_ckpt *ck) { return ck->n; }

const char *bf_ckpt_entry(const bf_ckpt *ck, size_t k, const char **kind,
                          size_t *n, const void **data)
{
    if (k >= ck->n)
        return NULL;
    const item *it = &ck->items[k];
    if (kind)
        *kind = kind_name[it->k];
    if (n)
        *n = it->n;
    if (data)
        *data = it->data;
    return it->name;
}

/* ------------------------------------------------------------------ file */

static hid_t h5type(kind k)
{
    return k == K_REAL ? H5T_IEEE_F64LE : k == K_INT ? H5T_STD_I64LE
                                                     : H5T_STD_U8LE;
}

static hid_t memtype(kind k)
{
    return k == K_REAL ? H5T_NATIVE_DOUBLE : k == K_INT ? H5T_NATIVE_INT64
                                                        : H5T_NATIVE_UCHAR;
}

static int write_kind_attr(hid_t d, kind k)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen(kind_name[k]) + 1);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(d, "kind", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a < 0 || H5Awrite(a, t, kind_name[k]) < 0;
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    return rc;
}

/* The checksum of a checkpoint: the sum over its entries of a hash of each
 * (name, kind, length, bytes), so that it does not depend on the order in
 * which the file lists them.  Stored as the entry CHECKSUM, left out of
 * its own sum. */
#define CHECKSUM "checksum"

static uint64_t checksum_of(const bf_ckpt *ck)
{
    uint64_t sum = 0;
    for (size_t k = 0; k < ck->n; k++) {
        const item *it = &ck->items[k];
        if (!strcmp(it->name, CHECKSUM))
            continue;
        uint64_t h = bf_hash64(BF_HASH_INIT, it->name, strlen(it->name) + 1);
        uint64_t meta[2] = {(uint64_t)it->k, (uint64_t)it->n};
        h = bf_hash64(h, meta, sizeof meta);
        sum += bf_hash64(h, it->data, it->n * elsize(it->k));
    }
    return sum;
}

static bf_status write_file(const bf_ckpt *ck, const char *path, bf_err *err);

/* The user block: "ballfilm checkpoint\nbytes N\nfnv1a64 H\n", NUL-padded
 * to SEAL_BYTES (a power of two >= 512, as HDF5 requires). */
#define SEAL_BYTES 512
#define SEAL_MAGIC "ballfilm checkpoint\n"

/* The FNV-1a hash and the length of fd's bytes from SEAL_BYTES on; -1 on
 * a read error. */
static int hash_body(int fd, uint64_t *h, off_t *len)
{
    unsigned char buf[65536];
    *h = BF_HASH_INIT;
    *len = 0;
    for (off_t at = SEAL_BYTES;;) {
        ssize_t got = pread(fd, buf, sizeof buf, at);
        if (got < 0)
            return -1;
        if (got == 0)
            return 0;
        *h = bf_hash64(*h, buf, (size_t)got);
        at += got;
        *len += got;
    }
}

static int write_seal(int fd)
{
    uint64_t h;
    off_t len;
    if (hash_body(fd, &h, &len))
        return -1;
    char block[SEAL_BYTES] = {0};
    snprintf(block, sizeof block, SEAL_MAGIC "bytes %lld\nfnv1a64 %016llx\n",
             (long long)len, (unsigned long long)h);
    return pwrite(fd, block, sizeof block, 0) == (ssize_t)sizeof block ? 0 : -1;
}

/* The file at path is a sealed checkpoint whose bytes are as written;
 * *size receives its size. */
static bf_status check_seal(const char *path, off_t *size, bf_err *err)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0)
        return bf_fail(err, BF_EINPUT, "%s: cannot open checkpoint file",
                       path);
    char block[SEAL_BYTES + 1] = {0};
    long long want = -1;
    unsigned long long hash = 0;
    uint64_t h = 0;
    off_t len = -1;
    struct stat sb;
    int ok = !fstat(fd, &sb) &&
             pread(fd, block, SEAL_BYTES, 0) == (ssize_t)SEAL_BYTES &&
             !strncmp(block, SEAL_MAGIC, strlen(SEAL_MAGIC)) &&
             sscanf(block + strlen(SEAL_MAGIC), "bytes %lld\nfnv1a64 %llx",
                    &want, &hash) == 2 &&
             !hash_body(fd, &h, &len);
    close(fd);
    if (!ok)
        return bf_fail(err, BF_EINPUT, "%s: not a ballfilm checkpoint (no "
                       "seal)", path);
    if (len != want)
        return bf_fail(err, BF_EINPUT, "%s: the checkpoint is damaged: %lld "
                       "bytes where %lld were written (cut short?); it cannot "
                       "be trusted", path, (long long)len + SEAL_BYTES,
                       want + SEAL_BYTES);
    if (h != hash)
        return bf_fail(err, BF_EINPUT, "%s: the checkpoint is damaged: its "
                       "bytes changed since it was written (edited, or a "
                       "disk error); it cannot be trusted", path);
    *size = sb.st_size;
    return BF_OK;
}

bf_status bf_ckpt_write(const bf_ckpt *ck, const char *path, bf_err *err)
{
    /* a copy of the entries with their checksum added */
    bf_ckpt sealed = *ck;
    item *items = malloc((ck->n + 1) * sizeof *items);
    if (!items)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    memcpy(items, ck->items, ck->n * sizeof *items);
    int64_t sum = (int64_t)checksum_of(ck);
    items[ck->n] = (item){CHECKSUM, K_INT, 1, &sum};
    sealed.items = items;
    sealed.n = ck->n + 1;
    bf_status st = find(ck, CHECKSUM)
                       ? bf_fail(err, BF_EINTERNAL, "checkpoint entry '%s' "
                                 "is reserved", CHECKSUM)
                       : write_file(&sealed, path, err);
    free(items);
    return st;
}

/* Every entry of ck as a dataset of the HDF5 file f; 0, or 1 if one
 * could not be written. */
static int write_entries(const bf_ckpt *ck, hid_t f)
{
    int bad = 0;
    for (size_t k = 0; k < ck->n && !bad; k++) {
        const item *it = &ck->items[k];
        hsize_t dims[1] = {it->n};
        hid_t sp = H5Screate_simple(1, dims, NULL);
        hid_t d = H5Dcreate2(f, it->name, h5type(it->k), sp, H5P_DEFAULT,
                             H5P_DEFAULT, H5P_DEFAULT);
        if (d < 0)
            bad = 1;
        else {
            if (it->n &&
                H5Dwrite(d, memtype(it->k), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                         it->data) < 0)
                bad = 1;
            if (write_kind_attr(d, it->k))
                bad = 1;
            H5Dclose(d);
        }
        H5Sclose(sp);
    }
    return bad;
}

/* The file is written as PATH.tmp and renamed over PATH.  PATH.tmp is
 * opened without following a link and must be this user's own file
 * (outpath.h); HDF5 writes that very file, through /proc/self/fd, and the
 * seal is written through the same descriptor. */
static bf_status write_file(const bf_ckpt *ck, const char *path, bf_err *err)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    size_t len = strlen(path);
    char *tmp = malloc(len + 5);
    if (!tmp)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(tmp, len + 5, "%s.tmp", path);
    int fd = bf_path_open_own(tmp, err);
    if (fd < 0) {
        free(tmp);
        return BF_EIO;
    }
    char h5name[32];
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    H5Pset_userblock(fcpl, SEAL_BYTES);
    hid_t f = ftruncate(fd, 0) ? -1
                               : H5Fcreate(bf_path_h5_name(fd, h5name,
                                                           sizeof h5name),
                                           H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
    H5Pclose(fcpl);
    if (f < 0) {
        bf_status st = bf_fail(err, BF_EIO, "%s: cannot create checkpoint", tmp);
        close(fd);
        unlink(tmp);
        free(tmp);
        return st;
    }
    int bad = write_entries(ck, f);
    if (H5Fclose(f) < 0)
        bad = 1;
    /* seal it, and make the data durable before the rename makes it
     * visible */
    if (!bad && (write_seal(fd) || fsync(fd)))
        bad = 1;
    close(fd);
    if (bad || rename(tmp, path)) {
        unlink(tmp);
        bf_status st = bf_fail(err, BF_EIO, "%s: writing the checkpoint failed "
                               "(disk full?); the previous checkpoint is kept",
                               path);
        free(tmp);
        return st;
    }
    free(tmp);
    return BF_OK;
}

typedef struct read_ctx {
    bf_ckpt *ck;
    bf_err *err;
    int bad;
    double file_bytes; /* no entry holds more */
} read_ctx;

static herr_t read_one(hid_t g, const char *name, const H5L_info_t *info,
                       void *op)
{
    (void)info;
    read_ctx *rc = op;
    hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d < 0) {
        rc->bad = 1;
        return -1;
    }
    /* the kind is one short string, checked before it is read
     * (h5check.h): an attribute of another class or shape is no kind */
    char *kname = NULL;
    hid_t a = H5Aexists(d, "kind") > 0 ? H5Aopen(d, "kind", H5P_DEFAULT)
                                       : -1;
    if (a >= 0) {
        bf_err ignore = {0};
        bf_h5_attr_string(a, "", name, "kind", &kname, &ignore);
        H5Aclose(a);
    }
    kind k = K_REAL;
    int found = 0;
    for (int q = 0; q < 4 && kname; q++)
        if (!strcmp(kname, kind_name[q])) {
            k = (kind)q;
            found = 1;
        }
    free(kname);
    hid_t sp = H5Dget_space(d), dt = H5Dget_type(d);
    const H5T_class_t cls = dt >= 0 ? H5Tget_class(dt) : H5T_NO_CLASS;
    if (dt >= 0)
        H5Tclose(dt);
    if (cls != (k == K_REAL ? H5T_FLOAT : H5T_INTEGER))
        found = 0;
    hsize_t n = 0;
    if (found && H5Sget_simple_extent_type(sp) == H5S_SIMPLE &&
        H5Sget_simple_extent_ndims(sp) == 1)
        H5Sget_simple_extent_dims(sp, &n, NULL);
    else
        found = 0;
    H5Sclose(sp);
    if ((double)n * (double)elsize(k) > rc->file_bytes)
        found = 0; /* a length the file cannot hold: never allocated */
    void *buf = found ? malloc((size_t)n * elsize(k) + 1) : NULL;
    if (!buf || (n && H5Dread(d, memtype(k), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                              buf) < 0) ||
        put(rc->ck, name, k, buf, (size_t)n, rc->err)) {
        rc->bad = 1;
        free(buf);
        H5Dclose(d);
        return -1;
    }
    free(buf);
    H5Dclose(d);
    return 0;
}

bf_status bf_ckpt_read(bf_ckpt **out, const char *path, bf_err *err)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    *out = NULL;
    off_t size;
    bf_status st = check_seal(path, &size, err);
    if (st)
        return st;
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0)
        return bf_fail(err, BF_EINPUT, "%s: cannot open checkpoint file", path);
    bf_ckpt *ck = bf_ckpt_new();
    read_ctx rc = {ck, err, 0, (double)size};
    if (!ck ||
        H5Literate(f, H5_INDEX_NAME, H5_ITER_INC, NULL, read_one, &rc) < 0 ||
        rc.bad) {
        H5Fclose(f);
        bf_ckpt_free(ck);
        return bf_fail(err, BF_EINPUT, "%s: not a readable ballfilm checkpoint",
                       path);
    }
    H5Fclose(f);
    /* every entry as written, or the file is refused */
    const item *sum = find(ck, CHECKSUM);
    if (!sum || sum->k != K_INT || sum->n != 1 ||
        *(const int64_t *)sum->data != (int64_t)checksum_of(ck)) {
        bf_ckpt_free(ck);
        return bf_fail(err, BF_EINPUT, "%s: the checkpoint's checksum does "
                       "not match its contents (damaged or edited); it "
                       "cannot be trusted", path);
    }
    *out = ck;
    return BF_OK;
}

/* ---------------------------------------------------------------- fields */

static size_t ftype_size(bf_ftype t)
{
    switch (t) {
    case BF_F_DOUBLE: return sizeof(double);
    case BF_F_INT: return sizeof(int);
    case BF_F_LONG: return sizeof(long);
    case BF_F_ULONG: return sizeof(unsigned long);
    case BF_F_ULL: return sizeof(unsigned long long);
    case BF_F_SIZE: return sizeof(size_t);
    case BF_F_I64: return sizeof(int64_t);
    case BF_F_I32: return sizeof(int32_t);
    case BF_F_U32: return sizeof(uint32_t);
    case BF_F_U8: return sizeof(uint8_t);
    }
    return 0;
}

/* element k of a field as int64 and back */
static int64_t get_int(bf_ftype t, const char *p)
{
    switch (t) {
    case BF_F_INT: return *(const int *)p;
    case BF_F_LONG: return *(const long *)p;
    case BF_F_ULONG: return (int64_t) * (const unsigned long *)p;
    case BF_F_ULL: return (int64_t) * (const unsigned long long *)p;
    case BF_F_SIZE: return (int64_t) * (const size_t *)p;
    case BF_F_I64: return *(const int64_t *)p;
    case BF_F_I32: return *(const int32_t *)p;
    case BF_F_U32: return *(const uint32_t *)p;
    case BF_F_U8: return *(const uint8_t *)p;
    case BF_F_DOUBLE: break;
    }
    return 0;
}

static void set_int(bf_ftype t, char *p, int64_t v)
{
    switch (t) {
    case BF_F_INT: *(int *)p = (int)v; break;
    case BF_F_LONG: *(long *)p = (long)v; break;
    case BF_F_ULONG: *(unsigned long *)p = (unsigned long)v; break;
    case BF_F_ULL: *(unsigned long long *)p = (unsigned long long)v; break;
    case BF_F_SIZE: *(size_t *)p = (size_t)v; break;
    case BF_F_I64: *(int64_t *)p = v; break;
    case BF_F_I32: *(int32_t *)p = (int32_t)v; break;
    case BF_F_U32: *(uint32_t *)p = (uint32_t)v; break;
    case BF_F_U8: *(uint8_t *)p = (uint8_t)v; break;
    case BF_F_DOUBLE: break;
    }
}

/* the elements of field f of obj and their number */
static char *field_data(const bf_field *f, const void *obj, size_t *n)
{
    char *base = (char *)obj;
    if (f->count) {
        *n = f->count;
        return base + f->offset;
    }
    memcpy(n, base + f->count_of, sizeof *n);
    char *p;
    memcpy(&p, base + f->offset, sizeof p);
    return p;
}

static void field_name(char *buf, size_t cap, const char *prefix,
                       const bf_field *f)
{
    snprintf(buf, cap, "%s.%s", prefix, f->name);
}

bf_status bf_ckpt_put_fields(bf_ckpt *ck, const char *prefix,
                             const bf_field *f, size_t nf, const void *obj,
                             bf_err *err)
{
    char name[256];
    for (size_t k = 0; k < nf; k++) {
        size_t n;
        const char *p = field_data(&f[k], obj, &n);
        field_name(name, sizeof name, prefix, &f[k]);
        bf_status st;
        if (f[k].type == BF_F_DOUBLE) {
            st = put(ck, name, K_REAL, p, n, err);
        } else {
            int64_t *v = malloc((n ? n : 1) * sizeof *v);
            if (!v)
                return bf_fail(err, BF_EINTERNAL, "out of memory");
            for (size_t i = 0; i < n; i++)
                v[i] = get_int(f[k].type, p + i * ftype_size(f[k].type));
            st = put(ck, name, K_INT, v, n, err);
            free(v);
        }
        if (st)
            return st;
    }
    return BF_OK;
}

bf_status bf_ckpt_get_fields(const bf_ckpt *ck, const char *prefix,
                             const bf_field *f, size_t nf, void *obj,
                             bf_err *err)
{
    char name[256];
    for (size_t k = 0; k < nf; k++) {
        size_t n;
        char *p = field_data(&f[k], obj, &n);
        field_name(name, sizeof name, prefix, &f[k]);
        bf_status st;
        if (f[k].type == BF_F_DOUBLE) {
            st = get(ck, name, K_REAL, p, n, err);
        } else {
            int64_t *v = malloc((n ? n : 1) * sizeof *v);
            if (!v)
                return bf_fail(err, BF_EINTERNAL, "out of memory");
            st = get(ck, name, K_INT, v, n, err);
            for (size_t i = 0; !st && i < n; i++)
                set_int(f[k].type, p + i * ftype_size(f[k].type), v[i]);
            free(v);
        }
        if (st)
            return st;
    }
    return BF_OK;
}
