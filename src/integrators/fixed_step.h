/* fixed_step.h: the [integrator] keys every fixed-step integrator without
 * keys of its own offers (private to src/integrators): `events`, the
 * event splitting of the ball system (integrator.h, split_events;
 * src/models/ballsys_events.c). */
#ifndef BALLFILM_FIXED_STEP_H
#define BALLFILM_FIXED_STEP_H

#include "ballfilm/integrator.h"

typedef struct bf_fixed_step_keys {
    int events;
    double events_zone;
} bf_fixed_step_keys;

extern const bf_section_spec bf_fixed_step_spec;

/* Take the keys (it->split_events) and allocate nvec work vectors. */
bf_status bf_fixed_step_init(bf_integrator *it, const void *params,
                             size_t nvec, bf_err *err);
/* For a type with keys of its own: keep a copy of them (`size` bytes) as
 * it->priv (freed by the type's free), take its event keys and allocate
 * nvec work vectors. */
bf_status bf_fixed_step_init_copy(bf_integrator *it, const void *params,
                                  size_t size, int events, double events_zone,
                                  size_t nvec, bf_err *err);

#endif
