/* heap.c: the program's heap made ready before a run, in two system calls.
 *
 * A small run spends most of its start-up touching memory for the first
 * time: HDF5 clears a metadata cache of about half a MiB for every file it
 * opens (the output file, then again for the XDMF sidecar), writes every
 * parameter as an attribute, and the heap grows page by page.  The first
 * write to a 4 KiB page is cheap on bare metal and expensive in some
 * virtual machines: on the AMD machine of docs/performance.md (a PVM
 * guest) bench/bench_pages prints about 9.6 us a page faulted in by the
 * write, 0.7-0.9 us for a page asked for at once (MADV_POPULATE_WRITE)
 * and then written, and 0.12 us for a 4 KiB part of a 2 MiB huge page.
 * So the program lays the start of its heap on one 2 MiB huge page
 * (MADV_HUGEPAGE: one entry for the whole page; honoured where
 * transparent huge pages are "always" or "madvise", the Linux default)
 * and asks the kernel for it at once (MADV_POPULATE_WRITE, Linux 5.14 and
 * later; elsewhere either call fails and nothing changes; where the kernel
 * has no free huge page it may compact memory first, "defrag", or give
 * 4 KiB pages).  Blocks below 4 MiB stay in the heap (M_MMAP_THRESHOLD)
 * and freed ones there (M_TRIM_THRESHOLD), so that a second file open
 * reuses the pages of the first.  The library does not do this: how the
 * heap of a process is run is its program's choice.  Only the command
 * line calls it.
 *
 * Measured with bench/startup.sh's scene run alternately with and without
 * the huge page (150 pairs): 12.8 -> 9.8 ms wall time at best, 15.6 ->
 * 12.4 ms the median, on that machine.
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

enum {
    HUGE_PAGE = 2 << 20,
    HEAP_BLOCKS = 4 << 20,
    PAGE = 4096,
    PROBE = 128 << 10
};

/* Holds the bytes between the heap's top at start-up and the next 2 MiB
 * boundary, so that the heap goes on from the boundary; never freed, and
 * never touched beyond its first page (it costs address space, not
 * memory). */
static void *volatile heap_filler;

void bf_cli_warm_heap(void)
{
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD) && defined(M_TRIM_THRESHOLD)
    if (!mallopt(M_MMAP_THRESHOLD, HEAP_BLOCKS) ||
        !mallopt(M_TRIM_THRESHOLD, 2 * HEAP_BLOCKS))
        return;
    /* where the heap ends now: a block larger than any freed before main
     * (libgomp's constructor frees some) and than glibc's caches of small
     * blocks comes from the top of the heap, and goes back to it when
     * freed */
    char *probe = malloc(PROBE);
    if (!probe)
        return;
    const uintptr_t top = (uintptr_t)probe;
    free(probe);
    const uintptr_t edge = (top + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
    if (edge - top > 2 * PAGE)
        heap_filler = malloc(edge - top - PAGE);
    /* The warm block then starts less than a page before the boundary
     * (when the heap works as glibc's does; if not, the advice below
     * covers whatever aligned range lies inside the block, or none). */
    char *p = malloc(HUGE_PAGE + 2 * PAGE);
    if (!p)
        return;
    const uintptr_t a = ((uintptr_t)p + PAGE - 1) & ~(uintptr_t)(PAGE - 1),
                    e = ((uintptr_t)p + HUGE_PAGE + 2 * PAGE) & ~(uintptr_t)(PAGE - 1),
                    h = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
    if (h + HUGE_PAGE <= e)
        (void)madvise((void *)h, HUGE_PAGE, MADV_HUGEPAGE);
    if (e > a)
        (void)madvise((void *)a, e - a, MADV_POPULATE_WRITE);
    free(p); /* stays in the heap: below M_TRIM_THRESHOLD */
#endif
}
