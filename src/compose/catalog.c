/* catalog.c: the built-in models, integrators and effects: one table, one
 * line per entry.  Adding a model, an integrator or an effect is one new
 * file and one line here. */
#include <stdlib.h>
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
extern const bf_effect_type bf_effect_drag;

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
    &bf_effect_spring,  &bf_effect_coupling, &bf_effect_drag,
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
    effects, COUNT(effects), analyses,    COUNT(analyses),  0,
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

/* ---- catalogs of a program's own ---- */

/* a copy of n pointers, room for one more */
static const void **copy_list(const void *const *list, size_t n)
{
    const void **c = malloc((n + 1) * sizeof *c);
    if (c && n)
        memcpy(c, list, n * sizeof *c);
    return c;
}

bf_catalog *bf_catalog_new(const bf_catalog *base)
{
    static const bf_catalog empty = {0};
    if (!base)
        base = &empty;
    bf_catalog *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->owned = 1;
    c->nmodels = base->nmodels;
    c->nintegrators = base->nintegrators;
    c->neffects = base->neffects;
    c->nanalyses = base->nanalyses;
    c->models = (const bf_model_type *const *)copy_list(
        (const void *const *)base->models, base->nmodels);
    c->integrators = (const bf_integrator_type *const *)copy_list(
        (const void *const *)base->integrators, base->nintegrators);
    c->effects = (const bf_effect_type *const *)copy_list(
        (const void *const *)base->effects, base->neffects);
    c->analyses = (const bf_analysis_type *const *)copy_list(
        (const void *const *)base->analyses, base->nanalyses);
    if (!c->models || !c->integrators || !c->effects || !c->analyses) {
        bf_catalog_free(c);
        return NULL;
    }
    return c;
}

void bf_catalog_free(bf_catalog *c)
{
    if (!c || !c->owned)
        return;
    free((void *)c->models);
    free((void *)c->integrators);
    free((void *)c->effects);
    free((void *)c->analyses);
    free(c);
}

/* Append entry (named `name`) to *list of *n, refusing a name the kind
 * already has: a scene names entries, so two with one name would make
 * which one runs depend on the order. */
static bf_status add_entry(bf_catalog *c, const void *const **list, size_t *n,
                           const void *entry, const char *kind,
                           const char *name, int taken, bf_err *err)
{
    if (!c->owned)
        return bf_fail(err, BF_EINPUT, "cannot add the %s '%s' to the "
                       "built-in catalog: add it to one of bf_catalog_new",
                       kind, name ? name : "(null)");
    if (!name || !*name)
        return bf_fail(err, BF_EINPUT, "a %s without a name", kind);
    if (taken)
        return bf_fail(err, BF_EINPUT, "the catalog already has a %s named "
                       "'%s'", kind, name);
    const void **grown = realloc((void *)*list, (*n + 2) * sizeof *grown);
    if (!grown)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    grown[(*n)++] = entry;
    *list = grown;
    return BF_OK;
}

bf_status bf_catalog_add_model(bf_catalog *c, const bf_model_type *t,
                               bf_err *err)
{
    return add_entry(c, (const void *const **)&c->models, &c->nmodels, t,
                     "model", t->name, bf_catalog_model(c, t->name) != NULL,
                     err);
}

bf_status bf_catalog_add_integrator(bf_catalog *c,
                                    const bf_integrator_type *t, bf_err *err)
{
    return add_entry(c, (const void *const **)&c->integrators,
                     &c->nintegrators, t, "integrator", t->name,
                     bf_catalog_integrator(c, t->name) != NULL, err);
}

bf_status bf_catalog_add_effect(bf_catalog *c, const bf_effect_type *t,
                                bf_err *err)
{
    return add_entry(c, (const void *const **)&c->effects, &c->neffects, t,
                     "effect", t->name, bf_catalog_effect(c, t->name) != NULL,
                     err);
}
