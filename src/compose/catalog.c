/* catalog.c: the built-in models, integrators and effects: one table, one
 * line per entry.  Adding a model, an integrator or an effect is one new
 * file and one line here. */
#include <string.h>

#include "ballfilm/run.h"
#include "compose.h"

extern const bf_model_type bf_model_balls;
extern const bf_model_type bf_model_film;
extern const bf_model_type bf_model_coupled;
extern const bf_model_type bf_model_greenspan72;
extern const bf_model_type bf_model_greenspan73;
extern const bf_model_type bf_model_mac;

extern const bf_integrator_type bf_integrator_verlet;
extern const bf_integrator_type bf_integrator_mv2m;
extern const bf_integrator_type bf_integrator_alpha;
extern const bf_integrator_type bf_integrator_rk3;
extern const bf_integrator_type bf_integrator_rk4;
extern const bf_integrator_type bf_integrator_impmid;
extern const bf_integrator_type bf_integrator_greenspan73;
extern const bf_integrator_type bf_integrator_rkn6;
extern const bf_integrator_type bf_integrator_arkode;
extern const bf_integrator_type bf_integrator_arkode_fixed;

extern const bf_effect_type bf_effect_gravity;
extern const bf_effect_type bf_effect_floor;
extern const bf_effect_type bf_effect_contact;
extern const bf_effect_type bf_effect_spring;
extern const bf_effect_type bf_effect_coupling;

extern const bf_analysis_type bf_retmap_analysis;
extern const bf_analysis_type bf_lyap_analysis;
extern const bf_analysis_type bf_compare_analysis;

static const bf_model_type *const models[] = {
    &bf_model_balls,       &bf_model_film,        &bf_model_coupled,
    &bf_model_greenspan72, &bf_model_greenspan73, &bf_model_mac,
};

static const bf_integrator_type *const integrators[] = {
    &bf_integrator_verlet, &bf_integrator_mv2m,   &bf_integrator_alpha,
    &bf_integrator_rk3,    &bf_integrator_rk4,    &bf_integrator_impmid,
    &bf_integrator_arkode, &bf_integrator_arkode_fixed,
    &bf_integrator_greenspan73, &bf_integrator_rkn6,
};

static const bf_effect_type *const effects[] = {
    &bf_effect_gravity, &bf_effect_floor,    &bf_effect_contact,
    &bf_effect_spring,  &bf_effect_coupling,
};

/* analyses of balls, observed in this order */
static const bf_analysis_type *const analyses[] = {
    &bf_retmap_analysis,
    &bf_lyap_analysis,
    &bf_compare_analysis,
};

#define COUNT(a) (sizeof a / sizeof a[0])

static const bf_catalog builtin = {
    models,  COUNT(models),  integrators, COUNT(integrators),
    effects, COUNT(effects), analyses,    COUNT(analyses),
};

const bf_catalog *bf_catalog_builtin(void) { return &builtin; }

const bf_model_type *const *bf_catalog_models(const bf_catalog *c, size_t *n)
{
    *n = c->nmodels;
    return c->models;
}

const bf_integrator_type *const *bf_catalog_integrators(const bf_catalog *c,
                                                        size_t *n)
{
    *n = c->nintegrators;
    return c->integrators;
}

const bf_effect_type *const *bf_catalog_effects(const bf_catalog *c, size_t *n)
{
    *n = c->neffects;
    return c->effects;
}

/* The entries of every kind start with their name. */
#define FIND(list, count, name)                                                \
    do {                                                                       \
        for (size_t k_ = 0; k_ < (count); k_++)                                \
            if (!strcmp((list)[k_]->name, (name)))                             \
                return (list)[k_];                                             \
        return NULL;                                                           \
    } while (0)

const bf_model_type *bf_catalog_model(const bf_catalog *c, const char *name)
{
    FIND(c->models, c->nmodels, name);
}

const bf_integrator_type *bf_catalog_integrator(const bf_catalog *c,
                                                const char *name)
{
    FIND(c->integrators, c->nintegrators, name);
}

const bf_effect_type *bf_catalog_effect(const bf_catalog *c, const char *name)
{
    FIND(c->effects, c->neffects, name);
}

size_t bf_catalog_analyses_of(const bf_catalog *c, const bf_model_type *mt,
                              const bf_analysis_type *const **list)
{
    *list = c->analyses;
    return mt->flags & BF_MODEL_BALL_ANALYSES ? c->nanalyses : 0;
}
