/* mk.h: the moments m_k(z) = integral_0^1 s^k exp(-z s) ds, k = 0..3,
 * z >= 0, of the coupling's exponential kernel over a cell (coupling.c):
 * by their series for z < 0.5 (Horner), by the upward recursion above.
 * Private to the library.
 */
#ifndef BALLFILM_COUPLING_MK_H
#define BALLFILM_COUPLING_MK_H

enum { BF_MK_NSER = 20 };

/* The series coefficients c[n][k] = (-1)^n / (n! (n + k + 1)) and the
 * number of terms the arguments up to zmax need. */
typedef struct bf_mk_table {
    double c[BF_MK_NSER][4];
    int ns; /* z^ns/ns! < 1e-24 for z <= zmax (at most BF_MK_NSER) */
} bf_mk_table;

/* The table for arguments of the series up to zmax (<= 0.5). */
void bf_mk_init(bf_mk_table *t, double zmax);

/* m_0..m_3 at z. */
void bf_mk(const bf_mk_table *t, double z, double m[4]);

/* At two arguments (the two sides of a ball): the same operations as two
 * calls of bf_mk, the two series interleaved. */
void bf_mk2(const bf_mk_table *t, double zl, double zr, double ml[4],
            double mr[4]);

/* The series alone (z < 0.5 each) at eight arguments, as eight lanes:
 * the same operations as bf_mk's series for each lane. */
void bf_mk_series8(const bf_mk_table *t, const double z[8], double m[8][4]);

#endif
