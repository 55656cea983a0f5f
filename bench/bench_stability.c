/* bench_stability.c: the largest stable time step of every integrator on
 * the bouncing ball of Yasuda sec. 2.4 (k = 1e7, R = 0.1 cm, m = 1 g,
 * dropped from 0.2 cm).
 *
 * For each method the step is raised on a geometric grid dt_k = 2e-5 s *
 * 2^(k/8) and the ball is run for 10 s (about 350 bounces) with the energy
 * checked after every step.  Printed: the largest dt before the first
 * failure of each criterion
 *   1%   max relative energy error below 1e-2
 *   50%  max relative energy error below 0.5 and the run completes
 *        (beyond it the ball is shot up or comes to rest on the floor, or
 *        the implicit iteration fails)
 * and what ended the scan.  The grid resolution is 2^(1/8) = 9%.
 * Stability need not be monotone in dt; the first failure is reported. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/ballsys.h"
#include "ballfilm/run.h"

static const char *base =
    "[scene]\nintegrator = %s\neffects = gravity floor\ndt = %.17g\n"
    "t_end = 10\n%s\n[gravity]\ng = 980\n[floor]\nk = 1e7\n"
    "[ball.1]\nposition = 0.2\nmass = 1\nradius = 0.1\n";

/* max relative energy error over 10 s, or +inf with a reason */
static double run(const char *name, const char *keys, double dt, char *why,
                  size_t cap)
{
    char text[1024];
    snprintf(text, sizeof text, base, name, dt, keys);
    bf_scene *sc;
    bf_err err = {0};
    bf_ballsys *sys;
    if (bf_scene_load_string(&sc, "stability", text, &err) ||
        bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ||
        bf_ballsys_from_scene(&sys, bf_catalog_builtin(), sc, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    double k, p;
    bf_ballsys_energy(sys, 0, &k, &p);
    const double e0 = k + p;
    double emax = 0;
    long n = (long)ceil(10.0 / dt);
    why[0] = '\0';
    for (long s = 0; s < n; s++) {
        bf_status st = bf_ballsys_step(sys, s * dt, dt, &err);
        if (st) {
            snprintf(why, cap, "%s", bf_status_name(st));
            emax = INFINITY;
            break;
        }
        bf_ballsys_energy(sys, (s + 1) * dt, &k, &p);
        double rel = fabs(k + p - e0) / e0;
        if (rel > emax)
            emax = rel;
        if (rel > 0.5) {
            snprintf(why, cap, "energy %s", k + p > e0 ? "gained"
                                                       : "lost (comes to rest)");
            break;
        }
    }
    bf_ballsys_free(sys);
    bf_scene_free(sc);
    return emax;
}

int main(void)
{
    const struct {
        const char *label, *name, *keys;
    } m[] = {
        {"verlet", "verlet", ""},
        {"mv2m", "mv2m", ""},
        {"impmid", "impmid", ""},
        {"rk3", "rk3", ""},
        {"rk4", "rk4", ""},
        {"alpha 0 verlet", "alpha", "[integrator]\nalpha = 0"},
        {"alpha 1/8 verlet", "alpha", "[integrator]\nalpha = 0.125"},
        {"alpha 1/4 verlet", "alpha", "[integrator]\nalpha = 0.25"},
        {"alpha 0 trapezoid", "alpha",
         "[integrator]\nalpha = 0\nposition = trapezoid"},
        {"alpha 1/8 trapezoid", "alpha",
         "[integrator]\nalpha = 0.125\nposition = trapezoid"},
    };
    printf("bouncing ball (k = 1e7), 10 s: largest dt on the grid 2e-5 * "
           "2^(k/8) s\n");
    printf("%-20s %12s %12s   %s\n", "method", "dt (1%)", "dt (50%)",
           "what ended the scan");
    for (size_t j = 0; j < sizeof m / sizeof m[0]; j++) {
        double ok1 = 0, ok50 = 0;
        int still1 = 1;
        char why[128] = "";
        for (int k = 0; k < 120; k++) {
            double dt = 2e-5 * pow(2.0, k / 8.0);
            double e = run(m[j].name, m[j].keys, dt, why, sizeof why);
            if (!(e < 1e-2))
                still1 = 0;
            if (still1)
                ok1 = dt;
            if (!(e < 0.5))
                break;
            ok50 = dt;
        }
        char a[32], b[32];
        snprintf(a, sizeof a, ok1 > 0 ? "%.3g" : "< 2e-05", ok1);
        snprintf(b, sizeof b, ok50 > 0 ? "%.3g" : "< 2e-05", ok50);
        printf("%-20s %12s %12s   %s\n", m[j].label, a, b, why);
    }
    return 0;
}
