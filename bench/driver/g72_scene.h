/* g72_scene.h: the scaled Greenspan 1972 scene of the benchmarks
 * (bench_greenspan72.c, and driver/g72_steps.c, which bench/
 * g72_vs_a752c43.sh builds against today's library and a752c43's):
 * Example 2's local physics (d = 5 cm, dx = 6.25 cm, cutoff 10 cm,
 * V = 500 cm/s, dt = 0.01 s, omega = 0.9) on an n x n grid in a box of
 * side 6.25 n cm, the top quarter heavy, support method fast, no output.
 * Written into buf (size bytes); returns buf.  g72_scene_model builds it,
 * g72_scene_warm_model also takes the warm-up steps; g72_cpu_now is the
 * drivers' clock, g72_sort their sort. */
#ifndef BALLFILM_BENCH_G72_SCENE_H
#define BALLFILM_BENCH_G72_SCENE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ballfilm/model.h"
#include "ballfilm/run.h"
#include "ballfilm/scene.h"

static inline const char *g72_scene_text(char *buf, size_t size, int n,
                                         int threads)
{
    const double L = 6.25 * n;
    snprintf(buf, size,
             "[scene]\nmodel = greenspan72\ndt = 0.01\nt_end = 1e9\n"
             "[greenspan72]\nwidth = %.17g\nheight = %.17g\ninterface = "
             "%.17g\nd = 5\nm_heavy = 1\nm_light = 0.25\nlayout = grid\n"
             "grid_nx = %d\ngrid_ny = %d\nv_random = 500\nseed = 1972\n"
             "output = diagnostics\nthreads = %d\n"
             "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
             "[support]\ndx = 6.25\nmethod = fast\n[walls]\nomega = 0.9\n",
             L, L, 0.75 * L, n, n, threads);
    return buf;
}

/* That scene with n x n particles and one thread, read (named `name` in
 * messages) and built into a greenspan72 model; *sc, *setup and *model
 * are the caller's to free.  Returns 0, or 1 with err set. */
static inline int g72_scene_model(int n, const char *name, bf_scene **sc,
                                  bf_setup **setup, void **model,
                                  bf_err *err)
{
    char text[2048];
    g72_scene_text(text, sizeof text, n, 1);
    *sc = NULL;
    *setup = NULL;
    *model = NULL;
    return bf_scene_load_string(sc, name, text, err) ||
           bf_catalog_resolve(bf_catalog_builtin(), *sc, err) ||
           bf_model_from_scene(bf_catalog_builtin(), *sc, setup, model, err);
}

/* That model (g72_scene_model), then `steps` steps of the scene's dt =
 * 0.01 s from t = 0: the state on which the drivers measure.  Returns 0,
 * or 1 with err set (a failed step's message starting with its number). */
static inline int g72_scene_warm_model(int n, const char *name, long steps,
                                       bf_scene **sc, bf_setup **setup,
                                       void **model, bf_err *err)
{
    if (g72_scene_model(n, name, sc, setup, model, err))
        return 1;
    const bf_model_type *mt =
        bf_catalog_model(bf_catalog_builtin(), "greenspan72");
    const double dt = 0.01;
    for (long k = 0; k < steps; k++)
        if (mt->step(*model, k, (double)k * dt, dt, err)) {
            char msg[sizeof err->msg + 32];
            snprintf(msg, sizeof msg, "step %ld: %s", k, err->msg);
            memcpy(err->msg, msg, sizeof err->msg - 1);
            err->msg[sizeof err->msg - 1] = '\0';
            return 1;
        }
    return 0;
}

/* v[0..n) sorted in increasing order (the drivers' shortest times and
 * medians). */
static inline int g72_by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static inline void g72_sort(double *v, size_t n)
{
    qsort(v, n, sizeof *v, g72_by_value);
}

/* CPU time of the process, s (the drivers run one thread). */
static inline double g72_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
