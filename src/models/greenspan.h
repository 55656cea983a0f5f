/* greenspan.h: read access to the state of the Greenspan particle models
 * (models "greenspan72" and "greenspan73") for drivers, tests and
 * benchmarks.  `model` is bf_sim_model() of a sim running that model.
 * Private to the library (beside the models' code; tests and benchmarks
 * include it as "models/greenspan.h"). */
#ifndef BALLFILM_MODELS_GREENSPAN_H
#define BALLFILM_MODELS_GREENSPAN_H

#include "ballfilm/model.h"
#include "ballfilm/particles.h"
#include "ballfilm/series.h"
#include "particles/support.h"
#include "particles/walls.h"

/* The particles of a greenspan72 model (positions x^k, velocities
 * v^{k-1/2}). */
bf_particles *bf_greenspan72_particles(void *model);
/* Its time integrator ([greenspan72] integrator) and nominal order. */
void bf_greenspan72_describe(void *model, char *buf, size_t cap, int *order);
/* Whether the setup's [greenspan72] integrator is adaptive (arkode). */
int bf_greenspan72_adaptive(const bf_model_setup *s);
/* Its support-set gravity workspace. */
bf_support *bf_greenspan72_support(void *model);

/* A greenspan72 run split over ranks (g72_ranks.c).  Each rank holds the
 * particles of its x-slab (in index order) and receives those of a halo
 * from the ranks beside it; the library does not link MPI: the program
 * gives the exchanges, which every rank calls in the same order (each
 * returns 0 on success).
 *   allgather: this rank's n doubles `send`, every rank's into `recv`
 *     one after the other in rank order (counts[r] from rank r);
 *   alltoallv: scounts[q] doubles of `send` (one part after the other in
 *     rank order) to rank q; the parts from every rank into *recv, one
 *     after the other in rank order, with their sizes in rcounts (*recv
 *     is grown with realloc to *rcap doubles when it is too small);
 *   allsum: v[0..n-1] summed over the ranks, in place (the callers sum
 *     integers below 2^53: exact in any order).
 * recut_every: evaluations of a(x) between two placements of the slabs'
 * cuts by particle counts (0: 256); any cuts give the same bits. */
typedef struct bf_ranks {
    int rank, size;
    void *ctx;
    int (*allgather)(void *ctx, const double *send, size_t n, double *recv,
                     const size_t *counts);
    int (*alltoallv)(void *ctx, const double *send, const size_t *scounts,
                     double **recv, size_t *rcap, size_t *rcounts);
    int (*allsum)(void *ctx, double *v, size_t n);
    long recut_every;
} bf_ranks;
/* Whether the run of `model` (a greenspan72 model) can be split over
 * ranks: BF_EINPUT naming the key for what the split does not support
 * (integrator arkode, [hertz], a repulsion without a cell list, the
 * naive support method). */
bf_status bf_greenspan72_ranks_refuse(void *model, bf_err *err);
/* Split the run of `model` over the ranks of r (kept): keep this rank's
 * particles and free the rest.  After it, output rows and checkpoints are
 * collective (every rank takes them at the same steps: bf_sim_opts
 * follower), and only rank 0 writes. */
bf_status bf_greenspan72_over_ranks(void *model, const bf_ranks *r,
                                    bf_err *err);
/* Over ranks: 1 if the run's failure was found in an exchange and is every
 * rank's (an unstable step, particles that coincide); 0 if it may be this
 * rank's alone (memory, the output), and the other ranks may be waiting
 * for it. */
int bf_greenspan72_failed_together(void *model);
/* Over ranks: the particle number (from 0) of each of this rank's
 * particles (bf_greenspan72_particles), increasing; NULL in one process. */
const uint32_t *bf_greenspan72_ids(void *model);

/* The particles of a greenspan73 model (time t_k). */
bf_particles *bf_greenspan73_particles(void *model);
/* Whether the setup's [greenspan73] integrator is adaptive (arkode). */
int bf_greenspan73_adaptive(const bf_model_setup *s);
/* Its time integrator ([greenspan73] integrator) with its parameters, and
 * its nominal order. */
void bf_greenspan73_describe(void *model, char *buf, size_t cap, int *order);

/* The particles as arrays (model.h, state): particles/x, particles/y
 * (cm), particles/vx, particles/vy (cm/s), all settable before the first
 * step; a particle keeps its number, fluid (tag) and mass. */
size_t bf_particles_state_vars(bf_particles *p, bf_state_var *vars,
                               size_t cap);
/* Replace one of them after checking every value (finite; positions
 * inside box, when given), naming the particle. */
bf_status bf_particles_set_var(bf_particles *p, const bf_box *box,
                               const char *name, const double *v, size_t n,
                               bf_err *err);
/* The per-particle datasets the two models share (series.h):
 * /particles/step (the step axis of rows written at a pace of their own),
 * x, y, vx, vy (velocities at t, or leapfrog half-step velocities), and
 * the static /particles/mass.  `on` picks the lines (BF_PO_*). */
typedef struct bf_particle_out {
    bf_series *step, *x, *y, *vx, *vy;
} bf_particle_out;
enum {
    BF_PO_STEP = 1u << 0,     /* /particles/step */
    BF_PO_POS = 1u << 1,      /* x, y */
    BF_PO_VEL = 1u << 2,      /* vx, vy at t */
    BF_PO_VEL_HALF = 1u << 3  /* vx, vy at t - dt/2 (leapfrog) */
};
extern const bf_series_table bf_particle_series;
/* Open the lines of `on` and write /particles/mass. */
bf_status bf_particles_output_open(bf_particle_out *po, bf_out *out,
                                   const bf_particles *p, unsigned on,
                                   bf_err *err);
/* Append the state to the series that are open (the step axis gets
 * `step`); nonzero when a buffer could not grow. */
/* The same for a row that comes in blocks of particles in index order:
 * the step with the first block (first = 1), then each block. */
int bf_particles_output_part(const bf_particle_out *po, const bf_particles *p,
                             int first, int64_t step);
int bf_particles_output_row(const bf_particle_out *po, const bf_particles *p,
                            int64_t step);

/* The particles as one vector y = (x, y, vx, vy) of 4n values (for
 * ARKODE), and back. */
void bf_particles_pack(const bf_particles *p, double *y);
void bf_particles_unpack(bf_particles *p, const double *y);

/* The keys of [greenspan72] and [greenspan73] integrator = arkode (ERK on
 * the particles' ODE), rows of the section's bf_param table: members
 * table, rtol, atol, max_step and max_steps of the keys struct T (needs
 * ballfilm/params.h and integrators/arkode.h where it is used). */
#define BF_PARTICLE_ARKODE_KEYS(T)                                             \
    {"table", BF_AT(T, table, BF_ENUM), "", "ARKODE_DORMAND_PRINCE_7_4_5",    \
     "integrator = arkode: ERK Butcher table", 0, 0, 0,                       \
     BF_ARKODE_TABLE_CHOICES},                                                \
    {"rtol", BF_AT(T, rtol, BF_REAL), "1", "1e-8",                             \
     "integrator = arkode: relative tolerance", BF_POS, 0, 0, NULL},          \
    {"atol", BF_AT(T, atol, BF_REAL), "cm, cm/s", "1e-10",                     \
     "integrator = arkode: absolute tolerance", BF_POS, 0, 0, NULL},          \
    {"max_step", BF_AT(T, max_step, BF_REAL), "s", "0",                        \
     "integrator = arkode: largest internal step (0: none)", BF_NONNEG, 0, 0, \
     NULL},                                                                   \
    {"max_steps", BF_AT(T, max_steps, BF_INT), "1", "1000000",                 \
     "integrator = arkode: internal steps allowed per [scene] dt", BF_MIN, 1, \
     0, NULL}

#endif
