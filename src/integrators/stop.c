/* stop.c: the watched stop flag of each thread (stop.h). */
#include "integrators/stop.h"

#include <stddef.h>

static _Thread_local bf_stop_flag watched = NULL;

bf_stop_flag bf_stop_watch(bf_stop_flag flag)
{
    bf_stop_flag before = watched;
    watched = flag;
    return before;
}

int bf_stop_requested(void)
{
    return watched && *watched;
}
