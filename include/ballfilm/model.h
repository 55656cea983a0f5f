/* model.h: a model is a solver for one kind of scene (balls on a line, the
 * two-phase film, balls in the film, particle fluids, the MAC tank).
 *
 * Solver versus problem (Basilisk): a model owns its state, its parameters
 * (declared in its section specs) and a function that advances one step.
 * The core time loop (sim.h) owns time, output schedule, energy bookkeeping
 * and stopping; it calls the model through this table.  Models are listed in
 * registry.c.
 */
#ifndef BALLFILM_MODEL_H
#define BALLFILM_MODEL_H

#include <stdio.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/h5out.h"
#include "ballfilm/integrator.h"
#include "ballfilm/scene.h"

enum {
    BF_MODEL_INTEGRATOR = 1u << 0, /* uses [scene] integrator */
    BF_MODEL_EFFECTS = 1u << 1     /* uses [scene] effects */
};

typedef struct bf_model_type {
    const char *name;
    const char *doc;
    unsigned flags;
    /* sections owned by the model, NULL-terminated (may be NULL) */
    const bf_section_spec *const *specs;

    /* Build from a resolved scene; validate physics (overlaps, stability)
     * with messages naming the key (bf_scene_fail).  dt is [scene] dt. */
    bf_status (*create)(void **self, const bf_scene *sc, bf_err *err);
    void (*destroy)(void *self);
    /* Largest stable time step for the current state (s), or 0 if the
     * model has no such limit.  Optional. */
    double (*stable_dt)(const void *self);
    /* Advance from t = n dt to t + dt.  A failure message should say what
     * went wrong and where (ball, node, cell); the loop adds step and time. */
    bf_status (*step)(void *self, long n, double t, double dt, bf_err *err);
    /* Kinetic and potential energy (erg).  Optional: NULL if the model has
     * no conserved energy to monitor. */
    void (*energy)(const void *self, double t, double *kin, double *pot);
    /* Create the model's datasets; called once before the first row. */
    bf_status (*output_open)(void *self, bf_out *out, bf_err *err);
    /* Append one output row of the model's series (state at t). */
    bf_status (*output_row)(void *self, long n, double t, bf_err *err);
    /* Write anything collected during the run (optional). */
    bf_status (*output_close)(void *self, bf_out *out, bf_err *err);
    /* Counters of the time integration (optional). */
    void (*counters)(const void *self, bf_counters *c);
    /* Extra lines for the end-of-run summary (optional). */
    void (*report)(const void *self, FILE *f);
    /* Save everything needed to continue bit for bit after `load` into a
     * model freshly created from the same scene: state, integrator
     * counters and history, RNG state, events collected for output_close.
     * Both are required for `ballfilm run --restart`; a model without them
     * refuses checkpoint_every and restarts with a clear message. */
    bf_status (*checkpoint_save)(const void *self, bf_ckpt *ck, bf_err *err);
    bf_status (*checkpoint_load)(void *self, const bf_ckpt *ck, bf_err *err);
    /* Optional: k >= 1 steps in one call, step j from t = (n + j) dt to
     * (n + j + 1) dt, with exactly the results of k calls of step (same
     * bits, counters, everything a checkpoint saves); *done receives the
     * number of steps that succeeded (on failure the state is that of the
     * failed step, as with step).  The loop hands such a model the runs of
     * steps between the events it owns (output rows, energy checks,
     * checkpoints, stop conditions), so that a step of a few nanoseconds
     * does not pay for a call and the loop's bookkeeping. */
    bf_status (*advance)(void *self, long n, long k, double dt, long *done,
                         bf_err *err);
} bf_model_type;

const bf_model_type *bf_model_find(const char *name);
const bf_model_type *const *bf_model_types(size_t *n);

#endif
