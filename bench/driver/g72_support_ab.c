/* g72_support_ab.c: the support-set gravity's fast method of this tree
 * against another version of src/particles/support_fast.c, both in one
 * process, for bench/support_ab.sh (which compiles the other version with
 * its entry renamed bf_sup_eval_fast_other and links it in).
 *
 *   g72_support_ab n [pairs]
 *
 * The scene of bench_greenspan72 (g72_scene.h), one thread, 160 steps;
 * then, on the state reached (a cell list of side 10 cm built on it, as
 * the model's), `pairs` (default 30) pairs of evaluations, this tree's and
 * the other's one after the other (which one first alternates), in CPU
 * time.  Prints each one's
 * shortest and median time, the median of the pairs' ratios
 * (other / this: above 1 when this tree is faster) and whether g and the
 * kinds are the same bits.
 *
 * Why in one process: on a virtual machine whose processes have spells of
 * running 25 % slower (the AMD machine of docs/performance.md), two
 * programs run alternately scatter by more than the few per cent a change
 * of one phase makes; a pair of evaluations taken a few milliseconds
 * apart does not.  The other version must use the same workspace
 * (support_impl.h) as this tree's.
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
#include "particles/support_impl.h"

/* the other version's bf_sup_eval_fast, renamed when it was compiled */
void bf_sup_eval_fast_other(bf_support *s, size_t n, const bf_cells *c,
                            double *g, uint8_t *kind);

enum { MAX_PAIRS = 1000 };

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 0;
    const int pairs = argc > 2 ? atoi(argv[2]) : 30;
    if (n < 8 || n > 4096 || pairs < 1 || pairs > MAX_PAIRS) {
        fprintf(stderr, "usage: g72_support_ab n [pairs]   (8 <= n <= 4096; "
                        "N = n^2; 1 <= pairs <= %d)\n", MAX_PAIRS);
        return 2;
    }
    bf_err err = {0};
    bf_scene *sc;
    bf_setup *setup;
    void *m;
    if (g72_scene_warm_model(n, "g72_support_ab.ini", 160, &sc, &setup, &m,
                             &err)) {
        fprintf(stderr, "g72_support_ab: %s\n", err.msg);
        return 1;
    }
    bf_particles *p = bf_greenspan72_particles(m);
    bf_support *sup = bf_greenspan72_support(m);
    const bf_support_params *sp = bf_support_params_of(sup);
    bf_cells c;
    double *g = malloc(p->n * sizeof *g), *g2 = malloc(p->n * sizeof *g2);
    uint8_t *kd = malloc(p->n), *kd2 = malloc(p->n);
    static double tt[MAX_PAIRS], to[MAX_PAIRS], ratio[MAX_PAIRS];
    if (!g || !g2 || !kd || !kd2 ||
        bf_cells_init(&c, sp->box.ax, sp->box.ay, sp->box.bx - sp->box.ax,
                      sp->box.by - sp->box.ay, 10.0, p->n, &err)) {
        fprintf(stderr, "g72_support_ab: out of memory\n");
        return 1;
    }
    bf_cells_build(&c, p->x, p->y, NULL, p->n);
    int same = 1;
    for (int k = 0; k < pairs; k++) {
        /* the order swapped in every pair: the second of two evaluations
         * finds the caches as the first left them */
        for (int which = 0; which < 2; which++) {
            const double t0 = g72_cpu_now();
            if ((which ^ k) & 1)
                bf_sup_eval_fast_other(sup, p->n, &c, g2, kd2);
            else
                bf_support_eval_with(sup, BF_SUPPORT_FAST, p->x, p->y, p->n,
                                     &c, g, kd);
            const double t = g72_cpu_now() - t0;
            if ((which ^ k) & 1)
                to[k] = t;
            else
                tt[k] = t;
        }
        ratio[k] = to[k] / tt[k];
        same = same && !memcmp(g, g2, p->n * sizeof *g) &&
               !memcmp(kd, kd2, p->n);
    }
    g72_sort(tt, (size_t)pairs);
    g72_sort(to, (size_t)pairs);
    g72_sort(ratio, (size_t)pairs);
    printf("N=%d pairs=%d this: shortest %.3f ms, median %.3f ms; other: "
           "shortest %.3f ms, median %.3f ms; other/this (median of the "
           "pairs) %.3f; g and kinds the same bits: %s\n",
           n * n, pairs, 1e3 * tt[0], 1e3 * tt[pairs / 2], 1e3 * to[0],
           1e3 * to[pairs / 2], ratio[pairs / 2], same ? "yes" : "NO");
    bf_cells_free(&c);
    free(g);
    free(g2);
    free(kd);
    free(kd2);
    bf_catalog_model(bf_catalog_builtin(), "greenspan72")->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return same ? 0 : 1;
}
