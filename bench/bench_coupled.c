/* bench_coupled.c: cost per simulated second of the coupled Fig. 8 scene
 * (runs/coupled_fig8.ini: 4 balls, 501-node film, dt = 1e-5 s, MV2M).
 *
 * The cost is this thread's CPU time, minimum of 3 repeats of 0.5
 * simulated seconds (other jobs share the machine).  The full run is 50
 * simulated seconds: multiply.
 *
 * The split is measured in a separate run with [coupled] timing = true:
 * the model reads the (wall) clock around each part of every step --
 *   film      the film step (3.15-3.16),
 *   balls     the ball step: integrator, contact and the coupling force
 *             -M dF/dr (its evaluations, O(1) each),
 *   coupling  mu_cpl for the film and what the coupling prepares for each
 *             film level (g, the moments at the balls' cells, their
 *             Taylor anchors),
 * and the rest of that run's wall time is "other" (events, output rows,
 * the core loop).  The model reads the clock five times a step; each read
 * costs ~60 ns on this VM (calibrated here, `clock`), which is 1-2 reads
 * inside each part's interval: they are taken out of the parts (film and
 * balls one read a step, coupling two, other one).  The parts are printed
 * as fractions of the timed run without the clock and as those fractions
 * of the untimed cost above.  Also: the linear quadrature, and the
 * multirate option (film_every = 10, 100, 300). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ballfilm/scene.h"
#include "ballfilm/sim.h"
#include "ballfilm/run.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* the cost of one clock read (s), minimum over batches */
static double clock_cost(void)
{
    double best = INFINITY, sink = 0;
    for (int r = 0; r < 50; r++) {
        double t0 = wall_now();
        for (int k = 0; k < 1000; k++)
            sink += wall_now();
        best = fmin(best, (wall_now() - t0) / 1001.0);
    }
    return sink == 0 ? best : best;
}

/* CPU seconds per simulated second; with timing (and the untimed cost
 * `base`), print the split */
static double run(const char *const *sets, int timing, double T, double base)
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
        if (bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ||
            bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
        double t0 = cpu_now(), w0 = wall_now();
        if (bf_sim_run(sim, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
        double wall = wall_now() - w0;
        best = fmin(best, (cpu_now() - t0) / T);
        if (timing) {
            /* the model's report has the split line */
            char *line = NULL;
            size_t len = 0;
            FILE *m = open_memstream(&line, &len);
            bf_sim_summary(sim, m);
            fclose(m);
            char *t = strstr(line, "time: balls");
            double b, f, c;
            if (!t || sscanf(t, "time: balls %lf s, film %lf s, coupling "
                                "(mu_cpl, refresh) %lf s",
                             &b, &f, &c) != 3) {
                fprintf(stderr, "no timing line in the summary\n");
                exit(1);
            }
            /* the clock reads: one a step in film, balls and other, two
             * in coupling */
            const double steps = T / bf_scene_real(sc, "scene", "dt");
            const double ck = clock_cost(), r1 = ck * steps;
            double part[4] = {f - r1, b - r1, c - 2 * r1, 0};
            const double net = wall - 5 * r1;
            part[3] = net - (part[0] + part[1] + part[2]);
            printf("  split (one timed run, %.3f CPU s per simulated second; "
                   "its clock reads, %.0f ns each, taken out):\n",
                   best, 1e9 * ck);
            const char *nm[4] = {"film", "balls", "coupling", "other"};
            for (int k = 0; k < 4; k++)
                printf("    %-8s %5.1f%%  %.3f CPU s per simulated second "
                       "of the untimed cost\n",
                       nm[k], 100.0 * part[k] / net, base * part[k] / net);
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
    double c = run(NULL, 0, T, 0);
    printf("single rate, spline: %.3f CPU s per simulated second (full 50 s "
           "run: %.1f s)\n", c, 50 * c);
    run(NULL, 1, T, c);
    const char *lin[] = {"coupling.quadrature=linear", NULL};
    c = run(lin, 0, T, 0);
    printf("single rate, linear quadrature: %.3f CPU s per simulated second "
           "(50 s: %.1f s)\n", c, 50 * c);
    const char *ks[] = {"10", "100", "300"};
    for (int k = 0; k < 3; k++) {
        char set[64];
        snprintf(set, sizeof set, "coupled.film_every=%s", ks[k]);
        const char *mr[] = {set, NULL};
        c = run(mr, 0, T, 0);
        printf("multirate film_every = %-3s: %.3f CPU s per simulated second "
               "(50 s: %.1f s)\n", ks[k], c, 50 * c);
    }
    return 0;
}
