/* h5out.c: buffered, extendible HDF5 series (see h5out.h for the design).
 *
 * Owning the output path.  A run writes PATH.part, which it holds under an
 * exclusive lock (a record lock on its own descriptor, taken before
 * anything is truncated, outpath.c's bf_path_lock; the writer's HDF5
 * locking is off, so that it does not fight ours, and readers may open
 * the file while it is written, as SWMR readers once it is in SWMR mode:
 * h5swmr.c), and renames it over PATH only when it commits: a previous
 * result at PATH survives until the new one exists, and a second run on
 * the same path is refused instead of truncating the first one's file.  The lock
 * goes with the descriptor, also when the process is killed.  PATH.part
 * is opened without following a link and must be this user's own file
 * (outpath.h), and PATH must be replaceable, both before anything runs.
 *
 * Flush discipline.  Before a flush writes anything, the space it may need
 * (the buffered rows, whole chunks, metadata) is reserved on the file
 * system (fallocate without changing the size) and checked against the
 * process's file-size limit; if it is not there the flush writes nothing
 * and fails, so the file on disk stays the consistent state of the last
 * flush.  After a failed write nothing more is written (not even at
 * close), for the same reason.
 *
 * A kill inside a flush: h5swmr.c. */
#define _GNU_SOURCE /* fallocate's FALLOC_FL_KEEP_SIZE */
#include "base/clock.h"
#include "base/utf8.h"
#include "ballfilm/h5out.h"
#include "h5lock.h"
#include "h5out_impl.h"
#include "h5part.h"
#include "outpath.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#define FLUSH_BYTES (1u << 19) /* flush when this much is buffered: at most
                                  * 512 KiB of rows in memory, so the memory of
                                  * a run does not grow with its length */

/* Arrays above this size are compressed when compression is on. */
#define COMPRESS_ARRAY_BYTES (64u << 10)

void bf_out_set_compression(bf_out *out, int level)
{
    out->deflate = level < 0 ? 0 : level > 9 ? 9 : level;
}

void bf_out_expect_rows(bf_out *out, size_t rows) { out->expect_rows = rows; }

/* Shuffle (bytes of a value grouped, which deflate packs better) and
 * deflate on a chunked dataset's creation properties. */
static void add_filters(const bf_out *out, hid_t dcpl)
{
    if (out->deflate > 0) {
        H5Pset_shuffle(dcpl);
        H5Pset_deflate(dcpl, (unsigned)out->deflate);
    }
}

static void quiet_hdf5(void)
{
    /* We report errors ourselves, with the file and dataset named. */
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

hid_t bf_out_lcpl_(void)
{
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    return lcpl;
}

/* The writer's file-access list: HDF5's own file locking off (ours is the
 * lock), the 1.10 file format (SWMR mode needs it; bounded above so that
 * a newer HDF5 writes files that 1.10 reads), and, to continue a run that
 * was killed in SWMR mode, HDF5's "open for writing" mark cleared (what
 * `h5clear -s` does, through the property it sets). */
hid_t bf_out_fapl_(int append)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
#if H5_VERSION_GE(1, 10, 7)
    H5Pset_file_locking(fapl, 0, 1);
#endif
#if H5_VERSION_GE(1, 10, 2)
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
#else
    H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
#endif
    if (append)
        bf_h5_fapl_past_mark(fapl);
    return fapl;
}

/* Open and lock PATH.part; fails with BF_EIO when another run holds it,
 * or when it is a link or not a file of this user's (outpath.h). */
static bf_status claim(bf_out *o, const char *path, bf_err *err)
{
    size_t len = strlen(path) + 6;
    o->path = strdup(path);
    o->part = malloc(len);
    o->lock_fd = -1;
    if (!o->path || !o->part)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(o->part, len, "%s.part", path);
    int fd = bf_path_open_own(o->part, err);
    if (fd < 0)
        return BF_EIO;
    int e = bf_path_lock(fd);
    if (e) {
        close(fd);
        if (e == EAGAIN)
            return bf_fail(err, BF_EIO, "%s is in use: another run is writing "
                           "it (%s is locked); wait for it to end or choose "
                           "another output file",
                           path, o->part);
        return bf_fail(err, BF_EIO, "%s: cannot lock %s: %s", path, o->part,
                       strerror(e));
    }
    o->lock_fd = fd;
    bf_path_h5_name(fd, o->h5name, sizeof o->h5name);
    return BF_OK;
}

static void release(bf_out *o)
{
    if (o->lock_fd >= 0)
        close(o->lock_fd); /* the lock goes with it */
    o->lock_fd = -1;
    free(o->path);
    free(o->part);
    free(o);
}

/* A finished run continued (seed): its result PATH copied into the new,
 * locked and empty PATH.part, so that PATH stays the finished result
 * until the continued run replaces it. */
static bf_status seed_part(const bf_out *o, bf_err *err)
{
    struct stat sb;
    if (fstat(o->lock_fd, &sb) || sb.st_size != 0)
        return bf_fail(err, BF_EIO, "%s: %s appeared while the run was "
                       "being continued; run again", o->path, o->part);
    int e = bf_path_copy_into(o->path, o->lock_fd);
    if (e)
        return bf_fail(err, BF_EIO, "%s: cannot copy it to %s to continue "
                       "it: %s", o->path, o->part, strerror(e));
    return BF_OK;
}

/* Claim PATH (its lock) and create PATH.part, or open it to continue
 * (seeded from PATH when seed).  HDF5 opens the locked descriptor's own
 * file through /proc/self/fd (outpath.h): a link or file put at
 * PATH.part's name after the checks of claim is not what HDF5 writes. */
static bf_status open_part(bf_out **out, const char *path, int append,
                           int seed, bf_err *err)
{
    bf_status st = bf_path_check_replaceable(path, err);
    if (st)
        return st;
    bf_out *o = calloc(1, sizeof *o);
    if (!o)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    o->root = -1;
    o->log = -1;
    st = claim(o, path, err);
    if (!st && seed && (st = seed_part(o, err)))
        unlink(o->part);
    if (!st && !append && ftruncate(o->lock_fd, 0))
        st = bf_fail(err, BF_EIO, "%s: cannot truncate %s: %s", path,
                     o->part, strerror(errno));
    if (st) {
        release(o);
        return st;
    }
    hid_t fapl = bf_out_fapl_(append);
    o->file = append ? H5Fopen(o->h5name, H5F_ACC_RDWR, fapl)
                     : H5Fcreate(o->h5name, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    if (o->file < 0) {
        if (append)
            st = bf_fail(err, BF_EIO, "%s: cannot open the run's HDF5 file "
                         "%s to continue it", path, o->part);
        else {
            st = bf_fail(err, BF_EIO, "%s: cannot create the HDF5 file %s",
                         path, o->part);
            unlink(o->part);
        }
        release(o);
        return st;
    }
    o->append = append;
    /* a run writes some hundred attributes on "/" (its parameters), and
     * opening and closing the root group for each cost about a twentieth
     * of a small case of a sweep (docs/performance.md, "Sweeps") */
    o->root = H5Oopen(o->file, "/", H5P_DEFAULT);
    o->last_flush = bf_coarse_time();
    *out = o;
    return BF_OK;
}

bf_status bf_out_create(bf_out **out, const char *path, bf_err *err)
{
    quiet_hdf5();
    *out = NULL;
    return open_part(out, path, 0, 0, err);
}

bf_status bf_out_open_append(bf_out **out, const char *path, bf_err *err)
{
    quiet_hdf5();
    *out = NULL;
    /* a run that ended (its result at PATH) continues in a copy of it,
     * PATH.part; a run that did not end continues its PATH.part */
    size_t len = strlen(path) + 6;
    char *part = malloc(len);
    if (!part)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(part, len, "%s.part", path);
    struct stat sb;
    const int seed = lstat(part, &sb) && errno == ENOENT && !lstat(path, &sb);
    free(part);
    return open_part(out, path, 1, seed, err);
}

const char *bf_out_path(const bf_out *out) { return out->path; }

static void series_free(bf_series *s)
{
    if (!s)
        return;
    if (s->dset >= 0)
        H5Dclose(s->dset);
    free(s->buf);
    free(s->path);
    free(s);
}

/* Flush and close the HDF5 file, keep the lock.  After a failed write
 * nothing is flushed and the file is not closed (closing would write
 * HDF5's metadata cache into a file that could not take it); the process
 * is expected to end (the command line leaves without exit handlers). */
static bf_status finish(bf_out *out, bf_err *err)
{
    out->appending = 0;
    bf_status st = out->failed ? BF_EIO
                   : out->swmr ? bf_out_leave_swmr_(out, err)
                               : BF_OK;
    /* the flush log is for a file whose run has not ended; a writer that
     * never started appending (a restart refused after opening a killed
     * run's file) leaves that run's log, which its readers still need */
    if (!st && out->started &&
        H5Lexists(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT) > 0) {
        out->dirty = 1;
        if (H5Ldelete(out->file, BF_H5_FLUSH_LOG, H5P_DEFAULT) < 0)
            st = bf_fail(err, BF_EIO, "%s: cannot delete %s", out->path,
                         BF_H5_FLUSH_LOG);
    }
    if (!st)
        st = bf_out_flush(out, err);
    if (st && !out->failed)
        out->failed = 1;
    for (size_t k = 0; k < out->nseries; k++) {
        if (out->failed)
            out->series[k]->dset = -1; /* leave HDF5's objects alone */
        series_free(out->series[k]);
    }
    free(out->series);
    out->series = NULL;
    out->nseries = 0;
    if (!out->failed && out->root >= 0)
        H5Oclose(out->root);
    if (!out->failed && H5Fclose(out->file) < 0)
        st = bf_fail(err, BF_EIO, "%s: closing the HDF5 file failed", out->part);
    /* give back the space reserved beyond the end and not used */
    struct stat sb;
    if (!out->failed && out->lock_fd >= 0 && !fstat(out->lock_fd, &sb) &&
        ftruncate(out->lock_fd, sb.st_size)) {
        /* nothing lost: only unused blocks stay allocated */
    }
    return st;
}

int bf_out_failed(const bf_out *out) { return out->failed; }

bf_status bf_out_close(bf_out *out, bf_err *err)
{
    if (!out)
        return BF_OK;
    int failed = out->failed;
    bf_status st = finish(out, failed ? NULL : err);
    /* the new result replaces the old one at once (POSIX rename) */
    if (failed)
        st = BF_EIO;
    else if (!st && rename(out->part, out->path))
        st = bf_fail(err, BF_EIO, "%s: cannot rename %s to it: %s", out->path,
                     out->part, strerror(errno));
    release(out);
    return st;
}

bf_status bf_out_close_keep(bf_out *out, bf_err *err)
{
    if (!out)
        return BF_OK;
    bf_status st = finish(out, err);
    release(out);
    return st;
}

/* A copy of s with every byte that is not part of well-formed UTF-8
 * written as \xNN (a file name in another encoding), or NULL if s is
 * well-formed: attributes are tagged UTF-8. */
static char *utf8_escaped(const char *s)
{
    size_t n = strlen(s);
    if (bf_utf8_invalid(s, n) == n)
        return NULL;
    char *out = malloc(4 * n + 1), *o = out;
    if (!out)
        return NULL;
    const unsigned char *u = (const unsigned char *)s;
    for (size_t k = 0; k < n;) {
        size_t len = bf_utf8_seq(u + k, n - k);
        if (len) {
            memcpy(o, u + k, len);
            o += len;
            k += len;
        } else {
            o += sprintf(o, "\\x%02x", u[k++]);
        }
    }
    *o = '\0';
    return out;
}

bf_status bf_out_str_attr_(hid_t obj, const char *name, const char *value)
{
    char *escaped = utf8_escaped(value ? value : "");
    if (escaped)
        value = escaped;
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = -1;
    if (H5Aexists(obj, name) > 0) {
        /* a string attribute of ours (the run's status, written when the
         * run starts and again at its end) is written over: deleting it
         * made HDF5 rewrite the root's object header, nearly a third of
         * a short run's instructions */
        a = H5Aopen(obj, name, H5P_DEFAULT);
        hid_t at = a >= 0 ? H5Aget_type(a) : -1;
        hid_t as = a >= 0 ? H5Aget_space(a) : -1;
        int same = at >= 0 && as >= 0 && H5Tis_variable_str(at) > 0 &&
                   H5Sget_simple_extent_type(as) == H5S_SCALAR;
        if (at >= 0)
            H5Tclose(at);
        if (as >= 0)
            H5Sclose(as);
        if (!same) {
            if (a >= 0)
                H5Aclose(a);
            a = -1;
            H5Adelete(obj, name);
        }
    }
    if (a < 0)
        a = H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    herr_t rc = -1;
    if (a >= 0) {
        const char *v = value ? value : "";
        rc = H5Awrite(a, t, &v);
        H5Aclose(a);
    }
    H5Sclose(sp);
    H5Tclose(t);
    free(escaped);
    return rc < 0 ? BF_EIO : BF_OK;
}

/* A series is appended to: only its last, partial chunk is ever written
 * again, so the chunk cache holds one chunk of a 2-D series (HDF5's
 * default, 1 MiB per dataset, filled up with finished chunks and made a
 * long run's memory grow with its length), finished chunks evicted first.
 * A 1-D series (ncols 0) gets 64 bytes, no room for a chunk: each flush
 * reads its partial chunk back, and a long run's memory stays close to a
 * short one's (caching a 64 KiB chunk per 1-D series took
 * bench/memory.sh's difference from 1.3 to 1.9 MiB). */
hid_t bf_out_series_dapl_(size_t rows_per_chunk, size_t ncols)
{
    hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
    H5Pset_chunk_cache(dapl, 7, rows_per_chunk * 8 * ncols + 64, 1.0);
    return dapl;
}

bf_series *bf_out_series(bf_out *out, const char *path, size_t ncols,
                         int is_int, const char *unit, const char *doc,
                         bf_err *err)
{
    if (bf_out_before_metadata_(out, err))
        return NULL;
    bf_series *s = calloc(1, sizeof *s);
    if (!s) {
        bf_fail(err, BF_EINTERNAL, "out of memory");
        return NULL;
    }
    s->dset = -1;
    s->ncols = ncols;
    s->width = ncols ? ncols : 1;
    s->is_int = is_int;
    s->path = strdup(path);
    int rank = ncols ? 2 : 1;
    hsize_t dims[2] = {0, ncols}, maxdims[2] = {H5S_UNLIMITED, ncols};
    /* about 64 KiB per chunk */
    size_t rows = 65536 / (8 * s->width);
    if (rows < 1)
        rows = 1;
    if (rows > 8192)
        rows = 8192;
    if (out->expect_rows) {
        size_t fit = BF_OUT_MIN_CHUNK_ROWS;
        while (fit < out->expect_rows && fit < rows)
            fit *= 2;
        if (fit < rows)
            rows = fit;
    }
    hsize_t chunk[2] = {rows, ncols};
    s->rpc = rows;
    hid_t dapl = bf_out_series_dapl_(rows, ncols);
    if (out->append && H5Lexists(out->file, path, H5P_DEFAULT) > 0) {
        s->dset = H5Dopen2(out->file, path, dapl);
        H5Pclose(dapl);
        /* the rows per chunk of the file (the run that made it may have
         * had another hint): what flush_need reserves for */
        hid_t dc = s->dset >= 0 ? H5Dget_create_plist(s->dset) : -1;
        hsize_t fc[2] = {0, 0};
        if (dc >= 0 && H5Pget_layout(dc) == H5D_CHUNKED &&
            H5Pget_chunk(dc, 2, fc) >= 1 && fc[0] > 0)
            s->rpc = (size_t)fc[0];
        if (dc >= 0)
            H5Pclose(dc);
        hid_t fsp = s->dset >= 0 ? H5Dget_space(s->dset) : -1;
        hsize_t have[2] = {0, 0};
        int hrank = fsp >= 0 ? H5Sget_simple_extent_ndims(fsp) : -1;
        if (fsp >= 0) {
            H5Sget_simple_extent_dims(fsp, have, NULL);
            H5Sclose(fsp);
        }
        /* the file continued is an input: a series of another shape or
         * class (a string where numbers go) is refused before any row is
         * written into it */
        hid_t ft = s->dset >= 0 ? H5Dget_type(s->dset) : -1;
        const H5T_class_t cls = ft >= 0 ? H5Tget_class(ft) : H5T_NO_CLASS;
        if (ft >= 0)
            H5Tclose(ft);
        if (hrank != rank || (rank == 2 && have[1] != ncols) ||
            cls != (is_int ? H5T_INTEGER : H5T_FLOAT)) {
            bf_fail(err, BF_EINPUT, "%s: dataset %s does not match the run "
                    "(rank %d, columns %llu, %s)", out->part, path, hrank,
                    (unsigned long long)have[1],
                    cls == H5T_INTEGER ? "integers"
                    : cls == H5T_FLOAT ? "floating point"
                                       : "neither integers nor floating point");
            series_free(s);
            return NULL;
        }
        s->written = (size_t)have[0];
        goto registered;
    }
    hid_t sp = H5Screate_simple(rank, dims, maxdims);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, rank, chunk);
    add_filters(out, dcpl);
    hid_t lcpl = bf_out_lcpl_();
    s->dset = H5Dcreate2(out->file, path,
                         is_int ? H5T_STD_I64LE : H5T_IEEE_F64LE, sp, lcpl, dcpl,
                         dapl);
    H5Pclose(dapl);
    H5Pclose(lcpl);
    H5Pclose(dcpl);
    H5Sclose(sp);
    if (s->dset < 0) {
        bf_fail(err, BF_EIO, "%s: cannot create dataset %s", out->path, path);
        series_free(s);
        return NULL;
    }
    if (bf_out_str_attr_(s->dset, "unit", unit ? unit : "") ||
        bf_out_str_attr_(s->dset, "description", doc ? doc : "")) {
        bf_fail(err, BF_EIO, "%s: cannot write attributes of %s", out->path,
                path);
        series_free(s);
        return NULL;
    }
registered:
    if (out->nseries == out->capseries) {
        out->capseries = out->capseries ? 2 * out->capseries : 16;
        bf_series **ns = realloc(out->series, out->capseries * sizeof *ns);
        if (!ns) {
            bf_fail(err, BF_EINTERNAL, "out of memory");
            series_free(s);
            return NULL;
        }
        out->series = ns;
    }
    out->series[out->nseries++] = s;
    s->buffered = &out->buffered_bytes;
    s->out = out;
    return s;
}

/* rows rows of s leave its buffer */
static void series_unbuffer(bf_series *s, size_t rows)
{
    if (s->buffered)
        *s->buffered -= rows * 8 * s->width;
}

/* room in the buffer for row nbuf */
static bf_status series_room(bf_series *s)
{
    size_t rowbytes = 8 * s->width;
    if (s->nbuf == s->capbuf) {
        /* 64 rows to start with, fewer when rows are large (a film
         * profile of 10^7 nodes is 80 MB a row): the buffer is flushed
         * beyond FLUSH_BYTES anyway (bf_out_maybe_flush) */
        size_t first = FLUSH_BYTES / rowbytes;
        size_t cap = s->capbuf ? 2 * s->capbuf
                               : first < 1 ? 1 : first > 64 ? 64 : first;
        unsigned char *nb = realloc(s->buf, cap * rowbytes);
        if (!nb)
            return BF_EINTERNAL;
        s->buf = nb;
        s->capbuf = cap;
    }
    return BF_OK;
}

static bf_status append_raw(bf_series *s, const void *row)
{
    size_t rowbytes = 8 * s->width;
    if (s->partial || series_room(s))
        return BF_EINTERNAL;
    unsigned char *dst = s->buf + s->nbuf * rowbytes;
    /* the usual widths with a constant size: a move, not a call */
    if (s->width == 1)
        memcpy(dst, row, 8);
    else if (s->width == 2)
        memcpy(dst, row, 16);
    else
        memcpy(dst, row, rowbytes);
    s->nbuf++;
    if (s->buffered)
        *s->buffered += rowbytes;
    return BF_OK;
}

bf_status bf_series_append(bf_series *s, const double *row)
{
    return append_raw(s, row);
}

bf_status bf_series_append_i64(bf_series *s, const int64_t *row)
{
    return append_raw(s, row);
}

bf_status bf_series_append_part(bf_series *s, const double *vals, size_t n)
{
    const size_t rowbytes = 8 * s->width;
    if (n > s->width - s->partial || (!s->partial && series_room(s)))
        return BF_EINTERNAL;
    memcpy(s->buf + s->nbuf * rowbytes + 8 * s->partial, vals, 8 * n);
    s->partial += n;
    if (s->partial == s->width) {
        s->partial = 0;
        s->nbuf++;
        if (s->buffered)
            *s->buffered += rowbytes;
    }
    return BF_OK;
}

size_t bf_series_rows(const bf_series *s) { return s->written + s->nbuf; }

const char *bf_series_path(const bf_series *s) { return s->path; }

size_t bf_series_width(const bf_series *s) { return s->width; }

size_t bf_out_nseries(const bf_out *out) { return out->nseries; }

bf_series *bf_out_series_at(bf_out *out, size_t k)
{
    return k < out->nseries ? out->series[k] : NULL;
}

bf_status bf_series_truncate(bf_series *s, size_t rows, bf_err *err)
{
    /* a length shrinks only outside SWMR mode */
    if (rows < s->written && s->out && bf_out_before_metadata_(s->out, err))
        return BF_EIO;
    if (rows > s->written + s->nbuf)
        return bf_fail(err, BF_EIO, "%s has %zu rows, fewer than the %zu the "
                       "checkpoint expects", s->path, s->written + s->nbuf,
                       rows);
    if (rows >= s->written) {
        series_unbuffer(s, s->nbuf - (rows - s->written));
        s->nbuf = rows - s->written;
        return BF_OK;
    }
    series_unbuffer(s, s->nbuf);
    s->nbuf = 0;
    hsize_t dims[2] = {rows, s->ncols};
    if (H5Dset_extent(s->dset, dims) < 0)
        return bf_fail(err, BF_EIO, "cannot truncate %s", s->path);
    s->written = rows;
    return BF_OK;
}

bf_status bf_out_failed_before_(const bf_out *out, bf_err *err)
{
    return bf_fail(err, BF_EIO, "%s: not written: an earlier write failed",
                   out->path);
}

/* Bytes a flush may add to the file: the whole chunks its rows start
 * (HDF5 allocates a chunk of a dataset without filters in full when it is
 * first written), 4 KiB of chunk index for each, and 64 KiB for the other
 * metadata. */
static off_t flush_need(const bf_out *out)
{
    off_t need = 64 * 1024;
    for (size_t k = 0; k < out->nseries; k++) {
        const bf_series *s = out->series[k];
        if (!s->nbuf)
            continue;
        size_t rpc = s->rpc ? s->rpc : 1;
        size_t have = (s->written + rpc - 1) / rpc,
               want = (s->written + s->nbuf + rpc - 1) / rpc;
        need += (off_t)((want - have) * (rpc * 8 * s->width + 4096));
    }
    return need;
}

/* Reserve the space of the next flush before anything is written; fails
 * (writing nothing) when the disk or the file-size limit cannot hold it. */
static bf_status reserve(bf_out *out, bf_err *err)
{
    struct stat sb;
    if (out->lock_fd < 0 || fstat(out->lock_fd, &sb))
        return BF_OK;
    const off_t need = flush_need(out);
    struct rlimit rl;
    if (!getrlimit(RLIMIT_FSIZE, &rl) && rl.rlim_cur != RLIM_INFINITY &&
        (rlim_t)(sb.st_size + need) > rl.rlim_cur)
        return bf_fail(err, BF_EIO, "%s: disk full: the next write needs "
                       "about %.1f MiB beyond the %.1f MiB the file may grow "
                       "to (file size limit)",
                       out->path, (double)need / 1048576.0,
                       (double)rl.rlim_cur / 1048576.0);
    /* blocks beyond the end, the size unchanged: the next writes land in
     * them (released at close if unused) */
    int rc = fallocate(out->lock_fd, FALLOC_FL_KEEP_SIZE, sb.st_size, need)
                 ? errno
                 : 0;
    if (rc == ENOSPC || rc == EFBIG || rc == EDQUOT)
        return bf_fail(err, BF_EIO, "%s: disk full: the next write needs "
                       "about %.1f MiB (%s)",
                       out->path, (double)need / 1048576.0, strerror(rc));
    return BF_OK; /* other errors: a file system without fallocate */
}

/* A flush refused by reserve() wrote nothing.  If nothing else was
 * written since the last flush either, HDF5 holds nothing that the file
 * lacks, and closing the file writes only its superblock, without the
 * mark of a file open for writing that the 1.10 format keeps until close
 * (and that keeps readers out of a file not in SWMR mode); the file then
 * opens, holding the last flush.  Otherwise it is left alone. */
static void close_refused(bf_out *out)
{
    if (out->dirty)
        return;
    bf_out_close_series_(out);
    if (out->log >= 0)
        H5Dclose(out->log);
    if (out->root >= 0)
        H5Oclose(out->root);
    out->log = out->root = -1;
    H5Fclose(out->file);
    out->file = -1;
}

static bf_status series_flush(bf_out *out, bf_series *s, bf_err *err)
{
    if (s->partial)
        return bf_fail(err, BF_EINTERNAL, "%s: a row is half built", s->path);
    if (!s->nbuf)
        return BF_OK;
    int rank = s->ncols ? 2 : 1;
    hsize_t newdims[2] = {s->written + s->nbuf, s->ncols};
    if (H5Dset_extent(s->dset, newdims) < 0)
        return bf_fail(err, BF_EIO, "%s: cannot extend %s (disk full?)",
                       out->path, s->path);
    hid_t fsp = H5Dget_space(s->dset);
    hsize_t start[2] = {s->written, 0}, count[2] = {s->nbuf, s->ncols};
    H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, count, NULL);
    hid_t msp = H5Screate_simple(rank, count, NULL);
    herr_t rc = H5Dwrite(s->dset, s->is_int ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE,
                         msp, fsp, H5P_DEFAULT, s->buf);
    H5Sclose(msp);
    H5Sclose(fsp);
    if (rc < 0)
        return bf_fail(err, BF_EIO, "%s: writing %s failed (disk full?)",
                       out->path, s->path);
    s->written += s->nbuf;
    series_unbuffer(s, s->nbuf);
    s->nbuf = 0;
    return BF_OK;
}

bf_status bf_out_flush(bf_out *out, bf_err *err)
{
    if (out->failed)
        return bf_fail(err, BF_EIO, "%s: an earlier write failed; the file "
                       "holds what was flushed before it", out->path);
    bf_status st = reserve(out, err);
    if (st) {
        out->failed = 1;
        close_refused(out);
        return st;
    }
    for (size_t k = 0; !st && k < out->nseries; k++)
        st = series_flush(out, out->series[k], err);
    if (!st && H5Fflush(out->file, H5F_SCOPE_GLOBAL) < 0)
        st = bf_fail(err, BF_EIO, "%s: flushing the HDF5 file failed (disk "
                     "full?)", out->path);
    if (!st && out->swmr)
        st = bf_out_log_flush_(out, err);
    if (st) {
        out->failed = 1;
        return st;
    }
    out->last_flush = bf_coarse_time();
    out->dirty = 0;
    return BF_OK;
}

bf_status bf_out_maybe_flush(bf_out *out, double seconds, bf_err *err)
{
    const double now = bf_coarse_time();
    const int enter = out->appending && !out->swmr && !out->failed &&
                      now - out->appending_since > SWMR_AFTER;
    if (!(enter || out->buffered_bytes > FLUSH_BYTES ||
          now - out->last_flush > seconds))
        return BF_OK;
    /* the test above touches no HDF5 state: the lock only for a flush */
    bf_h5_lock();
    bf_status st = enter ? bf_out_enter_swmr_(out, err) : BF_OK;
    if (!st)
        st = bf_out_flush(out, err);
    bf_h5_unlock();
    return st;
}

bf_status bf_out_start_appending(bf_out *out, bf_err *err)
{
    if (out->failed)
        return bf_fail(err, BF_EIO, "%s: an earlier write failed; the file "
                       "holds what was flushed before it", out->path);
    out->appending = 1;
    out->appending_since = bf_coarse_time();
    bf_status st = bf_out_flush(out, err);
    out->started = !st;
    return st;
}

static bf_status write_array(bf_out *out, const char *path, const void *data,
                             size_t n0, size_t n1, int is_int, const char *unit,
                             const char *doc, bf_err *err)
{
    if (out->failed)
        return bf_out_failed_before_(out, err);
    if (bf_out_before_metadata_(out, err))
        return BF_EIO;
    int rank = n1 ? 2 : 1;
    hsize_t dims[2] = {n0, n1};
    if (out->append && H5Lexists(out->file, path, H5P_DEFAULT) > 0)
        H5Ldelete(out->file, path, H5P_DEFAULT);
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t lcpl = bf_out_lcpl_();
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (out->deflate > 0 && 8.0 * (double)n0 * (double)(n1 ? n1 : 1) >
                                COMPRESS_ARRAY_BYTES) {
        /* chunks of about 1 MiB of whole rows */
        size_t rowbytes = 8 * (n1 ? n1 : 1), rows = (1u << 20) / rowbytes;
        hsize_t chunk[2] = {rows < 1 ? 1 : rows > n0 ? n0 : rows, n1};
        H5Pset_chunk(dcpl, rank, chunk);
        add_filters(out, dcpl);
    }
    hid_t d = H5Dcreate2(out->file, path, is_int ? H5T_STD_I64LE : H5T_IEEE_F64LE,
                         sp, lcpl, dcpl, H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Pclose(lcpl);
    herr_t rc = -1;
    if (d >= 0) {
        rc = (n0 && (n1 || rank == 1))
                 ? H5Dwrite(d, is_int ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE,
                            H5S_ALL, H5S_ALL, H5P_DEFAULT, data)
                 : 0;
        if (rc >= 0 && (bf_out_str_attr_(d, "unit", unit ? unit : "") ||
                        bf_out_str_attr_(d, "description", doc ? doc : "")))
            rc = -1;
        H5Dclose(d);
    }
    H5Sclose(sp);
    if (rc < 0)
        return bf_fail(err, BF_EIO, "%s: cannot write dataset %s", out->path,
                       path);
    return BF_OK;
}

bf_status bf_out_array(bf_out *out, const char *path, const double *data,
                       size_t n0, size_t n1, const char *unit, const char *doc,
                       bf_err *err)
{
    return write_array(out, path, data, n0, n1, 0, unit, doc, err);
}

bf_status bf_out_array_i64(bf_out *out, const char *path, const int64_t *data,
                           size_t n0, size_t n1, const char *unit,
                           const char *doc, bf_err *err)
{
    return write_array(out, path, data, n0, n1, 1, unit, doc, err);
}
