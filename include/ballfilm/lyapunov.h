/* lyapunov.h: largest Lyapunov exponent of a ball system by two nearby
 * trajectories with periodic renormalisation (Benettin et al. 1976).
 *
 * A shadow copy of the balls starts at a distance d0 from the real one in
 * the scaled phase space (x, tau v), along the fixed direction with equal
 * components; it is advanced by its own instance of the same integrator
 * (same [integrator] parameters) through the same forces.  Every
 * [lyapunov] renormalise_every the distance d is measured, log(d/d0) is
 * accumulated and the shadow is pulled back to distance d0 along the
 * current separation.  The estimate after K renormalisations at time t_K is
 *
 *   lambda = (1/t_K) sum_k log(d_k/d0)   (1/s).
 *
 * It converges like 1/t: a quasi-periodic orbit gives a small positive
 * value that keeps falling (~ log(t)/t), a chaotic orbit a value that
 * settles.  /lyapunov/time and /lyapunov/estimate record the running
 * estimate at every renormalisation; the final value is the root attribute
 * lyapunov_exponent (1/s) and is printed in the run summary.
 *
 * The choice of tau (a time scale turning velocities into lengths) changes
 * the transient, not the limit.
 */
#ifndef BALLFILM_LYAPUNOV_H
#define BALLFILM_LYAPUNOV_H

#include "ballfilm/ballsys.h"
#include "ballfilm/checkpoint.h"
#include "ballfilm/h5out.h"

typedef struct bf_lyap bf_lyap;

extern const bf_section_spec bf_lyap_spec; /* [lyapunov] */

/* Create from [lyapunov]; *out is NULL when it is not enabled. */
bf_status bf_lyap_create(bf_lyap **out, const bf_scene *sc,
                         const bf_ballsys *sys, bf_err *err);
void bf_lyap_free(bf_lyap *ly);

/* Advance the shadow over the step t -> t + dt that the ball system has
 * just taken (step number n_done = steps done after it), renormalising
 * when due. */
bf_status bf_lyap_after_step(bf_lyap *ly, const bf_ballsys *sys, long n_done,
                             double t, double dt, bf_err *err);

/* Current estimate (1/s) and the time it refers to (last
 * renormalisation); NAN before the first renormalisation. */
double bf_lyap_estimate(const bf_lyap *ly, double *t_ref);

bf_status bf_lyap_output_open(bf_lyap *ly, bf_out *out, bf_err *err);
bf_status bf_lyap_output_close(const bf_lyap *ly, bf_out *out, bf_err *err);
bf_status bf_lyap_save(const bf_lyap *ly, bf_ckpt *ck, bf_err *err);
bf_status bf_lyap_load(bf_lyap *ly, const bf_ckpt *ck, bf_err *err);
/* Counters of the shadow integrator (work spent on the estimate). */
const bf_counters *bf_lyap_counters(const bf_lyap *ly);

#endif
