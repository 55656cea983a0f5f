/* h5out_impl.h: what h5out.c, h5attr.c and h5swmr.c share of an output file
 * (private to src/io; the interface is include/ballfilm/h5out.h). */
#ifndef BALLFILM_IO_H5OUT_IMPL_H
#define BALLFILM_IO_H5OUT_IMPL_H

#include <hdf5.h>
#include <stdint.h>

#include "ballfilm/h5out.h"

/* A run enters SWMR mode once it has stepped this long (s of wall time):
 * entering and leaving it cost a flush, the log, and the file closed and
 * opened again at the end, which a run of a few steps, or each case of a
 * sweep of tiny cases (bench/startup.sh), then does not pay. */
#define SWMR_AFTER 0.05

struct bf_series {
    hid_t dset;
    size_t ncols;    /* 0 for 1-D */
    size_t width;    /* values per row (max(ncols, 1)) */
    int is_int;
    size_t written;  /* rows on disk */
    size_t rpc;      /* rows per chunk */
    size_t nbuf, capbuf;
    size_t partial;  /* values of the row being built (bf_series_append_part) */
    unsigned char *buf;
    char *path;
    size_t *buffered; /* the output's count of bytes in every buffer */
    bf_out *out;
};

struct bf_out {
    hid_t file;
    hid_t root; /* "/", held open for its attributes (open_obj; -1: not) */
    int append; /* opened to continue a run */
    char *path; /* the result's path */
    char *part; /* the file written: path + ".part" */
    int lock_fd; /* descriptor of part holding the lock (-1: none) */
    char h5name[32]; /* the name HDF5 opens lock_fd's file by (outpath.h) */
    int failed;  /* a write failed: touch nothing more */
    bf_series **series;
    size_t nseries, capseries;
    size_t buffered_bytes; /* rows in the series' buffers, B: kept as they
                              are appended, truncated and flushed, so that
                              the test after every row is one compare */
    double last_flush;
    int deflate; /* level of new datasets' deflate filter (0: none) */
    size_t expect_rows; /* rows the series are expected to reach (0: not
                           known), for the size of their chunks */
    int swmr;        /* the file is in HDF5's SWMR mode (bf_out_enter_swmr_) */
    int appending;   /* bf_out_start_appending was called: the file enters
                        SWMR mode once the run has stepped SWMR_AFTER */
    double appending_since; /* when (bf_coarse_time) */
    hid_t log;       /* the flush log (h5part.h) while in SWMR mode, or -1 */
    int dirty;       /* something other than rows was written since the
                        last flush (HDF5 may hold metadata the file lacks) */
    int started;     /* bf_out_start_appending succeeded: this writer's
                        rows are the file's (finish may drop the log) */
    int64_t flushes; /* rows of the log */
};


/* h5out.c */
/* The writer's file-access list (append: to continue a killed run). */
hid_t bf_out_fapl_(int append);
/* A link-creation list that creates the groups of a path. */
hid_t bf_out_lcpl_(void);
/* After a failed write nothing more reaches the file: BF_EIO saying so. */
bf_status bf_out_failed_before_(const bf_out *out, bf_err *err);
/* A series' dataset-access list: its chunk cache. */
hid_t bf_out_series_dapl_(size_t rows_per_chunk, size_t ncols);
/* A UTF-8 string attribute written (or written over). */
bf_status bf_out_str_attr_(hid_t obj, const char *name, const char *value);

/* h5swmr.c */
/* Every series' dataset closed (its id -1). */
void bf_out_close_series_(bf_out *out);
/* Before writing anything other than rows (an attribute, an array, a new
 * or shorter series): out of SWMR mode, which allows only rows, and the
 * file marked dirty until the next flush. */
bf_status bf_out_before_metadata_(bf_out *out, bf_err *err);
bf_status bf_out_enter_swmr_(bf_out *out, bf_err *err);
bf_status bf_out_leave_swmr_(bf_out *out, bf_err *err);
bf_status bf_out_log_flush_(bf_out *out, bf_err *err);

#endif
