/* film.h: the two-phase shallow-water film with Ginzburg-Landau phase
 * separation (Yasuda 2010, sec. 3.1-3.4) and its invariant
 * (Lax-Wendroff-type) difference scheme, eqs 3.15-3.16.
 *
 * One job: hold the state of one film and advance it by one step; report
 * the largest stable step for the current state.  The film knows nothing
 * of balls: a coupling hands its chemical potential to each step
 * (bf_film_step_invariant's mu_cpl) and reads the film through
 * bf_film_psi()/bf_film_h().
 *
 * Model (phase k = d, c; s_d = +1, s_c = -1; CGS units):
 *   (3.1-3.2)  d/dt(alpha_k h) + d/dx(alpha_k h u_k) = 0
 *   (3.9)      d/dt u_k + u_k du_k/dx = -(1/rho_k) d/dx(P + s_k mu)
 *                                        + nu d2u_k/dx2     (sec. 3.4)
 *   P = rho_m g h,  rho_m = alpha_d rho_d + alpha_c rho_c,
 *   (3.8)      psi = alpha_d - alpha_c,
 *              mu = -a psi + b psi^3 - gamma d2psi/dx2 + mu_cpl
 *
 * Grid: nodes x_i = -L/2 + i dx, i = 0..N, N = L/dx; walls on nodes 0
 * and N; zero Neumann for alpha and h, zero Dirichlet for velocities
 * (sec. 3.4), by one mirrored ghost node on each side.
 *
 * The scheme and the choices it leaves open are documented in
 * src/film/film.c and in docs/models/film.md.
 */
#ifndef BALLFILM_FILM_H
#define BALLFILM_FILM_H

#include <stddef.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"

/* How the chemical potential enters the dt^2/2 term of the velocity
 * update (3.16); see film.c for the analysis. */
typedef enum bf_film_mu_taylor {
    /* mu at the time mid-point (mu^n + mu^{n+1})/2 in the gradient term,
     * W = P u_m: the consistent Taylor term (second order in time) */
    BF_FILM_MU_MIDPOINT = 0,
    /* the printed reading W = (P +- mu) u_m: first order in time for the
     * phase-separation mode, unstable without viscosity */
    BF_FILM_MU_UM,
    /* W = (P +- mu) u_k */
    BF_FILM_MU_UK
} bf_film_mu_taylor;

typedef struct bf_film_params {
    double length;       /* L, cm */
    double dx;           /* cm; L/dx must be a whole number */
    double rho_d, rho_c; /* g/cm^3 */
    double nu;           /* lateral viscosity, cm^2/s */
    double g;            /* cm/s^2 */
    double a, b;         /* Ginzburg-Landau constants, g/(cm s^2) */
    double gamma;        /* g cm/s^2 */
    bf_film_mu_taylor mu_taylor;
    /* 1: limit the fluxes of (alpha_k h) so that no volume fraction becomes
     * negative (see film.c); 0: leave them and let the caller stop */
    int limit_positive;
    /* Where a phase is (nearly) absent, alpha_k < vanish, its velocity is
     * set to the mixture velocity u_m after each step (0: never); see
     * film.c. */
    double vanish;
} bf_film_params;

typedef struct bf_film bf_film;

/* Allocate a film at rest with h = 1, psi = 0 (set the state next).
 * Refuses a length that is not a whole number of dx with BF_EINPUT. */
bf_status bf_film_create(bf_film **f, const bf_film_params *p, bf_err *err);
void bf_film_free(bf_film *f);
const bf_film_params *bf_film_params_of(const bf_film *f);

/* Number of nodes N + 1 and their positions (cm). */
size_t bf_film_nodes(const bf_film *f);
const double *bf_film_x(const bf_film *f);

/* Set the state from h (cm), psi (1) and the velocities (cm/s) on the
 * nodes; u at the walls is forced to zero.  Fails (BF_EINPUT, naming the
 * node) if h <= 0 or psi is outside [-1, 1] or a value is not finite. */
bf_status bf_film_set_state(bf_film *f, const double *h, const double *psi,
                            const double *u_d, const double *u_c, bf_err *err);

/* Current state on the nodes (level n). */
const double *bf_film_h(const bf_film *f);
const double *bf_film_psi(const bf_film *f);
const double *bf_film_u_d(const bf_film *f);
const double *bf_film_u_c(const bf_film *f);
/* alpha_k h, the conserved variables (cm) */
const double *bf_film_ah_d(const bf_film *f);
const double *bf_film_ah_c(const bf_film *f);

/* Largest stable step for the current state (s), and a short text naming
 * the limit that decides it (`why` may be NULL). */
double bf_film_stable_dt(const bf_film *f, char *why, size_t cap);

/* Advance by dt with the invariant scheme (3.15)-(3.16).  mu_cpl: the
 * coupling chemical potential (eq. 3.11) on the nodes 0..N, in the units
 * of mu (g/(cm s^2)), added to mu during this step; NULL: none (zero).
 * Fails with BF_EUNSTABLE, naming the node and the value, at the first
 * non-finite or out-of-range value (alpha outside [0, 1], h <= 0); the
 * film is then left at the failed state. */
bf_status bf_film_step_invariant(bf_film *f, double dt, const double *mu_cpl,
                                 bf_err *err);

/* Phase totals integral(alpha_k h) dx (cm^2), trapezoid weights: conserved
 * to round-off by the scheme. */
void bf_film_totals(const bf_film *f, double *mass_d, double *mass_c);
/* max |u_k| over nodes and phases (cm/s) */
double bf_film_max_speed(const bf_film *f);
/* smallest volume fraction of either phase over the nodes */
double bf_film_min_alpha(const bf_film *f);
/* Steps in which the positivity limiter changed a flux, and the number of
 * limited faces in total. */
void bf_film_limiter_counts(const bf_film *f, unsigned long long *steps,
                            unsigned long long *faces);

/* Mirror symmetry x -> -x, psi -> -psi (node i <-> N - i; the nodes are
 * x_i = (i - N/2) dx, so x_(N-i) = -x_i exactly).  With rho_d = rho_c and
 * an odd mu_cpl the equations map a state onto its mirror image
 *   A_d(i) <-> A_c(N-i),  u_d(i) <-> -u_c(N-i)
 * (h even, psi odd, mu odd, the mixture velocity odd).  bf_film_mirror
 * measures the distance of the state from its mirror image and, with
 * apply, replaces the state by the mean of the two (the projection onto
 * the symmetric subspace), also the rounding carries of A; h and psi are
 * derived again.  The sum of the two phase totals is kept to round-off of
 * the carries (the rounding error of each mean goes into the carry); the
 * projection sets each phase total to their mean, which is its own value
 * in a symmetric state.  corr[0]: max |A_d(i) - A_c(N-i)|/2 over nodes
 * divided by max h (1); corr[1]: max |u_d(i) + u_c(N-i)|/2 divided by
 * max |u_k| (1; 0 for a film at rest): the largest change the projection
 * makes, relative. */
void bf_film_mirror(bf_film *f, int apply, double corr[2]);

/* The Ginzburg-Landau kink (3.17) with the corrected width:
 * psi = sqrt(a/b) tanh((x - x0) / (sqrt(2) xi)), xi = sqrt(gamma/a). */
double bf_film_kink(const bf_film_params *p, double x0, double x);

/* The arrays that make up the film's state, each on the nodes 0..N (what
 * a checkpoint saves): alpha_d h, alpha_c h (cm), u_d, u_c (cm/s) and the
 * rounding carries of alpha_d h and alpha_c h (cm).  Fills arr and
 * returns the number of nodes.  A caller that writes them (the Lyapunov
 * shadow's renormalisation, coupled.c) calls bf_film_state_changed, which
 * derives h and psi again as a checkpoint load does. */
enum { BF_FILM_NSTATE = 6 };
size_t bf_film_state(bf_film *f, double *arr[BF_FILM_NSTATE]);
void bf_film_state_changed(bf_film *f);

/* Checkpoint: state and counters under names starting with `prefix`. */
bf_status bf_film_save(const bf_film *f, bf_ckpt *ck, const char *prefix,
                       bf_err *err);
bf_status bf_film_load(bf_film *f, const bf_ckpt *ck, const char *prefix,
                       bf_err *err);

#endif
