/* setup.c: a model's setup from a resolved scene (see run.h): every
 * section the model declares, its integrator's and its effects' sections,
 * filled into their structs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/sysmem.h"
#include "models/ballsys.h"
#include "compose.h"

struct bf_setup {
    const bf_model_type *mt;
    bf_model_setup pub;
    bf_setup_section *sections;
    void **blocks; /* the values of each section (owned) */
    void *it_params;
    const bf_effect_type **effects;
    void **effect_params;
    /* the keys of the model's analyses (bf_catalog_analyses_of) */
    const bf_analysis_type *const *analyses;
    void **analysis_keys;
    size_t nanalyses;
};

void bf_setup_free(bf_setup *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->pub.nsections; k++)
        free(s->blocks[k]);
    free(s->blocks);
    free(s->sections);
    free(s->it_params);
    for (size_t k = 0; k < s->pub.neffects; k++)
        free(s->effect_params[k]);
    free(s->effect_params);
    free(s->effects);
    for (size_t k = 0; k < s->nanalyses; k++)
        free(s->analysis_keys[k]);
    free(s->analysis_keys);
    free(s);
}

const bf_model_setup *bf_setup_model(const bf_setup *s) { return &s->pub; }

void bf_setup_set_nranks(bf_setup *s, int nranks) { s->pub.nranks = nranks; }
const bf_model_type *bf_setup_model_type(const bf_setup *s) { return s->mt; }

/* One struct of spec filled from section `name` (NULL for a spec with no
 * struct yet). */
static void *fill_one(const bf_scene *sc, const char *name,
                      const bf_section_spec *spec)
{
    if (!spec->size)
        return NULL;
    void *v = calloc(1, spec->size);
    if (v)
        bf_scene_fill(sc, name, spec, v);
    return v;
}

/* All sections of an indexed spec "NAME.N": [NAME.1] .. [NAME.count]. */
static void *fill_indexed(const bf_scene *sc, const bf_section_spec *spec,
                          size_t *count)
{
    char base[128], name[160];
    size_t L = strlen(spec->name) - 2;
    snprintf(base, sizeof base, "%.*s", (int)L, spec->name);
    *count = (size_t)bf_scene_count(sc, base);
    if (!spec->size)
        return NULL;
    char *v = calloc(*count ? *count : 1, spec->size);
    for (size_t i = 0; v && i < *count; i++) {
        snprintf(name, sizeof name, "%s.%zu", base, i + 1);
        bf_scene_fill(sc, name, spec, v + i * spec->size);
    }
    return v;
}

static int indexed(const bf_section_spec *spec)
{
    size_t L = strlen(spec->name);
    return L > 2 && !strcmp(spec->name + L - 2, ".N");
}

bf_status bf_setup_create(bf_setup **out, const bf_catalog *c,
                          const bf_scene *sc, const bf_run_ctx *run,
                          bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status ast = bf_compose_args_("bf_setup_create", out, c, sc, NULL, 0,
                                     err);
    if (!ast && !run)
        ast = bf_fail(err, BF_EINPUT, "bf_setup_create: run is NULL");
    if (ast)
        return ast;
    *out = NULL;
    const char *model = bf_scene_str(sc, "scene", "model");
    const bf_model_type *mt = bf_catalog_model(c, model);
    if (!mt)
        return bf_fail(err, BF_EINTERNAL, "model '%s' is not in the catalog",
                       model);
    bf_setup *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->mt = mt;
    s->pub.run = *run;
    size_t ns = 0;
    while (mt->specs && mt->specs[ns])
        ns++;
    s->sections = calloc(ns ? ns : 1, sizeof *s->sections);
    s->blocks = calloc(ns ? ns : 1, sizeof *s->blocks);
    int oom = !s->sections || !s->blocks;
    for (size_t k = 0; !oom && k < ns; k++) {
        const bf_section_spec *spec = mt->specs[k];
        size_t count = 1;
        s->blocks[k] = indexed(spec) ? fill_indexed(sc, spec, &count)
                                     : fill_one(sc, spec->name, spec);
        s->sections[k] = (bf_setup_section){spec, s->blocks[k], count};
        s->pub.nsections = k + 1;
        oom = spec->size && !s->blocks[k];
    }
    s->pub.sections = s->sections;
    if (!oom && (mt->flags & BF_MODEL_INTEGRATOR)) {
        const bf_integrator_type *it =
            bf_catalog_integrator(c, bf_scene_str(sc, "scene", "integrator"));
        s->pub.integrator = it;
        if (it && it->spec) {
            s->it_params = fill_one(sc, "integrator", it->spec);
            oom = it->spec->size && !s->it_params;
        }
        s->pub.integrator_params = s->it_params;
    }
    if (!oom && (mt->flags & BF_MODEL_EFFECTS)) {
        size_t ne;
        const char *const *names = bf_scene_names(sc, "scene", "effects", &ne);
        s->effects = calloc(ne ? ne : 1, sizeof *s->effects);
        s->effect_params = calloc(ne ? ne : 1, sizeof *s->effect_params);
        oom = !s->effects || !s->effect_params;
        for (size_t k = 0; !oom && k < ne; k++) {
            const bf_effect_type *et = bf_catalog_effect(c, names[k]);
            s->effects[k] = et;
            s->pub.neffects = k + 1;
            if (et && et->spec) {
                s->effect_params[k] = fill_one(sc, et->spec->name, et->spec);
                oom = et->spec->size && !s->effect_params[k];
            }
        }
        s->pub.effects = s->effects;
        s->pub.effect_params = (const void *const *)s->effect_params;
    }
    const bf_analysis_type *const *an;
    size_t na = bf_catalog_analyses_of(c, mt, &an);
    if (!oom && na) {
        s->analyses = an;
        s->analysis_keys = calloc(na, sizeof *s->analysis_keys);
        oom = !s->analysis_keys;
        for (size_t k = 0; !oom && k < na; k++) {
            s->analysis_keys[k] = fill_one(sc, an[k]->spec->name, an[k]->spec);
            s->nanalyses = k + 1;
            oom = !s->analysis_keys[k];
        }
    }
    if (oom) {
        bf_setup_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    *out = s;
    return BF_OK;
}

/* The integrators of the catalog by name, for the analyses. */
static const bf_integrator_type *find_integrator(const void *ctx,
                                                 const char *name)
{
    return bf_catalog_integrator(ctx, name);
}

bf_status bf_setup_observe(const bf_setup *s, const bf_catalog *c,
                           bf_sim *sim, bf_err *err)
{
    bf_ball_view view = {0}; /* a model's ball_view may leave step_twin */
    if (!s->nanalyses || !s->mt->ball_view ||
        !s->mt->ball_view(bf_sim_model(sim), &view))
        return BF_OK;
    const bf_analysis_env env = {&view, &s->pub.run, find_integrator, c};
    for (size_t k = 0; k < s->nanalyses; k++) {
        void *self = NULL;
        bf_status st =
            s->analyses[k]->create(&self, s->analysis_keys[k], &env, err);
        if (!st && self)
            st = bf_sim_observe(sim, s->analyses[k]->observer, self, err);
        if (st)
            return st;
    }
    return BF_OK;
}

/* What every run needs beyond its model's arrays: HDF5's caches and the
 * working memory of the libraries, a few threads' stacks.  Without it a
 * run under a tight ulimit -v would fail inside HDF5 (which crashes when
 * its own allocations fail) instead of being refused. */
#define PROGRAM_RESERVE (64.0 * 1048576.0)

/* "12.3 GiB", "45 MiB" */
static void human(double bytes, char *buf, size_t cap)
{
    if (bytes >= 1073741824.0)
        snprintf(buf, cap, "%.3g GiB", bytes / 1073741824.0);
    else
        snprintf(buf, cap, "%.3g MiB", bytes / 1048576.0);
}

/* A run that needs more memory than the process may allocate is refused
 * before its model allocates anything (the estimate is the model's,
 * model.h memory; the limit base/sysmem.h's). */
static bf_status check_memory(const bf_setup *s, bf_err *err)
{
    bf_mem_need need = {0};
    if (s->mt->memory)
        s->mt->memory(&s->pub, &need);
    double total = need.bytes + PROGRAM_RESERVE;
    bf_mem_avail av;
    bf_mem_available(&av);
    if (!(total > av.bytes))
        return BF_OK;
    char t[32], a[32];
    human(total, t, sizeof t);
    human(av.bytes, a, sizeof a);
    if (need.bytes > 0)
        return bf_fail_key(err, BF_EINPUT, need.section, need.key,
                           "%s need about %s of memory (with the program's "
                           "own %.0f MiB); %s leaves %s: make the run smaller",
                           need.what, t, PROGRAM_RESERVE / 1048576.0,
                           av.source, a);
    return bf_fail(err, BF_EINPUT, "the run needs about %s of memory (HDF5 "
                   "and the libraries' working memory); %s leaves %s",
                   t, av.source, a);
}

bf_status bf_setup_build_model(const bf_setup *s, const bf_scene *sc,
                               void **model, bf_err *err)
{
    *model = NULL;
    bf_status st = check_memory(s, err);
    if (!st)
        st = s->mt->create(model, &s->pub, err);
    if (st)
        bf_scene_locate(sc, err);
    return st;
}

bf_status bf_ballsys_from_scene(bf_ballsys **out, const bf_catalog *c,
                                const bf_scene *sc, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status ast =
        bf_compose_args_("bf_ballsys_from_scene", out, c, sc, NULL, 0, err);
    if (ast)
        return ast;
    *out = NULL;
    bf_setup *setup;
    bf_run_ctx run = {bf_scene_real(sc, "scene", "dt"),
                      bf_scene_real(sc, "scene", "t_end"), 0, 1, 0};
    bf_status st = bf_setup_create(&setup, c, sc, &run, err);
    if (st)
        return st;
    st = bf_ballsys_create(out, &setup->pub, NULL, 0, err);
    if (st)
        bf_scene_locate(sc, err);
    bf_setup_free(setup);
    return st;
}

bf_status bf_compose_setup(bf_setup **setup, const bf_catalog *c,
                           const bf_scene *sc, bf_err *err)
{
    double dt = bf_scene_real(sc, "scene", "dt"),
           t_end = bf_scene_real(sc, "scene", "t_end");
    bf_run_ctx run = {dt, t_end, (long)ceil(t_end / dt * (1.0 - 1e-12)),
                      bf_interval_steps(bf_scene_interval(sc, "scene",
                                                          "output_every"),
                                        dt),
                      0};
    return bf_setup_create(setup, c, sc, &run, err);
}

bf_status bf_model_from_scene(const bf_catalog *c, const bf_scene *sc,
                              bf_setup **setup, void **model, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status ast =
        bf_compose_args_("bf_model_from_scene", setup, c, sc, NULL, 0, err);
    if (!ast && !model)
        ast = bf_fail(err, BF_EINPUT, "bf_model_from_scene: model is NULL");
    if (ast)
        return ast;
    *model = NULL;
    bf_status st = bf_compose_setup(setup, c, sc, err);
    if (!st && (st = bf_setup_build_model(*setup, sc, model, err))) {
        bf_setup_free(*setup);
        *setup = NULL;
    }
    return st;
}
