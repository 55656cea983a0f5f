/* outpath.h: the files a run creates, in directories it may share with
 * people it does not trust (private to the library).
 *
 * A world-writable directory (/tmp) or a group's scratch space lets anyone
 * plant a symbolic link, or a file of their own, at a name the program is
 * about to write (OUT.h5.part, OUT.h5.ckpt.tmp): opened by name, the
 * program would write through the link into the link's target.  So every
 * file the program writes is opened here: never through a link at its last
 * component (O_NOFOLLOW), and only if it is a regular file of this user
 * with no other name (fstat of the descriptor opened, so what is checked
 * is what is written).  HDF5 then gets that very file (bf_path_h5_name).
 * Links in the directories of the path are the user's own choice and are
 * followed.
 *
 * The result's name itself is replaced by a rename, which replaces a link
 * rather than writing through it; whether that rename will be possible is
 * checked at the start (bf_path_check_replaceable), not found at the end
 * of a long run. */
#ifndef BALLFILM_IO_OUTPATH_H
#define BALLFILM_IO_OUTPATH_H

#include <stdio.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "ballfilm/error.h"

/* Why a file described by sb may not be written in place by user euid
 * (a link, a directory, another user's file, a file with other names),
 * or NULL if it may. */
const char *bf_path_own_refusal(const struct stat *sb, uid_t euid);

/* A descriptor (O_RDWR, close-on-exec) of the file at path, created
 * (mode 0666 less the umask) if there is none, refused (-1, BF_EIO with a
 * message naming path and what it is) if it is a link or anything
 * bf_path_own_refusal refuses.  Its contents are kept: truncate through
 * the descriptor once it is checked (O_TRUNC would truncate first). */
int bf_path_open_own(const char *path, bf_err *err);

/* Nothing at path, or a file bf_path_open_own would open: otherwise
 * BF_EIO naming it (to refuse at the start what would fail later). */
bf_status bf_path_check_own(const char *path, bf_err *err);

/* The writer's lock on the file of fd (the output's PATH.part): 0, or an
 * errno (EAGAIN: another process holds it). */
int bf_path_lock(int fd);

/* bf_path_open_own, truncated, as a stream for writing ("w"). */
FILE *bf_path_fopen_own(const char *path, bf_err *err);

/* The name under which HDF5 opens the file of descriptor fd (buf of at
 * least 32 bytes): /proc/self/fd/FD, which the kernel resolves to the
 * descriptor's own file, whatever has become of its name since. */
const char *bf_path_h5_name(int fd, char *buf, size_t cap);

/* Why a rename onto a file described by target (NULL: there is none) in a
 * directory described by dir may fail for user euid, or NULL.
 * dir_writable: the directory can be written and searched by euid.
 * *status: BF_EINPUT for a directory (the name was mistyped), BF_EIO for
 * permissions. */
const char *bf_path_replace_refusal(const struct stat *target,
                                    const struct stat *dir, uid_t euid,
                                    int dir_writable, bf_status *status);

/* path can be created, or replaced by a rename from its directory, by
 * this process: otherwise a failure naming it (bf_path_replace_refusal). */
bf_status bf_path_check_replaceable(const char *path, bf_err *err);

/* 1 if a and b are the same existing file (device and inode, through
 * links), whatever their names. */
int bf_path_same_file(const char *a, const char *b);

/* Copy the whole file at from into the empty file of descriptor to (a
 * reflink where the file system has them).  0, or an errno. */
int bf_path_copy_into(const char *from, int to);

#endif
