/* g72_gather.c: rank 0's gathers of the whole state of a greenspan72
 * run split over ranks, a block of particles at a time in index order
 * (for its output rows and checkpoints). */
#include <string.h>

#include "models/g72_ranks_impl.h"

/* The first of the n own particles whose number is at least g. */
static size_t first_from(const uint32_t *gid, size_t n, size_t g)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (gid[mid] < g)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* rank 0's block of the whole state, for up to BF_G72_BLOCK particles */
static int block_reserve(g72_ranks *r)
{
    if (r->blk_ready)
        return 0;
    const size_t n = BF_G72_BLOCK;
    bf_particles *b = &r->blk;
    RESIZE(b->x, n);
    RESIZE(b->y, n);
    RESIZE(b->vx, n);
    RESIZE(b->vy, n);
    RESIZE(b->m, n);
    RESIZE(b->tag, n);
    RESIZE(b->flags, n);
    r->blk_ready = 1;
    return 0;
}

bf_status bf_g72_gather_block(g72 *m, size_t a, size_t b,
                              const bf_particles **blk, bf_err *err)
{
    g72_ranks *r = m->ranks;
    const bf_particles *p = &m->p;
    const int root = r->comm.rank == 0;
    *blk = NULL;
    if (b < a || b - a > BF_G72_BLOCK || b > r->total)
        return bf_fail(err, BF_EINTERNAL, "gather of particles %zu..%zu", a,
                       b);
    const size_t lo = first_from(r->gid, p->n, a),
                 hi = first_from(r->gid, p->n, b);
    memset(r->scnt, 0, (size_t)r->comm.size * sizeof *r->scnt);
    r->scnt[0] = (hi - lo) * MIG;
    /* a rank that cannot take part would leave the others waiting: the
     * program aborts the run (cmd_run.c) */
    if (bf_g72r_send_reserve(r, r->scnt[0]) || (root && block_reserve(r)))
        return bf_g72r_oom(err, "a gathered block");
    for (size_t i = lo; i < hi; i++)
        bf_g72r_pack(p, i, r->gid[i], r->sbuf + (i - lo) * MIG);
    if (r->comm.alltoallv(r->comm.ctx, r->sbuf, r->scnt, &r->rbuf, &r->rcap,
                          r->rcnt))
        return bf_g72r_exchange_failed(err);
    if (!root)
        return BF_OK;
    size_t got = 0;
    for (int q = 0; q < r->comm.size; q++)
        got += r->rcnt[q] / MIG;
    if (got != b - a)
        return bf_fail(err, BF_EINTERNAL, "gathered %zu of particles "
                       "%zu..%zu", got, a, b - 1);
    bf_particles *o = &r->blk;
    for (size_t k = 0; k < got; k++) {
        const double *d = r->rbuf + k * MIG;
        /* every number of a..b-1 once: in range */
        bf_g72r_unpack(d, o, (size_t)d[0] - a);
    }
    o->n = got;
    *blk = o;
    return BF_OK;
}

bf_status bf_g72_gather(g72 *m, bf_particles *all, bf_err *err)
{
    g72_ranks *r = m->ranks;
    const int root = r->comm.rank == 0;
    memset(all, 0, sizeof *all);
    bf_status st = root ? bf_particles_init(all, r->total, err) : BF_OK;
    if (st)
        return st; /* rank 0 alone: the program aborts the run */
    for (size_t a = 0; a < r->total && !st; a += BF_G72_BLOCK) {
        const size_t b = r->total - a < BF_G72_BLOCK ? r->total
                                                     : a + BF_G72_BLOCK;
        const bf_particles *blk;
        if ((st = bf_g72_gather_block(m, a, b, &blk, err)) || !root)
            continue;
        const size_t k = blk->n;
        memcpy(all->x + a, blk->x, k * sizeof *blk->x);
        memcpy(all->y + a, blk->y, k * sizeof *blk->y);
        memcpy(all->vx + a, blk->vx, k * sizeof *blk->vx);
        memcpy(all->vy + a, blk->vy, k * sizeof *blk->vy);
        memcpy(all->m + a, blk->m, k * sizeof *blk->m);
        memcpy(all->tag + a, blk->tag, k * sizeof *blk->tag);
        memcpy(all->flags + a, blk->flags, k * sizeof *blk->flags);
    }
    if (st)
        bf_particles_free(all);
    return st;
}
