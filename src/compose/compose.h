/* compose.h: what the files of src/compose share (private). */
#ifndef BALLFILM_COMPOSE_H
#define BALLFILM_COMPOSE_H

#include "ballfilm/run.h"
#include "ballfilm/sim.h"

struct bf_catalog {
    const bf_model_type *const *models;
    size_t nmodels;
    const bf_integrator_type *const *integrators;
    size_t nintegrators;
    const bf_effect_type *const *effects;
    size_t neffects;
    const bf_analysis_type *const *analyses;
    size_t nanalyses;
    int owned; /* 1: made by bf_catalog_new, the arrays are its own */
};

/* What the public calls of this layer refuse (BF_EINPUT, "fn: arg is
 * NULL"): a NULL result pointer `out`, catalog or scene, and sets NULL or
 * holding a NULL with nsets > 0 (sc: pass a non-NULL stand-in when the
 * call takes none). */
bf_status bf_compose_args_(const char *fn, const void *out,
                           const bf_catalog *c, const void *sc,
                           const char *const *sets, size_t nsets,
                           bf_err *err);

/* The setup of resolved scene sc's model, with the run its [scene] keys
 * describe (dt, t_end, the steps and the output interval). */
bf_status bf_compose_setup(bf_setup **setup, const bf_catalog *c,
                           const bf_scene *sc, bf_err *err);

/* The analyses of balls a model takes (none unless it has
 * BF_MODEL_BALL_ANALYSES). */
size_t bf_catalog_analyses_of(const bf_catalog *c, const bf_model_type *mt,
                              const bf_analysis_type *const **list);

/* The processes that will run the setup's model split between them
 * (bf_model_setup nranks; bf_sim_opts nranks). */
void bf_setup_set_nranks(bf_setup *s, int nranks);

#endif
