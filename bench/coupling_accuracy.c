/* coupling_accuracy.c: accuracy of the coupling integral (Yasuda eq. 3.10)
 * as the balls see it, for the analytic kink h = 1, psi = tanh(x/sqrt 2)
 * sampled on the film's nodes: I(r) = integral g exp(-|x - r|/r0) dx and
 * dI/dr against GSL's adaptive quadrature (QAG, 1e-13) of the analytic
 * integrand, piecewise on each side of r; spline and linear interpolation
 * of g, dx = 0.1 and 0.05; and the cost of one evaluation.  Numbers quoted
 * in the README. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "coupling/coupling.h"

static const double R0 = 0.5;

typedef struct qctx {
    double r;
    int right;
} qctx;

static double integrand(double x, void *p)
{
    const qctx *q = p;
    double g = tanh(x / sqrt(2.0));
    return g * g * exp(-(q->right ? x - q->r : q->r - x) / R0);
}

static double qag(qctx *q, double a, double b)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(2000);
    gsl_function fn = {integrand, q};
    double v = 0, e, s = 0;
    /* split at 0 where g has its structure */
    if (a < 0 && b > 0) {
        gsl_integration_qag(&fn, a, 0, 0, 1e-13, 2000, GSL_INTEG_GAUSS61, w, &v,
                            &e);
        gsl_integration_qag(&fn, 0, b, 0, 1e-13, 2000, GSL_INTEG_GAUSS61, w, &s,
                            &e);
        v += s;
    } else {
        gsl_integration_qag(&fn, a, b, 0, 1e-13, 2000, GSL_INTEG_GAUSS61, w, &v,
                            &e);
    }
    gsl_integration_workspace_free(w);
    return v;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    gsl_set_error_handler_off();
    const double rs[] = {0.0137, 0.2, -0.45, 0.777, 1.5, -2.2};
    const size_t nr = sizeof rs / sizeof rs[0];
    printf("coupling integral against QAG of the analytic kink "
           "(r0 = 0.5 cm, L = 50 cm; max relative error over r = 0.0137, "
           "0.2, -0.45, 0.777, 1.5, -2.2 cm)\n");
    for (int q = 0; q < 2; q++)
        for (int k = 0; k < 2; k++) {
            double dx = k ? 0.05 : 0.1;
            bf_film_params p = {.length = 50, .dx = dx, .rho_d = 1,
                                .rho_c = 1, .nu = 0.01, .g = 980, .a = 1,
                                .b = 1, .gamma = 1, .limit_positive = 1};
            bf_film *f;
            bf_err err = {0};
            if (bf_film_create(&f, &p, &err))
                return 1;
            size_t n = bf_film_nodes(f);
            double *h = malloc(n * sizeof *h), *psi = malloc(n * sizeof *psi),
                   *z = calloc(n, sizeof *z);
            for (size_t i = 0; i < n; i++) {
                h[i] = 1;
                psi[i] = tanh(bf_film_x(f)[i] / sqrt(2.0));
            }
            bf_film_set_state(f, h, psi, z, z, &err);
            bf_coupling_params cp = {.V0 = 0.01, .r0 = R0, .M = 1e5,
                                     .quad = (bf_coupling_quad)q};
            bf_coupling *c;
            if (bf_coupling_create(&c, &cp, f, 1, &err))
                return 1;
            double eI = 0, eD = 0;
            for (size_t j = 0; j < nr; j++) {
                double I, dI;
                bf_coupling_integral(c, rs[j], &I, &dI);
                qctx ql = {rs[j], 0}, qr = {rs[j], 1};
                double L = qag(&ql, -25, rs[j]), R = qag(&qr, rs[j], 25);
                eI = fmax(eI, fabs(I - (L + R)) / (L + R));
                eD = fmax(eD, fabs(dI - (R - L) / R0) / fabs((R - L) / R0));
            }
            /* cost of one exact evaluation (moments cached per cell) */
            long reps = 200000;
            double t0 = now(), sink = 0;
            for (long r = 0; r < reps; r++) {
                double I, dI;
                bf_coupling_integral(c, 0.2 + 1e-9 * (double)(r % 1000), &I,
                                     &dI);
                sink += dI;
            }
            double te = (now() - t0) / (double)reps;
            printf("  %-6s dx = %-4g: I %.2e, dI/dr %.2e; %.0f ns per exact "
                   "evaluation%s\n",
                   q ? "linear" : "spline", dx, eI, eD, 1e9 * te,
                   sink == 0.123 ? " " : "");
            bf_coupling_free(c);
            bf_film_free(f);
            free(h);
            free(psi);
            free(z);
        }
    return 0;
}
