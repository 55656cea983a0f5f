/* build.c: a run from a scene (see run.h): the [scene] keys, the model's
 * setup, the model, the loop, the analyses, the provenance; and a run
 * rebuilt from its checkpoint. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/checkpoint.h"
#include "compose.h"
#include "io/h5lock.h"
#include "io/outpath.h"

bf_status bf_compose_args_(const char *fn, const void *out,
                           const bf_catalog *c, const void *sc,
                           const char *const *sets, size_t nsets,
                           bf_err *err)
{
    const char *null = !out ? "the result pointer"
                       : !c ? "the catalog"
                       : !sc ? "the scene"
                       : !sets && nsets ? "sets (with nsets > 0)"
                                        : NULL;
    for (size_t k = 0; !null && k < nsets; k++)
        if (!sets[k])
            return bf_fail(err, BF_EINPUT, "%s: sets[%zu] is NULL (nsets = "
                           "%zu)", fn, k, nsets);
    return null ? bf_fail(err, BF_EINPUT, "%s: %s is NULL", fn, null)
                : BF_OK;
}

/* ------------------------------------------------------------ provenance */

typedef struct visit_ctx {
    bf_out *out;
    bf_err *err;
} visit_ctx;

static int write_param(void *ctx, const char *name, const char *value,
                       const char *unit, int is_default)
{
    visit_ctx *v = ctx;
    char aname[600];
    double r;
    bf_status st;
    /* numbers as numbers, everything else as text */
    if (bf_parse_real(value, &r))
        st = bf_out_attr_real(v->out, "/", name, r, v->err);
    else
        st = bf_out_attr_str(v->out, "/", name, value, v->err);
    if (st)
        return 1;
    snprintf(aname, sizeof aname, "%s.unit", name);
    if (bf_out_attr_str(v->out, "/", aname, unit, v->err))
        return 1;
    if (is_default) {
        snprintf(aname, sizeof aname, "%s.default", name);
        if (bf_out_attr_int(v->out, "/", aname, 1, v->err))
            return 1;
    }
    return 0;
}

/* every resolved parameter of the scene as root attributes */
static bf_status write_params(void *ctx, bf_out *out, bf_err *err)
{
    visit_ctx v = {out, err};
    if (bf_scene_visit(ctx, write_param, &v))
        return err->status ? err->status : BF_EIO;
    return BF_OK;
}

/* The overrides joined by newlines (a newline cannot occur in one). */
static char *join_sets(const bf_scene *sc)
{
    const char *const *list;
    size_t n = bf_scene_overrides(sc, &list), len = 1;
    for (size_t k = 0; k < n; k++)
        len += strlen(list[k]) + 1;
    char *j = malloc(len);
    if (!j)
        return NULL;
    j[0] = '\0';
    for (size_t k = 0; k < n; k++) {
        strcat(j, list[k]);
        strcat(j, "\n");
    }
    return j;
}

static void free_setup(void *s) { bf_setup_free(s); }

static bf_status sim_from_scene(bf_sim **out, const bf_catalog *c,
                                const bf_scene *sc, const bf_sim_opts *opts,
                                bf_err *err)
{
    *out = NULL;
    bf_sim_keys k;
    bf_scene_fill(sc, "scene", &bf_sim_scene_spec, &k);
    /* a bound given replaces the model's (0 included: no bound at all) */
    if (bf_scene_given(sc, "scene", "max_energy_error"))
        k.energy_bound = 0;
    bf_run_ctx run;
    bf_setup *setup = NULL;
    void *model = NULL;
    bf_status st = bf_sim_run_ctx(&k, &run, err);
    if (!st && opts)
        run.keep_map = opts->keep_map_points;
    if (!st)
        st = bf_setup_create(&setup, c, sc, &run, err);
    if (!st && opts)
        bf_setup_set_nranks(setup, opts->nranks);
    if (!st)
        st = bf_setup_build_model(setup, sc, &model, err);
    char *sets = st ? NULL : join_sets(sc);
    if (!st && !sets) {
        bf_setup_model_type(setup)->destroy(model);
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    bf_sim *sim = NULL;
    if (!st) {
        bf_provenance prov = {bf_scene_path(sc), bf_scene_text(sc), sets,
                              write_params, (void *)sc};
        st = bf_sim_create(&sim, &k, bf_setup_model_type(setup), model, &prov,
                           opts, err);
    }
    free(sets);
    if (st) {
        bf_setup_free(setup);
        bf_scene_locate(sc, err);
        return st;
    }
    bf_sim_own(sim, setup, free_setup);
    if ((st = bf_setup_observe(setup, c, sim, err))) {
        bf_scene_locate(sc, err);
        bf_sim_free(sim);
        return st;
    }
    *out = sim;
    return BF_OK;
}

/* A model may read HDF5 files when it is built (an initial profile):
 * under the process's HDF5 lock (io/h5lock.h), as the restart. */
bf_status bf_sim_from_scene(bf_sim **out, const bf_catalog *c,
                            const bf_scene *sc, const bf_sim_opts *opts,
                            bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st =
        bf_compose_args_("bf_sim_from_scene", out, c, sc, NULL, 0, err);
    if (st)
        return st;
    bf_h5_lock();
    st = sim_from_scene(out, c, sc, opts, err);
    bf_h5_unlock();
    return st;
}

/* The keys a continued run may change: when it ends, how often it writes
 * and checks, not what it computes. */
static const char *const restart_keys[] = {
    "scene.t_end",        "scene.output_every",    "scene.energy_every",
    "scene.flush_seconds", "scene.checkpoint_every", "scene.max_energy_error",
    "scene.energy_bound", "film.profile_every",
};

static bf_status restart_key_allowed(const char *set, bf_err *err)
{
    const char *eq = strchr(set, '=');
    size_t len = eq ? (size_t)(eq - set) : strlen(set);
    while (len && (set[len - 1] == ' ' || set[len - 1] == '\t'))
        len--;
    for (size_t k = 0; k < sizeof restart_keys / sizeof *restart_keys; k++)
        if (strlen(restart_keys[k]) == len && !strncmp(set, restart_keys[k], len))
            return BF_OK;
    return bf_fail(err, BF_EINPUT, "--restart --set %.*s: a continued run "
                   "cannot change what it computes; only t_end, "
                   "output_every, energy_every, flush_seconds, "
                   "checkpoint_every, max_energy_error, energy_bound "
                   "([scene]) and "
                   "profile_every ([film]) may change (start a new run for "
                   "another scene)",
                   (int)len, set);
}

/* The stored overrides (one per line), then the new ones. */
static bf_status apply_sets(bf_scene *sc, const char *stored,
                            const char *cpath, const char *const *sets,
                            size_t nsets, bf_err *err)
{
    for (const char *p = stored; *p;) {
        const char *nl = strchr(p, '\n');
        size_t l = nl ? (size_t)(nl - p) : strlen(p);
        char buf[1024];
        if (l >= sizeof buf)
            return bf_fail(err, BF_EINPUT, "%s: override too long", cpath);
        memcpy(buf, p, l);
        buf[l] = '\0';
        bf_status st;
        if (l && (st = bf_scene_set(sc, buf, "--set (stored)", err)))
            return st;
        p += l + (nl ? 1 : 0);
    }
    for (size_t k = 0; k < nsets; k++) {
        bf_status st = restart_key_allowed(sets[k], err);
        if (!st)
            st = bf_scene_set(sc, sets[k], "--set", err);
        if (st)
            return st;
    }
    return BF_OK;
}

static bf_status sim_restart(bf_sim **out, bf_scene **scene,
                             const bf_catalog *c, const char *out_path,
                             const char *const *sets, size_t nsets,
                             const bf_sim_opts *opts, int output, bf_err *err)
{
    *out = NULL;
    *scene = NULL;
    size_t len = strlen(out_path) + 6;
    char *cpath = malloc(len);
    if (!cpath)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(cpath, len, "%s.ckpt", out_path);
    bf_ckpt *ck = NULL;
    bf_scene *sc = NULL;
    bf_sim *s = NULL;
    bf_status st = bf_ckpt_read(&ck, cpath, err);
    if (st) {
        bf_err_prefix(err, "cannot restart %s", out_path);
        free(cpath);
        return st;
    }
    const char *spath = bf_ckpt_str(ck, "scene.path");
    const char *stext = bf_ckpt_str(ck, "scene.text");
    const char *ssets = bf_ckpt_str(ck, "scene.sets");
    if (!spath || !stext || !ssets)
        st = bf_fail(err, BF_EINPUT, "%s: checkpoint lacks the scene", cpath);
    if (!st)
        st = bf_scene_load_string(&sc, spath, stext, err);
    if (!st)
        st = apply_sets(sc, ssets, cpath, sets, nsets, err);
    if (!st)
        st = bf_catalog_resolve(c, sc, err);
    if (!st)
        st = bf_sim_from_scene(&s, c, sc, opts, err);
    if (!st)
        st = output ? bf_sim_resume(s, ck, out_path, err)
                    : bf_sim_resume_state(s, ck, out_path, err);
    bf_ckpt_free(ck);
    free(cpath);
    if (st) {
        bf_sim_free(s);
        bf_scene_free(sc);
        return st;
    }
    *out = s;
    *scene = sc;
    return BF_OK;
}

bf_status bf_sim_restart(bf_sim **out, bf_scene **scene, const bf_catalog *c,
                         const char *out_path, const char *const *sets,
                         size_t nsets, const bf_sim_opts *opts, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_compose_args_("bf_sim_restart", out, c, out_path, sets,
                                    nsets, err);
    if (!st && !scene)
        st = bf_fail(err, BF_EINPUT, "bf_sim_restart: scene is NULL");
    if (st)
        return st;
    bf_h5_lock();
    st = sim_restart(out, scene, c, out_path, sets, nsets, opts, 1, err);
    bf_h5_unlock();
    return st;
}

/* ------------------------------------------------------------ bf_run */

struct bf_run {
    bf_scene *sc;
    bf_sim *sim;
};

/* The run of scene sc (taken over, also on failure; NULL when it could
 * not be read, with st its failure) after the overrides. */
static bf_status run_of(bf_run **out, const bf_catalog *c, bf_scene *sc,
                        bf_status st, const char *const *sets, size_t nsets,
                        const bf_sim_opts *opts, bf_err *err)
{
    *out = NULL;
    bf_run *r = calloc(1, sizeof *r);
    if (!r) {
        bf_scene_free(sc);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    r->sc = sc;
    for (size_t k = 0; !st && k < nsets; k++)
        st = bf_scene_set(r->sc, sets[k], "--set", err);
    if (!st)
        st = bf_catalog_resolve(c, r->sc, err);
    if (!st)
        st = bf_sim_from_scene(&r->sim, c, r->sc, opts, err);
    if (st) {
        bf_run_free(r);
        return st;
    }
    *out = r;
    return BF_OK;
}

bf_status bf_run_load(bf_run **out, const bf_catalog *c, const char *path,
                      const char *const *sets, size_t nsets,
                      const bf_sim_opts *opts, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st =
        bf_compose_args_("bf_run_load", out, c, path, sets, nsets, err);
    if (st)
        return st;
    bf_scene *sc = NULL;
    st = bf_scene_load(&sc, path, err);
    return run_of(out, c, sc, st, sets, nsets, opts, err);
}

bf_status bf_run_from_text(bf_run **out, const bf_catalog *c,
                           const char *name, const char *text,
                           const char *const *sets, size_t nsets,
                           const bf_sim_opts *opts, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st =
        bf_compose_args_("bf_run_from_text", out, c, name, sets, nsets, err);
    if (st)
        return st;
    bf_scene *sc = NULL;
    st = bf_scene_load_string(&sc, name, text ? text : "", err);
    return run_of(out, c, sc, st, sets, nsets, opts, err);
}

bf_status bf_run_from_scene(bf_run **out, const bf_catalog *c, bf_scene *sc,
                            const bf_sim_opts *opts, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st =
        bf_compose_args_("bf_run_from_scene", out, c, sc, NULL, 0, err);
    if (st) {
        bf_scene_free(sc); /* taken over, also on failure */
        return st;
    }
    return run_of(out, c, sc, BF_OK, NULL, 0, opts, err);
}

/* bf_run_restart (output 1) and bf_run_restart_state (0) */
static bf_status run_restart(const char *fn, bf_run **out,
                             const bf_catalog *c, const char *out_path,
                             const char *const *sets, size_t nsets,
                             const bf_sim_opts *opts, int output, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    bf_status st = bf_compose_args_(fn, out, c, out_path, sets, nsets, err);
    if (st)
        return st;
    *out = NULL;
    bf_run *r = calloc(1, sizeof *r);
    if (!r)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_h5_lock();
    st = sim_restart(&r->sim, &r->sc, c, out_path, sets, nsets, opts, output,
                     err);
    bf_h5_unlock();
    if (st) {
        bf_run_free(r);
        return st;
    }
    *out = r;
    return BF_OK;
}

bf_status bf_run_restart(bf_run **out, const bf_catalog *c,
                         const char *out_path, const char *const *sets,
                         size_t nsets, const bf_sim_opts *opts, bf_err *err)
{
    return run_restart("bf_run_restart", out, c, out_path, sets, nsets, opts,
                       1, err);
}

bf_status bf_run_restart_state(bf_run **out, const bf_catalog *c,
                               const char *out_path, const char *const *sets,
                               size_t nsets, const bf_sim_opts *opts,
                               bf_err *err)
{
    return run_restart("bf_run_restart_state", out, c, out_path, sets, nsets,
                       opts, 0, err);
}

bf_sim *bf_run_sim(bf_run *r) { return r ? r->sim : NULL; }

const bf_scene *bf_run_scene_of(const bf_run *r) { return r ? r->sc : NULL; }

/* 1 if a and b are one file: by device and inode, so that a link or a
 * second name of an input is seen for what it is (outpath.h) */
static int same_file(const char *a, const char *b)
{
    return bf_path_same_file(a, b);
}

bf_status bf_run_open_output(bf_run *r, const char *path, bf_err *err)
{
    bf_err own;
    if (!err)
        err = &own;
    if (!r || !path)
        return bf_fail(err, BF_EINPUT, "bf_run_open_output: %s is NULL",
                       !r ? "run" : "path");
    const char *inputs[2] = {bf_scene_path(r->sc), NULL};
    if (bf_scene_has_key(r->sc, "film", "file"))
        inputs[1] = bf_scene_str(r->sc, "film", "file");
    for (int k = 0; k < 2; k++)
        if (same_file(path, inputs[k]))
            return bf_fail(err, BF_EINPUT, "-o %s: that is %s, an input of "
                           "this run; the result would overwrite it",
                           path, k ? "[film] file" : "the scene file");
    return bf_sim_open_output(r->sim, path, err);
}

void bf_run_free(bf_run *r)
{
    if (!r)
        return;
    bf_sim_free(r->sim);
    bf_scene_free(r->sc);
    free(r);
}
