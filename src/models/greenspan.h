/* greenspan.h: read access to the state of the Greenspan particle models
 * (models "greenspan72" and "greenspan73") for drivers, tests and
 * benchmarks.  `model` is bf_sim_model() of a sim running that model.
 * Private to the library (beside the models' code; tests and benchmarks
 * include it as "models/greenspan.h"). */
#ifndef BALLFILM_MODELS_GREENSPAN_H
#define BALLFILM_MODELS_GREENSPAN_H

#include "ballfilm/particles.h"
#include "particles/support.h"

/* The particles of a greenspan72 model (positions x^k, velocities
 * v^{k-1/2}). */
bf_particles *bf_greenspan72_particles(void *model);
/* Its support-set gravity workspace. */
bf_support *bf_greenspan72_support(void *model);

/* The particles of a greenspan73 model (time t_k). */
bf_particles *bf_greenspan73_particles(void *model);

#endif
