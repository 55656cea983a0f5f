/* resolve.c: which sections a scene may contain, decided from its [scene]
 * section (model, integrator, effects) and the catalog, and the help
 * listing generated from the same tables. */
#include <string.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "compose.h"

/* A name the catalog does not have: the message lists what it has.  The
 * catalog's entries of every kind start with their name (const char *),
 * so the list is read through that first member. */
static bf_status unknown(const bf_scene *sc, bf_err *err, const char *key,
                         const char *kind, const char *name,
                         const void *const *list, size_t n)
{
    char names[1024];
    size_t used = 0;
    names[0] = '\0';
    for (size_t k = 0; k < n; k++) {
        const char *nk = *(const char *const *)list[k];
        int w = snprintf(names + used, sizeof names - used, "%s%s",
                         k ? ", " : "", nk);
        if (w < 0 || (size_t)w >= sizeof names - used)
            break;
        used += (size_t)w;
    }
    return bf_scene_fail(sc, err, "scene", key, "unknown %s '%s' (%ss: %s)",
                         kind, name, kind, names);
}

static bf_status add_spec(const bf_section_spec **specs, size_t cap, size_t *n,
                          const bf_section_spec *s, bf_err *err)
{
    for (size_t k = 0; k < *n; k++)
        if (specs[k] == s || !strcmp(specs[k]->name, s->name))
            return BF_OK;
    if (*n == cap)
        return bf_fail(err, BF_EINTERNAL, "too many sections");
    specs[(*n)++] = s;
    return BF_OK;
}

static bf_status select_specs(const bf_scene *sc, const bf_section_spec **specs,
                              size_t cap, size_t *n, const void *ctx,
                              bf_err *err)
{
    const bf_catalog *cat = ctx;
    *n = 0;
    const char *model = bf_scene_str(sc, "scene", "model");
    const bf_model_type *mt = bf_catalog_model(cat, model);
    if (!mt)
        return unknown(sc, err, "model", "model", model,
                       (const void *const *)cat->models, cat->nmodels);
    bf_status st;
    for (const bf_section_spec *const *s = mt->specs; s && *s; s++)
        if ((st = add_spec(specs, cap, n, *s, err)))
            return st;
    const bf_analysis_type *const *an;
    size_t na = bf_catalog_analyses_of(cat, mt, &an);
    for (size_t k = 0; k < na; k++)
        if ((st = add_spec(specs, cap, n, an[k]->spec, err)))
            return st;
    if (mt->flags & BF_MODEL_INTEGRATOR) {
        const char *iname = bf_scene_str(sc, "scene", "integrator");
        const bf_integrator_type *it = bf_catalog_integrator(cat, iname);
        if (!it)
            return unknown(sc, err, "integrator", "integrator", iname,
                           (const void *const *)cat->integrators,
                           cat->nintegrators);
        if (it->spec && (st = add_spec(specs, cap, n, it->spec, err)))
            return st;
    } else if (bf_scene_given(sc, "scene", "integrator")) {
        return bf_scene_fail(sc, err, "scene", "integrator",
                             "model '%s' has its own time stepping and takes "
                             "no integrator",
                             model);
    }
    size_t ne;
    const char *const *eff = bf_scene_names(sc, "scene", "effects", &ne);
    if (ne && !(mt->flags & BF_MODEL_EFFECTS))
        return bf_scene_fail(sc, err, "scene", "effects",
                             "model '%s' takes no ball effects", model);
    for (size_t k = 0; k < ne; k++) {
        const bf_effect_type *et = bf_catalog_effect(cat, eff[k]);
        if (!et)
            return unknown(sc, err, "effects", "effect", eff[k],
                           (const void *const *)cat->effects, cat->neffects);
        if (et->spec && (st = add_spec(specs, cap, n, et->spec, err)))
            return st;
    }
    return BF_OK;
}

bf_status bf_catalog_resolve(const bf_catalog *c, bf_scene *sc, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st =
        bf_compose_args_("bf_catalog_resolve", "", c, sc, NULL, 0, err);
    if (st)
        return st;
    const bf_spec_provider provider = {&bf_sim_scene_spec, select_specs, c};
    return bf_scene_resolve_with(sc, &provider, err);
}

/* A model's sections: its own, then its analyses'. */
static size_t model_sections(const bf_catalog *c, const bf_model_type *mt,
                             const bf_section_spec **out, size_t cap)
{
    size_t n = 0;
    for (const bf_section_spec *const *s = mt->specs; s && *s && n < cap; s++)
        out[n++] = *s;
    const bf_analysis_type *const *an;
    size_t na = bf_catalog_analyses_of(c, mt, &an);
    for (size_t k = 0; k < na && n < cap; k++)
        out[n++] = an[k]->spec;
    return n;
}

/* Print a section's keys unless already printed. */
static void show(FILE *f, const bf_section_spec *s, const char *owner,
                 const bf_section_spec **seen, size_t *nseen)
{
    if (!s || *nseen >= 128)
        return;
    for (size_t q = 0; q < *nseen; q++)
        if (seen[q] == s)
            return;
    seen[(*nseen)++] = s;
    fprintf(f, "\n-- used by %s --", owner);
    const bf_section_spec *one[1] = {s};
    bf_params_print(f, one, 1);
}

void bf_catalog_print_help(const bf_catalog *c, FILE *f)
{
    const bf_section_spec *one[1];
    fprintf(f, "Scene files are INI files.  Every key, with its unit and "
               "default:\n");
    one[0] = &bf_sim_scene_spec;
    bf_params_print(f, one, 1);

    size_t nm, ni, ne;
    const bf_model_type *const *models = bf_catalog_models(c, &nm);
    const bf_integrator_type *const *ints = bf_catalog_integrators(c, &ni);
    const bf_effect_type *const *effs = bf_catalog_effects(c, &ne);

    fprintf(f, "\nModels ([scene] model):\n");
    for (size_t k = 0; k < nm; k++)
        fprintf(f, "  %-14s %s\n", models[k]->name, models[k]->doc);
    fprintf(f, "\nIntegrators ([scene] integrator, models that take one):\n");
    for (size_t k = 0; k < ni; k++)
        fprintf(f, "  %-14s %s\n", ints[k]->name, ints[k]->doc);
    fprintf(f, "\nEffects ([scene] effects, for ball models):\n");
    for (size_t k = 0; k < ne; k++)
        fprintf(f, "  %-14s %s\n", effs[k]->name, effs[k]->doc);

    /* every section once, in catalog order, with the models that use it
     * (a section shared by models, [ball.N] or [lyapunov], names them
     * all) */
    const bf_section_spec *seen[128];
    size_t nseen = 0;
    for (size_t k = 0; k < nm; k++) {
        const bf_section_spec *mine[64];
        size_t nmine = model_sections(c, models[k], mine, 64);
        for (size_t q = 0; q < nmine; q++) {
            char owners[256] = "";
            for (size_t j = 0; j < nm; j++) {
                const bf_section_spec *theirs[64];
                size_t nt = model_sections(c, models[j], theirs, 64);
                for (size_t t = 0; t < nt; t++)
                    if (theirs[t] == mine[q]) {
                        size_t len = strlen(owners);
                        snprintf(owners + len, sizeof owners - len, "%s%s",
                                 len ? ", " : "", models[j]->name);
                    }
            }
            show(f, mine[q], owners, seen, &nseen);
        }
    }
    for (size_t k = 0; k < ni; k++)
        show(f, ints[k]->spec, ints[k]->name, seen, &nseen);
    for (size_t k = 0; k < ne; k++)
        show(f, effs[k]->spec, effs[k]->name, seen, &nseen);
}
