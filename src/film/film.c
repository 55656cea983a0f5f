/* film.c: the invariant (Lax-Wendroff-type) scheme for the two-phase
 * shallow-water film, Yasuda 2010 eqs 3.15-3.16 (see film.h for the model
 * and docs/models/film.md for the term-by-term reconstruction).
 *
 * For each phase k (s_d = +1, s_c = -1), with A = alpha_k h, u = u_k,
 * Q = P + s_k mu, everything on the right at level n:
 *
 * (3.15)  A_i^{n+1} = A_i - (F_{i+1/2} - F_{i-1/2}),
 *         F_{i+1/2} = dt/(2dx) (A_i u_i + A_{i+1} u_{i+1})
 *                   - dt^2/(2dx^2) [ ub^2 (A_{i+1} - A_i)
 *                                    + 2 ub Ab (u_{i+1} - u_i)
 *                                    + Ab (Q_{i+1} - Q_i) / rho_k ]
 *         (ub, Ab: arithmetic means of the two nodes).  The flux form is
 *         algebraically the printed scheme and makes the totals of A_d and
 *         A_c telescope: they are conserved to round-off (trapezoid
 *         weights, the wall ghosts make F_{-1/2} = -F_{1/2} exactly).
 *         The rounding error of A + dA is carried to the next step
 *         (compensated summation): without it, increments below half an
 *         ulp of A (the far field at small dt) are lost systematically and
 *         the totals drift by ~5e-14 per 1e5 steps of 1e-5 s.
 *
 * (3.16)  u_i^{n+1} = u_i - dt/(2dx) (u_{i+1} + u_{i-1})/2 (u_{i+1} - u_{i-1})
 *                   - dt/(2 rho_k dx) (Q*_{i+1} - Q*_{i-1})
 *                   + dt^2/(2dx^2) (G_{i+1/2} - G_{i-1/2}),
 *         G_{i+1/2} = (ub^2 + 2 nu/dt) (u_{i+1} - u_i)
 *                   + [ ub (Q_{i+1} - Q_i) + (W_{i+1} - W_i) ] / rho_k
 *         The 2 nu/dt part is the lateral viscosity nu u_xx of sec. 3.4,
 *         added once, explicitly.
 *
 * The one term the garbled print leaves in doubt is how mu enters the
 * dt^2/2 part of (3.16) (docs/models/film.md).  The exact Taylor term
 * is -(1/rho_k) d/dx(dQ/dt).  For the hydrostatic part dP/dt = -(P u_m)_x
 * exactly, so W = P u_m.  For mu the print puts mu into W = (P +- mu) u_m,
 * but dmu/dt is not -(mu u_m)_x.  Linearised about a uniform mixture
 * (psi0, beta = 2 alpha_d alpha_c, m = -a + 3b psi0^2 + gamma sigma,
 * sigma = 4 sin^2(theta/2)/dx^2, S = sin(theta)/dx) the phase-separation
 * mode (psi, w = u_d - u_c) of the printed reading has the amplification
 * determinant 1 - a + 2b with a = dt^2 beta sigma m/rho, b = dt^2 beta S^2
 * m/rho: it exceeds 1 for every theta < pi/2, so the mode grows unless the
 * viscosity damps it, and the scheme is first order in time there.  We
 * therefore offer (mu_taylor):
 *   midpoint (default)  Q* = P +- (mu^n + mu^{n+1})/2 in the gradient
 *                       term, W = P u_m.  mu^{n+1} comes from the already
 *                       updated (3.15); this supplies the exact mu_t term
 *                       (second order), and the determinant becomes
 *                       1 - (a - b) <= 1: stable for a <= 2, i.e.
 *                       dt <= dx sqrt(rho / (2 beta m_max)).
 *   um                  the printed reading, Q* = Q, W = (P +- mu) u_m.
 *   uk                  Q* = Q, W = (P +- mu) u_k.
 * In every variant W's P part is g (rho_d A_d u_d + rho_c A_c u_c), i.e.
 * P u_m without the division.
 *
 * h^{n+1} = A_d^{n+1} + A_c^{n+1} and alpha_k = A_k / h (so alpha_d +
 * alpha_c = 1), psi = (A_d - A_c)/h.  mu uses the 3-point Laplacian.
 *
 * Boundaries (sec. 3.4): one ghost node each side, scalars mirrored even
 * (f_{-1} = f_1), velocities odd (u_{-1} = -u_1, u_0 = 0).  (3.15) holds at
 * the wall nodes, (3.16) at interior nodes only.
 *
 * Negative volume fractions.  In the kink's far field alpha_minor ~ 1e-16;
 * the model is ill-posed for alpha < 0 (linearised, psi_tt = 4 alpha_d
 * alpha_c (...)_xx changes type).  With limit_positive, each phase's face
 * fluxes are limited so that no node loses more of that phase than it
 * holds: a node whose outgoing fluxes exceed its content scales them by
 * content/outflow (a positivity limiter in flux form).  It keeps the totals
 * conserved, changes nothing when no node would go negative (bit for bit),
 * and is counted (bf_film_limiter_counts) so that a run shows whether it
 * ever acted.  Without it, the step fails at the first negative fraction.
 *
 * Stable step (bf_film_stable_dt): gravity waves, Lax-Wendroff condition
 * with the viscous term, lambda^2 + 2 nu dt/dx^2 <= 1, lambda = dt (|u| +
 * sqrt(g h rho_m / rho_min))/dx; and the phase-separation mode above,
 * dt <= dx sqrt(rho_min / (2 beta m_max)) combined the same way.
 *
 * Layout: every node array has one ghost each side (index -1..N+1), face
 * arrays hold face i+1/2 at index i (-1..N).  One allocation; no
 * allocation per step; the loops are plain and branch-free so that GCC
 * vectorises them at -O2 (the storage: film_impl.h).
 *
 * This file is the scheme (create, state, stable step, step); the
 * diagnostics are in film_diag.c, the mirror projection in film_mirror.c,
 * the state arrays and the checkpoint in film_state.c.
 */
#include "ballfilm/film.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "film/film_impl.h"

static double *alloc_block(size_t n)
{
    /* 64-byte alignment of each array start (the ghost sits before it) */
    void *p = NULL;
    if (posix_memalign(&p, 64, n * sizeof(double)))
        return NULL;
    memset(p, 0, n * sizeof(double));
    return p;
}

bf_status bf_film_create(bf_film **out, const bf_film_params *p, bf_err *err)
{
    *out = NULL;
    double nd = p->length / p->dx;
    double nr = floor(nd + 0.5);
    if (!(nr >= 2) || fabs(nd - nr) > 1e-9 * nr)
        return bf_fail(err, BF_EINPUT,
                       "film length %g cm is not a whole number (>= 2) of "
                       "dx = %g cm (L/dx = %.12g)",
                       p->length, p->dx, nd);
    if (nr > 1e8)
        return bf_fail(err, BF_EINPUT, "film of %g nodes is too large", nr);
    bf_film *f = calloc(1, sizeof *f);
    if (!f)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    f->p = *p;
    f->N = (long)nr;
    /* 8 doubles in front (ghosts at -1, -2; index 0 64-byte aligned), N+1
     * nodes, ghosts and padding behind */
    size_t len = ((size_t)f->N + 1 + 8 + 16) & ~(size_t)7;
    f->len = len;
    f->mem = alloc_block(len * V_COUNT);
    f->zero = alloc_block(len);
    if (!f->mem || !f->zero) {
        free(f->mem);
        free(f->zero);
        free(f);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (int k = 0; k < V_COUNT; k++)
        f->v[k] = f->mem + (size_t)k * len + 8;
    const long N = f->N;
    double *x = ARR(f, V_X);
    /* x_i = (i - N/2) dx: x_(N-i) = -x_i exactly, so that a symmetric
     * set-up stays symmetric until the dynamics breaks it */
    for (long i = -1; i <= N + 1; i++)
        x[i] = ((double)i - 0.5 * (double)N) * p->dx;
    double *ad = ARR(f, V_AD), *ac = ARR(f, V_AC), *h = ARR(f, V_H);
    for (long i = -1; i <= N + 1; i++) {
        ad[i] = ac[i] = 0.5;
        h[i] = 1.0;
    }
    *out = f;
    return BF_OK;
}

void bf_film_free(bf_film *f)
{
    if (!f)
        return;
    free(f->mem);
    free(f->zero);
    free(f);
}

const bf_film_params *bf_film_params_of(const bf_film *f) { return &f->p; }
size_t bf_film_nodes(const bf_film *f) { return (size_t)f->N + 1; }
const double *bf_film_x(const bf_film *f) { return ARR(f, V_X); }
const double *bf_film_h(const bf_film *f) { return ARR(f, V_H); }
const double *bf_film_psi(const bf_film *f) { return ARR(f, V_PSI); }
const double *bf_film_u_d(const bf_film *f) { return ARR(f, V_UD); }
const double *bf_film_u_c(const bf_film *f) { return ARR(f, V_UC); }
const double *bf_film_ah_d(const bf_film *f) { return ARR(f, V_AD); }
const double *bf_film_ah_c(const bf_film *f) { return ARR(f, V_AC); }

/* h, psi from A_d, A_c on nodes lo..hi (one definition: the step and
 * set_state/load must produce the same bits). */
static void derive(long lo, long hi, const double *restrict ad,
                   const double *restrict ac, double *restrict h,
                   double *restrict psi)
{
    for (long i = lo; i <= hi; i++) {
        double hh = ad[i] + ac[i];
        h[i] = hh;
        psi[i] = (ad[i] - ac[i]) / hh;
    }
}

void bf_film_state_changed(bf_film *f)
{
    derive(0, f->N, ARR(f, V_AD), ARR(f, V_AC), ARR(f, V_H), ARR(f, V_PSI));
}

/* mirror ghosts: even for scalars, odd for velocities */
static inline void ghost_even(double *a, long N)
{
    a[-1] = a[1];
    a[N + 1] = a[N - 1];
}

static inline void ghost_odd(double *u, long N)
{
    u[-1] = -u[1];
    u[N + 1] = -u[N - 1];
}

bf_status bf_film_set_state(bf_film *f, const double *h, const double *psi,
                            const double *u_d, const double *u_c, bf_err *err)
{
    const long N = f->N;
    for (long i = 0; i <= N; i++) {
        if (!(h[i] > 0) || !isfinite(h[i]))
            return bf_fail(err, BF_EINPUT, "film node %ld (x = %g cm): h = %g "
                           "must be positive", i, ARR(f, V_X)[i], h[i]);
        if (!(psi[i] >= -1 && psi[i] <= 1))
            return bf_fail(err, BF_EINPUT, "film node %ld (x = %g cm): psi = "
                           "%g is outside [-1, 1]", i, ARR(f, V_X)[i], psi[i]);
        if (!isfinite(u_d[i]) || !isfinite(u_c[i]))
            return bf_fail(err, BF_EINPUT, "film node %ld: velocity not "
                           "finite", i);
    }
    double *ad = ARR(f, V_AD), *ac = ARR(f, V_AC);
    double *ud = ARR(f, V_UD), *uc = ARR(f, V_UC);
    for (long i = 0; i <= N; i++) {
        /* alpha_d = (1 + psi)/2, alpha_c = (1 - psi)/2 */
        ad[i] = 0.5 * (1.0 + psi[i]) * h[i];
        ac[i] = 0.5 * (1.0 - psi[i]) * h[i];
        ud[i] = u_d[i];
        uc[i] = u_c[i];
    }
    ud[0] = uc[0] = ud[N] = uc[N] = 0.0;
    memset(ARR(f, V_KD), 0, ((size_t)N + 1) * sizeof(double));
    memset(ARR(f, V_KC), 0, ((size_t)N + 1) * sizeof(double));
    derive(0, N, ad, ac, ARR(f, V_H), ARR(f, V_PSI));
    return BF_OK;
}

double bf_film_kink(const bf_film_params *p, double x0, double x)
{
    double psi_e = sqrt(p->a / p->b), xi = sqrt(p->gamma / p->a);
    return psi_e * tanh((x - x0) / (sqrt(2.0) * xi));
}

/* ------------------------------------------------------------ stability */

double bf_film_stable_dt(const bf_film *f, char *why, size_t cap)
{
    const bf_film_params *p = &f->p;
    const long N = f->N;
    const double *ad = ARR(f, V_AD), *ac = ARR(f, V_AC);
    const double *ud = ARR(f, V_UD), *uc = ARR(f, V_UC);
    const double rmin = fmin(p->rho_d, p->rho_c);
    const double lap = 4.0 * p->gamma / (p->dx * p->dx);
    double rg = 0.0, rs = 0.0; /* 1/dt of gravity waves, of separation */
    long ig = 0, is = 0;
    for (long i = 0; i <= N; i++) {
        double h = ad[i] + ac[i];
        double c = sqrt(p->g * (p->rho_d * ad[i] + p->rho_c * ac[i]) / rmin);
        double r = (fmax(fabs(ud[i]), fabs(uc[i])) + c) / p->dx;
        if (r > rg) {
            rg = r;
            ig = i;
        }
        double al = ad[i] / h, psi = 2.0 * al - 1.0;
        double beta = 2.0 * al * (1.0 - al);
        double m = fmax(-p->a + 3.0 * p->b * psi * psi, 0.0) + lap;
        double s = sqrt(2.0 * beta * m / rmin) / p->dx;
        if (s > rs) {
            rs = s;
            is = i;
        }
    }
    double R = fmax(rg, rs), B = 2.0 * p->nu / (p->dx * p->dx);
    /* R^2 dt^2 + B dt <= 1 */
    double dt = 2.0 / (B + sqrt(B * B + 4.0 * R * R));
    if (why && cap) {
        const double *x = ARR(f, V_X);
        if (rg >= rs)
            snprintf(why, cap,
                     "gravity-wave CFL: dt (|u| + sqrt(g h)) / dx <= 1 with "
                     "the viscous term, at node %ld (x = %g cm): "
                     "dx/(|u| + c) = %.4g s",
                     ig, x[ig], 1.0 / rg);
        else
            snprintf(why, cap,
                     "phase-separation mode: dt <= dx sqrt(rho / (2 beta "
                     "(-a + 3 b psi^2 + 4 gamma/dx^2))) at node %ld (x = %g "
                     "cm): %.4g s",
                     is, x[is], 1.0 / rs);
    }
    return dt;
}

/* ------------------------------------------------------------ the step */

/* Speed.  The loops below are written so that GCC vectorises them:
 * contiguous arrays, restrict pointers, no branches (selects instead), and
 * the per-step checks as a bitwise OR of the values' bit patterns (sign
 * bit: a negative value; exponent bits of x*0: a non-finite one), which the
 * vectoriser accepts where it rejects a comparison reduction.  GCC 12 at
 * -O2 uses the "very cheap" cost model, which rejects every loop that needs
 * an epilogue; the "cheap" model is enabled for this file's hot loops, and
 * bf_film_step_invariant is cloned for AVX2 and AVX-512 (picked at load
 * time by the CPU; the SSE2 version elsewhere).  Vectorising element-wise
 * arithmetic changes no bit of the results: no reduction is reordered and
 * nothing is contracted (-ffp-contract=off), so every clone gives the same
 * numbers.  Each pass runs over the whole film before the next one starts.
 * The arrays start 64-byte aligned at index 0, and so do the vector loops
 * that store into them: an AVX-512 store off that alignment straddles two
 * cache lines (costs ~10% of the step).
 * Measured on the 501-node film and not kept: sweeping the passes over
 * blocks of 48 nodes, each pass lagging the one it depends on, to keep a
 * block's data in the L1 cache (25-30% slower: the per-block set-up of
 * five vector loops cost more than the L2 traffic it saved); the passes
 * written by hand with GCC's vector extension, eight nodes a chunk (5%
 * faster on AVX-512, but 2-3 times slower in the AVX2 and SSE2 clones,
 * and 5% slower than these loops when written at each clone's width). */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("vect-cost-model=cheap")
#endif

#define HOT static inline __attribute__((always_inline))

HOT uint64_t bits_of(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

/* the OR of bits_of(x) (in s) and bits_of(x*0) (in z) over values is "bad"
 * if its sign bit is set (some value < 0 or -0) or its exponent is all
 * ones (some value inf or NaN) */
static int bits_bad(uint64_t s, uint64_t z)
{
    const uint64_t expo = 0x7ff0000000000000ull;
    return (s >> 63) != 0 || (z & expo) == expo;
}

/* Positivity limiter for one phase (see the file comment).  F holds the
 * face fluxes (face i+1/2 at i, i = -1..N, ghost faces mirrored); A the
 * content at level n; s is scratch.  Returns the number of faces changed.
 * Rarely called; scalar. */
static unsigned long long limit_phase(long N, const double *A, double *F,
                                      double *s)
{
    const double keep = 1.0 - 8.0 * DBL_EPSILON;
    for (long i = 0; i <= N; i++) {
        double out;
        if (i == 0)
            out = 2.0 * fmax(F[0], 0.0);
        else if (i == N)
            out = 2.0 * fmax(-F[N - 1], 0.0);
        else
            out = fmax(F[i], 0.0) + fmax(-F[i - 1], 0.0);
        s[i] = out > A[i] ? (A[i] > 0 ? keep * A[i] / out : 0.0) : 1.0;
    }
    unsigned long long changed = 0;
    for (long i = 0; i < N; i++) {
        double si = F[i] > 0 ? s[i] : s[i + 1];
        if (si < 1.0) {
            F[i] *= si;
            changed++;
        }
    }
    F[-1] = -F[0];
    F[N] = -F[N - 1];
    return changed;
}

static int any_negative(long N, const double *a)
{
    for (long i = 0; i <= N; i++)
        if (a[i] < 0)
            return 1;
    return 0;
}

/* Everything one step reads and writes. */
typedef struct step_ctx {
    long N;
    double c1, c2, ird, irc, visc, g, rd, rc, a, b, gl, va;
    const double *ad, *ac, *ud, *uc, *psi, *mc;
    double *mu, *wd, *wc, *Fd, *Fc, *Gd, *Gc;
    double *ad1, *ac1, *h1, *psi1, *mus, *ud1, *uc1;
    const double *kd, *kc;
    double *kd1, *kc1;
} step_ctx;

/* mu (3.8) on nodes lo..hi (of -1..N+1), and for the um and uk variants
 * W = (P +- mu) u; inlined with a constant `variant`: one branch-free
 * loop each.  P = g (rho_d A_d + rho_c A_c) is not stored: the passes
 * that need its differences form them from A (fewer arrays to stream). */
HOT void node_loop(int variant, long lo, long hi, double a, double b,
               double gl, double g, double rd, double rc,
               const double *restrict ad, const double *restrict ac,
               const double *restrict ud, const double *restrict uc,
               const double *restrict psi, const double *restrict mc,
               long moff, double *restrict mu, double *restrict wd,
               double *restrict wc)
{
    for (long i = lo; i <= hi; i++) {
        double ps = psi[i];
        double m = ps * (b * ps * ps - a) -
                   gl * ((psi[i + 1] - ps) - (ps - psi[i - 1])) + mc[i + moff];
        mu[i] = m;
        if (variant == BF_FILM_MU_UM) {
            double md = rd * ad[i], mcc = rc * ac[i], pp = g * (md + mcc);
            double um = (md * ud[i] + mcc * uc[i]) / (md + mcc);
            wd[i] = (pp + m) * um;
            wc[i] = (pp - m) * um;
        } else if (variant == BF_FILM_MU_UK) {
            double pp = g * (rd * ad[i] + rc * ac[i]);
            wd[i] = (pp + m) * ud[i];
            wc[i] = (pp - m) * uc[i];
        }
    }
}

/* the densities, or the constant 1 in the unit-density sweep (see sweep) */
#define RHO(unit, r) ((unit) ? 1.0 : (r))

/* moff: mu_cpl is read at node i + moff (the caller's array has no ghost
 * nodes: its mirror image at a wall ghost is two nodes inwards) */
HOT void node_pass(const step_ctx *c, int variant, int unit, long lo, long hi,
                   long moff)
{
    node_loop(variant, lo, hi, c->a, c->b, c->gl, c->g, RHO(unit, c->rd),
              RHO(unit, c->rc), c->ad, c->ac, c->ud, c->uc, c->psi, c->mc,
              moff, c->mu, c->wd, c->wc);
}

/* Face fluxes F of (3.15) and G of (3.16) at faces i+1/2, i = lo..hi (of
 * -1..N).  Midpoint variant: W = P u_m = g (rho_d A_d u_d + rho_c A_c u_c)
 * for both phases, from the fluxes A u formed here; otherwise W from the
 * node pass. */
HOT void face_loop(int variant, long lo, long hi, double c1, double c2,
               double ird, double irc, double visc, double g, double rd,
               double rc, const double *restrict mu,
               const double *restrict ad, const double *restrict ac,
               const double *restrict ud, const double *restrict uc,
               const double *restrict wd, const double *restrict wc,
               double *restrict Fd, double *restrict Fc, double *restrict Gd,
               double *restrict Gc)
{
    for (long i = lo; i <= hi; i++) {
        double fd0 = ad[i] * ud[i], fd1 = ad[i + 1] * ud[i + 1];
        double fc0 = ac[i] * uc[i], fc1 = ac[i + 1] * uc[i + 1];
        double dad = ad[i + 1] - ad[i], dac = ac[i + 1] - ac[i];
        double dP = g * (rd * dad + rc * dac), dm = mu[i + 1] - mu[i];
        double dwd, dwc;
        if (variant == BF_FILM_MU_MIDPOINT) {
            dwd = g * (rd * (fd1 - fd0) + rc * (fc1 - fc0));
            dwc = dwd;
        } else {
            dwd = wd[i + 1] - wd[i];
            dwc = wc[i + 1] - wc[i];
        }
        /* phase d */
        double ub = 0.5 * (ud[i] + ud[i + 1]), u2 = ub * ub;
        double du = ud[i + 1] - ud[i];
        double ab = 0.5 * (ad[i] + ad[i + 1]);
        double dq = dP + dm;
        Fd[i] = c1 * (fd0 + fd1) -
                c2 * (u2 * dad + 2.0 * ub * ab * du + ab * dq * ird);
        Gd[i] = (u2 + visc) * du + (ub * dq + dwd) * ird;
        /* phase c */
        ub = 0.5 * (uc[i] + uc[i + 1]);
        u2 = ub * ub;
        du = uc[i + 1] - uc[i];
        ab = 0.5 * (ac[i] + ac[i + 1]);
        dq = dP - dm;
        Fc[i] = c1 * (fc0 + fc1) -
                c2 * (u2 * dac + 2.0 * ub * ab * du + ab * dq * irc);
        Gc[i] = (u2 + visc) * du + (ub * dq + dwc) * irc;
    }
}

HOT void face_pass(const step_ctx *c, int variant, int unit, long lo, long hi)
{
    face_loop(variant, lo, hi, c->c1, c->c2, RHO(unit, c->ird),
              RHO(unit, c->irc), c->visc, c->g, RHO(unit, c->rd),
              RHO(unit, c->rc), c->mu, c->ad, c->ac, c->ud, c->uc, c->wd, c->wc,
              c->Fd, c->Fc, c->Gd, c->Gc);
}

/* (3.15) for both phases on nodes lo..hi (of 0..N), with h and psi of the
 * new level; returns non-zero if a content may be negative or a value is
 * not finite (a quick check: -0 also counts). */
HOT int update_loop(long lo, long hi, const double *restrict ad,
                const double *restrict ac, const double *restrict Fd,
                const double *restrict Fc, const double *restrict kd,
                const double *restrict kc, double *restrict ad1,
                double *restrict ac1, double *restrict kd1,
                double *restrict kc1, double *restrict h1,
                double *restrict psi1)
{
    uint64_t s = 0, z = 0;
    for (long i = lo; i <= hi; i++) {
        /* A + dA with the rounding error of the sum kept (Knuth's
         * TwoSum) and added to the next step's increment: an increment
         * below half an ulp of A is then not lost, and the totals cannot
         * drift by round-off (5e6 steps of the coupled run) */
        double ia = kd[i] - (Fd[i] - Fd[i - 1]);
        double ic = kc[i] - (Fc[i] - Fc[i - 1]);
        double a = ad[i] + ia, cc = ac[i] + ic;
        double ba = a - ad[i], bc = cc - ac[i];
        kd1[i] = (ad[i] - (a - ba)) + (ia - ba);
        kc1[i] = (ac[i] - (cc - bc)) + (ic - bc);
        double h = a + cc;
        double ps = (a - cc) / h;
        ad1[i] = a;
        ac1[i] = cc;
        h1[i] = h;
        psi1[i] = ps;
        s |= bits_of(a) | bits_of(cc);
        z |= bits_of(ps * 0.0);
    }
    return bits_bad(s, z);
}

HOT int update_pass(const step_ctx *c, long lo, long hi)
{
    return update_loop(lo, hi, c->ad, c->ac, c->Fd, c->Fc, c->kd, c->kc,
                       c->ad1, c->ac1, c->kd1, c->kc1, c->h1, c->psi1);
}

/* Midpoint variant: mu* = (mu^n + mu^{n+1})/2 on nodes lo..hi (of 0..N);
 * mu^{n+1} from psi^{n+1} (its ghosts set by the caller). */
HOT void midmu_loop(long lo, long hi, double a, double b, double gl,
                const double *restrict psi1, const double *restrict mc,
                const double *restrict mu, double *restrict mus)
{
    for (long i = lo; i <= hi; i++) {
        double ps = psi1[i];
        double m1 = ps * (b * ps * ps - a) -
                    gl * ((psi1[i + 1] - ps) - (ps - psi1[i - 1])) + mc[i];
        mus[i] = 0.5 * (mu[i] + m1);
    }
}

HOT void midmu_pass(const step_ctx *c, long lo, long hi)
{
    midmu_loop(lo, hi, c->a, c->b, c->gl, c->psi1, c->mc, c->mu, c->mus);
}

/* (3.16) at nodes lo..hi (of 1..N-1); mus: mu* of the pressure gradient.
 * A vanishing phase (alpha_k < vanish) takes the other phase's velocity.
 * Returns non-zero if a velocity is not finite. */
HOT int velocity_loop(long lo, long hi, double c1, double c2, double ird,
                  double irc, double va, double g, double rd, double rc,
                  const double *restrict ad, const double *restrict ac,
                  const double *restrict mus, const double *restrict ud,
                  const double *restrict uc, const double *restrict Gd,
                  const double *restrict Gc, const double *restrict ad1,
                  const double *restrict ac1, const double *restrict h1,
                  double *restrict ud1, double *restrict uc1)
{
    uint64_t z = 0;
    for (long i = lo; i <= hi; i++) {
        double dP = g * (rd * (ad[i + 1] - ad[i - 1]) +
                         rc * (ac[i + 1] - ac[i - 1]));
        double dm = mus[i + 1] - mus[i - 1];
        double v = ud[i], vp = ud[i + 1], vm = ud[i - 1];
        double nd = v - c1 * (0.5 * (vp + vm)) * (vp - vm) -
                    c1 * ird * (dP + dm) + c2 * (Gd[i] - Gd[i - 1]);
        v = uc[i];
        vp = uc[i + 1];
        vm = uc[i - 1];
        double nc = v - c1 * (0.5 * (vp + vm)) * (vp - vm) -
                    c1 * irc * (dP - dm) + c2 * (Gc[i] - Gc[i - 1]);
        double vh = va * h1[i];
        ud1[i] = ad1[i] < vh ? nc : nd;
        uc1[i] = ac1[i] < vh ? nd : nc;
        z |= bits_of(nd * 0.0) | bits_of(nc * 0.0);
    }
    return bits_bad(0, z);
}

HOT int velocity_pass(const step_ctx *c, int unit, const double *mus, long lo,
                      long hi)
{
    return velocity_loop(lo, hi, c->c1, c->c2, RHO(unit, c->ird),
                         RHO(unit, c->irc), c->va, c->g, RHO(unit, c->rd),
                         RHO(unit, c->rc), c->ad, c->ac, mus, c->ud, c->uc, c->Gd,
                         c->Gc, c->ad1, c->ac1, c->h1, c->ud1, c->uc1);
}

/* Locate the first bad value after a step whose quick check failed and
 * describe it; BF_OK if there is none (the quick check also flags -0). */
static bf_status report_bad(const bf_film *f, const double *ad1,
                            const double *ac1, const double *ud1,
                            const double *uc1, bf_err *err)
{
    const long N = f->N;
    const double *x = ARR(f, V_X);
    for (long i = 0; i <= N; i++) {
        double h = ad1[i] + ac1[i];
        if (!isfinite(ad1[i]) || !isfinite(ac1[i]) || !isfinite(ud1[i]) ||
            !isfinite(uc1[i]))
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): non-finite value "
                           "(alpha_d h = %g, alpha_c h = %g, u_d = %g, u_c = "
                           "%g cm/s)",
                           i, x[i], ad1[i], ac1[i], ud1[i], uc1[i]);
        if (!(h > 0))
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): h = %g <= 0", i, x[i],
                           h);
        if (ad1[i] < 0 || ac1[i] < 0)
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): volume fraction "
                           "alpha_%c = %.3g outside [0, 1] (alpha_d h = %g, "
                           "alpha_c h = %g); the model is ill-posed there "
                           "(set [film] positivity = limit)",
                           i, x[i], ad1[i] < 0 ? 'd' : 'c',
                           (ad1[i] < 0 ? ad1[i] : ac1[i]) / h, ad1[i], ac1[i]);
    }
    return BF_OK;
}

/* The whole step for one variant (inlined with a constant `variant`).
 * With unit = 1 (rho_d = rho_c = 1, as in all of the paper's scenes) the
 * densities and their inverses are the constant 1 and GCC drops the
 * multiplications by them: x * 1.0 is x exactly, so this sweep gives the
 * same bits as the general one with ten floating-point operations fewer
 * per node (~8% of the step). */
HOT int sweep(bf_film *f, step_ctx *c, int variant, int unit)
{
    const long N = c->N;
    const int mid = variant == BF_FILM_MU_MIDPOINT;
    const double *mus = mid ? c->mus : c->mu;
    /* one pass after the other over the whole film (see "Speed"); the
     * vector loops start at index 0 (64-byte aligned) so that their stores
     * do not straddle cache lines: the ghost node -1 and face -1 go first
     * on their own, and the velocities of nodes 1..7; the ghost nodes read
     * mu_cpl at their mirror images 1 and N - 1 */
    node_pass(c, variant, unit, -1, -1, 2);
    node_pass(c, variant, unit, 0, N, 0);
    node_pass(c, variant, unit, N + 1, N + 1, -2);
    face_pass(c, variant, unit, -1, -1);
    face_pass(c, variant, unit, 0, N);
    int bad = update_pass(c, 0, N);
    if (mid) {
        ghost_even(c->psi1, N);
        midmu_pass(c, 0, N);
    }
    const long v8 = N - 1 < 7 ? N - 1 : 7;
    int badu = velocity_pass(c, unit, mus, 1, v8);
    badu |= velocity_pass(c, unit, mus, v8 + 1, N - 1);
    if (bad && f->p.limit_positive &&
        (any_negative(N, c->ad1) || any_negative(N, c->ac1))) {
        /* some content would go negative: limit the fluxes of that phase
         * and redo what depends on them (scratch: the new mu) */
        unsigned long long nf = 0;
        if (any_negative(N, c->ad1))
            nf += limit_phase(N, c->ad, c->Fd, c->mus);
        if (any_negative(N, c->ac1))
            nf += limit_phase(N, c->ac, c->Fc, c->mus);
        f->lim_steps++;
        f->lim_faces += nf;
        bad = update_pass(c, 0, N);
        if (mid) {
            ghost_even(c->psi1, N);
            midmu_pass(c, 0, N);
        }
        badu = velocity_pass(c, unit, mus, 1, N - 1);
    }
    c->ud1[0] = c->uc1[0] = c->ud1[N] = c->uc1[N] = 0.0;
    return bad | badu;
}

#if defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
bf_status bf_film_step_invariant(bf_film *f, double dt, const double *mu_cpl,
                                 bf_err *err)
{
    const bf_film_params *p = &f->p;
    const long N = f->N;
    step_ctx c = {
        .N = N,
        .c1 = dt / (2.0 * p->dx),
        .c2 = dt * dt / (2.0 * p->dx * p->dx),
        .ird = 1.0 / p->rho_d,
        .irc = 1.0 / p->rho_c,
        .visc = 2.0 * p->nu / dt,
        .g = p->g,
        .rd = p->rho_d,
        .rc = p->rho_c,
        .a = p->a,
        .b = p->b,
        .gl = p->gamma / (p->dx * p->dx),
        .va = p->vanish,
        .ad = ARR(f, V_AD), .ac = ARR(f, V_AC),
        .ud = ARR(f, V_UD), .uc = ARR(f, V_UC),
        .psi = ARR(f, V_PSI), .mc = mu_cpl ? mu_cpl : f->zero + 8,
        .mu = ARR(f, V_MU),
        .wd = ARR(f, V_WD), .wc = ARR(f, V_WC),
        .Fd = ARR(f, V_FD), .Fc = ARR(f, V_FC),
        .Gd = ARR(f, V_GD), .Gc = ARR(f, V_GC),
        .ad1 = ARR(f, V_AD1), .ac1 = ARR(f, V_AC1),
        .h1 = ARR(f, V_H1), .psi1 = ARR(f, V_PSI1),
        .mus = ARR(f, V_MU1),
        .ud1 = ARR(f, V_UD1), .uc1 = ARR(f, V_UC1),
        .kd = ARR(f, V_KD), .kc = ARR(f, V_KC),
        .kd1 = ARR(f, V_KD1), .kc1 = ARR(f, V_KC1),
    };
    /* ghosts of level n: psi needs two (mu on -1..N+1); mu_cpl none (the
     * node pass reads it at the ghosts' mirror images) */
    ghost_even(ARR(f, V_AD), N);
    ghost_even(ARR(f, V_AC), N);
    ghost_odd(ARR(f, V_UD), N);
    ghost_odd(ARR(f, V_UC), N);
    double *psi = ARR(f, V_PSI);
    ghost_even(psi, N);
    psi[-2] = psi[2];
    psi[N + 2] = psi[N - 2];

    int bad;
    const int unit = p->rho_d == 1.0 && p->rho_c == 1.0;
    switch (p->mu_taylor) {
    case BF_FILM_MU_MIDPOINT:
        bad = unit ? sweep(f, &c, BF_FILM_MU_MIDPOINT, 1)
                   : sweep(f, &c, BF_FILM_MU_MIDPOINT, 0);
        break;
    case BF_FILM_MU_UM:
        bad = unit ? sweep(f, &c, BF_FILM_MU_UM, 1)
                   : sweep(f, &c, BF_FILM_MU_UM, 0);
        break;
    default:
        bad = unit ? sweep(f, &c, BF_FILM_MU_UK, 1)
                   : sweep(f, &c, BF_FILM_MU_UK, 0);
        break;
    }

    /* the new level becomes the current one (also on failure, so that the
     * caller sees the failed state) */
    double *t;
#define SWAP(a, b) (t = f->v[a], f->v[a] = f->v[b], f->v[b] = t)
    SWAP(V_AD, V_AD1);
    SWAP(V_AC, V_AC1);
    SWAP(V_UD, V_UD1);
    SWAP(V_UC, V_UC1);
    SWAP(V_H, V_H1);
    SWAP(V_PSI, V_PSI1);
    SWAP(V_KD, V_KD1);
    SWAP(V_KC, V_KC1);
#undef SWAP
    if (bad)
        return report_bad(f, ARR(f, V_AD), ARR(f, V_AC), ARR(f, V_UD),
                          ARR(f, V_UC), err);
    return BF_OK;
}

#undef HOT
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
