/* registry.h: the lists of models, integrators and effects, and the scene
 * resolution that uses them to decide which sections a scene may contain. */
#ifndef BALLFILM_REGISTRY_H
#define BALLFILM_REGISTRY_H

#include <stdio.h>

#include "ballfilm/error.h"
#include "ballfilm/scene.h"

/* Validate a scene against the tables of its model, integrator and effects. */
bf_status bf_registry_resolve(bf_scene *sc, bf_err *err);

/* Print every section and key that any scene may contain (--help). */
void bf_registry_print_help(FILE *f);

#endif
