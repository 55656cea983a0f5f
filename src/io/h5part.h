/* h5part.h: reading a run's file while it is written, or after the run was
 * killed, and the pieces of HDF5 reading that src/io's readers and writer
 * share (private to src/io).
 *
 * While a run is stepping, h5out.c keeps its PATH.part in HDF5's
 * single-writer/multiple-reader (SWMR) mode: HDF5 then writes its
 * metadata in an order in which every state of the file on disk is a
 * file that opens, so a kill at any moment leaves one.  Two things remain
 * for a reader, and these functions do them:
 *
 * - A file of a writer in SWMR mode (running, or killed) carries HDF5's
 *   "open for writing" mark, and a plain read-only open refuses it;
 *   bf_h5_open_read then opens it as a SWMR reader.
 * - Each dataset's length reaches the disk on its own, so a kill inside a
 *   flush may leave some series longer than others, and rows whose length
 *   reached the disk before their data.  The writer therefore appends, once
 *   a flush has reached the file (after H5Fflush), a row to the log
 *   BF_H5_FLUSH_LOG: [g, rows of series 1, rows of series 2, ...], with the
 *   series' paths in its attribute "series" (one per line).  A reader takes
 *   the rows of the last complete flush: the last log row whose first
 *   value is its own number (counted from 1; a row whose length reached the
 *   disk before its values reads 0 there).  The log is deleted when the run
 *   ends (h5out.c, finish). */
#ifndef BALLFILM_IO_H5PART_H
#define BALLFILM_IO_H5PART_H

#include <hdf5.h>

#include "ballfilm/error.h"

#define BF_H5_FLUSH_LOG "/flushed_rows"

/* Set on a file-access list the property that `h5clear -s` sets: an open
 * goes past HDF5's open-for-writing mark (a read-write open clears it, a
 * read-only one leaves it in the file).  0, or -1 if this HDF5 has none. */
int bf_h5_fapl_past_mark(hid_t fapl);

/* FILE read-only: a plain open; for the file of a writer in SWMR mode, a
 * SWMR reader's open; for a file that HDF5 marks as open for writing by a
 * writer outside SWMR mode (killed at set-up, in its first 50 ms or at its
 * end), an open past the mark, which stays in the file.  A negative id if
 * none opens it. */
hid_t bf_h5_open_read(const char *file);

/* " (...)": why FILE may not open, to append to a message that it does
 * not: HDF5's open-for-writing mark when its superblock carries it (a run
 * killed outside SWMR mode, at set-up, in its first 50 ms of stepping or
 * while writing its last attributes, in the middle of a flush), naming
 * `h5clear -s`; "" otherwise.
 * Points into a buffer of this thread's last call. */
const char *bf_h5_open_hint(const char *file);

typedef struct bf_h5_flushed bf_h5_flushed;

/* The rows of the last complete flush of file f, named `file` (see
 * above), into *out: NULL when f has no log (a finished run's file, or one
 * not written by h5out.c) or no complete row of it.  A log that is not a
 * bounded table of integers with its series named is refused (BF_EINPUT,
 * naming the file). */
bf_status bf_h5_flushed_load(hid_t f, const char *file, bf_h5_flushed **out,
                             bf_err *err);
/* The rows of dataset `path` ("/time") that a reader may take: `extent`,
 * or fewer when the log holds fewer for it. */
hsize_t bf_h5_flushed_rows(const bf_h5_flushed *fl, const char *path,
                           hsize_t extent);
void bf_h5_flushed_free(bf_h5_flushed *fl);

/* The one check of a dataset before its rows are read (every reader of
 * src/io): bf_h5_dataset_shape (rank 1 or 2, numbers), its rows cut to
 * those of the last flush (fl; NULL: all), then bf_h5_dataset_fits
 * against a file of file_bytes bytes.  dims[1] is 0 for rank 1; *count
 * the doubles of the rows (count may be NULL). */
bf_status bf_h5_dataset_rows(hid_t d, const char *file, const char *path,
                             const bf_h5_flushed *fl, double file_bytes,
                             int *rank, hsize_t dims[2], size_t *count,
                             bf_err *err);

#endif
