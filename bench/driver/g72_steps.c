/* g72_steps.c: the time of a step of the Greenspan 1972 model at large N,
 * for bench/g72_vs_a752c43.sh, which builds it against two versions of
 * the library (this one and main at a752c43, before issue 21 item 5) and
 * runs them alternately.  It uses only what both versions have.
 *
 *   g72_steps n
 *
 * The scene of bench_greenspan72 (g72_scene.h), one thread: 100 warm-up
 * steps, then the shortest of 3 runs of 20 steps in CPU time of the
 * process; then the support-set gravity alone on the state reached (a
 * cell list of side 10 cm built on it, as the model's), the shortest of 5
 * evaluations.  Prints
 *
 *   N=<n^2> s_per_step=<CPU s> s_support=<CPU s> hash=<FNV-1a of the
 *   positions' bits> ghash=<FNV-1a of g's bits>
 *
 * so that the script can check that both versions end in the same state.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/model.h"
#include "ballfilm/run.h"
#include "ballfilm/scene.h"
#include "g72_scene.h"
#include "models/greenspan.h"
#include "particles/cells.h"
#include "particles/support.h"

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 0;
    if (n < 8 || n > 4096) {
        fprintf(stderr, "usage: g72_steps n   (8 <= n <= 4096; N = n^2)\n");
        return 2;
    }
    bf_err err = {0};
    bf_scene *sc;
    bf_setup *setup;
    void *m;
    if (g72_scene_model(n, "g72_steps.ini", &sc, &setup, &m, &err)) {
        fprintf(stderr, "g72_steps: %s\n", err.msg);
        return 1;
    }
    const bf_model_type *mt =
        bf_catalog_model(bf_catalog_builtin(), "greenspan72");
    const double dt = 0.01;
    long k = 0;
    double best = 1e300;
    for (int run = -1; run < 3; run++) {
        const long steps = run < 0 ? 100 : 20; /* run -1: the warm-up */
        const double t0 = g72_cpu_now();
        for (long s = 0; s < steps; s++, k++)
            if (mt->step(m, k, (double)k * dt, dt, &err)) {
                fprintf(stderr, "g72_steps: step %ld: %s\n", k, err.msg);
                return 1;
            }
        const double per = (g72_cpu_now() - t0) / (double)steps;
        if (run >= 0 && per < best)
            best = per;
    }
    bf_particles *p = bf_greenspan72_particles(m);
    uint64_t h = 1469598103934665603ULL;
    for (size_t i = 0; i < p->n; i++) {
        uint64_t a, b;
        memcpy(&a, &p->x[i], sizeof a);
        memcpy(&b, &p->y[i], sizeof b);
        h = (h ^ a) * 1099511628211ULL;
        h = (h ^ b) * 1099511628211ULL;
    }
    /* the support-set gravity alone */
    bf_support *sup = bf_greenspan72_support(m);
    const bf_support_params *sp = bf_support_params_of(sup);
    bf_cells c;
    double *g = malloc(p->n * sizeof *g);
    if (!g || bf_cells_init(&c, sp->box.ax, sp->box.ay,
                            sp->box.bx - sp->box.ax, sp->box.by - sp->box.ay,
                            10.0, p->n, &err)) {
        fprintf(stderr, "g72_steps: out of memory\n");
        return 1;
    }
    bf_cells_build(&c, p->x, p->y, NULL, p->n);
    double sbest = 1e300;
    for (int rep = 0; rep < 5; rep++) {
        const double t0 = g72_cpu_now();
        bf_support_eval_with(sup, BF_SUPPORT_FAST, p->x, p->y, p->n, &c, g,
                             NULL);
        const double t = g72_cpu_now() - t0;
        sbest = t < sbest ? t : sbest;
    }
    uint64_t gh = 1469598103934665603ULL;
    for (size_t i = 0; i < p->n; i++) {
        uint64_t a;
        memcpy(&a, &g[i], sizeof a);
        gh = (gh ^ a) * 1099511628211ULL;
    }
    printf("N=%d s_per_step=%.6g s_support=%.6g hash=%016llx "
           "ghash=%016llx\n",
           n * n, best, sbest, (unsigned long long)h,
           (unsigned long long)gh);
    bf_cells_free(&c);
    free(g);
    mt->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return 0;
}
