/* xdmf_file.h: the file of an XDMF sidecar (private to src/io, for
 * xdmf.c): how it names the HDF5 file, and its opening and closing. */
#ifndef BALLFILM_IO_XDMF_FILE_H
#define BALLFILM_IO_XDMF_FILE_H

#include <stdio.h>

#include "ballfilm/error.h"

/* h5_path named relative to the directory of xmf_path, XML-escaped
 * (malloc'd); NULL when either cannot be resolved or out of memory. */
char *bf_xdmf_href(const char *h5_path, const char *xmf_path);

/* Open xmf_path for writing in place, without following a link: a
 * symbolic link, a FIFO or another non-regular file (but a character
 * device such as /dev/null), or a file of another user there is refused
 * (BF_EIO, naming it).  *created: the file was not there before. */
bf_status bf_xdmf_open(const char *xmf_path, int *fd, int *created,
                       bf_err *err);

/* Close f (on fd): a regular file is cut to what was written; after a
 * failure (st, or a failed write) it is removed when bf_xdmf_open created
 * it and cut to nothing when it was written over in place, so that no
 * partial sidecar remains.  Returns st, or BF_EIO when writing failed. */
bf_status bf_xdmf_close(FILE *f, int fd, const char *xmf_path, int created,
                        bf_status st, bf_err *err);

#endif
