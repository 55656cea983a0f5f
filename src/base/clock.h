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

#endif
