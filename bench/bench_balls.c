/* bench_balls.c: cost per step of the generic ball interface against a
 * hand-fused loop for the same problem (two balls, gravity + floor +
 * contact, Yasuda sec. 2.5), for MV2M and Verlet.  Both run in this process,
 * one after the other, several times; the minimum time of each is used.
 * Prints the ratio generic/fused (goal <= 1.3). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "ballfilm/ballsys.h"
#include "ballfilm/registry.h"
#include "ballfilm/scene.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const double G = 980, K = 1e7, R = 0.1, M1 = 0.8, M2 = 1.0;

static inline void fused_acc(const double *x, double *a)
{
    double a1 = -G, a2 = -G;
    double xf = R - x[0];
    if (xf > 0)
        a1 += K * xf * sqrt(xf) / M1;
    double xc = R - 0.5 * (x[1] - x[0]);
    if (xc > 0) {
        double f = K * xc * sqrt(xc);
        a1 -= f / M1;
        a2 += f / M2;
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

static void fused_verlet(double *x, double *v, double dt, long n)
{
    double a0[2], a1[2];
    fused_acc(x, a0);
    for (long s = 0; s < n; s++) {
        for (int i = 0; i < 2; i++)
            x[i] += dt * v[i] + 0.5 * dt * dt * a0[i];
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

static double generic(const char *method, long n, double *xout)
{
    char text[512];
    snprintf(text, sizeof text, scene_text, method);
    bf_scene *sc;
    bf_err err = {0};
    bf_ballsys *sys;
    bf_effect_env env = {0};
    if (bf_scene_load_string(&sc, "bench", text, &err) ||
        bf_registry_resolve(sc, &err) ||
        bf_ballsys_create(&sys, sc, &env, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    double t0 = now();
    for (long s = 0; s < n; s++)
        if (bf_ballsys_step(sys, (double)s * 1e-4, 1e-4, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
    double el = now() - t0;
    xout[0] = sys->b.x[0];
    xout[1] = sys->b.x[1];
    bf_ballsys_free(sys);
    bf_scene_free(sc);
    return el;
}

int main(void)
{
    const long n = 2000000;
    const char *methods[] = {"mv2m", "verlet"};
    printf("two falling balls (gravity, floor, contact), %ld steps, dt = 1e-4 s,"
           " best of 5\n",
           n);
    printf("%-8s %14s %14s %8s   %s\n", "method", "generic ns/step",
           "fused ns/step", "ratio", "same final state");
    for (int m = 0; m < 2; m++) {
        double best_g = 1e30, best_f = 1e30, xg[2], xf[2];
        for (int rep = 0; rep < 5; rep++) {
            double tg = generic(methods[m], n, xg);
            double x[2] = {0.2, 0.5}, v[2] = {0, 0};
            double t0 = now();
            if (m == 0)
                fused_mv2m(x, v, 1e-4, n);
            else
                fused_verlet(x, v, 1e-4, n);
            double tf = now() - t0;
            xf[0] = x[0];
            xf[1] = x[1];
            if (tg < best_g)
                best_g = tg;
            if (tf < best_f)
                best_f = tf;
        }
        printf("%-8s %14.2f %14.2f %8.2f   |dx| = %.1e\n", methods[m],
               1e9 * best_g / n, 1e9 * best_f / n, best_g / best_f,
               fmax(fabs(xg[0] - xf[0]), fabs(xg[1] - xf[1])));
    }
    return 0;
}
