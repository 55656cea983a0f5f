/* film_mol.h: the film's equations (film.h) in method-of-lines form on
 * the grid of the invariant scheme: dy/dt = f(y) for y = (alpha_d h,
 * alpha_c h, u_d, u_c) on the nodes, the limit dt -> 0 of the invariant
 * scheme (3.15)-(3.16), so that an ODE integrator at tight tolerance on it
 * gives the time-exact solution of the scheme's space discretisation
 * (docs/models/film.md, "Method of lines").  Private to the library
 * (the film's ARKODE integrators in src/models/filmsys.c use it).
 *
 * Layout of y: node after node, y[4i + 0..3] = A_d, A_c, u_d, u_c at node
 * i = 0..N, so that the Jacobian is banded (bf_film_mol_bandwidth). */
#ifndef BALLFILM_FILM_MOL_H
#define BALLFILM_FILM_MOL_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/film.h"

/* Which terms a right-hand side evaluates (IMEX splittings). */
typedef enum bf_film_mol_part {
    BF_FILM_MOL_ALL = 0,      /* the whole right-hand side */
    BF_FILM_MOL_EXPLICIT = 1, /* the non-stiff part of the splitting */
    BF_FILM_MOL_IMPLICIT = 2  /* the stiff part */
} bf_film_mol_part;

/* The IMEX splittings offered ([film] imex_implicit). */
typedef enum bf_film_mol_split {
    /* implicit: every term of the phase-separation and gravity waves (the
     * phase fluxes (A_k u_k)_x, the gradients of P and mu, the viscosity);
     * explicit: the self-advection u_k (u_k)_x only */
    BF_FILM_MOL_WAVES = 0,
    /* implicit: the gamma psi_xx part of mu (its gradient in the velocity
     * equations) and the viscosity nu u_xx; explicit: the rest */
    BF_FILM_MOL_CAPILLARY = 1
} bf_film_mol_split;

typedef struct bf_film_mol bf_film_mol;

/* A right-hand side for the film f (its parameters and grid; the film's
 * state is not read). */
bf_status bf_film_mol_create(bf_film_mol **m, const bf_film *f, bf_err *err);
void bf_film_mol_free(bf_film_mol *m);

/* Length of y, 4 (N + 1), and the half-bandwidth of df/dy in that
 * layout (the gradient of mu reaches two nodes to each side). */
size_t bf_film_mol_size(const bf_film_mol *m);
long bf_film_mol_bandwidth(void);

/* The film's state into y, and y into the film's state (h and psi
 * derived, the rounding carries of the invariant scheme zeroed). */
void bf_film_mol_pack(const bf_film *f, double *y);
void bf_film_mol_unpack(bf_film *f, const double *y);

/* The vanish rule of the scheme, applied to y after a step: where a
 * phase is absent (alpha_k < vanish) its velocity becomes the other's (the
 * right-hand side moves it with the other; this removes what it had
 * before the node entered the rule). */
void bf_film_mol_vanish(const bf_film_mol *m, double *y);

/* dy/dt (or the part `part` of it under `split`) at y, with the coupling
 * chemical potential mu_cpl on the nodes 0..N (NULL: none).  Returns 0,
 * or 1 (a recoverable failure: ARKODE retries a smaller step) if h <= 0
 * or a value is not finite at some node. */
int bf_film_mol_rhs(bf_film_mol *m, const double *y, const double *mu_cpl,
                    bf_film_mol_part part, bf_film_mol_split split,
                    double *ydot);

/* The first node whose state in y is bad (non-finite, h <= 0, a negative
 * phase content), described into err as BF_EUNSTABLE; BF_OK if none. */
bf_status bf_film_mol_check(const bf_film_mol *m, const double *y,
                            bf_err *err);

#endif
