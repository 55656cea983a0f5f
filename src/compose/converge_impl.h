/* converge_impl.h: what the files of the convergence study share
 * (converge.c: the driver; converge_out.c: the table printed and
 * written).  What a model's study is comes from its descriptor
 * (ballfilm/study.h).  Private. */
#ifndef BALLFILM_COMPOSE_CONVERGE_IMPL_H
#define BALLFILM_COMPOSE_CONVERGE_IMPL_H

#include "ballfilm/converge.h"
#include "ballfilm/run.h"
#include "ballfilm/study.h"

struct bf_converge_priv {
    bf_scene *base; /* the scene as given, resolved */
    bf_setup *setup; /* its model's setup (the study's filled structs) */
    const bf_study_type *S; /* the model's study (its descriptor's) */
    double T;    /* final time, s */
    double hmax; /* largest internal step of adaptive runs, s (0: none) */
    long R;      /* output rows compared */
    int repeats;
    int skip_checks; /* opts.skip_checks */
    FILE *progress;
    const volatile sig_atomic_t *stop_flag; /* opts.stop_flag */
    /* the compared state: nstate values, group g at off[g], len[g] */
    size_t nstate, ngroups;
    size_t off[BF_CONVERGE_MAX_GROUPS], len[BF_CONVERGE_MAX_GROUPS];
    double *ref_rows; /* R x nstate: the reference at the rows */
    double *ref_final; /* nstate: the reference at T (one call to T) */
    double *rows;     /* 2 x R x nstate: scratch of the runs */
    int *adaptive;    /* per method */
    long *last;       /* per method: its last row (-1: none) */
    size_t cap;       /* rows allocated */
};

/* What one run of a method gives. */
typedef struct bf_converge_runout {
    double *rows; /* R x nstate: the state at the rows (NULL: not kept) */
    size_t nstate;
    double invariant_err;
    bf_counters count;
    double wall;
    bf_status status;
    char msg[BF_ERR_MSG];
    char label[160];
    int order;
} bf_converge_runout;

/* One run of the model of the resolved scene sc from 0 to T: nper steps of
 * h per output row, or (nper = 0, adaptive) with BF_RUN_SYNC one call of
 * the model's step per output row, else one call from 0 to T (the state
 * at T only, in the last row).  With BF_RUN_MEASURE the invariants are
 * checked after every step and the scene's energy bound applies.  A
 * failed run is o->status (BF_OK returned); the return value is for
 * failures of the study itself. */
enum { BF_RUN_MEASURE = 1, BF_RUN_SYNC = 2 };
bf_status bf_converge_run_once(const bf_converge_priv *P, const bf_scene *sc,
                               long nper, double h, unsigned flags,
                               bf_converge_runout *o, bf_err *err);

/* Errors of rows (R x nstate) against ref per group: at T, max and RMS
 * over the rows (rms may be NULL). */
void bf_converge_errors(const bf_converge_priv *P, const double *rows,
                        const double *ref, double *at_T, double *mx,
                        double *rms);

#endif
