/* compose.h: what the files of src/compose share (private). */
#ifndef BALLFILM_COMPOSE_H
#define BALLFILM_COMPOSE_H

#include "ballfilm/run.h"

struct bf_catalog {
    const bf_model_type *const *models;
    size_t nmodels;
    const bf_integrator_type *const *integrators;
    size_t nintegrators;
    const bf_effect_type *const *effects;
    size_t neffects;
};

#endif
