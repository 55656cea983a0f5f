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
 * multirate option (film_every = 10, 100, 300).
 *
 * Last, film_every = auto against the single-rate run on 5 simulated s:
 * five rounds, each running the single-rate scene and then every variant
 * (auto at three tolerances, fixed K = 30 and 100), all in this process;
 * the speed-up is the median over the rounds of single-rate CPU time /
 * variant CPU time (the machine is shared).  The error is the largest
 * |x - x_ref| of the ball positions at the output rows (every 1e-3 s) over
 * the first 1 s, beside the tolerance's promise tol t^2/2 at t = 1 s, and
 * over the whole 5 s, where the scene's chaos (separations growing as
 * exp(4 t/s)) has amplified any difference to the size of the motion. */
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

/* the run's summary (bf_sim_summary) as text, malloc'd */
static char *summary_of(const bf_sim *sim)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    bf_sim_summary(sim, m);
    fclose(m);
    /* a copy: GCC takes a strstr into the stream's buffer for a pointer
     * into this frame (-Wdangling-pointer) */
    char *copy = strdup(text);
    free(text);
    return copy;
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
            char *line = summary_of(sim);
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

/* One run of T simulated s (the scene with `sets`): the ball positions
 * after every output interval (rows x nb, malloc'd), its CPU time and the
 * model's multirate line of the summary. */
typedef struct traj {
    double *x, cpu;
    size_t rows, nb;
    char mr[512];
} traj;

static void run_traj(const char *const *sets, double T, traj *tr)
{
    const char *root = getenv("BALLFILM_ROOT");
    char path[1024], buf[64];
    snprintf(path, sizeof path, "%s/runs/coupled_fig8.ini", root ? root : ".");
    bf_scene *sc;
    bf_err err = {0};
    bf_sim *sim;
    snprintf(buf, sizeof buf, "scene.t_end=%g", T);
    if (bf_scene_load(&sc, path, &err) ||
        bf_scene_set(sc, buf, "bench", &err))
        goto fail;
    for (const char *const *s = sets; s && *s; s++)
        if (bf_scene_set(sc, *s, "bench", &err))
            goto fail;
    if (bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ||
        bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err))
        goto fail;
    const long every = 100; /* the scene's output_every, 1e-3 s */
    const long rows = bf_sim_steps_total(sim) / every;
    size_t nb;
    bf_sim_get(sim, "balls/position", &nb);
    tr->x = malloc((size_t)rows * nb * sizeof(double));
    tr->rows = (size_t)rows;
    tr->nb = nb;
    double t0 = cpu_now();
    for (long r = 0; r < rows; r++) {
        if (bf_sim_steps(sim, every, &err))
            goto fail;
        memcpy(tr->x + (size_t)r * nb, bf_sim_get(sim, "balls/position", &nb),
               nb * sizeof(double));
    }
    tr->cpu = cpu_now() - t0;
    char *line = summary_of(sim);
    char *t = strstr(line, "multirate:");
    snprintf(tr->mr, sizeof tr->mr, "%s", t ? t : "");
    char *nl = strchr(tr->mr, '\n');
    if (nl)
        *nl = 0;
    free(line);
    bf_sim_free(sim);
    bf_scene_free(sc);
    return;
fail:
    fprintf(stderr, "%s\n", err.msg);
    exit(1);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* film_every = auto (and fixed K) against single rate on 5 s */
static void adaptive(void)
{
    enum { NV = 5, ROUNDS = 5 };
    const double T = 5;
    static const char *const name[NV] = {"auto, tol 1e-4", "auto, tol 1e-5",
                                         "auto, tol 1e-6", "K = 30",
                                         "K = 100"};
    static const double tol[NV] = {1e-4, 1e-5, 1e-6, 0, 0};
    static const char *const sets[NV][3] = {
        {"coupled.film_every=auto", "coupled.multirate_tol=1e-4", NULL},
        {"coupled.film_every=auto", "coupled.multirate_tol=1e-5", NULL},
        {"coupled.film_every=auto", "coupled.multirate_tol=1e-6", NULL},
        {"coupled.film_every=30", NULL, NULL},
        {"coupled.film_every=100", NULL, NULL}};
    double ratio[NV][ROUNDS], cref[ROUNDS];
    double e1[NV], e5[NV];
    char mr[NV][512];
    for (int r = 0; r < ROUNDS; r++) {
        traj ref;
        run_traj(NULL, T, &ref);
        cref[r] = ref.cpu;
        for (int v = 0; v < NV; v++) {
            traj a;
            run_traj(sets[v], T, &a);
            ratio[v][r] = ref.cpu / a.cpu;
            e1[v] = e5[v] = 0;
            for (size_t i = 0; i < a.rows; i++)
                for (size_t j = 0; j < a.nb; j++) {
                    double e = fabs(a.x[i * a.nb + j] - ref.x[i * a.nb + j]);
                    e5[v] = fmax(e5[v], e);
                    if (i < 1000) /* rows at 1e-3 .. 1 s */
                        e1[v] = fmax(e1[v], e);
                }
            snprintf(mr[v], sizeof mr[v], "%s", a.mr);
            free(a.x);
        }
        free(ref.x);
    }
    qsort(cref, ROUNDS, sizeof(double), cmp_double);
    printf("adaptive multirate, %g simulated s of the scene, %d rounds "
           "(single rate: median %.2f CPU s):\n",
           T, ROUNDS, cref[ROUNDS / 2]);
    printf("  %-15s %9s %13s %11s %11s %11s\n", "variant", "speed-up",
           "(min-max)", "err 0-1 s", "tol t^2/2", "err 0-5 s");
    for (int v = 0; v < NV; v++) {
        qsort(ratio[v], ROUNDS, sizeof(double), cmp_double);
        char promise[32] = "-";
        if (tol[v] > 0)
            snprintf(promise, sizeof promise, "%.2g cm", tol[v] / 2);
        printf("  %-15s %8.1fx %5.1f-%-5.1f %8.2g cm %11s %8.2g cm\n",
               name[v], ratio[v][ROUNDS / 2], ratio[v][0],
               ratio[v][ROUNDS - 1], e1[v], promise, e5[v]);
    }
    for (int v = 0; v < 3; v++)
        printf("  %s: %s\n", name[v], mr[v]);
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
    adaptive();
    return 0;
}
