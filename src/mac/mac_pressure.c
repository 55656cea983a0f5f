/* mac_pressure.c: the pressure equation of the MAC solver and its two
 * solvers.
 *
 * (3.10), as printed and as coded in the listing (label 108), comes from
 * putting the update (3.6)-(3.9) into continuity (3.2):
 *   P_ij = B1 P_{i+1,j} + B2 P_{i-1,j} + B3 P_{i,j+1} + B4 P_{i,j-1} + A,
 *   C  = (dt/dx^2)(1/rho_{i+1/2} + 1/rho_{i-1/2})
 *      + (dt/dy^2)(1/rho_{j+1/2} + 1/rho_{j-1/2}),
 *   B1 = dt/(dx^2 rho_{i+1/2} C), ..., B4 = dt/(dy^2 rho_{j-1/2} C),
 *   A  = [(psi_{i-1/2}/rho_{i-1/2} - psi_{i+1/2}/rho_{i+1/2})/dx
 *        + (zeta_{j-1/2}/rho_{j-1/2} - zeta_{j+1/2}/rho_{j+1/2})/dy] / C,
 * face densities the mean of the two cells, all at n+1.  The thesis then
 * applies the "modified" update (3.11)/(3.12), whose pressure term is
 * (dt/dx)(P_ij/rho_ij - P_{i+1,j}/rho_{i+1,j}); the equation that makes
 * those velocities divergence-free has the cell densities instead:
 *   C = (2 dt/dx^2 + 2 dt/dy^2)/rho_ij,  B1 = dt/(dx^2 rho_{i+1,j} C), ...
 * (BF_MAC_CONSISTENT).  Written in x = P (3.10) or x = P/rho (consistent),
 * both are  sum_faces w_f (x_c - x_n) = b_c  with w_f = dt k_f/delta^2,
 * k_f = 1/rho_f or 1: symmetric, and positive definite once every fluid
 * region touches a Dirichlet pressure (free surface or the inflow).
 *
 * Relaxation (listing labels 200-247): Gauss-Seidel in place over the FULL
 * cells, I outer and J inner, no over-relaxation (omega = 1), boundary
 * and surface pressures re-applied before every sweep.  After each sweep
 * the test DP = |PN - P| / |rho g DEPTH| < tol in every FULL cell; the
 * crude test (.0003) in the corrector passes, the fine test (.0002) in the
 * last, at most 500 sweeps each ("TOO MANY ITERATIONS", here BF_ENOCONV).
 * This tests the change per sweep, not the error.
 *
 * Direct solve: the same equations with the ghost cells eliminated
 * (Dirichlet values moved to the right-hand side, fixed-flux faces as
 * known fluxes), factored by a band Cholesky (interior cells numbered with
 * J fastest, bandwidth nj - 2) and checked by its residual.
 */
#include "mac/mac_pressure.h"

#include "mac/mac_bc.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* The same bits (a density is never -0 or NaN here, but the test must
 * not care). */
static int same_bits(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

/* The coefficients of a FULL cell depend on psi, zeta (fixed within a
 * step) and the densities of the cell and its four neighbours.  The
 * corrector passes after the first change the densities of a few cells
 * only: a cell whose coefficients were computed in this step (cstamp =
 * the step's number, kept only while the cell stays FULL) and whose five
 * densities have the same bits as at the last call (rcoef) keeps them.
 * The same numbers as computing every cell every pass, without their 17
 * divisions. */
void bf_mac_pressure_coefficients(bf_mac *m)
{
    const double dx = m->dx, dy = m->dy, dt = m->dt;
    const double *R = m->r, *XI = m->xi, *ZE = m->zeta, *RC = m->rcoef;
    const int K = mac_consistent(m);
    const long now = m->nstep;
    const size_t st = (size_t)m->st;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            size_t c = IX(i, j);
            if (m->ic[c] != BF_MAC_FULL) {
                m->cstamp[c] = 0;
                continue;
            }
            if (m->cstamp[c] == now && !m->full_passes &&
                same_bits(R[c], RC[c]) && same_bits(R[c - st], RC[c - st]) &&
                same_bits(R[c + st], RC[c + st]) &&
                same_bits(R[c - 1], RC[c - 1]) &&
                same_bits(R[c + 1], RC[c + 1])) {
                m->kept_coefficients++;
                continue;
            }
            m->cstamp[c] = now;
            double rl = 0.5 * (R[IX(i - 1, j)] + R[c]);
            double rr = 0.5 * (R[IX(i + 1, j)] + R[c]);
            double rt = 0.5 * (R[IX(i, j + 1)] + R[c]);
            double rb = 0.5 * (R[IX(i, j - 1)] + R[c]);
            double num = (XI[c] / rl - XI[IX(i + 1, j)] / rr) / dx +
                         (ZE[c] / rb - ZE[IX(i, j + 1)] / rt) / dy;
            if (!K) {
                double cc = dt * (1.0 / rl + 1.0 / rr) / (dx * dx) +
                            dt * (1.0 / rt + 1.0 / rb) / (dy * dy);
                m->a[c] = num / cc;
                m->b1[c] = (dt / (dx * dx * rr)) / cc;
                m->b2[c] = (dt / (dx * dx * rl)) / cc;
                m->b3[c] = (dt / (dy * dy * rt)) / cc;
                m->b4[c] = (dt / (dy * dy * rb)) / cc;
            } else {
                double cc = (2.0 * dt / (dx * dx) + 2.0 * dt / (dy * dy)) / R[c];
                m->a[c] = num / cc;
                m->b1[c] = dt / (dx * dx * R[IX(i + 1, j)] * cc);
                m->b2[c] = dt / (dx * dx * R[IX(i - 1, j)] * cc);
                m->b3[c] = dt / (dy * dy * R[IX(i, j + 1)] * cc);
                m->b4[c] = dt / (dy * dy * R[IX(i, j - 1)] * cc);
            }
        }
    memcpy(m->rcoef, R, m->ncell * sizeof *m->rcoef);
}

/* Each sweep runs in place on P: a cell's new value is computed from its
 * neighbours' newest values as the listing's copy PN would hold them, and
 * its change per sweep from the value it replaces, so no copy is needed
 * (the same numbers in the same order as sweeping a copy). */
bf_status bf_mac_relax(bf_mac *m, int fine, long *sweeps, bf_err *err)
{
    const double tol = fine ? m->prm.fine_tol : m->prm.crude_tol;
    const double om = m->prm.omega;
    const double gd = fabs(m->prm.g) * m->depth;
    double *P = m->p;
    const double *R = m->r;
    const int *F = m->ic;
    const size_t st = (size_t)m->st;
    double worst = 0;
    int wi = 0, wj = 0;
    for (long l = 1;; l++) {
        bf_mac_ghost_pressure(m, P);
        worst = 0;
        for (int i = 2; i <= m->ni - 1; i++)
            for (int j = 2; j <= m->nj - 1; j++) {
                size_t c = IX(i, j);
                if (F[c] != BF_MAC_FULL)
                    continue;
                double old = P[c];
                double gs = m->b1[c] * P[c + st] + m->b2[c] * P[c - st] +
                            m->b3[c] * P[c + 1] + m->b4[c] * P[c - 1] + m->a[c];
                P[c] = om == 1.0 ? gs : old + om * (gs - old);
                double dp = fabs((P[c] - old) / (R[c] * gd));
                if (!(dp <= worst)) /* NaN counts as worst */
                    worst = dp, wi = i, wj = j;
            }
        if (worst < tol) {
            *sweeps = l;
            return BF_OK;
        }
        if (l >= m->prm.max_sweeps) {
            *sweeps = l;
            return bf_fail(err, BF_ENOCONV,
                           "too many iterations in the %s test: the pressure "
                           "relaxation did not converge in %ld sweeps "
                           "(largest change |dP|/|rho g DEPTH| = %.3g > %g at "
                           "cell (%d,%d))",
                           fine ? "fine" : "crude", l, worst, tol, wi, wj);
        }
    }
}

/* ------------------------------------------------------ direct solve */

#define unk mac_unk

static int is_full(int flag) { return flag == BF_MAC_FULL; }

/* Every FULL region must reach a Dirichlet pressure (a SUR cell, an empty
 * cell, or the inflow's hydrostatic P0); otherwise its pressure is
 * undetermined and the matrix singular.  Returns 0 or the first cell of an
 * unreached region in *bi, *bj. */
static int check_regions(bf_mac *m, int *bi, int *bj)
{
    int n = 0;
    for (int k = 0; k < m->nunk; k++)
        m->mark[k] = 0;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            if (m->ic[IX(i, j)] != BF_MAC_FULL)
                continue;
            int seed = 0;
            for (int d = 0; d < 4 && !seed; d++) {
                mac_face f;
                bf_mac_face_of(m, i, j, d, &f);
                if (mac_interior(m, f.i, f.j)) {
                    seed = m->ic[IX(f.i, f.j)] != BF_MAC_FULL;
                } else {
                    double v;
                    seed = bf_mac_boundary_face(m, f.i, f.j, i, j, &v) ==
                           MAC_DIRICHLET;
                }
            }
            if (seed) {
                m->mark[unk(m, i, j)] = 1;
                m->queue[n++] = unk(m, i, j);
            }
        }
    bf_mac_flood(m, n, is_full);
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            if (m->ic[IX(i, j)] == BF_MAC_FULL && !m->mark[unk(m, i, j)]) {
                *bi = i;
                *bj = j;
                return 1;
            }
    return 0;
}

/* Band storage: row k holds A(k, k - d) at band[k (bw+1) + d]. */
static double *bel(bf_mac *m, double *band, int k, int d)
{
    return &band[(size_t)k * (size_t)(m->bw + 1) + (size_t)d];
}

static void assemble(bf_mac *m)
{
    const int K = mac_consistent(m);
    const double dt = m->dt;
    const size_t nb = (size_t)m->nunk * (size_t)(m->bw + 1);
    memset(m->band, 0, nb * sizeof *m->band);
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            int k = unk(m, i, j);
            size_t c = IX(i, j);
            if (m->ic[c] != BF_MAC_FULL) {
                *bel(m, m->band, k, 0) = 1.0;
                m->rhs[k] = 0.0;
                continue;
            }
            double diag = 0, b = 0;
            for (int d = 0; d < 4; d++) {
                mac_face f;
                bf_mac_face_of(m, i, j, d, &f);
                double w = dt * (K ? 1.0 : 1.0 / f.rhof) / (f.delta * f.delta);
                size_t n = IX(f.i, f.j);
                double val = 0;
                int kind = mac_interior(m, f.i, f.j)
                               ? -1
                               : bf_mac_boundary_face(m, f.i, f.j, i, j, &val);
                if (kind == MAC_FLUX) {
                    b -= f.s * val / f.delta;
                    continue;
                }
                b -= f.s * f.psi / (f.rhof * f.delta);
                diag += w;
                if (kind == -1 && m->ic[n] == BF_MAC_FULL) {
                    int kn = unk(m, f.i, f.j);
                    if (kn < k)
                        *bel(m, m->band, k, k - kn) = -w;
                } else {
                    double pn = kind == MAC_DIRICHLET ? val : m->p[n];
                    b += w * (K ? pn / m->r[n] : pn);
                }
            }
            *bel(m, m->band, k, 0) = diag;
            m->rhs[k] = b;
        }
}

/* In-place band Cholesky A = L L^T; returns -1 or the row of a
 * non-positive pivot. */
static int cholesky(bf_mac *m)
{
    const int n = m->nunk, bw = m->bw;
    for (int i = 0; i < n; i++) {
        int j0 = i - bw < 0 ? 0 : i - bw;
        for (int j = j0; j <= i; j++) {
            double s = *bel(m, m->band, i, i - j);
            int k0 = j - bw > j0 ? j - bw : j0;
            for (int k = k0; k < j; k++)
                s -= *bel(m, m->band, i, i - k) * *bel(m, m->band, j, j - k);
            if (j == i) {
                if (!(s > 1e-12 * *bel(m, m->band0, i, 0)))
                    return i;
                *bel(m, m->band, i, 0) = sqrt(s);
            } else {
                *bel(m, m->band, i, i - j) = s / *bel(m, m->band, j, 0);
            }
        }
    }
    return -1;
}

static void band_solve(bf_mac *m, const double *b, double *x)
{
    const int n = m->nunk, bw = m->bw;
    for (int i = 0; i < n; i++) {
        double s = b[i];
        int k0 = i - bw < 0 ? 0 : i - bw;
        for (int k = k0; k < i; k++)
            s -= *bel(m, m->band, i, i - k) * x[k];
        x[i] = s / *bel(m, m->band, i, 0);
    }
    for (int i = n - 1; i >= 0; i--) {
        double s = x[i];
        int k1 = i + bw > n - 1 ? n - 1 : i + bw;
        for (int k = i + 1; k <= k1; k++)
            s -= *bel(m, m->band, k, k - i) * x[k];
        x[i] = s / *bel(m, m->band, i, 0);
    }
}

/* r = b - A0 x with the unfactored matrix; returns max |r_k| / scale_k
 * (scale: |diag x_k| + sum |offdiag x_n| + |b_k|) and its row. */
static double residual(bf_mac *m, const double *x, double *r, int *worst)
{
    const int n = m->nunk, bw = m->bw;
    double rel = 0;
    *worst = 0;
    for (int i = 0; i < n; i++) {
        double ax = *bel(m, m->band0, i, 0) * x[i];
        double sc = fabs(ax) + fabs(m->rhs[i]);
        for (int d = 1; d <= bw; d++) {
            if (i - d >= 0) {
                double t = *bel(m, m->band0, i, d) * x[i - d];
                ax += t;
                sc += fabs(t);
            }
            if (i + d < n) {
                double t = *bel(m, m->band0, i + d, d) * x[i + d];
                ax += t;
                sc += fabs(t);
            }
        }
        r[i] = m->rhs[i] - ax;
        double q = sc > 0 ? fabs(r[i]) / sc : fabs(r[i]);
        if (!(q <= rel))
            rel = q, *worst = i;
    }
    return rel;
}

bf_status bf_mac_direct(bf_mac *m, double *pout, bf_err *err)
{
    int bi, bj;
    const int nyu = m->nj - 2;
    if (check_regions(m, &bi, &bj))
        return bf_fail(err, BF_ENOCONV,
                       "pressure undetermined: the fluid region containing "
                       "cell (%d,%d) touches no free surface and no inflow "
                       "pressure (fluid trapped between walls and empty "
                       "cells), so the exact pressure equation is singular",
                       bi, bj);
    assemble(m);
    const size_t nb = (size_t)m->nunk * (size_t)(m->bw + 1);
    memcpy(m->band0, m->band, nb * sizeof *m->band);
    int bad = cholesky(m);
    if (bad >= 0)
        return bf_fail(err, BF_ENOCONV,
                       "direct pressure solve: non-positive pivot at cell "
                       "(%d,%d); the pressure matrix is singular",
                       bad / nyu + 2, bad % nyu + 2);
    band_solve(m, m->rhs, m->sol);
    /* one step of iterative refinement, then the residual check */
    double *r = m->pn; /* scratch of at least nunk values */
    int worst;
    residual(m, m->sol, r, &worst);
    band_solve(m, r, r);
    for (int k = 0; k < m->nunk; k++)
        m->sol[k] += r[k];
    double rel = residual(m, m->sol, r, &worst);
    if (!(rel <= m->prm.direct_tol))
        return bf_fail(err, BF_ENOCONV,
                       "direct pressure solve: relative residual %.3g > "
                       "direct_tol = %g at cell (%d,%d)",
                       rel, m->prm.direct_tol, worst / nyu + 2, worst % nyu + 2);
    const int K = mac_consistent(m);
    if (pout != m->p)
        memcpy(pout, m->p, m->ncell * sizeof *pout);
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            size_t c = IX(i, j);
            if (m->ic[c] == BF_MAC_FULL) {
                double x = m->sol[unk(m, i, j)];
                pout[c] = K ? m->r[c] * x : x;
            }
        }
    return BF_OK;
}
