/* implicit.h: one step of Greenspan's implicit scheme (1973, eqs 2.1-2.3)
 * with the discrete force of dforce.h:
 *
 *   (v^{k+1} + v^k)/2 = (x^{k+1} - x^k)/dt                      (2.1)
 *   mu (v^{k+1} - v^k)/dt = F(x^k, x^{k+1})                      (2.2-2.3)
 *
 * for the free particles (fixed ones keep x and v).  mu is the inertia of
 * the update: the mass (the text, F = m a) or 1 (the listing, which adds
 * dt F to v without dividing by m).  When both hold exactly, K + V is
 * conserved exactly (dforce.h); the residual of the solve is the only
 * energy error.
 *
 * Solvers:
 *   fixed_point  the listing's relaxed iteration (MAIN loop 75-120):
 *       x^(n) = (1-w) x^(n-1) + w [x^k + dt/2 (v^(n-1) + v^k)]
 *       v^(n) = (1-w) v^(n-1) + w [v^k + dt F(x^k, x^(n)) / mu]
 *     from x^(0) = x^k, v^(0) = v^k, until every |dx|, |dv| <= tol;
 *   newton  the text's choice: unknowns D = x^{k+1} - x^k,
 *       G(D) = (2 mu/dt^2)(D - dt v^k) - F(x^k, x^k + D) = 0,
 *     from D = dt v^k, with the analytic Jacobian (dense LU, or sparse
 *     GMRES with pairs beyond a cutoff left out of the Jacobian, which
 *     only slows the convergence, not the solution) and a backtracking
 *     line search on |G|; stops when every |dD| and |dv| = 2|dD|/dt is
 *     <= tol; then v^{k+1} = 2D/dt - v^k.
 * Both stop with BF_ENOCONV (state unchanged, the message says how far the
 * last iterate moved and where) after max_iter iterations or when an
 * iterate is not finite.
 */
#ifndef BALLFILM_PARTICLES_IMPLICIT_H
#define BALLFILM_PARTICLES_IMPLICIT_H

#include "particles/dforce.h"
#include "ballfilm/error.h"

typedef enum bf_implicit_method {
    BF_IMPLICIT_FIXED_POINT = 0,
    BF_IMPLICIT_NEWTON = 1
} bf_implicit_method;

typedef struct bf_implicit_opts {
    bf_implicit_method method;
    double omega;      /* relaxation of the fixed point, (0, 1] */
    double tol;        /* absolute, on the change of x and v per iteration */
    int max_iter;
    int sparse;        /* Newton: sparse Jacobian and GMRES */
    double jac_cutoff; /* sparse Jacobian: pairs farther apart left out */
} bf_implicit_opts;

typedef struct bf_implicit bf_implicit;

bf_status bf_implicit_create(bf_implicit **out, const bf_dforce *f,
                             const bf_implicit_opts *o, bf_err *err);
void bf_implicit_free(bf_implicit *s);

/* Advance (x, y, vx, vy) from time k to k+1 in place; *iters gets the
 * number of iterations.  On BF_ENOCONV the state is unchanged. */
bf_status bf_implicit_step(bf_implicit *s, const bf_dforce *f,
                           const double *mu, double *x, double *y, double *vx,
                           double *vy, double dt, int *iters, bf_err *err);

#endif
