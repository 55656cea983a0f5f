/* h5check.h: the checks every reader of an HDF5 file makes before it reads
 * (private to src/io).  A file given to the program may have been written
 * by anyone: an attribute or dataset is read only after its class, rank,
 * shape and size are those the reader expects, and a size only after it is
 * known that the file could hold it.
 *
 * What is accepted:
 * - a numeric attribute: integer or float class, scalar or of one element;
 * - a text attribute: string class (fixed or variable length), scalar or
 *   of one element, at most BF_H5_MAX_TEXT bytes;
 * - a dataset read as numbers: integer or float class, rank 1 or 2, whose
 *   elements (of the rows read) take at most the file's size in bytes on
 *   disk as stored, or BF_H5_MAX_RATIO times that when the dataset is
 *   stored through filters (compressed).  HDF5 reads the unallocated parts
 *   of a dataset as its fill value: without this bound a file of a few
 *   kilobytes could claim, and have a reader allocate, terabytes.
 *
 * Everything else is refused with BF_EINPUT and a message naming the file
 * and the object; a read that HDF5 fails on a dataset that passed is
 * BF_EIO. */
#ifndef BALLFILM_IO_H5CHECK_H
#define BALLFILM_IO_H5CHECK_H

#include <hdf5.h>
#include <stddef.h>

#include "ballfilm/error.h"

/* A text attribute longer than this is not one the program wrote (the
 * longest is a scene's text). */
#define BF_H5_MAX_TEXT ((size_t)1 << 20)
/* Deflate cannot compress more than about 1032 to 1 (a 258-byte match per
 * two bits of output); a dataset stored through filters may therefore hold
 * this many times its file's size, and no more. */
#define BF_H5_MAX_RATIO 1100.0

/* The size of FILE in bytes (stat), or -1 when it cannot be had. */
double bf_h5_file_bytes(const char *file);

/* The numeric attribute `name` of object `obj` (for messages) opened as a;
 * file names the file in messages. */
bf_status bf_h5_attr_number(hid_t a, const char *file, const char *obj,
                            const char *name, double *value, bf_err *err);
/* The text attribute opened as a, as a malloc'd, NUL-terminated copy (a
 * NUL byte inside ends it). */
bf_status bf_h5_attr_string(hid_t a, const char *file, const char *obj,
                            const char *name, char **value, bf_err *err);

/* The numeric root attribute `name` of the open file f (fname for
 * messages), or fallback when the file has none; one that is there but is
 * not one number, or cannot be read or looked up, is an error. */
bf_status bf_h5_root_number(hid_t f, const char *fname, const char *name,
                            double fallback, double *value, bf_err *err);

/* The shape of dataset d (path for messages) to be read as numbers: rank 1
 * or 2 of integer or float class; dims[1] is 0 for rank 1. */
bf_status bf_h5_dataset_shape(hid_t d, const char *file, const char *path,
                              int *rank, hsize_t dims[2], bf_err *err);
/* Whether the first `rows` rows of d, of `width` values each (1 for rank
 * 1), could be held by a file of file_bytes bytes (see above); their
 * count as doubles in *count.  BF_EINPUT if not, or if the count
 * overflows. */
bf_status bf_h5_dataset_fits(hid_t d, const char *file, const char *path,
                             hsize_t rows, hsize_t width, double file_bytes,
                             size_t *count, bf_err *err);

#endif
