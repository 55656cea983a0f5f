/* heap.c: the program's heap made ready before a run, in one system call.
 *
 * A small run spends most of its start-up in page faults: HDF5 clears a
 * metadata cache of about half a MiB for every file it opens (the output
 * file, then again for the XDMF sidecar), writes every parameter as an
 * attribute, and the heap grows page by page; some 600 faults in all
 * (perf stat -e page-faults on the scene of bench/startup.sh).  A fault
 * is cheap on bare metal and expensive in some virtual machines (about
 * 10 us each on the AMD machine of docs/performance.md, where they were
 * most of the 17 ms).  So the program asks the kernel once for the pages
 * of the first 2 MiB of its heap (MADV_POPULATE_WRITE, Linux 5.14 and
 * later; elsewhere the call fails and nothing changes) and keeps blocks
 * below 4 MiB in the heap (M_MMAP_THRESHOLD) and freed ones there
 * (M_TRIM_THRESHOLD), so that a second file open reuses the pages of the
 * first.  The library does not do this: how the heap of a process is run
 * is its program's choice.  Only the command line calls it.
 */
#define _DEFAULT_SOURCE 1 /* madvise */

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli.h"

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23 /* linux/mman.h, Linux 5.14 */
#endif

enum { WARM_BYTES = 2 << 20, HEAP_BLOCKS = 4 << 20, PAGE = 4096 };

void bf_cli_warm_heap(void)
{
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
    if (!mallopt(M_MMAP_THRESHOLD, HEAP_BLOCKS) ||
        !mallopt(M_TRIM_THRESHOLD, 2 * HEAP_BLOCKS))
        return;
    char *p = malloc(WARM_BYTES);
    if (!p)
        return;
    const uintptr_t a = ((uintptr_t)p + PAGE - 1) & ~(uintptr_t)(PAGE - 1),
                    e = ((uintptr_t)p + WARM_BYTES) & ~(uintptr_t)(PAGE - 1);
    if (e > a)
        (void)madvise((void *)a, e - a, MADV_POPULATE_WRITE);
    free(p); /* stays in the heap: below M_TRIM_THRESHOLD */
#endif
}
