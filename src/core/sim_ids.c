/* sim_ids.c: the identity of a run and of its input, written into its
 * output and its checkpoints (docs/reliability.md, "Checkpoints": tied
 * to their run). */
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/hash.h"
#include "core/sim_impl.h"

/* 64 random bits of the kernel mixed with the wall clock and the process
 * id: two runs never share one, even two started in the same
 * nanosecond or on a system without /dev/urandom. */
void bf_sim_new_run_id_(char buf[20])
{
    uint64_t r = 0;
    int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        if (read(fd, &r, sizeof r) != (ssize_t)sizeof r)
            r = 0;
        close(fd);
    }
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_REALTIME, &ts);
    int64_t mix[3] = {(int64_t)ts.tv_sec, (int64_t)ts.tv_nsec,
                      (int64_t)getpid()};
    r ^= bf_hash64(BF_HASH_INIT, mix, sizeof mix);
    snprintf(buf, 20, "%016llx", (unsigned long long)r);
}

/* FNV-1a of the scene's text, a NUL and its overrides (one per line):
 * everything the run's parameters are resolved from. */
void bf_sim_scene_hash_(const char *text, const char *sets, char buf[20])
{
    uint64_t h = bf_hash64(BF_HASH_INIT, text, strlen(text) + 1);
    h = bf_hash64(h, sets, strlen(sets));
    snprintf(buf, 20, "%016llx", (unsigned long long)h);
}
