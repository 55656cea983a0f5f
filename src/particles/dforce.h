/* dforce.h: Greenspan's discrete, exactly energy-conserving pair force
 * (1973, eqs 2.4, 2.12, 2.17).
 *
 * For particles i, j at distances a = r_ij^k (time k) and b = r_ij^{k+1}
 * (the unknown time k+1),
 *
 *   F_i = -gamma_i m_i g y^
 *         + m_i sum_{j != i} m_j [-p_ij S_alpha(a, b) + q_ij S_beta(a, b)]
 *                            (x_i^{k+1} + x_i^k - x_j^{k+1} - x_j^k),
 *
 *   S_n(a, b) = sum_{xi=0}^{n-2} a^xi b^{n-2-xi} / (a^{n-1} b^{n-1} (a + b))
 *             = (1/(a+b)) sum_{k=1}^{n-1} a^{-(n-k)} b^{-k},   n >= 2.
 *
 * Since S_n(a,b) (b^2 - a^2) = 1/a^{n-1} - 1/b^{n-1}, the work of the pair
 * term over a step is exactly V_ij^k - V_ij^{k+1} with
 *
 *   V_ij(r) = m_i m_j (-p_ij / r^{alpha-1} + q_ij / r^{beta-1})     (2.17)
 *
 * and gravity's is V_g^k - V_g^{k+1}, V_g = sum gamma_i m_i g y_i.  With the
 * update (2.1)-(2.3) solved exactly, K + V is conserved to round-off for
 * any dt (see implicit.h).  As b -> a, 2a S_n(a, a) = (n-1)/a^n: a
 * consistent discretisation of the Lennard-Jones-type force
 * m_i m_j (-(alpha-1) p / r^alpha + (beta-1) q / r^beta) r^.
 *
 * 2-D, gravity along -y.  Units: the papers' (dimensionless; read as CGS).
 */
#ifndef BALLFILM_PARTICLES_DFORCE_H
#define BALLFILM_PARTICLES_DFORCE_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"

typedef struct bf_dforce {
    size_t n;
    int alpha, beta;   /* integer exponents >= 2 (7 and 10 in the paper) */
    double *p, *q;     /* n x n symmetric pair constants */
    double *m;         /* masses in the force (pair strengths, gravity) */
    uint8_t *gravity;  /* gamma_i: 1 if particle i feels gravity */
    uint8_t *fixed;    /* 1: immobile (x^{k+1} = x^k, no force computed) */
    double g;          /* gravity */
} bf_dforce;

/* Allocate for n particles: p = q = 1, m = 1, no gravity, none fixed. */
bf_status bf_dforce_init(bf_dforce *f, size_t n, int alpha, int beta,
                         bf_err *err);
void bf_dforce_free(bf_dforce *f);

/* S_n(a, b) and dS_n/db (a, b > 0). */
void bf_dforce_s(int nexp, double a, double b, double *s, double *dsdb);

/* r_ij = |x_i - x_j| for all pairs (n x n, zero diagonal). */
void bf_dforce_distances(const bf_dforce *f, const double *x, const double *y,
                         double *r);

/* F_i for the free particles (fx, fy of fixed ones set to 0), given the
 * positions at time k (x0, y0; distances r0) and a guess of time k+1
 * (x1, y1; distances r1). */
void bf_dforce_eval(const bf_dforce *f, const double *x0, const double *y0,
                    const double *r0, const double *x1, const double *y1,
                    const double *r1, double *fx, double *fy);

/* dF/dx^{k+1}: the 2n x 2n matrix J[(2i+a)(2n) + 2j+b] = dF_{i,a}/dx_{j,b}
 * (a, b = 0: x, 1: y), dense, rows of fixed particles zero.  Pairs with
 * r1 > cutoff are left out when cutoff > 0 (an approximate Jacobian). */
void bf_dforce_jacobian(const bf_dforce *f, const double *x0, const double *y0,
                        const double *r0, const double *x1, const double *y1,
                        const double *r1, double cutoff, double *J);

/* Pair potential (2.17) summed over i < j, and the gravity potential. */
double bf_dforce_pair_energy(const bf_dforce *f, const double *r);
double bf_dforce_gravity_energy(const bf_dforce *f, const double *y);

/* Equilibrium distance of one pair: ((beta-1) q / ((alpha-1) p))^{1/(beta-alpha)}. */
double bf_dforce_r0(int alpha, int beta, double p, double q);

#endif
