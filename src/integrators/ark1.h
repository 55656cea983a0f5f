/* ark1.h: SUNDIALS ARKODE (6.4.1) on a first-order system
 * dy/dt = fe(t, y) + fi(t, y) of n unknowns (the film in method-of-lines
 * form, the coupled ball-film system): adaptive explicit Runge-Kutta
 * (ERKStep, fe only, any table of arkode.c with its issue-311 padding),
 * additive IMEX Runge-Kutta (ARKStep, fe explicit, fi implicit, Newton's
 * method with a banded direct linear solver and a difference-quotient
 * banded Jacobian), and multirate infinitesimal steps (MRIStep, fe the
 * slow part at a fixed slow step, fi the fast part integrated by an
 * adaptive inner ERK).  Private to the library.
 *
 * Synchronisation as in arkode.c: every bf_ark1_evolve(t, tend, y) resets
 * the integrator to (t, y), with the initial internal step carried over
 * from the previous call, and stops exactly at tend. */
#ifndef BALLFILM_INTEGRATORS_ARK1_H
#define BALLFILM_INTEGRATORS_ARK1_H

#include <stddef.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/integrator.h"

/* A part of the right-hand side: ydot = f(t, y).  Returns 0, > 0 for a
 * recoverable failure (ARKODE retries a smaller step) or < 0 to stop. */
typedef int (*bf_rhs_fn)(void *ctx, double t, const double *y, double *ydot);

typedef enum bf_ark1_kind {
    BF_ARK1_ERK = 0,  /* fe only, adaptive ERK */
    BF_ARK1_IMEX = 1, /* fe explicit + fi implicit, adaptive ARK */
    BF_ARK1_MRI = 2   /* fe slow (fixed step) + fi fast (adaptive ERK) */
} bf_ark1_kind;

typedef struct bf_ark1_opts {
    bf_ark1_kind kind;
    int table;        /* ERK and the MRI inner method: index of an ERK
                         table of arkode.c (bf_arkode_table_name) */
    int order;        /* IMEX: 3, 4 or 5 (ARKStep's ARK324L2SA,
                         ARK436L2SA, ARK548L2SA pairs); MRI: 3 or 4
                         (MRIStep's default MIS/MRI-GARK coupling) */
    double rtol, atol; /* ERK, IMEX, MRI inner */
    double max_step;   /* largest internal step (0: none) */
    long max_steps;    /* internal steps per call before failing */
    double budget_dt;  /* > 0: max_steps is per budget_dt of a call's
                          length ([scene] dt), at least one; 0: per call */
    const char *max_steps_key; /* the key that sets max_steps, named in
                                  that failure ("[coupled] max_steps";
                                  NULL: "max_steps") */
    double slow_step;  /* MRI: the fixed slow step */
    long band;         /* IMEX: half-bandwidth of dfi/dy */
    int work_around_311; /* pad ERK tables hit by issue 311 (arkode.c) */
} bf_ark1_opts;

typedef struct bf_ark1 bf_ark1;

bf_status bf_ark1_create(bf_ark1 **out, size_t n, bf_rhs_fn fe, bf_rhs_fn fi,
                         void *ctx, const bf_ark1_opts *o, bf_err *err);
void bf_ark1_free(bf_ark1 *a);

/* y at t -> y at tend, in place (on failure y is left as it was).  The
 * run's stop flag (stop.h) ends a call at its next evaluation with
 * BF_INTERRUPTED, the counters as before the call; more than max_steps
 * internal steps end it with BF_ENOCONV naming max_steps_key. */
bf_status bf_ark1_evolve(bf_ark1 *a, double t, double tend, double *y,
                         bf_err *err);

/* Kinks of the right-hand side (ERK only): where a component of g(t, y)
 * (n of them) changes sign inside a step, the integration restarts there:
 * the state at the root is integrated again from the step's start with
 * the root as the stop time, so that no step straddles it (as the balls'
 * ARKODE adapter does at contacts, integrators/arkode.c).  Returns 0 or
 * < 0 to stop. */
typedef int (*bf_root1_fn)(void *ctx, double t, const double *y, double *g);
bf_status bf_ark1_set_kinks(bf_ark1 *a, int n, bf_root1_fn g, bf_err *err);
/* The restarts at kinks so far (not kept in checkpoints). */
unsigned long long bf_ark1_restarts(const bf_ark1 *a);

/* steps (slow steps for MRI), evaluations of fe and fi (those of the
 * difference-quotient Jacobian included), rejected steps, Newton
 * iterations (IMEX) or fast steps (MRI); summed over all calls. */
void bf_ark1_counters(const bf_ark1 *a, bf_counters *c);
/* Nominal order and a one-line description ("ERK VERNER_8_5_6 rtol=..."). */
int bf_ark1_order(const bf_ark1 *a);
void bf_ark1_describe(const bf_ark1 *a, char *buf, size_t cap);
/* The initial internal step of the next call. */
double bf_ark1_h_next(const bf_ark1 *a);
void bf_ark1_set_h_next(bf_ark1 *a, double h);
/* Checkpoints: the next initial step and the counters so far, under
 * prefix + ".arkode_h_next" and prefix + ".arkode_counts.*"; after a load
 * bf_ark1_counters goes on from the saved counters, as in the run that
 * was not interrupted. */
bf_status bf_ark1_save(const bf_ark1 *a, bf_ckpt *ck, const char *prefix,
                       bf_err *err);
bf_status bf_ark1_load(bf_ark1 *a, const bf_ckpt *ck, const char *prefix,
                       bf_err *err);

#endif
