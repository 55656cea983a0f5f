/* sim.h: the single time loop shared by every model.
 *
 * The loop owns time (t = n dt, never accumulated), the output schedule
 * ([scene] output_every), energy bookkeeping (relative error against the
 * initial energy, every [scene] energy_every steps), the stop conditions
 * (non-finite state reported by the model, energy bound, interruption), the
 * progress line and the summary.  It ends with a named status (error.h).
 */
#ifndef BALLFILM_SIM_H
#define BALLFILM_SIM_H

#include <signal.h>
#include <stdio.h>

#include "ballfilm/error.h"
#include "ballfilm/h5out.h"
#include "ballfilm/integrator.h"
#include "ballfilm/model.h"
#include "ballfilm/scene.h"

typedef struct bf_sim bf_sim;

typedef struct bf_sim_opts {
    int progress; /* 1: print an updating progress line on stderr */
    /* Set asynchronously (signal handler) to stop after the current step
     * (or run of steps, at most 1024: model.h, advance). */
    const volatile sig_atomic_t *stop_flag;
    /* Stop as if interrupted after this many steps of this invocation
     * (0: never); used to run in chunks and by the restart tests. */
    long stop_after;
} bf_sim_opts;

/* The [scene] section every scene has (model, integrator, effects, dt,
 * t_end, output_every, ...). */
extern const bf_section_spec bf_sim_scene_spec;

/* Build the model of a resolved scene.  Validation errors: BF_EINPUT. */
bf_status bf_sim_create(bf_sim **sim, const bf_scene *sc,
                        const bf_sim_opts *opts, bf_err *err);
void bf_sim_free(bf_sim *sim);

/* Write provenance (version, scene text, every resolved parameter with its
 * unit) and create the datasets.  Without an output file the run still
 * tracks energy and counters. */
bf_status bf_sim_open_output(bf_sim *sim, const char *path, bf_err *err);

/* Run to t_end.  On failure the message names step, time and cause; the
 * output file keeps every row up to the last good step and records the
 * status in its root attributes. */
bf_status bf_sim_run(bf_sim *sim, bf_err *err);

/* Finish the output (final datasets, status, counters) and close it. */
bf_status bf_sim_close_output(bf_sim *sim, bf_status run_status,
                              const bf_err *run_err, bf_err *err);

void bf_sim_summary(const bf_sim *sim, FILE *f);

/* Rough size of the output the rest of the run will write, in bytes (every
 * series at the main output interval), so that the front end can warn
 * before a long run fills the disk. */
double bf_sim_output_estimate(const bf_sim *sim);

/* ---- checkpoints and restart ----
 * With an output file OUT, checkpoints go to OUT.ckpt (atomically), every
 * [scene] checkpoint_every and when a run is interrupted (BF_INTERRUPTED).
 * A restarted run produces bit for bit the datasets of an uninterrupted
 * one. */
int bf_sim_can_checkpoint(const bf_sim *sim);
const char *bf_sim_checkpoint_path(const bf_sim *sim); /* NULL: none */
bf_status bf_sim_checkpoint_write(bf_sim *sim, const char *path, bf_err *err);
/* Rebuild a run from the checkpoint of OUT (OUT.ckpt): its stored scene
 * plus extra overrides `sets` (for example a later t_end), the model state,
 * and OUT reopened with the rows written after the checkpoint dropped.
 * *scene receives the scene (free it after the sim). */
bf_status bf_sim_restart(bf_sim **sim, bf_scene **scene, const char *out_path,
                         const char *const *sets, size_t nsets,
                         const bf_sim_opts *opts, bf_err *err);

/* Read-only views for drivers and tests. */
void *bf_sim_model(bf_sim *sim);
const bf_model_type *bf_sim_model_type(const bf_sim *sim);
long bf_sim_steps_done(const bf_sim *sim);
long bf_sim_steps_total(const bf_sim *sim);
double bf_sim_time(const bf_sim *sim);
double bf_sim_dt(const bf_sim *sim);
double bf_sim_max_energy_error(const bf_sim *sim); /* relative; NAN if none */
double bf_sim_wall_seconds(const bf_sim *sim);
void bf_sim_counters(const bf_sim *sim, bf_counters *c);

#endif
