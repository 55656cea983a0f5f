/* coupled.h: the "coupled" model (balls in the two-phase film, Yasuda sec.
 * 3.4-3.5) as seen by tests (private to the library): its parts and, with
 * [lyapunov] enabled, those of its shadow system. */
#ifndef BALLFILM_COUPLED_H
#define BALLFILM_COUPLED_H

#include "ballfilm/film.h"
#include "ballfilm/sim.h"
#include "models/ballsys.h"

/* The parts of a coupled system: its balls, its film and the film's
 * coupling chemical potential mu_cpl (eq. 3.11, nodes 0..N) for the split
 * scheme's next film step (the whole-system schemes form it in every
 * evaluation and leave this one at zero). */
typedef struct bf_coupled_parts {
    bf_ballsys *sys;
    bf_film *film;
    const double *mu_cpl;
} bf_coupled_parts;

/* For a sim whose model is "coupled": the run's parts in *run and the
 * Lyapunov shadow's in *shadow (all NULL without [lyapunov]); BF_EINPUT
 * for another model. */
bf_status bf_coupled_sim_parts(bf_sim *sim, bf_coupled_parts *run,
                               bf_coupled_parts *shadow);

/* The same for a model built from a scene (bf_model_from_scene; model:
 * its self pointer, of the type bf_model_coupled), without the shadow. */
void bf_coupled_model_parts(void *model, bf_coupled_parts *p);
/* Its film system (the phase fluxes of the convergence study). */
struct bf_filmsys *bf_coupled_model_filmsys(void *model);
/* Its time integration in one line and the nominal order in dt: split,
 * the ball integrator's with the film scheme's (the coupling's lag and the
 * invariant film scheme are first order: 1 with a dynamic film); arkode,
 * mri: the whole system's integrator. */
void bf_coupled_model_describe(void *model, char *buf, size_t cap,
                               int *order);

#endif
