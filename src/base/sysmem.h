/* sysmem.h: how much more memory this process may allocate, so that a run
 * whose estimate exceeds it is refused before it allocates (private to the
 * library; model.h, memory; docs/reliability.md).
 *
 * The smallest of, where the system tells:
 *   MemAvailable of /proc/meminfo     what the kernel can hand out without
 *                                     swapping (Linux >= 3.14)
 *   physical memory                   sysconf(_SC_PHYS_PAGES) pages, where
 *                                     /proc/meminfo is missing
 *   RLIMIT_AS - VmSize                `ulimit -v` less the address space
 *                                     already mapped (/proc/self/status)
 *   RLIMIT_DATA - VmData              `ulimit -d` less the data mapped
 *   memory.max - memory.current       the cgroup (v2) of the process: a
 *                                     container's or a batch job's limit
 */
#ifndef BALLFILM_BASE_SYSMEM_H
#define BALLFILM_BASE_SYSMEM_H

typedef struct bf_mem_avail {
    double bytes;     /* the smallest limit, B (INFINITY: none known) */
    char source[128]; /* which it is, for messages */
} bf_mem_avail;

void bf_mem_available(bf_mem_avail *a);

#endif
