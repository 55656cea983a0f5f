/* lyapunov.h: the largest Lyapunov exponent of a ball system: a shadow
 * copy of the balls (src/diag/lyapsum.h says how the estimate is made),
 * advanced by its own instance of the run's integrator through the same
 * forces, stepped by the model as it steps its balls (model.h, step_twin:
 * with event splitting, at the shadow's own events).  An analysis of the
 * time loop (sim.h) over a model's ball view.  Private to the library. */
#ifndef BALLFILM_ANALYSIS_LYAPUNOV_H
#define BALLFILM_ANALYSIS_LYAPUNOV_H

#include "ballfilm/sim.h"
#include "diag/lyapsum.h"

typedef struct bf_lyap bf_lyap;

extern const bf_analysis_type bf_lyap_analysis; /* [lyapunov] of balls */
extern const bf_observer_type bf_lyap_observer;

/* Counters of the shadow integrator (work spent on the estimate). */
const bf_counters *bf_lyap_counters(const bf_lyap *ly);

#endif
