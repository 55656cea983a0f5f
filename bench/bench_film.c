/* bench_film.c: film cell-updates per second of the invariant scheme
 * (bf_film_step_invariant) for 500 and 5000 cells, for each reading of the
 * mu term, on the perturbed-kink state of Yasuda sec. 3.4 (dx = 0.1 cm,
 * dt = 1e-3 s).  Timing: this thread's CPU time, minimum of 5 repeats
 * (other jobs share the machine); the steps are the same in every repeat
 * so each repeat continues the same physics.  The step is cloned for
 * AVX-512, AVX2 and SSE2 (GCC target_clones); the line "vector unit" says
 * which one this CPU runs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "ballfilm/film.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double bench(long cells, bf_film_mu_taylor v)
{
    bf_film_params p = {.length = 0.1 * (double)cells, .dx = 0.1,
                        .rho_d = 1, .rho_c = 1, .nu = 0.01, .g = 980,
                        .a = 1, .b = 1, .gamma = 1, .mu_taylor = v,
                        .limit_positive = 1, .vanish = 1e-8};
    bf_film *f;
    bf_err err = {0};
    if (bf_film_create(&f, &p, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    size_t n = bf_film_nodes(f);
    const double *x = bf_film_x(f);
    double *h = malloc(n * sizeof *h), *psi = malloc(n * sizeof *psi),
           *u = calloc(n, sizeof *u);
    for (size_t i = 0; i < n; i++) {
        h[i] = 1.0;
        /* the kink with a 1e-4 wiggle, so that nothing is exactly at rest */
        psi[i] = tanh(x[i] / sqrt(2.0)) * (1.0 - 1e-4 * (1.0 + sin(7.0 * x[i])));
    }
    if (bf_film_set_state(f, h, psi, u, u, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    long steps = 20000000 / cells;
    double best = INFINITY;
    for (int r = 0; r < 5; r++) {
        double t0 = cpu_now();
        for (long s = 0; s < steps; s++)
            if (bf_film_step_invariant(f, 1e-3, NULL, &err)) {
                fprintf(stderr, "%s\n", err.msg);
                exit(1);
            }
        best = fmin(best, cpu_now() - t0);
    }
    free(h);
    free(psi);
    free(u);
    bf_film_free(f);
    return (double)steps * (double)n / best;
}

int main(void)
{
    __builtin_cpu_init();
    printf("vector unit: %s\n", __builtin_cpu_supports("avx512f") ? "AVX-512"
                                : __builtin_cpu_supports("avx2") ? "AVX2"
                                                                  : "SSE2");
    static const char *names[] = {"midpoint (default)", "um (printed)", "uk"};
    const long cells[2] = {500, 5000};
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 2; k++) {
            double r = bench(cells[k], (bf_film_mu_taylor)v);
            printf("film %-19s %5ld cells: %.3g cell-updates/s (%.2f ns per "
                   "cell, %.2f us per step)\n",
                   names[v], cells[k], r, 1e9 / r,
                   1e6 * (double)(cells[k] + 1) / r);
        }
    return 0;
}
