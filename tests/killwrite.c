/* killwrite.c: a kill at a chosen write, for tests/test_h5out.c
 * (kill_at_every_write_keeps_the_file), tests/python/test_load_run.py and
 * tests/killpoints.py.
 *
 * Preloaded into bin/ballfilm (LD_PRELOAD=build/tests/killwrite.so), it
 * wraps pwrite, by which HDF5's default file driver writes, and raises
 * SIGKILL before the BF_KILL_AT_WRITE-th write after the file entered
 * HDF5's SWMR mode: the write of a version 2 or 3 superblock (the format's
 * signature at offset 0) whose "file consistency flags" (byte 11) carry
 * the SWMR-writer bit 0x04.  Writes before that are not counted, so that
 * a number names the same place in the stepping run however long its
 * set-up took.  With BF_KILL_FROM_START=1 every write counts, from the
 * first (for a program that never enters SWMR mode: tests/killpoints.py).
 * With BF_KILL_IN=SUFFIX only writes to files whose name ends in SUFFIX
 * count, from the first (".ckpt.tmp": a kill while a checkpoint is being
 * written, between two flushes of the output).  Without BF_KILL_AT_WRITE,
 * every write passes.
 *
 * With BF_FREEZE_COARSE_CLOCK=1 the kernel's coarse monotonic clock (by
 * which the program decides when a flush is due and when the output
 * enters SWMR mode, src/base/clock.h) stands still at its first reading,
 * so that those decisions no longer depend on how fast the machine runs:
 * a test that kills "before SWMR mode" then does so on a loaded machine
 * and under the sanitizers too. */
#define _GNU_SOURCE /* RTLD_NEXT */
#include <dlfcn.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

typedef ssize_t (*pwrite_fn)(int, const void *, size_t, off_t);

static long kill_at = -1; /* 0: never */
static long counted;      /* writes since SWMR mode began */
static int in_swmr;

/* Whether descriptor fd names a file whose name ends in suffix. */
static int fd_ends_in(int fd, const char *suffix)
{
    char link[64], name[4096];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t len = readlink(link, name, sizeof name - 1);
    size_t ls = strlen(suffix);
    if (len < 0 || (size_t)len < ls)
        return 0;
    name[len] = '\0';
    return !strcmp(name + len - ls, suffix);
}

static void before_write(int fd, const void *buf, size_t n, off_t off)
{
    if (kill_at < 0) {
        const char *e = getenv("BF_KILL_AT_WRITE");
        kill_at = e ? atol(e) : 0;
    }
    if (!kill_at)
        return;
    const char *in = getenv("BF_KILL_IN");
    if (in) {
        if (fd_ends_in(fd, in) && ++counted == kill_at)
            raise(SIGKILL);
        return;
    }
    if (!in_swmr && getenv("BF_KILL_FROM_START"))
        in_swmr = 1;
    const unsigned char *b = buf;
    if (!in_swmr && off == 0 && n >= 12 && !memcmp(b, "\211HDF\r\n\032\n", 8) &&
        b[8] >= 2 && (b[11] & 0x04)) {
        in_swmr = 1;
        return; /* the write that enters SWMR mode is not counted */
    }
    if (in_swmr && ++counted == kill_at)
        raise(SIGKILL);
}

/* The write itself, by the next definition of `name` (libc's). */
static ssize_t forward(pwrite_fn *next, const char *name, int fd,
                       const void *buf, size_t n, off_t off)
{
    if (!*next)
        *next = (pwrite_fn)dlsym(RTLD_NEXT, name);
    before_write(fd, buf, n, off);
    return (*next)(fd, buf, n, off);
}

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off)
{
    static pwrite_fn next;
    return forward(&next, "pwrite", fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void *buf, size_t n, off_t off)
{
    static pwrite_fn next;
    return forward(&next, "pwrite64", fd, buf, n, off);
}

typedef int (*clock_gettime_fn)(clockid_t, struct timespec *);

int clock_gettime(clockid_t id, struct timespec *ts)
{
    static clock_gettime_fn next;
    static struct timespec frozen;
    static int have_frozen;
    if (!next)
        next = (clock_gettime_fn)dlsym(RTLD_NEXT, "clock_gettime");
#ifdef CLOCK_MONOTONIC_COARSE
    if (id == CLOCK_MONOTONIC_COARSE && getenv("BF_FREEZE_COARSE_CLOCK")) {
        if (!have_frozen) {
            int r = next(id, &frozen);
            if (r)
                return r;
            have_frozen = 1;
        }
        *ts = frozen;
        return 0;
    }
#endif
    return next(id, ts);
}
