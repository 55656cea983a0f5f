/* lyapunov.h: the largest Lyapunov exponent of a ball system: a shadow
 * copy of the balls (src/diag/lyapsum.h says how the estimate is made),
 * advanced by its own instance of the run's integrator through the same
 * forces.  Private to the library. */
#ifndef BALLFILM_ANALYSIS_LYAPUNOV_H
#define BALLFILM_ANALYSIS_LYAPUNOV_H

#include "ballfilm/ballsys.h"
#include "diag/lyapsum.h"

/* ------------------------------------------------ a ball system's shadow */

typedef struct bf_lyap bf_lyap;

/* Create from the [lyapunov] keys (bf_lyap_keys) for a ball system
 * stepped by dt; *out is NULL when it is not enabled. */
bf_status bf_lyap_create(bf_lyap **out, const void *keys, double dt,
                         const bf_ballsys *sys, bf_err *err);
void bf_lyap_free(bf_lyap *ly);

/* Advance the shadow over the step t -> t + dt that the ball system has
 * just taken (step number n_done = steps done after it), renormalising
 * when due. */
bf_status bf_lyap_after_step(bf_lyap *ly, const bf_ballsys *sys, long n_done,
                             double t, double dt, bf_err *err);

double bf_lyap_estimate(const bf_lyap *ly, double *t_ref);
void bf_lyap_report(const bf_lyap *ly, FILE *f);

bf_status bf_lyap_output_open(bf_lyap *ly, bf_out *out, bf_err *err);
bf_status bf_lyap_output_close(const bf_lyap *ly, bf_out *out, bf_err *err);
bf_status bf_lyap_save(const bf_lyap *ly, bf_ckpt *ck, bf_err *err);
bf_status bf_lyap_load(bf_lyap *ly, const bf_ckpt *ck, bf_err *err);
/* Counters of the shadow integrator (work spent on the estimate). */
const bf_counters *bf_lyap_counters(const bf_lyap *ly);

#endif
