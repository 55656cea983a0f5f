/* g72_impl.h: the state of model "greenspan72" (private to
 * src/models/greenspan72.c and src/models/g72_ranks.c, its run over
 * ranks).
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
} g72;

/* g72_ranks.c: a(x) of the own particles of this rank, gathered from
 * every rank into its exchange buffer (not into ax, ay, g, kind), and
 * the counts of the kinds of g. */
bf_status bf_g72_accel_ranks(g72 *m, bf_err *err);
/* The leapfrog (eqs 2.1-2.4) of every particle with the a(x) of the last
 * bf_g72_accel_ranks; the walls follow. */
void bf_g72_leapfrog_ranks(g72 *m, double h, double dt);
/* Particles of each kind of g (BF_SUP_*) at the current a(x), in one
 * process or over ranks. */
void bf_g72_kind_counts(const g72 *m, unsigned long long kinds[4]);
void bf_g72_ranks_free(g72_ranks *r);

#endif
