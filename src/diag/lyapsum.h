/* lyapsum.h: the bookkeeping of the largest Lyapunov exponent by two
 * nearby trajectories with periodic renormalisation (Benettin et al. 1976),
 * shared by the models that estimate it (private to the library).
 *
 * A shadow copy of the balls starts at a distance d0 from the real one in
 * the scaled phase space (x, tau v), along the fixed direction with equal
 * components; it is advanced by its own instance of the same integrator
 * (same [integrator] parameters) through the same forces.  Every
 * [lyapunov] renormalise_every the distance d_k is measured and
 * log(d_k/s_k) is accumulated, s_k being the distance the shadow started
 * that interval at; if d_k > d0 the shadow is pulled back to distance d0
 * along the current separation (s_(k+1) = d0), otherwise it is left alone
 * (s_(k+1) = d_k), unless it has shrunk below BF_LYAP_RESEED_BELOW d0:
 * then the shadow is re-seeded, run + the initial displacement
 * (s_(k+1) = d0), before the difference sinks into the state's round-off
 * (positions ~1 cm carry ~1e-16 cm of it) and the two merge, as they would
 * in a contracting (dissipative) motion.  The sum telescopes to log(total growth of the
 * separation), so the estimate after K renormalisations at time t_K is
 *
 *   lambda = (1/t_K) sum_k log(d_k/s_k)   (1/s),
 *
 * the same in the linear regime as pulling back every time; not pulling a
 * shrunken separation back out means the shadow is only ever moved
 * towards the run (a factor d0/d < 1), never extrapolated away from it,
 * which keeps a shadow film physical (coupled.c).
 *
 * It converges like 1/t: a quasi-periodic orbit gives a small positive
 * value that keeps falling (~ log(t)/t), a chaotic orbit a value that
 * settles.  /lyapunov/time and /lyapunov/estimate record the running
 * estimate at every renormalisation; the final value is the root attribute
 * lyapunov_exponent (1/s) and is printed in the run summary.
 *
 * The choice of tau (a time scale turning velocities into lengths) changes
 * the transient, not the limit.
 *
 * This file is the bookkeeping every estimate shares ([lyapunov] keys,
 * initial displacement, distance, running sum, output, checkpoint); the
 * shadow of a plain ball system is an analysis (src/analysis/lyapunov.c),
 * the coupled model keeps a shadow film as well (src/models).
 */
#ifndef BALLFILM_DIAG_LYAPSUM_H
#define BALLFILM_DIAG_LYAPSUM_H

#include <stdio.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/h5out.h"
#include "ballfilm/params.h"
#include "ballfilm/series.h"

/* The keys of [lyapunov]. */
typedef struct bf_lyap_keys {
    int enabled;
    double d0;                      /* cm */
    double tau;                     /* s */
    bf_interval renormalise_every; /* steps or s */
} bf_lyap_keys;

extern const bf_section_spec bf_lyap_spec; /* [lyapunov] */

typedef struct bf_lyap_sum {
    size_t n;       /* balls */
    double d0;      /* cm, distance of the shadow after a renormalisation */
    double tau;     /* s, turns velocity differences into lengths */
    long every;     /* steps between renormalisations */
    double d_start; /* cm, distance at the start of the current interval */
    double logsum;  /* sum of log(d_k/s_k) */
    long nrenorm;
    double t_last; /* s, time of the last renormalisation */
    bf_series *s_t, *s_l;
} bf_lyap_sum;

/* Re-seed the shadow when the separation shrinks below this fraction of
 * d0 (1e-4: with the default d0 = 1e-8 cm, 1e-12 cm, four orders above
 * the round-off of cm-sized positions). */
#define BF_LYAP_RESEED_BELOW 1e-4

/* From the [lyapunov] keys for n balls stepped by dt.  `adaptive` names
 * the run's integrator if it is adaptive (refused, naming the key), NULL
 * otherwise. */
bf_status bf_lyap_sum_init(bf_lyap_sum *ls, const bf_lyap_keys *k, double dt,
                           size_t n, const char *adaptive, bf_err *err);

/* The shadow's initial state: (xs, vs) = (x, v) + the displacement of
 * length d0 along equal components in (x, tau v). */
void bf_lyap_displace(const bf_lyap_sum *ls, const double *x, const double *v,
                      double *xs, double *vs);
/* Whether the step that made n_done steps ends an interval. */
static inline int bf_lyap_due(const bf_lyap_sum *ls, long n_done)
{
    return n_done % ls->every == 0;
}
/* At the end of an interval (time t_end): measure the distance of the
 * shadow (xs, vs) from (x, v), accumulate, record, and return in *factor
 * the factor d0/d (< 1) the caller must apply to the whole difference
 * shadow - run (bf_lyap_pull), 1 when BF_LYAP_RESEED_BELOW d0 <= d <= d0
 * (leave the shadow), or 0 below that: re-seed, i.e. make the whole
 * shadow state equal to the run's and displace its balls again as at the
 * start (bf_lyap_displace).
 * Fails with BF_EUNSTABLE if d is 0 or not finite. */
bf_status bf_lyap_measure(bf_lyap_sum *ls, const double *x, const double *v,
                          const double *xs, const double *vs, double t_end,
                          double *factor, bf_err *err);
/* shadow[i] = run[i] + factor (shadow[i] - run[i]), i < n */
void bf_lyap_pull(size_t n, double factor, const double *run, double *shadow);
/* Current estimate (1/s) and the time it refers to (last
 * renormalisation); NAN before the first renormalisation. */
double bf_lyap_sum_estimate(const bf_lyap_sum *ls, double *t_ref);
/* The summary line, with the shadow's force evaluations. */
void bf_lyap_sum_report(const bf_lyap_sum *ls, unsigned long long evals,
                        FILE *f);
/* /lyapunov/time and /lyapunov/estimate (series.h). */
extern const bf_series_table bf_lyap_series;
bf_status bf_lyap_sum_output_open(bf_lyap_sum *ls, bf_out *out, bf_err *err);
bf_status bf_lyap_sum_output_close(const bf_lyap_sum *ls, bf_out *out,
                                   bf_err *err);
bf_status bf_lyap_sum_save(const bf_lyap_sum *ls, bf_ckpt *ck, bf_err *err);
bf_status bf_lyap_sum_load(bf_lyap_sum *ls, const bf_ckpt *ck, bf_err *err);

#endif
