/* bench_coupled.c: cost per simulated second of the coupled Fig. 8 scene
 * (runs/coupled_fig8.ini: 4 balls, 501-node film, dt = 1e-5 s, MV2M), and
 * its split between the film step, the ball step and the coupling (mu_cpl
 * and the per-film-step tables), measured in one run with [coupled]
 * timing = true (wall clock around each part).  The total is this thread's
 * CPU time, minimum of 3 repeats of 0.5 simulated seconds (other jobs share
 * the machine).  Also: the linear quadrature, and the multirate option
 * (film_every = 10, 100, 300).  The full run is 50 simulated seconds:
 * multiply. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ballfilm/registry.h"
#include "ballfilm/scene.h"
#include "ballfilm/sim.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds per simulated second; with timing, print the split */
static double run(const char *const *sets, int timing, double T)
{
    const char *root = getenv("BALLFILM_ROOT");
    char path[1024];
    snprintf(path, sizeof path, "%s/runs/coupled_fig8.ini", root ? root : ".");
    double best = INFINITY;
    for (int r = 0; r < (timing ? 1 : 3); r++) {
        bf_scene *sc;
        bf_err err = {0};
        if (bf_scene_load(&sc, path, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
        char buf[64];
        snprintf(buf, sizeof buf, "scene.t_end=%g", T);
        bf_scene_set(sc, buf, "bench", &err);
        if (timing)
            bf_scene_set(sc, "coupled.timing=true", "bench", &err);
        for (const char *const *s = sets; s && *s; s++)
            if (bf_scene_set(sc, *s, "bench", &err)) {
                fprintf(stderr, "%s\n", err.msg);
                exit(1);
            }
        bf_sim *sim;
        if (bf_registry_resolve(sc, &err) ||
            bf_sim_create(&sim, sc, NULL, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
        double t0 = cpu_now();
        if (bf_sim_run(sim, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
        best = fmin(best, (cpu_now() - t0) / T);
        if (timing) {
            /* the model's report has the split line */
            char *line = NULL;
            size_t len = 0;
            FILE *m = open_memstream(&line, &len);
            bf_sim_summary(sim, m);
            fclose(m);
            char *t = strstr(line, "time: balls");
            if (t) {
                double b, f, c;
                if (sscanf(t, "time: balls %lf s, film %lf s, coupling "
                              "(mu_cpl, refresh) %lf s", &b, &f, &c) == 3)
                    printf("  split per simulated second: film %.3f s, balls "
                           "%.3f s, coupling %.3f s (wall clock, one run)\n",
                           f / T, b / T, c / T);
            }
            free(line);
        }
        bf_sim_free(sim);
        bf_scene_free(sc);
    }
    return best;
}

int main(void)
{
    const double T = 0.5;
    printf("coupled Fig. 8 scene (runs/coupled_fig8.ini), %g simulated s per "
           "repeat\n", T);
    double c = run(NULL, 0, T);
    printf("single rate, spline: %.3f CPU s per simulated second (full 50 s "
           "run: %.1f s)\n", c, 50 * c);
    run(NULL, 1, T);
    const char *lin[] = {"coupling.quadrature=linear", NULL};
    c = run(lin, 0, T);
    printf("single rate, linear quadrature: %.3f CPU s per simulated second "
           "(50 s: %.1f s)\n", c, 50 * c);
    const char *ks[] = {"10", "100", "300"};
    for (int k = 0; k < 3; k++) {
        char set[64];
        snprintf(set, sizeof set, "coupled.film_every=%s", ks[k]);
        const char *mr[] = {set, NULL};
        c = run(mr, 0, T);
        printf("multirate film_every = %-3s: %.3f CPU s per simulated second "
               "(50 s: %.1f s)\n", ks[k], c, 50 * c);
    }
    return 0;
}
