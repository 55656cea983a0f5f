/* g72_impl.h: the state of model "greenspan72" (private to
 * src/models/greenspan72.c and src/models/g72_ranks.c, its run over
 * ranks, where p and the other per-particle arrays hold the particles of
 * one rank).
 */
#ifndef BALLFILM_MODELS_G72_IMPL_H
#define BALLFILM_MODELS_G72_IMPL_H

#include "ballfilm/particles.h"
#include "models/g72_ode.h"
#include "models/greenspan.h"
#include "particles/cells.h"
#include "particles/hertz_pairs.h"
#include "particles/repulsion.h"
#include "particles/support.h"
#include "particles/walls.h"

enum { NSETTLE = 4 };
enum { TAG_HEAVY = 1, TAG_LIGHT = 2 };
enum { OUT_ALL = 0, OUT_POSITIONS = 1, OUT_DIAG = 2 };

typedef struct g72_ranks g72_ranks; /* g72_ranks.c */

typedef struct g72 {
    bf_particles p;
    size_t n_heavy;
    double width, height, interface, bottom;
    bf_walls walls;
    bf_repulsion rep;
    int hertz_on; /* [hertz] enabled */
    bf_hertz_pairs hertz;
    bf_support *sup;
    bf_g72_ode *ode; /* integrator = arkode (NULL: the leapfrog) */
    int need_cells;
    bf_cells cells;
    bf_repulsion_work rw;
    double *ax, *ay, *g, *x0, *y0;
    uint8_t *kind;
    int acc_valid; /* a(x) (ax, ay, g, kind, or over ranks the exchange
                    * buffer) is that of the current positions */
    /* after a restart: the next a(x) recomputes one the interrupted run
     * had computed (and counted) already */
    int acc_replay;
    unsigned long long steps, evals, wall_hits;
    unsigned long long kind_total[4]; /* particle-steps of each BF_SUP_ kind */
    int out_mode, threads, nthr; /* requested threads, threads used */
    long particles_every, rows; /* output rows written */
    bf_particle_out po;
    bf_series *s_kin, *s_mean, *s_layers, *s_kinds,
        *s_settle;
    /* settling criteria at output rows: first step it held, last step it
     * failed (-1: never) */
    long settle_first[NSETTLE], settle_lastfail[NSETTLE], settle_last_row;
    g72_ranks *ranks; /* the run over ranks (NULL: one process) */
    int split_ready;  /* built for a split: the work allocated by it */
} g72;

/* g72_out.c: the model's series and its output hooks (model.h). */
extern const bf_series_table *const bf_g72_tables[];
bf_status bf_g72_output_open(void *self, bf_out *out, bf_err *err);
bf_status bf_g72_output_row(void *self, long n, double t, bf_err *err);
bf_status bf_g72_output_close(void *self, bf_out *out, bf_err *err);
/* greenspan72.c: a(x) of every particle, here or split over ranks (the
 * same bits), counted in m->evals unless it replays one (acc_replay). */
bf_status bf_g72_accel(g72 *m, bf_err *err);
/* g72_ranks.c, over ranks (m->ranks; m->p holds this rank's particles):
 * a(x) of the own particles after the migration and the halo exchange,
 * and the counts of the kinds of g over all ranks. */
bf_status bf_g72_accel_ranks(g72 *m, bf_err *err);
/* The wall rule on the own particles (after their leapfrog step), the
 * wall hits summed over the ranks into m->wall_hits; a failure on any
 * rank is every rank's, with the message of the lowest such rank. */
bf_status bf_g72_walls_ranks(g72 *m, bf_err *err);
/* Collective: rank 0 gets particles a..b-1 (at most BF_G72_BLOCK) of the
 * whole state in *blk (its buffers, valid until the next call; NULL on
 * the other ranks, which send theirs). */
enum { BF_G72_BLOCK = 1 << 16 };
bf_status bf_g72_gather_block(g72 *m, size_t a, size_t b,
                              const bf_particles **blk, bf_err *err);
/* Collective: rank 0 gets the whole state in index order in *all (to
 * free with bf_particles_free), a block at a time; the other ranks send
 * theirs (*all empty). */
bf_status bf_g72_gather(g72 *m, bf_particles *all, bf_err *err);
/* Particles of each kind of g (BF_SUP_*) at the current a(x), in one
 * process or over ranks. */
void bf_g72_kind_counts(const g72 *m, unsigned long long kinds[4]);
/* The particles of the run (over ranks: of all ranks) and this rank. */
size_t bf_g72_total(const g72 *m);
int bf_g72_rank(const g72 *m);
void bf_g72_ranks_free(g72_ranks *r);

#endif
