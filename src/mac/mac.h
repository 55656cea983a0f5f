/* mac.h: the thesis's predictor-corrector MAC solver for a stratified,
 * viscous, incompressible fluid with marker particles ("A predictor-
 * corrector method for the transient motion of a nonhomogeneous
 * incompressible, viscous fluid", PROGRAM STRATRES; the model and its
 * readings of the listing: docs/models/mac.md).
 *
 * Velocity (u, v), pressure P and temperature T live on a staggered MAC
 * grid; the density is carried by marker particles and recomputed per cell
 * from them.  One time step is the thesis's eight-step algorithm (ch. III):
 *   1. predicted density (3.13),
 *   2. pressure by relaxation of (3.10), crude test,
 *   3. provisional velocities (3.11)/(3.12),
 *   4. particles moved with area-weighted (bilinear) velocities (Fig. 2),
 *   5. density corrected from the particles in each cell,
 *   6. back to 2 while the density changes,
 *   7. pressure with the fine test, final velocities, particles moved,
 *   8. temperature (3.14).
 *
 * Indexing follows the listing (1-based): cells I = 1..ni, J = 1..nj, where
 * the cells I = 1, ni and J = 1, nj form the ring of fictitious boundary
 * cells; cell (I,J) covers x in [(I-2)dx, (I-1)dx), y in [(J-2)dy,
 * (J-1)dy).  U(I,J) is the left face of cell (I,J) (I = 1..ni+1), V(I,J)
 * its bottom face (J = 1..nj+1).
 *
 * Units are the thesis's scaled units (eqs 2.11-2.14): lengths in L, times
 * in L/W, velocities in W, densities in R, pressures in R W^2; mu and alpha
 * are the scaled mu' = mu/(R L W) and alpha' = k/(R L W C_v).
 *
 * The solver is re-entrant: all state lives in one bf_mac object.
 * A private header: the mac model (src/models/mac_model.c) and the tests
 * include it as "mac/mac.h".
 */
#ifndef BALLFILM_MAC_MAC_H
#define BALLFILM_MAC_MAC_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/params.h"
#include "ballfilm/particles.h"
#include "mac/mac_types.h"

/* The keys of [mac], bound to bf_mac_params. */
extern const bf_section_spec bf_mac_spec;

/* The defaults of every key of bf_mac_spec. */
void bf_mac_params_default(bf_mac_params *p);

/* Build the problem's initial state (listing lines 2262-2440).  dt is the
 * time step the caller will use (it must be positive; the explicit limits
 * on it are the mac model's stable_dt). */
bf_status bf_mac_create(bf_mac **m, const bf_mac_params *p, double dt,
                        bf_err *err);
void bf_mac_free(bf_mac *m);

/* One time step (the eight steps).  Errors: BF_ENOCONV (relaxation or
 * corrector loop), BF_EUNSTABLE (CFL, non-finite values, particle slots);
 * the message names the cell or particle. */
bf_status bf_mac_step(bf_mac *m, double dt, bf_err *err);

/* Read-only views.  Arrays are (ni+2) x (nj+2), index I*(nj+2)+J with the
 * listing's 1-based I, J (row 0 and the last row are padding). */
void bf_mac_dims(const bf_mac *m, int *ni, int *nj, double *dx, double *dy);
size_t bf_mac_index(const bf_mac *m, int i, int j);
const double *bf_mac_u(const bf_mac *m);
const double *bf_mac_v(const bf_mac *m);
const double *bf_mac_p(const bf_mac *m);
const double *bf_mac_rho(const bf_mac *m);
const double *bf_mac_temp(const bf_mac *m);
const int *bf_mac_flags(const bf_mac *m);
const bf_particles *bf_mac_particles(const bf_mac *m); /* tag = flag */
const double *bf_mac_particle_density(const bf_mac *m);
const bf_mac_counts *bf_mac_get_counts(const bf_mac *m);
/* Largest |u| and |v| on faces of FULL or SUR cells, and the largest
 * |div w| over FULL cells (its largest is reported at *ic, *jc). */
void bf_mac_extremes(const bf_mac *m, double *umax, double *vmax,
                     double *divmax, int *ic, int *jc);
/* Particle counts by flag (index = flag 1..4; [0] unused). */
void bf_mac_flag_counts(const bf_mac *m, int64_t count[5]);
/* Sum of density x particle area over the fluid (REG) particles. */
double bf_mac_fluid_mass(const bf_mac *m);
/* Passes and sweeps of the last step. */
void bf_mac_last_step(const bf_mac *m, int *passes, long *sweeps);

bf_status bf_mac_save(const bf_mac *m, bf_ckpt *ck, const char *prefix,
                      bf_err *err);
bf_status bf_mac_load(bf_mac *m, const bf_ckpt *ck, const char *prefix,
                      bf_err *err);

#endif
