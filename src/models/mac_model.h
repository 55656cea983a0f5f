/* mac_model.h: read access to the "mac" model (mac_model.c) for the
 * convergence study (src/models/study_mac.c).  `model` is the model of
 * a sim or of bf_model_from_scene.  Private to the library. */
#ifndef BALLFILM_MODELS_MAC_MODEL_H
#define BALLFILM_MODELS_MAC_MODEL_H

#include <stddef.h>

#include "mac/mac.h"

/* The solver (its fields: bf_mac_u, bf_mac_v, ...). */
const bf_mac *bf_mac_model_solver(void *model);
/* "MAC, update = printed (...)" and the order in dt of its time
 * stepping (1: the forward-Euler predictor). */
void bf_mac_model_describe(void *model, char *buf, size_t cap, int *order);

#endif
