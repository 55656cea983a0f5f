/* coupled.h: the "coupled" model (balls in the two-phase film, Yasuda sec.
 * 3.4-3.5) as seen by tests (private to the library): its parts and, with
 * [lyapunov] enabled, those of its shadow system. */
#ifndef BALLFILM_COUPLED_H
#define BALLFILM_COUPLED_H

#include "ballfilm/film.h"
#include "ballfilm/sim.h"
#include "models/ballsys.h"

/* The parts of a coupled system: its balls, its film and the film's
 * coupling chemical potential mu_cpl (eq. 3.11, nodes 0..N). */
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

#endif
