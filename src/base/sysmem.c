/* sysmem.c: the memory this process may still allocate (see sysmem.h).
 * Every source is optional: what cannot be read is left out, and with
 * none the answer is INFINITY (no refusal). */
#define _DEFAULT_SOURCE /* sysconf(_SC_PHYS_PAGES) */
#include "base/sysmem.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* Take limit `bytes` from `what` if it is the smallest so far. */
static void consider(bf_mem_avail *a, double bytes, const char *what)
{
    if (!(bytes < a->bytes))
        return;
    a->bytes = bytes > 0 ? bytes : 0;
    snprintf(a->source, sizeof a->source, "%s", what);
}

/* The value of the line "key: N kB" of a /proc file, in bytes (-1: none). */
static double proc_kb(const char *file, const char *key)
{
    FILE *f = fopen(file, "r");
    if (!f)
        return -1;
    char line[256];
    double v = -1;
    size_t len = strlen(key);
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, key, len) && line[len] == ':') {
            double kb;
            if (sscanf(line + len + 1, "%lf", &kb) == 1)
                v = 1024.0 * kb;
            break;
        }
    fclose(f);
    return v;
}

/* A number of bytes in a file of one line (-1: none, or "max"). */
static double file_bytes(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    double v;
    int ok = fscanf(f, "%lf", &v) == 1;
    fclose(f);
    return ok ? v : -1;
}

static void rlimit(bf_mem_avail *a, int which, const char *status_key,
                   const char *what)
{
    struct rlimit rl;
    if (getrlimit(which, &rl) || rl.rlim_cur == RLIM_INFINITY)
        return;
    double used = proc_kb("/proc/self/status", status_key);
    char buf[128];
    snprintf(buf, sizeof buf, "%s (%.0f MiB, of which %.0f MiB are mapped)",
             what, (double)rl.rlim_cur / 1048576.0,
             used > 0 ? used / 1048576.0 : 0.0);
    consider(a, (double)rl.rlim_cur - (used > 0 ? used : 0), buf);
}

/* The memory controller of this process's cgroup: v2 (memory.max at the
 * path of the line "0::PATH" of /proc/self/cgroup), else v1. */
static void cgroup(bf_mem_avail *a)
{
    char path[600] = "", line[512];
    FILE *f = fopen("/proc/self/cgroup", "r");
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "0::", 3)) {
            line[strcspn(line, "\n")] = '\0';
            snprintf(path, sizeof path, "/sys/fs/cgroup%s",
                     strcmp(line + 3, "/") ? line + 3 : "");
        }
    if (f)
        fclose(f);
    char max[700], cur[700];
    snprintf(max, sizeof max, "%s/memory.max", path);
    snprintf(cur, sizeof cur, "%s/memory.current", path);
    double lim = path[0] ? file_bytes(max) : -1, used = file_bytes(cur);
    if (lim < 0) {
        lim = file_bytes("/sys/fs/cgroup/memory/memory.limit_in_bytes");
        used = file_bytes("/sys/fs/cgroup/memory/memory.usage_in_bytes");
    }
    /* "no limit" reads as 2^63 rounded to pages */
    if (lim > 0 && lim < 4e18)
        consider(a, lim - (used > 0 ? used : 0),
                 "the cgroup's memory limit (container or batch job)");
}

void bf_mem_available(bf_mem_avail *a)
{
    a->bytes = INFINITY;
    snprintf(a->source, sizeof a->source, "no limit known");
    double avail = proc_kb("/proc/meminfo", "MemAvailable");
    if (avail >= 0) {
        consider(a, avail, "MemAvailable of /proc/meminfo");
    } else {
        long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
        if (pages > 0 && size > 0)
            consider(a, (double)pages * (double)size, "the physical memory");
    }
    rlimit(a, RLIMIT_AS, "VmSize", "ulimit -v (RLIMIT_AS)");
    rlimit(a, RLIMIT_DATA, "VmData", "ulimit -d (RLIMIT_DATA)");
    cgroup(a);
}
