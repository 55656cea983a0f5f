/* scene.h: scene files (INI) and the parameter tables that describe them.
 *
 * One source of truth: every key a scene may contain is declared once, in a
 * bf_section_spec table owned by the module that uses it (the core [scene]
 * section, each model, each effect, each integrator).  The parser validates
 * against these tables, fills in defaults, and `ballfilm run --help` prints
 * them.  A key that no table declares is an error, so a typo never passes
 * silently.
 *
 * Sections named "NAME.N" in a table (for example "ball.N") are indexed:
 * a scene may contain [ball.1], [ball.2], ... with consecutive indices.
 *
 * Life cycle:
 *   bf_scene_load()       read the file (syntax errors, duplicate keys)
 *   bf_scene_set()        apply a "section.key=value" override (--set)
 *   bf_scene_resolve()    validate against the tables, parse values, fill
 *                         defaults; after this the accessors may be used.
 * Every error message starts with "FILE:LINE: error:" (or "FILE: error:" for
 * a key that is missing, "--set: error:" for an override) and names the key.
 */
#ifndef BALLFILM_SCENE_H
#define BALLFILM_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"

typedef struct bf_scene bf_scene;

/* Read a scene file.  On error returns BF_EINPUT (or BF_EIO) with a message
 * naming file and line; *out is NULL then. */
bf_status bf_scene_load(bf_scene **out, const char *path, bf_err *err);
/* Same, from text in memory (`name` is used in messages). */
bf_status bf_scene_load_string(bf_scene **out, const char *name,
                               const char *text, bf_err *err);
void bf_scene_free(bf_scene *sc);
/* A deep copy (raw entries and overrides; resolve it again before use). */
bf_scene *bf_scene_clone(const bf_scene *sc);

/* Apply an override "section.key=value" (the key is the part after the last
 * dot, so "ball.2.mass=0.8" sets key mass of [ball.2]).  `origin` names it in
 * messages (for example "--set").  Invalidates a previous resolve. */
bf_status bf_scene_set(bf_scene *sc, const char *assignment, const char *origin,
                       bf_err *err);

/* The overrides applied so far, in order (for checkpoints). */
size_t bf_scene_overrides(const bf_scene *sc, const char *const **list);

/* Which sections a scene may contain is decided in two stages: the root
 * section ([scene]) is resolved first; then `select` looks at it (model,
 * effects, integrator) and lists the further sections that are allowed.
 * The catalog (run.h) provides the provider used by the program. */
typedef struct bf_spec_provider {
    const bf_section_spec *root;
    bf_status (*select)(const bf_scene *sc, const bf_section_spec **specs,
                        size_t cap, size_t *n, const void *ctx, bf_err *err);
    const void *ctx; /* handed to select (the catalog) */
} bf_spec_provider;

/* Validate and fill defaults. */
bf_status bf_scene_resolve_with(bf_scene *sc, const bf_spec_provider *p,
                                bf_err *err);

/* The scene text as read (for the HDF5 provenance attribute). */
const char *bf_scene_text(const bf_scene *sc);
const char *bf_scene_path(const bf_scene *sc);

/* Accessors (valid after a successful resolve).  Asking for a key that no
 * table declares is a programming error and aborts with a message. */
double bf_scene_real(const bf_scene *sc, const char *section, const char *key);
long bf_scene_int(const bf_scene *sc, const char *section, const char *key);
int bf_scene_bool(const bf_scene *sc, const char *section, const char *key);
const char *bf_scene_str(const bf_scene *sc, const char *section,
                         const char *key);
/* Index of the chosen word in the param's `choices`. */
int bf_scene_enum(const bf_scene *sc, const char *section, const char *key);
/* For BF_REALS and BF_NAMES: number of elements and a pointer to them
 * (names: array of strings). */
const double *bf_scene_reals(const bf_scene *sc, const char *section,
                             const char *key, size_t *n);
const char *const *bf_scene_names(const bf_scene *sc, const char *section,
                                  const char *key, size_t *n);
int bf_scene_has_name(const bf_scene *sc, const char *section, const char *key,
                      const char *name);
bf_interval bf_scene_interval(const bf_scene *sc, const char *section,
                              const char *key);
/* Whether the section was given in the file (or by --set), and whether a key
 * was given explicitly rather than defaulted. */
int bf_scene_has_section(const bf_scene *sc, const char *section);
int bf_scene_given(const bf_scene *sc, const char *section, const char *key);
/* Whether a resolved scene has this key (declared for an active section). */
int bf_scene_has_key(const bf_scene *sc, const char *section, const char *key);
/* Number of consecutive indexed sections NAME.1 .. NAME.n ("ball" -> n). */
int bf_scene_count(const bf_scene *sc, const char *base);

/* Write the resolved values of one section ("film", "ball.2") into the
 * struct of its spec (zeroed first; params.h).  The section must be one
 * the scene resolved with that spec; strings and lists in the struct
 * point into the scene. */
void bf_scene_fill(const bf_scene *sc, const char *section,
                   const bf_section_spec *spec, void *dst);

/* A failure that names a key (bf_fail_key) becomes a message located in
 * the scene: "FILE:LINE: error: [section] key: ...", as bf_scene_fail
 * writes it; other failures are left alone. */
void bf_scene_locate(const bf_scene *sc, bf_err *err);

/* Report a semantic error about a key ("balls overlap", "dt above the stable
 * limit"): the message is prefixed with the key's file and line. */
bf_status bf_scene_fail(const bf_scene *sc, bf_err *err, const char *section,
                        const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* Visit every resolved parameter (for provenance in the output file).  The
 * callback receives "section.key", the value as text, the unit, and whether
 * the value was a default. */
typedef int (*bf_scene_visit_fn)(void *ctx, const char *name, const char *value,
                                 const char *unit, int is_default);
int bf_scene_visit(const bf_scene *sc, bf_scene_visit_fn fn, void *ctx);


#endif
