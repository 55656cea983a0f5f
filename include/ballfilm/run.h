/* run.h: the composition layer, the one place that builds a run from a
 * scene.
 *
 * The catalog lists what a scene may name: models, integrators, effects.
 * The built-in catalog holds the library's own (src/compose/catalog.c);
 * a program may add its own descriptors to a catalog of its own and build
 * scenes against it.
 *
 * A setup is what a model is built from: the scene's sections filled into
 * the typed structs of their specs (params.h), the integrator and the
 * effects the scene names, and the run context.  Only this layer and the
 * scene layer read a scene.
 */
/* Misuse is refused with BF_EINPUT naming the function and the argument,
 * never a crash: a NULL result pointer, catalog, scene or path, and sets
 * NULL (or holding a NULL) with nsets > 0.  err may be NULL wherever a
 * call takes one.  bf_run_open_output refuses what bf_sim_open_output
 * does (sim.h): a second output, one after the first step. */
#ifndef BALLFILM_RUN_H
#define BALLFILM_RUN_H

#include <stdio.h>

#include "ballfilm/effect.h"
#include "ballfilm/error.h"
#include "ballfilm/integrator.h"
#include "ballfilm/model.h"
#include "ballfilm/scene.h"
#include "ballfilm/sim.h"

typedef struct bf_catalog bf_catalog;

/* The library's models, integrators and effects. */
const bf_catalog *bf_catalog_builtin(void);

const bf_model_type *bf_catalog_model(const bf_catalog *c, const char *name);
const bf_integrator_type *bf_catalog_integrator(const bf_catalog *c,
                                                const char *name);
const bf_effect_type *bf_catalog_effect(const bf_catalog *c,
                                        const char *name);
/* All entries of a kind, in catalog order. */
const bf_model_type *const *bf_catalog_models(const bf_catalog *c, size_t *n);
const bf_integrator_type *const *bf_catalog_integrators(const bf_catalog *c,
                                                        size_t *n);
const bf_effect_type *const *bf_catalog_effects(const bf_catalog *c,
                                                size_t *n);

/* A catalog of a program's own: a copy of `base` (the built-in catalog,
 * another catalog, or NULL for an empty one) to which it adds its
 * descriptors; a scene resolved and built against it may name them like
 * the library's own.  The descriptors are kept by pointer (they are
 * usually static constants) and must outlive the catalog and every run
 * built with it.  NULL when out of memory. */
bf_catalog *bf_catalog_new(const bf_catalog *base);
/* Refuse (BF_EINPUT) a name the catalog already has for that kind, and the
 * built-in catalog itself. */
bf_status bf_catalog_add_model(bf_catalog *c, const bf_model_type *t,
                               bf_err *err);
bf_status bf_catalog_add_integrator(bf_catalog *c,
                                    const bf_integrator_type *t, bf_err *err);
bf_status bf_catalog_add_effect(bf_catalog *c, const bf_effect_type *t,
                                bf_err *err);
/* Free a catalog of bf_catalog_new (the built-in one is left alone). */
void bf_catalog_free(bf_catalog *c);

/* Validate a scene against the catalog: which sections it may contain is
 * decided by its [scene] section (model, integrator, effects); unknown
 * sections and keys are errors naming file and line. */
bf_status bf_catalog_resolve(const bf_catalog *c, bf_scene *sc, bf_err *err);

/* Print every section and key a scene may contain (help). */
void bf_catalog_print_help(const bf_catalog *c, FILE *f);

/* The setup of a resolved scene's model (it points into the scene: free
 * it before the scene). */
typedef struct bf_setup bf_setup;
bf_status bf_setup_create(bf_setup **out, const bf_catalog *c,
                          const bf_scene *sc, const bf_run_ctx *run,
                          bf_err *err);
void bf_setup_free(bf_setup *s);
const bf_model_setup *bf_setup_model(const bf_setup *s);
const bf_model_type *bf_setup_model_type(const bf_setup *s);

/* Create the scene's model from its setup; a failure that names a key is
 * located in the scene (FILE:LINE). */
bf_status bf_setup_build_model(const bf_setup *s, const bf_scene *sc,
                               void **model, bf_err *err);

/* Attach to sim (whose model the setup built) the analyses of balls its
 * keys enable (sim.h). */
struct bf_sim;
bf_status bf_setup_observe(const bf_setup *s, const bf_catalog *c,
                           struct bf_sim *sim, bf_err *err);

/* ---- runs from scenes ---- */

/* The run of a resolved scene: its model, the analyses its keys enable,
 * the loop (sim.h).  The scene must outlive the sim (the output's
 * provenance is read from it when the output opens).  Failures that are
 * about a key are located in the scene (FILE:LINE). */
bf_status bf_sim_from_scene(struct bf_sim **sim, const bf_catalog *c,
                            const bf_scene *sc,
                            const struct bf_sim_opts *opts, bf_err *err);

/* Rebuild a run from the checkpoint of OUT (OUT.ckpt): its stored scene
 * plus extra overrides `sets` (for example a later t_end), the state of
 * the model, its observers and the loop, and OUT reopened with the rows
 * written after the checkpoint dropped.  *scene receives the scene (free
 * it after the sim). */
bf_status bf_sim_restart(struct bf_sim **sim, bf_scene **scene,
                         const bf_catalog *c, const char *out_path,
                         const char *const *sets, size_t nsets,
                         const struct bf_sim_opts *opts, bf_err *err);

/* The model of a resolved scene, without a time loop (tests,
 * benchmarks): its setup in *setup (free it after the model). */
bf_status bf_model_from_scene(const bf_catalog *c, const bf_scene *sc,
                              bf_setup **setup, void **model, bf_err *err);

/* The ball system of a resolved ball scene ([ball.N], its effects and
 * integrator; no coupling), for drivers that step balls themselves
 * (converge, tests, benchmarks). */
struct bf_ballsys;
bf_status bf_ballsys_from_scene(struct bf_ballsys **out, const bf_catalog *c,
                                const bf_scene *sc, bf_err *err);

/* ---- a run owning its scene: what a program drives ---- */

typedef struct bf_run bf_run;

/* Read the scene file, apply the overrides "section.key=value" (origin
 * "--set"), validate it against the catalog and build its run. */
bf_status bf_run_load(bf_run **run, const bf_catalog *c,
                      const char *scene_path, const char *const *sets,
                      size_t nsets, const struct bf_sim_opts *opts,
                      bf_err *err);
/* The same from INI text in memory (`name` stands for the file in
 * messages: "name:LINE: error: ..."; text NULL: an empty scene that the
 * overrides fill). */
bf_status bf_run_from_text(bf_run **run, const bf_catalog *c,
                           const char *name, const char *text,
                           const char *const *sets, size_t nsets,
                           const struct bf_sim_opts *opts, bf_err *err);
/* The same from a scene made in code (taken over, also on failure; see
 * bf_setf and bf_add_ball below): validated, then built. */
bf_status bf_run_from_scene(bf_run **run, const bf_catalog *c, bf_scene *sc,
                            const struct bf_sim_opts *opts, bf_err *err);
/* The run of the output OUT continued from its checkpoint (bf_sim_restart). */
bf_status bf_run_restart(bf_run **run, const bf_catalog *c,
                         const char *out_path, const char *const *sets,
                         size_t nsets, const struct bf_sim_opts *opts,
                         bf_err *err);
/* The same without reopening OUT (bf_sim_resume_state): for a process
 * that computes and does not write, the ranks other than 0 of a run over
 * ranks. */
bf_status bf_run_restart_state(bf_run **run, const bf_catalog *c,
                               const char *out_path, const char *const *sets,
                               size_t nsets, const struct bf_sim_opts *opts,
                               bf_err *err);
struct bf_sim *bf_run_sim(bf_run *run);
/* The run's scene (resolved: its keys can be read; the output's
 * provenance). */
const bf_scene *bf_run_scene_of(const bf_run *run);
/* Create the run's output (bf_sim_open_output) after refusing a path that
 * is one of the run's inputs (the scene file, a file the scene reads),
 * which the result would overwrite (BF_EINPUT). */
bf_status bf_run_open_output(bf_run *run, const char *path, bf_err *err);
void bf_run_free(bf_run *run);

/* The size of a public struct by its name ("bf_err", "bf_sim_opts",
 * "bf_state_var", "bf_sweep", "bf_converge_result", ...), 0 for a name it
 * does not know: foreign-function interfaces (the Python package) check
 * their mirrors of the structs with it. */
size_t bf_sizeof(const char *name);

/* ---- scenes written in code ----
 * Start from bf_scene_load_string(&sc, "name", "", err) (an empty scene)
 * or from INI text, then set keys and add balls; bf_run_from_scene
 * validates the result like a file (an unknown key is an error naming
 * it).  Every key set is recorded as an override, so the output's
 * provenance and checkpoints carry the scene. */

/* Set "section.key=value" formatted like printf: bf_setf(sc, err,
 * "ball.%d.mass=%.17g", 2, 0.8).  Messages say "code: error: ...". */
bf_status bf_setf(bf_scene *sc, bf_err *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Add the next ball [ball.N] (N = 1 + the balls the scene has): centre
 * position (cm), velocity (cm/s), mass (g), radius (cm); *index (may be
 * NULL) receives N.  Values go in at full precision (%.17g); one that is
 * not finite is refused, naming it, and nothing is added. */
bf_status bf_add_ball(bf_scene *sc, double position, double velocity,
                      double mass, double radius, int *index, bf_err *err);

#endif
