/* stop.h: the stop flag of the run on the calling thread, for the loops
 * inside one step that can last long (ARKODE's internal steps).
 *
 * A stop flag (sim.h, bf_sim_opts) reaches the time loop and the drivers,
 * not the integrators inside a model's step; rather than thread it
 * through every model, the loop and the convergence driver name it here
 * for the time of their run and the ARKODE adapters read it before every
 * right-hand-side evaluation.  Per thread: two runs on two threads each
 * see their own.  Private to the library. */
#ifndef BALLFILM_INTEGRATORS_STOP_H
#define BALLFILM_INTEGRATORS_STOP_H

#include <signal.h>

typedef const volatile sig_atomic_t *bf_stop_flag;

/* Watch flag (NULL: none) from now on; returns the flag watched before,
 * which the caller restores when its run ends. */
bf_stop_flag bf_stop_watch(bf_stop_flag flag);

/* 1 when the watched flag is set. */
int bf_stop_requested(void);

#endif
