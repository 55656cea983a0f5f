/* bench_balls.c: cost per step of the ball system against a hand-fused loop
 * for the same problem (two balls, gravity + floor + contact, Yasuda
 * sec. 2.5, lower ball 0.8 g), for MV2M and Verlet.
 *
 * Four ways to take the same steps:
 *   run       bf_sim_run, the core time loop of every run (src/core/sim.c)
 *             through the model table of the "balls" model: the generic
 *             interface a run goes through.  No output file, energy checks
 *             off ([scene] energy_every = 0, output_every beyond the end),
 *             so that both sides do the same work: the loop's own
 *             bookkeeping (stop conditions, event schedule) is timed.
 *   step      bf_ballsys_step called once per step (what a run with a
 *             per-step analysis, return map or Lyapunov estimate, uses)
 *   generic   bf_integrator_step through the integrator descriptor and the
 *             bf_ode force callback (any integrator, any model)
 *   fused     a hand-written loop for exactly this problem: two balls, the
 *             three forces written out, parameters as constants, state in
 *             local variables (registers).  An earlier version of this
 *             bench advanced the state through pointers into main's
 *             arrays; the same MV2M loop then took 29 instead of 17 ns per
 *             step, which made the library look better than it was.
 * What the library sides do that the fused loop does not: the library
 * checks after every step that positions and velocities are finite (a
 * blow-up stops the run naming the ball) and counts steps and force
 * evaluations; "run" also does the core loop's bookkeeping, "generic" also
 * checks the force cache.  All four do the same floating-point operations
 * in the same order, so they must end in the same state bit for bit
 * (checked and printed).
 *
 * Timing on a shared machine: the variants advance in alternating chunks
 * of 100000 steps over the same stretch of trajectory (same contacts, same
 * branches), timed with the thread's CPU clock, 20 rounds.  Printed: the
 * minimum time per step of each variant over the rounds, and for each
 * library variant the median over the rounds of the per-round ratio to
 * fused and, in brackets, the ratio of the minima.  The goal (issue 3) is
 * run/fused <= 1.3.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "models/ballsys.h"
#include "ballfilm/run.h"
#include "contact/hertz.h"
#include "ballfilm/scene.h"
#include "ballfilm/sim.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const double G = 980, K = 1e7, R = 0.1, M1 = 0.8, M2 = 1.0;

/* The same arithmetic as the effect kernels (effect_kernels.h, contact.h)
 * in the same order, written out for two balls with the parameters as
 * constants, so that the result must agree with the library bit for bit. */
static inline __attribute__((always_inline)) void fused_acc(const double *x,
                                                            double *a)
{
    const double im1 = 1.0 / M1, im2 = 1.0 / M2;
    double a1 = 0.0, a2 = 0.0;
    a1 -= G;
    a2 -= G;
    if (x[0] < R)
        a1 += bf_hertz_floor_force(K, R, x[0]) * im1;
    if (x[1] < R)
        a2 += bf_hertz_floor_force(K, R, x[1]) * im2;
    double d = x[1] - x[0];
    if (d < R + R) {
        double f = bf_hertz_pair_force(K, R, R, d);
        a1 -= f * im1;
        a2 += f * im2;
    }
    a[0] = a1;
    a[1] = a2;
}

/* The fused loops copy the state into locals (kept in registers) and back:
 * the best a hand-written loop can do.  noinline: timed as what they are,
 * not as part of main. */
__attribute__((noinline)) static void fused_mv2m(double *xs, double *vs,
                                                 double dt, long n)
{
    const double dt2 = dt * dt, hdt = 0.5 * dt, hdt2 = 0.5 * dt2,
                 edt2 = 0.125 * dt2, dt6 = dt / 6.0, dt26 = dt2 / 6.0;
    double x[2] = {xs[0], xs[1]}, v[2] = {vs[0], vs[1]};
    double a0[2], aV[2], aT[2], xV[2], xT[2];
    for (long s = 0; s < n; s++) {
        fused_acc(x, a0);
        for (int i = 0; i < 2; i++) {
            xV[i] = x[i] + (dt * v[i] + hdt2 * a0[i]);
            xT[i] = x[i] + (hdt * v[i] + edt2 * a0[i]);
        }
        fused_acc(xV, aV);
        fused_acc(xT, aT);
        for (int i = 0; i < 2; i++) {
            double dv = dt6 * (a0[i] + aV[i] + 4.0 * aT[i]);
            double dx = dt * v[i] + dt26 * (2.0 * a0[i] + aV[i]);
            x[i] += dx;
            v[i] += dv;
        }
    }
    memcpy(xs, x, sizeof x);
    memcpy(vs, v, sizeof v);
}

/* as carries the force at x between chunks (first same as last) */
__attribute__((noinline)) static void fused_verlet(double *xs, double *vs,
                                                   double *as, double dt,
                                                   long n)
{
    double x[2] = {xs[0], xs[1]}, v[2] = {vs[0], vs[1]};
    double a0[2] = {as[0], as[1]}, a1[2];
    const double h2 = 0.5 * dt * dt;
    for (long s = 0; s < n; s++) {
        for (int i = 0; i < 2; i++)
            x[i] += dt * v[i] + h2 * a0[i];
        fused_acc(x, a1);
        for (int i = 0; i < 2; i++) {
            v[i] += 0.5 * dt * (a1[i] + a0[i]);
            a0[i] = a1[i];
        }
    }
    memcpy(xs, x, sizeof x);
    memcpy(vs, v, sizeof v);
    memcpy(as, a0, sizeof a0);
}

/* energy checks off and no output row before the end (t_end = 1000 s is
 * far beyond the 20 * 10^5 steps taken) */
static const char *scene_text =
    "[scene]\nintegrator = %s\neffects = gravity floor contact\n"
    "dt = 1e-4\nt_end = 1000\nenergy_every = 0\noutput_every = 100000000\n"
    "[ball.1]\nposition = 0.2\nmass = 0.8\n[ball.2]\nposition = 0.5\n";

static void load(const char *method, bf_scene **sc)
{
    char text[512];
    snprintf(text, sizeof text, scene_text, method);
    bf_err err = {0};
    if (bf_scene_load_string(sc, "bench", text, &err) ||
        bf_catalog_resolve(bf_catalog_builtin(), *sc, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
}

static bf_ballsys *make(const char *method, bf_scene **sc)
{
    load(method, sc);
    bf_err err = {0};
    bf_ballsys *sys;
    if (bf_ballsys_from_scene(&sys, bf_catalog_builtin(), *sc, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    return sys;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int same_state(const bf_ballsys *s, const double *x, const double *v)
{
    return !memcmp(s->b.x, x, 2 * sizeof *x) &&
           !memcmp(s->b.v, v, 2 * sizeof *v);
}

enum { RUN, STEP, GENERIC, FUSED, NVAR };

int main(void)
{
    const long chunk = 100000;
    const int rounds = 20;
    const double dt = 1e-4;
    const char *methods[] = {"mv2m", "verlet"};
    const char *names[NVAR] = {"run", "step", "generic", "fused"};
    printf("two falling balls (gravity, floor, contact), dt = 1e-4 s, %d "
           "rounds of %ld steps per variant, thread CPU time\n"
           "run: core loop (bf_sim_run, no output, no energy checks); step: "
           "bf_ballsys_step per step;\ngeneric: integrator descriptor and "
           "force callback; fused: hand-written loop (no finiteness check,\n"
           "no counters); ratio = median over rounds of variant/fused "
           "(in brackets: min/min)\n",
           rounds, chunk);
    printf("%-7s %-8s %9s %16s\n", "method", "variant", "ns/step",
           "ratio to fused");
    for (int m = 0; m < 2; m++) {
        bf_scene *sr, *sa, *sb;
        bf_err err = {0};
        load(methods[m], &sr);
        bf_sim_opts opts = {0};
        bf_sim *sim;
        if (bf_sim_from_scene(&sim, bf_catalog_builtin(), sr, &opts, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return 1;
        }
        bf_ballsys *r = bf_balls_model_system(bf_sim_model(sim));
        bf_ballsys *a = make(methods[m], &sa), *b = make(methods[m], &sb);
        double x[2] = {0.2, 0.5}, v[2] = {0, 0}, af[2];
        fused_acc(x, af);
        double best[NVAR], ratio[NVAR][64];
        for (int k = 0; k < NVAR; k++)
            best[k] = 1e30;
        long s0 = 0;
        for (int round = 0; round < rounds; round++) {
            double t[NVAR];
            double t0 = now();
            /* the next `chunk` steps of the run (the loop of bf_sim_run;
             * its --stop-after limit counts the steps of a whole process,
             * so it would stop every round after the first at once) */
            bf_status st = bf_sim_steps(sim, chunk, &err);
            t[RUN] = now() - t0;
            if (st != BF_OK || bf_sim_steps_done(sim) != s0 + chunk) {
                fprintf(stderr, "run: %s\n", err.msg);
                return 1;
            }
            t0 = now();
            for (long s = s0; s < s0 + chunk; s++)
                if (bf_ballsys_step(a, (double)s * dt, dt, &err)) {
                    fprintf(stderr, "%s\n", err.msg);
                    return 1;
                }
            t[STEP] = now() - t0;
            t0 = now();
            for (long s = s0; s < s0 + chunk; s++)
                if (bf_integrator_step(b->it, &b->ode, (double)s * dt, dt,
                                       b->b.x, b->b.v, &err)) {
                    fprintf(stderr, "%s\n", err.msg);
                    return 1;
                }
            t[GENERIC] = now() - t0;
            t0 = now();
            if (m == 0)
                fused_mv2m(x, v, dt, chunk);
            else
                fused_verlet(x, v, af, dt, chunk);
            t[FUSED] = now() - t0;
            for (int k = 0; k < NVAR; k++) {
                if (t[k] < best[k])
                    best[k] = t[k];
                ratio[k][round] = t[k] / t[FUSED];
            }
            s0 += chunk;
        }
        int same = same_state(r, x, v) && same_state(a, x, v) &&
                   same_state(b, x, v);
        for (int k = 0; k < NVAR; k++) {
            qsort(ratio[k], (size_t)rounds, sizeof **ratio, cmp);
            char rs[40] = "";
            if (k != FUSED)
                snprintf(rs, sizeof rs, "%.2f (%.2f)", ratio[k][rounds / 2],
                         best[k] / best[FUSED]);
            printf("%-7s %-8s %9.2f %16s%s\n", k ? "" : methods[m], names[k],
                   1e9 * best[k] / (double)chunk, rs,
                   k == RUN ? "   goal <= 1.3" : "");
        }
        printf("%-7s final states of the four: %s\n", "",
               same ? "bit-identical" : "DIFFER");
        bf_sim_free(sim);
        bf_ballsys_free(a);
        bf_ballsys_free(b);
        bf_scene_free(sr);
        bf_scene_free(sa);
        bf_scene_free(sb);
        if (!same)
            return 1;
    }
    return 0;
}
