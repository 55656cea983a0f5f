/* g72_ranks_impl.h: the state of a greenspan72 run split over ranks,
 * shared by src/models/g72_ranks.c (the split, the exchanges of a step)
 * and src/models/g72_gather.c (rank 0's gathers of the whole state). */
#ifndef BALLFILM_MODELS_G72_RANKS_IMPL_H
#define BALLFILM_MODELS_G72_RANKS_IMPL_H

#include <stdlib.h>

#include "models/g72_impl.h"
#include "particles/slabs.h"

/* Evaluations between two placements of the cuts by particle counts
 * (every rank sums the counts of the columns: O(columns) a time), unless
 * bf_ranks says otherwise.  Any cuts give the same bits; between
 * placements the particles that cross a cut migrate. */
enum { RECUT_EVERY = 256 };
/* doubles a migrating particle: gid, x, y, vx, vy, m, tag, flags */
enum { MIG = 8 };
/* doubles a halo particle: gid, x, y, m */
enum { HALO = 4 };
/* an evaluation's trailer: status, the pair's gids, its position, the
 * counts of the four kinds of g */
enum { TRAIL = 9 };
/* after the walls: status, wall hits, which check failed, the particle */
enum { WALLT = 4 };
/* a failure's message, exchanged when a rank has one (512 bytes) */
enum { MSGD = 64 };

struct g72_ranks {
    bf_ranks comm;
    bf_slabs sl;
    size_t total;  /* particles of the run */
    size_t cap;    /* capacity of the own arrays (m->p and the rest) */
    uint32_t *gid; /* [cap]: particle number of each own particle */
    int32_t *col;  /* [cap]: its cell column */
    uint32_t *lown; /* [cap]: its index in the local set */
    /* the local set: own and halo particles, in index order */
    size_t lcap, nl;
    uint32_t *lid;
    double *lx, *ly, *lm, *lax, *lay, *lg;
    uint8_t *lkind;
    size_t wcap; /* particles the cells, support and repulsion work take */
    double *sbuf, *rbuf;
    size_t scap, rcap;
    size_t *scnt, *rcnt, *at, *tcnt; /* [size] */
    size_t *pos, *end;               /* [size]: merge scratch */
    int *runs;                       /* [size] */
    double *trail;                   /* [MSGD size] */
    uint32_t *ord;                   /* merge order of received records */
    size_t ocap;
    bf_particles blk; /* rank 0: a gathered block (BF_G72_BLOCK) */
    int blk_ready;
    /* particles of each kind of g (BF_SUP_*) at the last a(x): sums of
     * integers, exact in any order */
    unsigned long long kinds[4];
    long evals; /* evaluations since the split */
    /* the last failure of a(x) or the walls was agreed by every rank */
    int failed_together;
};

/* realloc that keeps the array on failure: 1 then */
#define RESIZE(ptr, n)                                                       \
    do {                                                                     \
        void *q_ = realloc((ptr), ((n) ? (n) : 1) * sizeof *(ptr));          \
        if (!q_)                                                             \
            return 1;                                                        \
        (ptr) = q_;                                                          \
    } while (0)

static inline size_t bf_g72r_roomy(size_t n) { return n + n / 4 + 64; }

/* Particle i of p with its number g as MIG doubles (a migration, a
 * gathered block): g, x, y, vx, vy, m, tag, flags (the integers below
 * 2^53: exact). */
static inline void bf_g72r_pack(const bf_particles *p, size_t i, uint32_t g,
                                double *d)
{
    d[0] = g;
    d[1] = p->x[i];
    d[2] = p->y[i];
    d[3] = p->vx[i];
    d[4] = p->vy[i];
    d[5] = p->m[i];
    d[6] = p->tag[i];
    d[7] = p->flags[i];
}

/* MIG doubles into particle i of p (the number d[0] is the caller's). */
static inline void bf_g72r_unpack(const double *d, bf_particles *p, size_t i)
{
    p->x[i] = d[1];
    p->y[i] = d[2];
    p->vx[i] = d[3];
    p->vy[i] = d[4];
    p->m[i] = d[5];
    p->tag[i] = (int32_t)d[6];
    p->flags[i] = (uint32_t)d[7];
}

/* The send buffer for `need` doubles; 1 when out of memory. */
int bf_g72r_send_reserve(g72_ranks *r, size_t need);
/* BF_EINTERNAL: out of memory for `what`. */
bf_status bf_g72r_oom(bf_err *err, const char *what);
/* BF_EIO: an exchange failed. */
bf_status bf_g72r_exchange_failed(bf_err *err);

#endif
