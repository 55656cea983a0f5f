/* h5out.h: self-describing, crash-tolerant HDF5 output.
 *
 * A run appends rows to "series" (extendible, chunked datasets [n] or
 * [n x ncols]).  Rows are buffered in memory and reach the file only in
 * bf_out_flush(), which writes every buffered row of every series, updates
 * the extents and calls H5Fflush.  bf_out_maybe_flush() flushes when a
 * wall-clock interval has passed or the buffers grow large.
 *
 * A killed run.  Once set-up is written (bf_out_start_appending) and the
 * run has stepped 50 ms, the file is in HDF5's single-writer/multiple-
 * reader (SWMR) mode, in which every state on disk is a file that opens;
 * each complete flush adds a row to a log that readers (h5read.c,
 * h5info.c, xdmf.c, python/ballfilm/result.py) use to cut every series
 * to the rows of the last complete flush.  So a run killed with SIGKILL
 * while it steps, even inside a flush, leaves a file that opens and holds
 * every row of the last complete flush, the same number in every series
 * (src/io/h5swmr.c).  Set-up, the first 50 ms and the writing of a run's
 * last attributes are outside SWMR mode; a kill there leaves a file that
 * HDF5 marks as open for writing, which the program's readers read past
 * (h5py needs `h5clear -s` first), and a kill inside a flush there may
 * leave it torn or not opening (docs/reliability.md, "What is not
 * promised").
 *
 * Every dataset carries "unit" and "description" attributes.
 *
 * The file written is PATH.part, under an exclusive lock for as long as it
 * is open; bf_out_close renames it over PATH (the result appears at once,
 * a previous result survives until then), bf_out_close_keep leaves it as
 * PATH.part (an interrupted run continues it).  A second writer of the same
 * PATH is refused (BF_EIO).  A flush first reserves the space it needs; a
 * flush that cannot have it writes nothing and fails (BF_EIO "disk full"),
 * and nothing more is written after a failure, so the file on disk stays
 * the consistent state of the last flush.
 */
#ifndef BALLFILM_H5OUT_H
#define BALLFILM_H5OUT_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"

typedef struct bf_out bf_out;
typedef struct bf_series bf_series;

/* Create PATH.part (after locking it; a previous PATH.part of a run that
 * ended is truncated).  Parent groups of every path are created on
 * demand.  PATH.part is never opened through a symbolic link and must be
 * a regular file of this user with one name, and PATH must be
 * replaceable by this user (not a directory, not another user's file in
 * a sticky directory): otherwise BF_EINPUT (a directory) or BF_EIO, before
 * anything is written. */
bf_status bf_out_create(bf_out **out, const char *path, bf_err *err);
/* Open the file of a run to continue it (restart): PATH.part, or a copy
 * of PATH in a new PATH.part when the run had ended (PATH stays the
 * finished result until bf_out_close); bf_out_series then reopens
 * existing datasets (keeping their rows) and bf_out_array replaces
 * existing fixed datasets. */
bf_status bf_out_open_append(bf_out **out, const char *path, bf_err *err);
/* Compress the datasets created from now on with HDF5's shuffle and
 * deflate filters at `level` (1-9; 0, the default: no filters, the file
 * is laid out as without this call): every series, and fixed arrays of
 * more than 64 KiB. */
void bf_out_set_compression(bf_out *out, int level);
/* The number of rows the series of this run are expected to reach (0, the
 * default: not known).  A series created from now on is stored in chunks
 * of about 64 KiB (8192 rows of one value, fewer rows of wider ones);
 * with a hint below that, in chunks of the next power of two at or above
 * the hint but at least BF_OUT_MIN_CHUNK_ROWS rows (or the 64 KiB rule's
 * rows, if fewer), so that a short run writes a small file (a chunk is
 * written whole) while a series that outgrows the hint (a run continued
 * further, or events such as return-map points and Lyapunov
 * renormalisations, which come at their own pace) still grows by chunks
 * of 4 KiB or more.  The values stored do not depend on it, only their
 * layout in the file. */
#define BF_OUT_MIN_CHUNK_ROWS 512
void bf_out_expect_rows(bf_out *out, size_t rows);
/* Flush, close and rename PATH.part to PATH; *out is freed even on
 * error (the file is then left as PATH.part). */
bf_status bf_out_close(bf_out *out, bf_err *err);
/* Flush and close, leaving PATH.part (for a run to be continued). */
bf_status bf_out_close_keep(bf_out *out, bf_err *err);
/* The result's path PATH (the file being written is PATH.part). */
const char *bf_out_path(const bf_out *out);
/* 1 after a write failed (nothing more is written). */
int bf_out_failed(const bf_out *out);

/* An extendible series: ncols == 0 gives a 1-D dataset [n], otherwise a 2-D
 * dataset [n x ncols].  `is_int` selects int64 instead of float64. */
bf_series *bf_out_series(bf_out *out, const char *path, size_t ncols,
                         int is_int, const char *unit, const char *doc,
                         bf_err *err);
/* Buffer one row (ncols values, or 1 if ncols == 0). */
bf_status bf_series_append(bf_series *s, const double *row);
bf_status bf_series_append_i64(bf_series *s, const int64_t *row);
/* Buffer the next n values of the row being built (float64 series); the
 * row is added when all its values are there.  For a row that comes in
 * parts (a run split over ranks gathers it a block of particles at a
 * time); a whole append or a flush in the middle of one fails. */
bf_status bf_series_append_part(bf_series *s, const double *vals, size_t n);
size_t bf_series_rows(const bf_series *s); /* written + buffered */
const char *bf_series_path(const bf_series *s);
size_t bf_series_width(const bf_series *s); /* values per row */
/* Drop rows beyond `rows` (restart: rows written after the checkpoint). */
bf_status bf_series_truncate(bf_series *s, size_t rows, bf_err *err);
/* All series of a file, in creation order. */
size_t bf_out_nseries(const bf_out *out);
bf_series *bf_out_series_at(bf_out *out, size_t k);

/* A fixed dataset written at once: dims n0 (n1 == 0) or n0 x n1. */
bf_status bf_out_array(bf_out *out, const char *path, const double *data,
                       size_t n0, size_t n1, const char *unit, const char *doc,
                       bf_err *err);
bf_status bf_out_array_i64(bf_out *out, const char *path, const int64_t *data,
                           size_t n0, size_t n1, const char *unit,
                           const char *doc, bf_err *err);

/* Attributes on an object ("/" for the root, or a group/dataset path; groups
 * are created if needed). */
bf_status bf_out_attr_str(bf_out *out, const char *obj, const char *name,
                          const char *value, bf_err *err);
bf_status bf_out_attr_real(bf_out *out, const char *obj, const char *name,
                           double value, bf_err *err);
bf_status bf_out_attr_int(bf_out *out, const char *obj, const char *name,
                          int64_t value, bf_err *err);

bf_status bf_out_flush(bf_out *out, bf_err *err);
/* Set-up is written (the series created, the arrays and attributes known
 * at the start): from now on the run appends rows.  Flushes the file;
 * once the run has stepped 50 ms (at a bf_out_maybe_flush) the file
 * enters HDF5's single-writer/multiple-reader (SWMR) mode, in which a kill
 * at any moment leaves a file that opens, holding the rows of the last
 * complete flush (src/io/h5part.h; docs/output.md, "A killed run's
 * file").  Writing anything other than rows afterwards (an attribute, an
 * array, a new series) first leaves that mode, closing and opening the
 * file again; the next bf_out_maybe_flush enters it again.  A file that
 * cannot enter it (one of an older format, continued) is written as
 * before. */
bf_status bf_out_start_appending(bf_out *out, bf_err *err);
/* Flush if more than `seconds` of wall time passed since the last flush or
 * more than a few MiB are buffered (under the library's HDF5 lock: runs in
 * several threads of one process may call it). */
bf_status bf_out_maybe_flush(bf_out *out, double seconds, bf_err *err);

/* ---- reading back (tests, restarts, initial profiles) ----
 * A file read may have been written by anyone: every attribute and dataset
 * is checked for class, shape and size before it is read (a numeric
 * attribute is one integer or float; a text attribute one string of at
 * most 1 MiB; a dataset read as float64 of integer or float class, rank 1
 * or 2, no larger than the file's bytes on disk could hold, or 1100 times
 * that when it is compressed).  A file that breaks this is refused with
 * BF_EINPUT, naming the file and the object; a missing file, dataset or
 * attribute, or a failed read, is BF_EIO. */
/* Read a whole float64 dataset; *data is malloc'd, dims in n0, n1 (n1 = 0 for
 * 1-D). */
bf_status bf_h5_read(const char *file, const char *path, double **data,
                     size_t *n0, size_t *n1, bf_err *err);
/* A numeric attribute (any integer or float type) as a double. */
bf_status bf_h5_read_attr_real(const char *file, const char *obj,
                               const char *name, double *value, bf_err *err);
bf_status bf_h5_read_attr_str(const char *file, const char *obj,
                              const char *name, char **value, bf_err *err);

/* Several reads from one file opened once (each call above opens and
 * closes the file: a sweep reading four things of every case paid four
 * opens).  The same results and messages as the calls above. */
typedef struct bf_h5_reader bf_h5_reader;
bf_status bf_h5_reader_open(bf_h5_reader **r, const char *file, bf_err *err);
bf_status bf_h5_reader_read(bf_h5_reader *r, const char *path, double **data,
                            size_t *n0, size_t *n1, bf_err *err);
bf_status bf_h5_reader_attr_real(bf_h5_reader *r, const char *obj,
                                 const char *name, double *value,
                                 bf_err *err);
bf_status bf_h5_reader_attr_str(bf_h5_reader *r, const char *obj,
                                const char *name, char **value, bf_err *err);
/* Whether object obj has attribute name: 1, 0, or -1 when that cannot be
 * told (no object obj, a damaged file; err set, BF_EIO), so that a caller
 * can show an absent attribute as absent and fail on one it cannot read. */
int bf_h5_reader_has_attr(bf_h5_reader *r, const char *obj, const char *name,
                          bf_err *err);
void bf_h5_reader_close(bf_h5_reader *r); /* NULL is fine */

/* What a file holds (`ballfilm info`): every dataset, ordered by path. */
typedef struct bf_h5_dataset {
    char path[256];
    int rank;          /* 0 for a scalar, 1 [n], 2 [n0 x n1] */
    size_t dims[2];
    char kind;         /* 'f' float, 'i' integer, 's' string, '?' other */
    char unit[64];     /* its "unit" attribute ("" if none) */
    char description[256];
    /* what it is over time and what a reader may do with it, its "kind"
     * and "role" attributes, written from its series spec (series.h:
     * rows, snapshot, events, static; time, position, field, ...; "" if
     * none) */
    char series_kind[16];
    char role[24];
} bf_h5_dataset;
/* *list is malloc'd (free it), *n datasets.  A unit, description, kind or
 * role that is not one bounded string, or that cannot be read, is refused
 * (BF_EINPUT or BF_EIO, naming the file, the dataset and the
 * attribute). */
bf_status bf_h5_list(const char *file, bf_h5_dataset **list, size_t *n,
                     bf_err *err);
/* The same, stopping with BF_INTERRUPTED once *stop_flag is set (checked
 * before each object; NULL: never stops). */
bf_status bf_h5_list_until(const char *file, bf_h5_dataset **list,
                           size_t *n, const volatile sig_atomic_t *stop_flag,
                           bf_err *err);

#endif
