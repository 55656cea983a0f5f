/* model_energy.h: the energy a model conserves, for the run's checks
 * (sim.c, sim_state.c) and the convergence studies (converge.c): its
 * energy, or with the work of non-conservative forces the balance
 * (private to the library). */
#ifndef BALLFILM_CORE_MODEL_ENERGY_H
#define BALLFILM_CORE_MODEL_ENERGY_H

#include "ballfilm/model.h"

/* Whether the model tracks the work of non-conservative forces (model.h,
 * work). */
static inline int bf_model_tracks_work(const bf_model_type *mt, void *model)
{
    double wd, wi;
    return mt->work && mt->work(model, &wd, &wi);
}

/* The model's kinetic and potential energy at t into *k, *p, erg, and
 * their sum, or with `work` (bf_model_tracks_work) the balance
 * E + W_dissipated - W_injected, which is what stays constant when forces
 * dissipate or drive. */
static inline double bf_model_balance(const bf_model_type *mt, void *model,
                                      double t, int work, double *k,
                                      double *p)
{
    double wd, wi;
    mt->energy(model, t, k, p);
    if (!work)
        return *k + *p;
    mt->work(model, &wd, &wi);
    return *k + *p + wd - wi;
}

#endif
