/* coupling.h: balls coupled to the film through a free energy (Yasuda
 * 2010, eqs 3.10-3.12), private to the library.  For a ball p at r_p with
 * radius R_p:
 *
 *   (3.10)  F_p = 4 pi R_p^2 V0 I(r_p),
 *           I(r) = integral h(x) (psi(x) - psi_s)^2 exp(-|x - r|/r0) dx
 *           (V(s) = V0 exp(-|s|/r0))
 *   (3.12)  dv_p/dt = -M dF_p/dr_p + (contact forces)/m_p
 *   (3.11)  mu_cpl(x) = sum_p 8 pi R_p^2 V0 exp(-|x - r_p|/r0) (psi - psi_s)
 *           (added to the film's mu)
 *
 * The integrand g = h (psi - psi_s)^2 is taken on the film's nodes and
 * interpolated by the natural cubic spline (the paper's "third-order
 * spline"; `quadrature = linear` drops the spline's curvature terms), and
 * integrated exactly against the kernel (`quadrature = nodes` instead
 * splines the integral's node sums, nodes.h), piecewise on each side of r (the
 * kernel has a kink there): I = L + R with
 *   L(r) = integral_{x < r} g exp(-(r - x)/r0) dx,
 *   R(r) = integral_{x > r} g exp(-(x - r)/r0) dx,
 *   dI/dr = (R - L)/r0   (exact: the kernel is continuous at x = r).
 * The moments a ball needs (the kernel's integrals of the interpolant on
 * each side of its cell, and the spline's M there) are linear in g: dot
 * products with rows built once per node.  Per film level g is formed
 * (bf_coupling_refresh) and, lazily, the moments at the cells holding
 * balls; a force evaluation then costs O(1).
 *
 * The folder src/coupling holds one job per file: this header and
 * coupling.c, the quadrature of F and dF/dr (the bf_coupling object: cell
 * and row moments, the integral, the Taylor anchors, its checkpoint), with
 * mk.h, the kernel's moments m_k(z) it integrates with; nodes.h, the
 * quadrature `nodes`;
 * mu_cpl.h, the chemical potential (3.11) the balls add to the film;
 * force.h, the effect "coupling" that applies -M dF/dr to the ball system
 * (its `self` is the bf_coupling), with the keys of [coupling].  Both use
 * this file only.  The same code serves the static kink (film never
 * stepped) and the dynamic film.
 */
#ifndef BALLFILM_COUPLING_COUPLING_H
#define BALLFILM_COUPLING_COUPLING_H

#include <stddef.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/film.h"

typedef enum bf_coupling_quad {
    BF_COUPLING_SPLINE = 0, /* natural cubic spline of g (default) */
    BF_COUPLING_LINEAR,     /* piecewise linear g */
    BF_COUPLING_NODES       /* the integral summed at the nodes, then
                               splined (nodes.h) */
} bf_coupling_quad;

typedef struct bf_coupling_params {
    double V0;    /* g/(cm^3 s^2), as in the paper */
    double r0;    /* cm */
    double M;     /* mobility, 1/g */
    double psi_s; /* order parameter of the ball surface */
    bf_coupling_quad quad;
    /* balls whose trial positions stay within taylor_radius of the first
     * position evaluated after a refresh use a 5th-order Taylor expansion
     * of L and R (exact to < 1e-17 relative); 0 disables it */
    double taylor_radius; /* cm */
} bf_coupling_params;

typedef struct bf_coupling bf_coupling;

bf_status bf_coupling_create(bf_coupling **c, const bf_coupling_params *p,
                             const bf_film *film, size_t nballs, bf_err *err);
void bf_coupling_free(bf_coupling *c);
const bf_coupling_params *bf_coupling_params_of(const bf_coupling *c);
/* The film it reads (its current level). */
const bf_film *bf_coupling_film(const bf_coupling *c);

/* The film's grid as the kernel sees it, and the kernel's tables (fixed
 * at creation; read by mu_cpl.c). */
typedef struct bf_coupling_grid {
    long N;          /* intervals: nodes 0..N */
    long K;          /* E^K < 2^-64 (E = exp(-kappa)): farther cells count
                        for nothing */
    double x0, dx;   /* first node and spacing, cm */
    double kappa;    /* dx / r0 */
    double *pw, *pwr; /* E^k (k = 0..N) and E^(N-1-k) (k < N), flushed to
                         zero below 1e-300; owned by the coupling */
} bf_coupling_grid;
const bf_coupling_grid *bf_coupling_grid_of(const bf_coupling *c);

/* The cell j of r (0 <= j < N) and its local coordinate t = (r - x_j)/dx,
 * in [0, 1] inside the film (t < 0 left of it, t > 1 right of it). */
static inline long bf_coupling_locate(const bf_coupling_grid *g, double r,
                                      double *t)
{
    double u = (r - g->x0) / g->dx;
    /* truncation instead of floor() (a library call here): the same for
     * u >= 0, and for u < 0 both are clamped to 0.  Clamped before the
     * conversion, which is undefined for NaN and for u beyond long's
     * range (a blown-up or edited ball position): j = 0 then, and t is
     * NaN for the caller's checks */
    long j = 0;
    if (u >= (double)(g->N - 1))
        j = g->N - 1;
    else if (u > 0)
        j = (long)u;
    *t = u - (double)j;
    return j;
}

/* exp(-kappa t) and exp(-kappa (1 - t)) of ball p as the last
 * bf_coupling_prepare computed them, if it was at x then (returns 1; 0:
 * not prepared there). */
int bf_coupling_prepared_exp(const bf_coupling *c, size_t p, double x,
                             double *el, double *er);

/* Rebuild everything that depends on the film's current level (call after
 * each film step; the ball integrator's force cache must be invalidated by
 * the caller, bf_ode.epoch). */
void bf_coupling_refresh(bf_coupling *c);

/* After a refresh, for balls at x (in increasing order): the moments at
 * their cells by two full sums and short recurrences between neighbours
 * (instead of two full sums per ball), and with taylor_radius > 0 each
 * ball's Taylor anchor at x, used by its next evaluation if that comes at
 * the same position (the integrator's first, at the start of the step).
 * Optional: an optimisation; the anchors give the bits of the lazy ones. */
void bf_coupling_prepare(bf_coupling *c, size_t nb, const double *x);

/* I(r) and dI/dr (see above), exact for the interpolated g. */
void bf_coupling_integral(bf_coupling *c, double r, double *I, double *dI);
/* The same for ball `p` (may use its Taylor anchor). */
void bf_coupling_integral_ball(bf_coupling *c, size_t p, double r, double *I,
                               double *dI);

/* Natural cubic spline second derivatives of the current g (for tests;
 * computed on demand). */
const double *bf_coupling_spline_m(bf_coupling *c);
const double *bf_coupling_g(const bf_coupling *c);

/* Counters: exact evaluations and Taylor evaluations since creation. */
void bf_coupling_counts(const bf_coupling *c, unsigned long long *exact,
                        unsigned long long *taylor);

/* Checkpoint: the per-ball Taylor anchors and the counters (everything
 * else is rebuilt from the film by bf_coupling_refresh; load after the
 * film), under names starting with prefix + "coupling". */
bf_status bf_coupling_save(const bf_coupling *c, bf_ckpt *ck,
                           const char *prefix, bf_err *err);
bf_status bf_coupling_load(bf_coupling *c, const bf_ckpt *ck,
                           const char *prefix, bf_err *err);

#endif
