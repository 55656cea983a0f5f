/* film_orders.c: observed orders of the invariant film scheme in dx and in
 * dt, measured separately (numbers quoted in the README).
 *
 * Problem: L = 20 cm, the kink psi = tanh(x/sqrt 2) with a smooth bump
 * 0.05 exp(-(x+0.5)^2)/cosh(x/sqrt 2), h = 1 + 1e-3 exp(-(x-1)^2),
 * u_d = 0.02 exp(-x^2), u_c = -0.01 exp(-(x-0.5)^2) cm/s, run to T = 0.5 s
 * (gravity waves cross the film, the phases separate and slip).  Errors are
 * max-norm differences of successive refinements (the nodes of a grid are
 * nodes of the next), order = log2 of the ratio of successive differences.
 *   dx: dt = 5e-5 s fixed (its error is far below the dx differences);
 *   dt: dx fixed, for each reading of the mu term, with nu = 0.01 (the
 *       paper's viscosity) and nu = 0.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "ballfilm/film.h"

static bf_film *run(double dx, double dt, double nu, int variant)
{
    bf_film_params p = {.length = 20, .dx = dx, .rho_d = 1, .rho_c = 1,
                        .nu = nu, .g = 980, .a = 1, .b = 1, .gamma = 1,
                        .mu_taylor = (bf_film_mu_taylor)variant,
                        .limit_positive = 1, .vanish = 0};
    bf_film *f;
    bf_err err = {0};
    if (bf_film_create(&f, &p, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    size_t n = bf_film_nodes(f);
    const double *x = bf_film_x(f);
    double *b = calloc(4 * n, sizeof *b);
    for (size_t i = 0; i < n; i++) {
        double X = x[i];
        b[i] = 1 + 1e-3 * exp(-(X - 1) * (X - 1));
        b[n + i] = tanh(X / sqrt(2.0)) +
                   0.05 * exp(-(X + 0.5) * (X + 0.5)) / cosh(X / sqrt(2.0));
        b[2 * n + i] = 0.02 * exp(-X * X);
        b[3 * n + i] = -0.01 * exp(-(X - 0.5) * (X - 0.5));
    }
    if (bf_film_set_state(f, b, b + n, b + 2 * n, b + 3 * n, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    free(b);
    long steps = lround(0.5 / dt);
    for (long s = 0; s < steps; s++)
        if (bf_film_step_invariant(f, dt, NULL, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            exit(1);
        }
    return f;
}

static double diff(const double *a, const double *b, size_t n, size_t sb)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i * sb]));
    return m;
}

typedef const double *(*field_fn)(const bf_film *);
static const field_fn fields[4] = {bf_film_psi, bf_film_h, bf_film_u_d,
                                   bf_film_u_c};
static const char *fname[4] = {"psi", "h", "u_d", "u_c"};

int main(void)
{
    static const char *vname[3] = {"midpoint", "um (printed)", "uk"};
    printf("order in dx (midpoint, nu = 0.01, dt = 5e-5 s): differences "
           "dx 0.2-0.1, 0.1-0.05, 0.05-0.025\n");
    const double dxs[4] = {0.2, 0.1, 0.05, 0.025};
    bf_film *g[4];
    for (int k = 0; k < 4; k++)
        g[k] = run(dxs[k], 5e-5, 0.01, 0);
    for (int q = 0; q < 4; q++) {
        printf("  %-4s", fname[q]);
        double prev = 0;
        for (int k = 0; k < 3; k++) {
            double d = diff(fields[q](g[k]), fields[q](g[k + 1]),
                            bf_film_nodes(g[k]), 2);
            printf("  %.3e", d);
            if (k)
                printf(" (order %.2f)", log2(prev / d));
            prev = d;
        }
        printf("\n");
    }
    for (int k = 0; k < 4; k++)
        bf_film_free(g[k]);

    printf("order in dt (psi): differences dt 1e-3 - 5e-4 - 2.5e-4 - "
           "1.25e-4 - 6.25e-5 s\n");
    const double nus[2] = {0.01, 0.0};
    for (int v = 0; v < 3; v++)
        for (int m = 0; m < 2; m++)
            for (int xk = 0; xk < 2; xk++) {
                double dx = xk ? 0.05 : 0.1;
                bf_film *f[5];
                double dt = 1e-3;
                for (int k = 0; k < 5; k++, dt /= 2)
                    f[k] = run(dx, dt, nus[m], v);
                printf("  %-12s nu = %-4g dx = %-4g", vname[v], nus[m], dx);
                double prev = 0;
                for (int k = 0; k < 4; k++) {
                    double d = diff(bf_film_psi(f[k]), bf_film_psi(f[k + 1]),
                                    bf_film_nodes(f[k]), 1);
                    printf("  %.3e", d);
                    if (k)
                        printf(" (%.2f)", log2(prev / d));
                    prev = d;
                }
                printf("\n");
                for (int k = 0; k < 5; k++)
                    bf_film_free(f[k]);
            }
    return 0;
}
