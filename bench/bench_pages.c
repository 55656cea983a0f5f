/* bench_pages.c: what the first write to fresh memory costs on this
 * machine, the reason for src/cli/heap.c (issue 21, start-up).
 *
 * Three ways to get 2 MiB of memory ready, each then cleared with memset
 * and cleared again (the second time the pages are there):
 *   4 KiB pages    an anonymous mapping, faulted in by the first write;
 *   populated      the same after madvise(MADV_POPULATE_WRITE);
 *   huge page      a 2 MiB-aligned range with MADV_HUGEPAGE, populated
 *                  (the kernel may give 4 KiB pages: transparent huge
 *                  pages off, or none free).
 * Prints, for each, the time of the advice and of the first and second
 * clearing, in microseconds per 4 KiB page (the shortest of 20 rounds,
 * each on new memory).  On bare metal the first clearing costs a fraction
 * of a microsecond a page; in some virtual machines several.
 */
#define _DEFAULT_SOURCE 1 /* madvise, MAP_ANONYMOUS */

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23 /* linux/mman.h, Linux 5.14 */
#endif

enum { HUGE_PAGE = 2 << 20, PAGES = HUGE_PAGE / 4096, ROUNDS = 20 };

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e6 * (double)ts.tv_sec + 1e-3 * (double)ts.tv_nsec;
}

/* One round of `way` (0: 4 KiB pages, 1: populated, 2: huge page); the
 * three times in t[] (us); 0, or -1 if no memory. */
static int one_round(int way, double t[3])
{
    char *m = mmap(NULL, 2 * HUGE_PAGE, PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED)
        return -1;
    char *p = (char *)(((uintptr_t)m + HUGE_PAGE - 1) &
                       ~(uintptr_t)(HUGE_PAGE - 1));
    const double t0 = now_us();
    if (way == 2)
        (void)madvise(p, HUGE_PAGE, MADV_HUGEPAGE);
    if (way >= 1)
        (void)madvise(p, HUGE_PAGE, MADV_POPULATE_WRITE);
    const double t1 = now_us();
    memset(p, 1, HUGE_PAGE);
    const double t2 = now_us();
    memset(p, 2, HUGE_PAGE);
    const double t3 = now_us();
    /* keep the stores */
    volatile char sink = p[HUGE_PAGE - 1];
    (void)sink;
    munmap(m, 2 * HUGE_PAGE);
    t[0] = t1 - t0;
    t[1] = t2 - t1;
    t[2] = t3 - t2;
    return 0;
}

int main(void)
{
    static const char *name[3] = {"4 KiB pages", "populated", "huge page"};
    printf("first writes to 2 MiB of fresh memory, us per 4 KiB page "
           "(shortest of %d rounds)\n", ROUNDS);
    printf("  %-12s %10s %14s %14s\n", "", "advice", "first memset",
           "second memset");
    for (int way = 0; way < 3; way++) {
        double best[3] = {1e300, 1e300, 1e300};
        for (int r = 0; r < ROUNDS; r++) {
            double t[3];
            if (one_round(way, t)) {
                fprintf(stderr, "bench_pages: out of memory\n");
                return 1;
            }
            /* the shortest round by its whole cost */
            if (t[0] + t[1] < best[0] + best[1])
                memcpy(best, t, sizeof best);
        }
        printf("  %-12s %10.3f %14.3f %14.3f\n", name[way], best[0] / PAGES,
               best[1] / PAGES, best[2] / PAGES);
    }
    return 0;
}
