/* bench_balls.c: cost per step of the ball system against a hand-fused loop
 * for the same problem (two balls, gravity + floor + contact, Yasuda
 * sec. 2.5, lower ball 0.8 g), for MV2M and Verlet.
 *
 * Three ways to take the same steps:
 *   ballsys   bf_ballsys_step, what every run uses (for Verlet and MV2M the
 *             specialised step of ballsys.c: the integrator kernel with
 *             the effect kernels inlined)
 *   generic   bf_integrator_step through the integrator descriptor and the
 *             bf_ode callback (any integrator, any model)
 *   fused     a hand-written loop for exactly this problem: two balls, the
 *             three forces written out, parameters as constants
 * All three do the same floating-point operations in the same order, so
 * they must end in the same state bit for bit (checked and printed).
 *
 * Timing on a shared machine: the variants advance in alternating chunks
 * of 100000 steps over the same stretch of trajectory (same contacts,
 * same branches), timed with the thread's CPU clock, 20 rounds; printed
 * are the minimum time per step of each variant over the rounds and the
 * median over the rounds of the per-round ratio ballsys/fused (goal
 * <= 1.3).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ballfilm/ballsys.h"
#include "ballfilm/contact.h"
#include "ballfilm/registry.h"
#include "ballfilm/scene.h"

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
static inline void fused_acc(const double *x, double *a)
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

static void fused_mv2m(double *x, double *v, double dt, long n)
{
    const double dt2 = dt * dt, hdt = 0.5 * dt, hdt2 = 0.5 * dt2,
                 edt2 = 0.125 * dt2, dt6 = dt / 6.0, dt26 = dt2 / 6.0;
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
}

/* a0 carries the force at x between chunks (first same as last) */
static void fused_verlet(double *x, double *v, double *a0, double dt, long n)
{
    double a1[2];
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
}

static const char *scene_text =
    "[scene]\nintegrator = %s\neffects = gravity floor contact\n"
    "dt = 1e-4\nt_end = 1\n"
    "[ball.1]\nposition = 0.2\nmass = 0.8\n[ball.2]\nposition = 0.5\n";

static bf_ballsys *make(const char *method, bf_scene **sc)
{
    char text[512];
    snprintf(text, sizeof text, scene_text, method);
    bf_err err = {0};
    bf_ballsys *sys;
    bf_effect_env env = {0};
    if (bf_scene_load_string(sc, "bench", text, &err) ||
        bf_registry_resolve(*sc, &err) ||
        bf_ballsys_create(&sys, *sc, &env, &err)) {
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

int main(void)
{
    const long chunk = 100000;
    const int rounds = 20;
    const double dt = 1e-4;
    const char *methods[] = {"mv2m", "verlet"};
    printf("two falling balls (gravity, floor, contact), dt = 1e-4 s, %d "
           "rounds of %ld steps per variant\n",
           rounds, chunk);
    printf("%-7s %9s %9s %9s  %16s %16s  %s\n", "method", "ballsys", "generic",
           "fused", "ballsys/fused", "generic/fused", "final states");
    printf("%-7s %9s %9s %9s  %16s %16s\n", "", "ns/step", "ns/step",
           "ns/step", "median (min/min)", "median (min/min)");
    for (int m = 0; m < 2; m++) {
        bf_scene *sa, *sb;
        bf_ballsys *a = make(methods[m], &sa), *b = make(methods[m], &sb);
        bf_err err = {0};
        double x[2] = {0.2, 0.5}, v[2] = {0, 0}, af[2];
        fused_acc(x, af);
        double best[3] = {1e30, 1e30, 1e30}, ra[64], rb[64];
        long s0 = 0;
        for (int r = 0; r < rounds; r++) {
            double t[3];
            double t0 = now();
            for (long s = s0; s < s0 + chunk; s++)
                if (bf_ballsys_step(a, s * dt, dt, &err)) {
                    fprintf(stderr, "%s\n", err.msg);
                    return 1;
                }
            t[0] = now() - t0;
            t0 = now();
            for (long s = s0; s < s0 + chunk; s++)
                if (bf_integrator_step(b->it, &b->ode, s * dt, dt, b->b.x,
                                       b->b.v, &err)) {
                    fprintf(stderr, "%s\n", err.msg);
                    return 1;
                }
            t[1] = now() - t0;
            t0 = now();
            if (m == 0)
                fused_mv2m(x, v, dt, chunk);
            else
                fused_verlet(x, v, af, dt, chunk);
            t[2] = now() - t0;
            for (int k = 0; k < 3; k++)
                if (t[k] < best[k])
                    best[k] = t[k];
            ra[r] = t[0] / t[2];
            rb[r] = t[1] / t[2];
            s0 += chunk;
        }
        qsort(ra, (size_t)rounds, sizeof *ra, cmp);
        qsort(rb, (size_t)rounds, sizeof *rb, cmp);
        int same = !memcmp(a->b.x, x, sizeof x) && !memcmp(a->b.v, v, sizeof v) &&
                   !memcmp(b->b.x, x, sizeof x) && !memcmp(b->b.v, v, sizeof v);
        char r1[32], r2[32];
        snprintf(r1, sizeof r1, "%.2f (%.2f)", ra[rounds / 2],
                 best[0] / best[2]);
        snprintf(r2, sizeof r2, "%.2f (%.2f)", rb[rounds / 2],
                 best[1] / best[2]);
        printf("%-7s %9.2f %9.2f %9.2f  %16s %16s  %s\n", methods[m],
               1e9 * best[0] / chunk, 1e9 * best[1] / chunk,
               1e9 * best[2] / chunk, r1, r2,
               same ? "bit-identical" : "DIFFER");
        bf_ballsys_free(a);
        bf_ballsys_free(b);
        bf_scene_free(sa);
        bf_scene_free(sb);
    }
    return 0;
}
