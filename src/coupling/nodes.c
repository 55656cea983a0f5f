/* nodes.c: the `nodes` quadrature of eq. 3.10 (see nodes.h): the kernel
 * summed at the nodes, then the natural cubic spline through the node
 * values. */
#include "coupling/nodes.h"

#include <math.h>
#include <stdlib.h>

struct bf_coupling_nodes {
    long N;          /* intervals: nodes 0..N */
    double dx;       /* cm */
    double E;        /* exp(-dx/r0) */
    int valid;       /* I and M belong to the current level */
    double *I;       /* node values, cm */
    double *M;       /* the spline's second derivatives, 1/cm */
    double *a, *b;   /* the two recurrences; b also the Thomas scratch */
};

bf_coupling_nodes *bf_coupling_nodes_create(long N, double dx, double r0)
{
    if (N < 1)
        return NULL;
    bf_coupling_nodes *q = calloc(1, sizeof *q);
    if (!q)
        return NULL;
    const size_t n = (size_t)N + 1;
    q->N = N;
    q->dx = dx;
    q->E = exp(-dx / r0);
    q->I = calloc(n, sizeof *q->I);
    q->M = calloc(n, sizeof *q->M);
    q->a = calloc(n, sizeof *q->a);
    q->b = calloc(n, sizeof *q->b);
    if (!q->I || !q->M || !q->a || !q->b) {
        bf_coupling_nodes_free(q);
        return NULL;
    }
    return q;
}

void bf_coupling_nodes_free(bf_coupling_nodes *q)
{
    if (!q)
        return;
    free(q->I);
    free(q->M);
    free(q->a);
    free(q->b);
    free(q);
}

void bf_coupling_nodes_invalidate(bf_coupling_nodes *q) { q->valid = 0; }

/* I_i = dx sum_j g_j E^|i-j| by a left and a right recurrence (each
 * includes g_i once, hence the - g_i) */
static void node_sums(bf_coupling_nodes *q, const double *g)
{
    const long N = q->N;
    double *a = q->a, *b = q->b;
    a[0] = g[0];
    for (long i = 1; i <= N; i++)
        a[i] = g[i] + q->E * a[i - 1];
    b[N] = g[N];
    for (long i = N - 1; i >= 0; i--)
        b[i] = g[i] + q->E * b[i + 1];
    for (long i = 0; i <= N; i++)
        q->I[i] = q->dx * ((a[i] + b[i]) - g[i]);
}

/* natural spline through (x_i, I_i): M_0 = M_N = 0 and
 * M_i-1 + 4 M_i + M_i+1 = 6 (I_i+1 - 2 I_i + I_i-1) / dx^2, by Thomas */
static void spline(bf_coupling_nodes *q)
{
    const long N = q->N;
    double *M = q->M, *c = q->b; /* c: the eliminated super-diagonal */
    const double s = 6.0 / (q->dx * q->dx);
    M[0] = M[N] = 0.0;
    if (N < 2)
        return;
    double w = 4.0;
    c[1] = 1.0 / w;
    M[1] = s * ((q->I[2] - 2.0 * q->I[1]) + q->I[0]) / w;
    for (long i = 2; i < N; i++) {
        w = 4.0 - c[i - 1];
        c[i] = 1.0 / w;
        const double d = s * ((q->I[i + 1] - 2.0 * q->I[i]) + q->I[i - 1]);
        M[i] = (d - M[i - 1]) / w;
    }
    for (long i = N - 2; i >= 1; i--)
        M[i] -= c[i] * M[i + 1];
}

static void update(bf_coupling_nodes *q, const double *g)
{
    if (q->valid)
        return;
    node_sums(q, g);
    spline(q);
    q->valid = 1;
}

void bf_coupling_nodes_eval(bf_coupling_nodes *q, const double *g, long j,
                            double t, double *I, double *dI)
{
    update(q, g);
    const double tc = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t, sc = 1.0 - tc;
    const double h = q->dx, I0 = q->I[j], I1 = q->I[j + 1];
    const double M0 = q->M[j], M1 = q->M[j + 1];
    const double S = sc * I0 + tc * I1 +
                     h * h / 6.0 * ((sc * sc * sc - sc) * M0 +
                                    (tc * tc * tc - tc) * M1);
    const double dS = (I1 - I0) / h +
                      h / 6.0 * ((1.0 - 3.0 * sc * sc) * M0 +
                                 (3.0 * tc * tc - 1.0) * M1);
    /* beyond the end nodes: the line of the end slope */
    *I = S + dS * (t - tc) * h;
    *dI = dS;
}
