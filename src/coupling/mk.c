/* mk.c: the moments of the coupling's kernel (mk.h).
 *
 * m_k(z) = integral_0^1 s^k exp(-z s) ds for k = 0..3, z >= 0: for
 * z < 0.5 the series sum_n (-z)^n / (n! (n + k + 1)) by Horner (the
 * coefficients are set up once; 0.5^20/20! < 1e-24), above it the upward
 * recursion m_k = (k m_(k-1) - exp(-z))/z (error growth k/z <= 6). */
#include "coupling/mk.h"

#include <math.h>

void bf_mk_init(bf_mk_table *t, double zmax)
{
    double f = 1.0; /* (-1)^n / n! */
    for (int n = 0; n < BF_MK_NSER; n++) {
        for (int k = 0; k < 4; k++)
            t->c[n][k] = f / (double)(n + k + 1);
        f *= -1.0 / (double)(n + 1);
    }
    /* z^n/n! < 1e-24 for z <= zmax */
    double term = 1.0;
    t->ns = 1;
    while (t->ns < BF_MK_NSER && term > 1e-24) {
        term *= zmax / (double)t->ns;
        t->ns++;
    }
}

void bf_mk(const bf_mk_table *t, double z, double m[4])
{
    const double(*c)[4] = t->c;
    const int ns = t->ns;
    if (z < 0.5) {
        double a0 = c[ns - 1][0], a1 = c[ns - 1][1], a2 = c[ns - 1][2],
               a3 = c[ns - 1][3];
        for (int n = ns - 2; n >= 0; n--) {
            a0 = a0 * z + c[n][0];
            a1 = a1 * z + c[n][1];
            a2 = a2 * z + c[n][2];
            a3 = a3 * z + c[n][3];
        }
        m[0] = a0;
        m[1] = a1;
        m[2] = a2;
        m[3] = a3;
        return;
    }
    double e = exp(-z);
    m[0] = -expm1(-z) / z;
    for (int k = 1; k < 4; k++)
        m[k] = ((double)k * m[k - 1] - e) / z;
}

/* m_k at two arguments (the two sides of a ball): the same operations as
 * two calls of bf_mk, with the series' eight Horner chains interleaved so
 * that their latencies overlap (the chains are ~17 dependent steps long). */
void bf_mk2(const bf_mk_table *t, double zl, double zr, double ml[4],
            double mr[4])
{
    if (!(zl < 0.5 && zr < 0.5)) {
        bf_mk(t, zl, ml);
        bf_mk(t, zr, mr);
        return;
    }
    const double(*c)[4] = t->c;
    const int ns = t->ns;
    const double *e = c[ns - 1];
    double a0 = e[0], a1 = e[1], a2 = e[2], a3 = e[3];
    double b0 = e[0], b1 = e[1], b2 = e[2], b3 = e[3];
    for (int n = ns - 2; n >= 0; n--) {
        e = c[n];
        a0 = a0 * zl + e[0];
        a1 = a1 * zl + e[1];
        a2 = a2 * zl + e[2];
        a3 = a3 * zl + e[3];
        b0 = b0 * zr + e[0];
        b1 = b1 * zr + e[1];
        b2 = b2 * zr + e[2];
        b3 = b3 * zr + e[3];
    }
    ml[0] = a0;
    ml[1] = a1;
    ml[2] = a2;
    ml[3] = a3;
    mr[0] = b0;
    mr[1] = b1;
    mr[2] = b2;
    mr[3] = b3;
}

/* GCC's "cheap" vectoriser cost model and clones for AVX-512 and AVX2,
 * as the hot loops of coupling.c (lane by lane: the same bits on every
 * clone). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("vect-cost-model=cheap")
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void bf_mk_series8(const bf_mk_table *t, const double z[8], double m[8][4])
{
    const double(*c)[4] = t->c;
    const int ns = t->ns;
    double a0[8], a1[8], a2[8], a3[8];
    for (int q = 0; q < 8; q++) {
        a0[q] = c[ns - 1][0];
        a1[q] = c[ns - 1][1];
        a2[q] = c[ns - 1][2];
        a3[q] = c[ns - 1][3];
    }
    for (int n = ns - 2; n >= 0; n--) {
        const double c0 = c[n][0], c1 = c[n][1], c2 = c[n][2], c3 = c[n][3];
        for (int q = 0; q < 8; q++) {
            a0[q] = a0[q] * z[q] + c0;
            a1[q] = a1[q] * z[q] + c1;
            a2[q] = a2[q] * z[q] + c2;
            a3[q] = a3[q] * z[q] + c3;
        }
    }
    for (int q = 0; q < 8; q++) {
        m[q][0] = a0[q];
        m[q][1] = a1[q];
        m[q][2] = a2[q];
        m[q][3] = a3[q];
    }
}

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
