/* outpath.c: files created without following links, renames checked at
 * the start (see outpath.h). */
#define _GNU_SOURCE /* copy_file_range */
#include "io/outpath.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *bf_path_own_refusal(const struct stat *sb, uid_t euid)
{
    if (S_ISLNK(sb->st_mode))
        return "it is a symbolic link";
    if (S_ISDIR(sb->st_mode))
        return "it is a directory";
    if (!S_ISREG(sb->st_mode))
        return "it is not a regular file";
    if (sb->st_uid != euid)
        return "it belongs to another user";
    /* a hard link planted by someone who could read the file: writing it
     * would change the file under its other name too */
    if (sb->st_nlink != 1)
        return "it has other names (hard links)";
    return NULL;
}

int bf_path_open_own(const char *path, bf_err *err)
{
    int fd = open(path, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
        /* O_NOFOLLOW fails with ELOOP on a link at the last component */
        if (errno == ELOOP)
            bf_fail(err, BF_EIO, "%s: refused: it is a symbolic link (a file "
                    "the program writes is never written through a link); "
                    "remove it", path);
        else
            bf_fail(err, BF_EIO, "%s: cannot create it: %s", path,
                    strerror(errno));
        return -1;
    }
    struct stat sb;
    if (fstat(fd, &sb)) {
        bf_fail(err, BF_EIO, "%s: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    const char *why = bf_path_own_refusal(&sb, geteuid());
    if (why) {
        bf_fail(err, BF_EIO, "%s: refused: %s, not a file of this run's; "
                "remove it or choose another output file", path, why);
        close(fd);
        return -1;
    }
    return fd;
}

bf_status bf_path_check_own(const char *path, bf_err *err)
{
    struct stat sb;
    if (lstat(path, &sb))
        return errno == ENOENT ? BF_OK
                               : bf_fail(err, BF_EIO, "%s: %s", path,
                                         strerror(errno));
    const char *why = bf_path_own_refusal(&sb, geteuid());
    if (why)
        return bf_fail(err, BF_EIO, "%s: refused: %s, not a file of this "
                       "run's; remove it or choose another output file",
                       path, why);
    return BF_OK;
}

FILE *bf_path_fopen_own(const char *path, bf_err *err)
{
    int fd = bf_path_open_own(path, err);
    if (fd < 0)
        return NULL;
    FILE *f = NULL;
    if (ftruncate(fd, 0) || !(f = fdopen(fd, "w"))) {
        bf_fail(err, BF_EIO, "%s: cannot write it: %s", path,
                strerror(errno));
        close(fd);
    }
    return f;
}

/* The writer's lock on PATH.part: a write lock on the whole file, held
 * by this open file description (Linux OFD locks; POSIX record locks
 * elsewhere).  Not flock(2): HDF5 (1.10 and later) takes flock(LOCK_SH)
 * when a reader opens a file, and an exclusive flock would keep h5py and
 * `ballfilm xdmf` from reading a run while it is written.  Record locks
 * and flock locks do not conflict on Linux.  Returns 0 or an errno. */
int bf_path_lock(int fd)
{
    struct flock lk = {.l_type = F_WRLCK, .l_whence = SEEK_SET};
#ifdef F_OFD_SETLK
    if (!fcntl(fd, F_OFD_SETLK, &lk))
        return 0;
#else
    if (!fcntl(fd, F_SETLK, &lk))
        return 0;
#endif
    return errno == EACCES ? EAGAIN : errno;
}

const char *bf_path_h5_name(int fd, char *buf, size_t cap)
{
    snprintf(buf, cap, "/proc/self/fd/%d", fd);
    return buf;
}

/* The directory of path, as a path ("." for a bare name). */
static void dir_of(const char *path, char *dir, size_t cap)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, cap, ".");
    else
        snprintf(dir, cap, "%.*s", (int)(slash - path + (slash == path)),
                 path);
}

const char *bf_path_replace_refusal(const struct stat *target,
                                    const struct stat *dir, uid_t euid,
                                    int dir_writable, bf_status *status)
{
    *status = BF_EINPUT;
    if (target && S_ISDIR(target->st_mode))
        return "it is a directory; name a file";
    *status = BF_EIO;
    if (!S_ISDIR(dir->st_mode))
        return "its directory is not a directory";
    if (!dir_writable)
        return "its directory is not writable by this user";
    /* in a sticky directory (/tmp) only the owner of an entry, the
     * directory's owner or root may remove or replace it (rename(2)) */
    if (target && (dir->st_mode & S_ISVTX) && euid != 0 &&
        target->st_uid != euid && dir->st_uid != euid)
        return "it belongs to another user in a sticky directory (such as "
               "/tmp), where this user cannot replace it";
    return NULL;
}

bf_status bf_path_check_replaceable(const char *path, bf_err *err)
{
    char dir[4096];
    dir_of(path, dir, sizeof dir);
    struct stat tsb, dsb;
    const int has = !lstat(path, &tsb);
    if (!has && errno != ENOENT)
        return bf_fail(err, BF_EIO, "%s: %s", path, strerror(errno));
    if (stat(dir, &dsb))
        return bf_fail(err, BF_EIO, "%s: its directory %s: %s", path, dir,
                       strerror(errno));
    const int writable = !faccessat(AT_FDCWD, dir, W_OK | X_OK, AT_EACCESS);
    bf_status st;
    const char *why = bf_path_replace_refusal(has ? &tsb : NULL, &dsb,
                                              geteuid(), writable, &st);
    if (why)
        return bf_fail(err, st, "%s: the result cannot be written there: %s",
                       path, why);
    return BF_OK;
}

int bf_path_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return a && b && *a && *b && !stat(a, &sa) && !stat(b, &sb) &&
           sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

int bf_path_copy_into(const char *from, int to)
{
    int in = open(from, O_RDONLY | O_CLOEXEC);
    if (in < 0)
        return errno;
    struct stat sb;
    int e = fstat(in, &sb) ? errno : !S_ISREG(sb.st_mode) ? EINVAL : 0;
    /* copy_file_range shares the blocks where the file system can (a
     * reflink on btrfs, XFS); read and write where it cannot */
    off_t done = 0;
    int plain = 0;
    while (!e && done < sb.st_size) {
        ssize_t got;
        if (!plain) {
            loff_t at_in = done, at_out = done;
            got = copy_file_range(in, &at_in, to, &at_out,
                                  (size_t)(sb.st_size - done), 0);
            if (got < 0 && (errno == EXDEV || errno == ENOSYS ||
                            errno == EINVAL || errno == EOPNOTSUPP)) {
                plain = 1;
                continue;
            }
        } else {
            char buf[1 << 16];
            got = pread(in, buf, sizeof buf, done);
            if (got > 0 && pwrite(to, buf, (size_t)got, done) != got)
                got = -1;
        }
        if (got < 0)
            e = errno ? errno : EIO;
        else if (got == 0)
            e = EIO; /* the file shrank while it was copied */
        else
            done += got;
    }
    close(in);
    return e;
}
