/* bench_greenspan72.c: speed of the 1972 two-fluid model (support-set
 * gravity, repulsion, walls).
 *
 * 1. Example 2 (runs/greenspan72_ex2.ini, 256 particles, 30000 steps), the
 *    run the paper reports as 72 minutes on a UNIVAC 1108: CPU time of the
 *    whole run without output, minimum of 3.
 * 2. Scaling: Example 2's local physics (d = 5, dx = 6.25, cutoff 10,
 *    V = 500, dt = 0.01, omega = 0.9) on an n x n grid in a box of side
 *    6.25 n, the top quarter heavy, for N = n^2 = 4096 ... 262144.  After
 *    100 warm-up steps (the layers break up), the time of 20 steps, minimum
 *    of 3; printed as particle-steps per second and as the cost per
 *    N log2 N relative to N = 4096 (flat or falling: no worse than N log N).
 * 3. The support-set gravity alone on the same states: fast against the
 *    cell-list method (naive is O(N^2) and only timed at 4096).
 * 4. At N = 65536 and 262144: the step with the fast method's free-fall
 *    skipping and cut lists against the exhaustive path (every particle
 *    asks the sweep, the cut squares from the cell list's window; the same
 *    bits, tested), 5 alternating pairs of 10 steps, the median ratio.
 *    (Today against main before issue 21 item 5, a752c43, both built and
 *    measured in one run: bench/g72_vs_a752c43.sh.)
 *
 * Times are CPU times of the process (one thread) except where two
 * threads run, where they are wall times: on a shared machine CPU time
 * moves less.  Ratios are measured within one run; other processes on
 * the machine make absolute numbers noisy, hence the minimum of repeats.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "driver/g72_scene.h"
#include "models/greenspan.h"
#include "ballfilm/scene.h"
#include "ballfilm/model.h"
#include "ballfilm/run.h"

/* Seconds of CPU time of the process, or wall time (two threads). */
static int use_wall;

static double now(void)
{
    struct timespec ts;
    clock_gettime(use_wall ? CLOCK_MONOTONIC : CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static bf_scene *load(const char *path, const char *text, bf_err *err)
{
    bf_scene *sc = NULL;
    bf_status st = text ? bf_scene_load_string(&sc, "bench.ini", text, err)
                        : bf_scene_load(&sc, path, err);
    if (!st)
        st = bf_catalog_resolve(bf_catalog_builtin(), sc, err);
    if (st) {
        fprintf(stderr, "bench: %s\n", err->msg);
        exit(1);
    }
    return sc;
}

/* A model driven step by step, without the time loop's output. */
typedef struct run {
    const bf_model_type *mt;
    bf_setup *setup;
    void *m;
    long n;
    double dt;
} run;

static run start(const bf_scene *sc)
{
    bf_err err = {0};
    run r = {bf_catalog_model(bf_catalog_builtin(), "greenspan72"), NULL,
             NULL, 0, bf_scene_real(sc, "scene", "dt")};
    if (bf_model_from_scene(bf_catalog_builtin(), sc, &r.setup, &r.m, &err)) {
        fprintf(stderr, "bench: %s\n", err.msg);
        exit(1);
    }
    return r;
}

/* `steps` more steps; the wall time. */
static double advance(run *r, long steps)
{
    bf_err err = {0};
    double t0 = now();
    for (long k = 0; k < steps; k++, r->n++)
        if (r->mt->step(r->m, r->n, (double)r->n * r->dt, r->dt, &err)) {
            fprintf(stderr, "bench: %s\n", err.msg);
            exit(1);
        }
    return now() - t0;
}

/* Seconds per step: the minimum over 3 runs of 20 steps. */
static double per_step(run *r)
{
    double per = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        double t = advance(r, 20) / 20.0;
        if (t < per)
            per = t;
    }
    return per;
}

/* One support-set gravity evaluation with `method` on the model's state
 * (a fresh cell list of side 10, the cutoff, as the model uses). */
static double time_support(run *r, bf_support_method method)
{
    bf_err err = {0};
    bf_particles *p = bf_greenspan72_particles(r->m);
    bf_support *s = bf_greenspan72_support(r->m);
    const bf_support_params *sp = bf_support_params_of(s);
    bf_cells c;
    double *g = malloc(p->n * sizeof *g);
    uint8_t *kind = malloc(p->n);
    if (!g || !kind ||
        bf_cells_init(&c, sp->box.ax, sp->box.ay, sp->box.bx - sp->box.ax,
                      sp->box.by - sp->box.ay, 10.0, p->n, &err)) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    double t0 = now();
    bf_cells_build(&c, p->x, p->y, NULL, p->n);
    bf_support_eval_with(s, method, p->x, p->y, p->n, &c, g, kind);
    double t = now() - t0;
    bf_cells_free(&c);
    free(g);
    free(kind);
    return t;
}

static int cmp_double(const void *a, const void *b)
{
    double u = *(const double *)a, v = *(const double *)b;
    return u < v ? -1 : u > v;
}

/* Rank of x in the sorted array s[0..n) (x is in it). */
static double rank_of(const double *s, size_t n, double x)
{
    const double *p = bsearch(&x, s, n, sizeof *s, cmp_double);
    return (double)(p - s);
}

/* How far the particles move in one step: the mean |dx| (cm), the
 * fraction that changes its cell of side h (the cell list's), and the
 * mean change of a particle's place in the x order (what a sort reused
 * from the step before would have to repair). */
static void motion(run *r, double h)
{
    bf_particles *p = bf_greenspan72_particles(r->m);
    const size_t n = p->n;
    double *x0 = malloc(n * sizeof *x0), *y0 = malloc(n * sizeof *y0);
    double *s0 = malloc(n * sizeof *s0), *s1 = malloc(n * sizeof *s1);
    if (!x0 || !y0 || !s0 || !s1) {
        fprintf(stderr, "bench: out of memory\n");
        exit(1);
    }
    memcpy(x0, p->x, n * sizeof *x0);
    memcpy(y0, p->y, n * sizeof *y0);
    memcpy(s0, p->x, n * sizeof *s0);
    advance(r, 1);
    memcpy(s1, p->x, n * sizeof *s1);
    qsort(s0, n, sizeof *s0, cmp_double);
    qsort(s1, n, sizeof *s1, cmp_double);
    double dx = 0, moved = 0, dr = 0;
    for (size_t i = 0; i < n; i++) {
        dx += fabs(p->x[i] - x0[i]);
        moved += floor(p->x[i] / h) != floor(x0[i] / h) ||
                 floor(p->y[i] / h) != floor(y0[i] / h);
        dr += fabs(rank_of(s1, n, p->x[i]) - rank_of(s0, n, x0[i]));
    }
    printf("    one step: mean |dx| %.2f cm, %.0f %% change their cell of "
           "%g cm, mean shift in the x order %.0f places\n",
           dx / (double)n, 100.0 * moved / (double)n, h, dr / (double)n);
    free(x0);
    free(y0);
    free(s0);
    free(s1);
}

static const char *scaled_scene(int n, int threads)
{
    static char buf[2048];
    return g72_scene_text(buf, sizeof buf, n, threads);
}

int main(void)
{
    bf_err err = {0};
    /* ---- 1. Example 2 */
    const char *root = getenv("BALLFILM_ROOT");
    char path[1024];
    snprintf(path, sizeof path, "%s/runs/greenspan72_ex2.ini", root ? root : ".");
    double best = INFINITY;
    for (int rep = 0; rep < 3; rep++) {
        bf_scene *sc = load(path, NULL, &err);
        run r = start(sc);
        long steps = lround(bf_scene_real(sc, "scene", "t_end") / r.dt);
        double t = advance(&r, steps);
        if (t < best)
            best = t;
        r.mt->destroy(r.m);
        bf_setup_free(r.setup);
        bf_scene_free(sc);
    }
    printf("Example 2 (N = 256, 30000 steps, no output): %.3f s  "
           "(%.3g particle-steps/s; the paper: 72 min on a UNIVAC 1108)\n",
           best, 256.0 * 30000.0 / best);

    /* ---- 2. scaling */
    printf("\nOne thread, support method fast (the O(N log N) sweep):\n");
    printf("%8s %12s %14s %16s %12s %12s\n", "N", "s/step", "particle-st/s",
           "cost/(N log2 N)", "sup fast [s]", "sup cell [s]");
    double ref = 0;
    const int sizes[] = {64, 128, 256, 512};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int n = sizes[k];
        double N = (double)n * n;
        bf_scene *sc = load(NULL, scaled_scene(n, 1), &err);
        run r = start(sc);
        advance(&r, 100);
        double per = per_step(&r);
        double c = per / (N * log2(N));
        if (k == 0)
            ref = c;
        /* the support-set gravity alone, fast vs cell, on this state */
        double tf = INFINITY, tc = INFINITY;
        for (int rep = 0; rep < 3; rep++) {
            double a = time_support(&r, BF_SUPPORT_FAST);
            double b = time_support(&r, BF_SUPPORT_CELL);
            tf = a < tf ? a : tf;
            tc = b < tc ? b : tc;
        }
        printf("%8.0f %12.4g %14.3g %16.3f %12.4g %12.4g\n", N, per, N / per,
               c / ref, tf, tc);
        fflush(stdout);
        r.mt->destroy(r.m);
        bf_setup_free(r.setup);
        bf_scene_free(sc);
    }
    printf("(goal: N = 65536 at >= 3e6 particle-steps/s; cost/(N log2 N) "
           "not growing)\n");

    /* ---- 4. the free-fall skipping and the cut lists */
    printf("\nFree-fall skipping and cut lists against the exhaustive path "
           "(same bits; today against a752c43: bench/g72_vs_a752c43.sh):\n");
    printf("%8s %14s %16s\n", "N", "particle-st/s", "exhaustive/skip");
    const int big[] = {256, 512};
    for (size_t k = 0; k < sizeof big / sizeof big[0]; k++) {
        double N = (double)big[k] * big[k], rat[5];
        bf_scene *sc = load(NULL, scaled_scene(big[k], 1), &err);
        run r = start(sc);
        bf_support *s = bf_greenspan72_support(r.m);
        advance(&r, 100);
        double per = per_step(&r);
        for (int rep = 0; rep < 5; rep++) {
            bf_support_set_exhaustive(s, 1);
            double te = advance(&r, 10);
            bf_support_set_exhaustive(s, 0);
            rat[rep] = te / advance(&r, 10);
        }
        for (int a = 1; a < 5; a++) /* median of 5 */
            for (int b = a; b > 0 && rat[b - 1] > rat[b]; b--) {
                double t = rat[b];
                rat[b] = rat[b - 1];
                rat[b - 1] = t;
            }
        printf("%8.0f %14.3g %16.3f\n", N, N / per, rat[2]);
        motion(&r, 10.0);
        fflush(stdout);
        r.mt->destroy(r.m);
        bf_setup_free(r.setup);
        bf_scene_free(sc);
    }

    /* ---- 3. two threads at N = 65536 (pays only if the other core is
     * free; the results are the same bits, see tests) */
    {
        use_wall = 1;
        bf_scene *sc = load(NULL, scaled_scene(256, 2), &err);
        run r = start(sc);
        advance(&r, 100);
        double per = per_step(&r);
        printf("\nN = 65536 with 2 threads: %.4g s/step, %.3g particle-steps/s"
               "\n", per, 65536.0 / per);
        r.mt->destroy(r.m);
        bf_setup_free(r.setup);
        bf_scene_free(sc);
    }
    return 0;
}
