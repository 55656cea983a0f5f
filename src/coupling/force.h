/* force.h: the effect "coupling" (Yasuda eq. 3.12: dv_p/dt = -M dF_p/dr_p
 * + ...) and the keys of its section [coupling], private to the library.
 * The catalog lists the effect (src/compose/catalog.c); the coupled model
 * makes the coupling from the keys (bf_coupling_params_from_keys) and
 * hands it to its ball system as the effect's `self` (bf_ballsys_create's
 * `given`).
 */
#ifndef BALLFILM_COUPLING_FORCE_H
#define BALLFILM_COUPLING_FORCE_H

#include "ballfilm/effect.h"
#include "ballfilm/params.h"
#include "coupling/coupling.h"

/* The keys of [coupling] (the coupling effect's section). */
typedef struct bf_coupling_keys {
    double V0, r0, mobility, psi_s;
    int quadrature; /* 0 spline, 1 linear, 2 nodes */
    int taylor;
} bf_coupling_keys;
extern const bf_section_spec bf_coupling_spec;

/* The coupling's parameters from the keys (taylor: a radius of 2e-3 r0). */
bf_coupling_params bf_coupling_params_from_keys(const bf_coupling_keys *k);

/* The effect applying -M dF/dr to the balls; its instance is the
 * coupled model's bf_coupling. */
extern const bf_effect_type bf_effect_coupling;

#endif
