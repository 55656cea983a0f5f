/* xdmf_file.c: the sidecar's file and how it names its HDF5 file (see
 * xdmf_file.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "io/xdmf_file.h"

#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The directory of path, resolved (malloc'd). */
static char *real_dir(const char *path)
{
    char *d = strdup(path);
    if (!d)
        return NULL;
    char *slash = strrchr(d, '/');
    if (slash)
        *(slash == d ? slash + 1 : slash) = '\0';
    char *r = realpath(slash ? d : ".", NULL);
    free(d);
    return r;
}

/* target named relative to the directory dir (both absolute). */
static char *relative(const char *target, const char *dir)
{
    size_t common = 0, k = 0;
    for (; target[k] && target[k] == dir[k]; k++)
        if (target[k] == '/')
            common = k;
    if (!dir[k] && target[k] == '/')
        common = k;
    size_t ups = 0;
    for (const char *p = dir + common; *p; p++)
        ups += *p == '/' && p[1] != '\0';
    if (!strcmp(dir, "/"))
        ups = 0;
    const char *rest = target + common + 1;
    char *r = malloc(3 * ups + strlen(rest) + 1);
    if (!r)
        return NULL;
    r[0] = '\0';
    for (size_t u = 0; u < ups; u++)
        strcat(r, "../");
    strcat(r, rest);
    return r;
}

/* XML-escaped copy of s (malloc'd). */
static char *xml_escape(const char *s)
{
    char *e = malloc(6 * strlen(s) + 1), *o = e;
    if (!e)
        return NULL;
    for (; *s; s++) {
        const char *r = *s == '&'    ? "&amp;"
                        : *s == '<'  ? "&lt;"
                        : *s == '>'  ? "&gt;"
                        : *s == '"'  ? "&quot;"
                        : *s == '\'' ? "&apos;"
                                     : NULL;
        if (r) {
            strcpy(o, r);
            o += strlen(r);
        } else {
            *o++ = *s;
        }
    }
    *o = '\0';
    return e;
}

char *bf_xdmf_href(const char *h5_path, const char *xmf_path)
{
    char *target = realpath(h5_path, NULL), *dir = real_dir(xmf_path);
    char *rel = target && dir ? relative(target, dir) : NULL;
    char *e = rel ? xml_escape(rel) : NULL;
    free(target);
    free(dir);
    free(rel);
    return e;
}

/* The sidecar's file, opened for writing in place without following a
 * link: a symbolic link planted at xmf_path, or a file of another user,
 * is refused (BF_EIO, naming it); a character device (/dev/null) is
 * written to.  *created: the file was not there before. */
bf_status bf_xdmf_open(const char *xmf_path, int *fd, int *created,
                       bf_err *err)
{
    struct stat sb;
    *created = lstat(xmf_path, &sb) != 0;
    if (!*created && S_ISLNK(sb.st_mode))
        return bf_fail(err, BF_EIO, "%s: is a symbolic link; the XDMF file "
                       "is not written through one (remove it)", xmf_path);
    /* O_NONBLOCK: a FIFO planted there is refused, not waited on */
    *fd = open(xmf_path, O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK |
                             O_CLOEXEC, 0666);
    if (*fd < 0)
        return bf_fail(err, BF_EIO, "%s: cannot create the XDMF file",
                       xmf_path);
    const char *why = NULL;
    if (fstat(*fd, &sb))
        why = "cannot be examined";
    else if (S_ISREG(sb.st_mode) && sb.st_uid != geteuid())
        why = "belongs to another user; it is not written over";
    else if (S_ISREG(sb.st_mode) && sb.st_nlink > 1)
        why = "has other names (a hard link); writing it would change "
              "them too";
    else if (!S_ISREG(sb.st_mode) && !S_ISCHR(sb.st_mode))
        why = "is not a regular file";
    else if (fcntl(*fd, F_SETFL, fcntl(*fd, F_GETFL) & ~O_NONBLOCK) < 0)
        why = "cannot be written";
    if (why) {
        close(*fd);
        *fd = -1;
        return bf_fail(err, BF_EIO, "%s: %s", xmf_path, why);
    }
    return BF_OK;
}

/* Close the sidecar: a regular file cut to what was written, or after a
 * failure removed when this call created it and cut to nothing when it
 * was written over in place (no earlier sidecar's tail makes a partial
 * one look complete; a pipe or a device is not cut). */
bf_status bf_xdmf_close(FILE *f, int fd, const char *xmf_path, int created,
                        bf_status st, bf_err *err)
{
    struct stat sb, now;
    const int regular = !fstat(fd, &sb) && S_ISREG(sb.st_mode);
    const int flushed = !fflush(f);
    const off_t end = regular && flushed ? ftello(f) : 0;
    int bad = !flushed || end < 0 || ferror(f);
    if (regular && ftruncate(fd, st || bad ? 0 : end))
        bad = 1;
    if ((st || bad) && regular && created && !lstat(xmf_path, &now) &&
        now.st_dev == sb.st_dev && now.st_ino == sb.st_ino)
        unlink(xmf_path);
    if ((fclose(f) | bad) && !st)
        st = bf_fail(err, BF_EIO, "%s: writing the XDMF file failed "
                     "(disk full?)", xmf_path);
    return st;
}

