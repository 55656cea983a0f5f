/* g72_support_tiles.c: does the support-set gravity's fast method get
 * slower per particle when its arrays outgrow the caches?  For
 * bench/support_tiles.sh (docs/performance.md, "Support-set gravity: the
 * 2x goal").
 *
 *   g72_support_tiles n T1 [T2 ...]
 *
 * The scene of bench_greenspan72 (g72_scene.h) at n x n particles, one
 * thread, 100 warm-up steps.  The state reached is then copied T times
 * side by side in x (copy t shifted by t times the box's width, the box
 * T times as wide, the same height), so that every copy holds the same
 * local configuration: the same levels, the same particles held up or
 * falling freely, the same work per particle; only the number of
 * particles, N = T n^2, and with it the size of every array that the
 * method streams, grows.  For each T the fast method (one thread) is
 * evaluated on a cell list of side 10 cm built on the copies, as the
 * model's; the T's are taken in turn, 3 evaluations each, in 7 rounds.
 * Printed: the highest level K of the state, and per T: N, the memory
 * that the copies, their cell list and the method's workspace took (the
 * growth of the resident set, /proc/self/statm, from before the copies
 * were made to after their first evaluation), the CPU time per particle
 * (median over the rounds of each round's shortest), the median over the
 * rounds of the ratio to the first T's time per particle in the same
 * round, and the share of particles falling freely.
 *
 * If the time per particle stays flat from a few thousand particles
 * (every array in the second-level cache: 1 MiB on the AMD machine of
 * docs/performance.md) to a quarter of a million (tens of MiB), the
 * method is not bound by memory traffic, and doing it chunk by chunk of x
 * to keep a chunk's arrays in the cache cannot make it faster.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "ballfilm/model.h"
#include "ballfilm/run.h"
#include "ballfilm/scene.h"
#include "g72_scene.h"
#include "models/greenspan.h"
#include "particles/cells.h"
#include "particles/support.h"

enum { MAX_T = 16, ROUNDS = 7, EVALS = 3 };

typedef struct tiling {
    int T;
    size_t n;
    double *x, *y, *g;
    bf_support *sup;
    bf_cells cells;
    double mib;           /* resident memory the tiling added */
    double t[ROUNDS];     /* shortest evaluation of each round, s */
    double ratio[ROUNDS]; /* per particle, to the first tiling's */
} tiling;

/* Resident memory of the process, MiB (0 where /proc is missing). */
static double resident_mib(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, res = 0;
    if (f) {
        if (fscanf(f, "%ld %ld", &size, &res) != 2)
            res = 0;
        fclose(f);
    }
    return (double)res * (double)sysconf(_SC_PAGESIZE) / 1048576.0;
}

static double median(double *v, int k)
{
    g72_sort(v, (size_t)k);
    return k % 2 ? v[k / 2] : 0.5 * (v[k / 2 - 1] + v[k / 2]);
}

int main(int argc, char **argv)
{
    const int n = argc > 2 ? atoi(argv[1]) : 0;
    const int nt = argc - 2;
    int bad = n < 8 || n > 1024 || nt > MAX_T;
    for (int k = 0; k < nt && !bad; k++) {
        const int T = atoi(argv[2 + k]);
        bad = T < 1 || (double)T * n * n > 4.2e6;
    }
    if (bad) {
        fprintf(stderr, "usage: g72_support_tiles n T1 [T2 ...]   (8 <= n <= "
                        "1024, T >= 1, T n^2 <= 4.2e6, at most %d T's)\n",
                MAX_T);
        return 2;
    }
    bf_err err = {0};
    bf_scene *sc;
    bf_setup *setup;
    void *m;
    if (g72_scene_warm_model(n, "g72_support_tiles.ini", 100, &sc, &setup,
                             &m, &err)) {
        fprintf(stderr, "g72_support_tiles: %s\n", err.msg);
        return 1;
    }
    const bf_particles *p = bf_greenspan72_particles(m);
    const bf_support_params *sp0 =
        bf_support_params_of(bf_greenspan72_support(m));
    const double width = sp0->box.bx - sp0->box.ax;
    int kmax = 0;
    for (size_t i = 0; i < p->n; i++) {
        const int K = (int)((p->y[i] - sp0->box.ay) * sp0->inv_dx);
        kmax = K > kmax ? K : kmax;
    }

    tiling tl[MAX_T];
    for (int k = 0; k < nt; k++) {
        tiling *c = &tl[k];
        const double rss0 = resident_mib();
        c->T = atoi(argv[2 + k]);
        c->n = p->n * (size_t)c->T;
        bf_support_params sp = *sp0;
        sp.box.bx = sp.box.ax + c->T * width;
        sp.threads = 1;
        c->x = malloc(c->n * sizeof *c->x);
        c->y = malloc(c->n * sizeof *c->y);
        c->g = malloc(c->n * sizeof *c->g);
        if (!c->x || !c->y || !c->g ||
            bf_support_create(&c->sup, &sp, c->n, &err) ||
            bf_cells_init(&c->cells, sp.box.ax, sp.box.ay,
                          sp.box.bx - sp.box.ax, sp.box.by - sp.box.ay, 10.0,
                          c->n, &err)) {
            fprintf(stderr, "g72_support_tiles: T = %d: %s\n", c->T,
                    err.msg[0] ? err.msg : "out of memory");
            return 1;
        }
        for (int t = 0; t < c->T; t++)
            for (size_t i = 0; i < p->n; i++) {
                c->x[(size_t)t * p->n + i] = p->x[i] + t * width;
                c->y[(size_t)t * p->n + i] = p->y[i];
            }
        bf_cells_build(&c->cells, c->x, c->y, NULL, c->n);
        bf_support_eval_with(c->sup, BF_SUPPORT_FAST, c->x, c->y, c->n,
                             &c->cells, c->g, NULL);
        c->mib = resident_mib() - rss0;
    }
    for (int r = 0; r < ROUNDS; r++)
        for (int k = 0; k < nt; k++) {
            tiling *c = &tl[k];
            double best = 1e300;
            for (int e = 0; e < EVALS; e++) {
                const double t0 = g72_cpu_now();
                bf_support_eval_with(c->sup, BF_SUPPORT_FAST, c->x, c->y,
                                     c->n, &c->cells, c->g, NULL);
                const double t = g72_cpu_now() - t0;
                best = t < best ? t : best;
            }
            c->t[r] = best;
            c->ratio[r] = (best / (double)c->n) / (tl[0].t[r] / (double)tl[0].n);
        }

    printf("support-set gravity (fast, one thread) of the n = %d state after "
           "100 steps, copied T times side by side in x (highest level K = "
           "%d)\n", n, kmax);
    printf("%4s %8s %14s %14s %22s %8s\n", "T", "N", "memory (MiB)",
           "ns/particle", "per particle / T=first", "free");
    for (int k = 0; k < nt; k++) {
        tiling *c = &tl[k];
        size_t nfree = 0;
        for (size_t i = 0; i < c->n; i++)
            nfree += c->g[i] == -sp0->g0;
        double per[ROUNDS];
        for (int r = 0; r < ROUNDS; r++)
            per[r] = c->t[r] / (double)c->n * 1e9;
        printf("%4d %8zu %14.1f %14.1f %22.3f %8.3f\n", c->T, c->n,
               c->mib,
               median(per, ROUNDS), median(c->ratio, ROUNDS),
               (double)nfree / (double)c->n);
    }
    for (int k = 0; k < nt; k++) {
        bf_cells_free(&tl[k].cells);
        bf_support_free(tl[k].sup);
        free(tl[k].x);
        free(tl[k].y);
        free(tl[k].g);
    }
    bf_catalog_model(bf_catalog_builtin(), "greenspan72")->destroy(m);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return 0;
}
