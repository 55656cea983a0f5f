/* clock.h: wall-clock time for timings and flush intervals (never for
 * simulated time, which is always step * dt). */
#ifndef BALLFILM_BASE_CLOCK_H
#define BALLFILM_BASE_CLOCK_H

#include <time.h>

/* Monotonic wall-clock seconds. */
static inline double bf_wall_time(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Monotonic seconds from the kernel's coarse clock (its resolution is
 * the scheduler's tick, a few ms): for decisions on the scale of seconds
 * taken often, such as whether an output is due for a flush after every
 * row, where the precise clock's read was a few per cent of a short ball
 * run on a virtual machine.  The precise clock where there is none. */
static inline double bf_coarse_time(void)
{
    struct timespec ts;
#ifdef CLOCK_MONOTONIC_COARSE
    clock_gettime(CLOCK_MONOTONIC_COARSE, &ts);
#else
    clock_gettime(CLOCK_MONOTONIC, &ts);
#endif
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
