/* g72_ranks.c: model "greenspan72" split over ranks, with the same bits
 * as one process at any rank count.
 *
 * Each rank holds the particles of its x-slab of cell columns (slabs.h),
 * in index order, with their particle numbers (gid).  Before every a(x)
 * the particles that moved into another rank's columns migrate to it
 * (after the wall rule), and every rank sends the ranks beside it the
 * particles of their halo; a rank then evaluates a(x) on its own
 * particles and its halo, and steps its own particles.  Sums over all
 * particles are either of integers (the counts of the kinds of g, the
 * wall hits: exact in any order, summed over the ranks) or taken by rank
 * 0 in index order on the state it gathers for an output row or a
 * checkpoint (g72_out.c, g72_gather.c).
 *
 * Why the same bits: the acceleration of a particle is a sum of terms
 * from the particles near it, taken in an order that the serial code
 * fixes by the cell list (repulsion.h: stripes of columns, then column,
 * row and slot; support.h: the columns of the strip in slot order, the
 * sweep in x order from the start of its chunk), and the slot order inside
 * a cell is the particles' index order (cells.h: a stable sort).  A rank
 * builds the cell list of the whole box on its own particles and those of
 * its halo, merged in index order; every term of its own particles' sums
 * is then there, in the same relative order, and the sums are the same
 * bits.  The halo: the repulsion reads `reach` columns each way
 * (repulsion.c), the support-set gravity the squares within
 * bf_support_reach (one column more for the rounding of a column index).
 * The leapfrog and the wall rule act on each particle alone.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/g72_ranks_impl.h"

void bf_g72_ranks_free(g72_ranks *r)
{
    if (!r)
        return;
    bf_slabs_free(&r->sl);
    free(r->gid);
    free(r->col);
    free(r->lown);
    free(r->lid);
    free(r->lx);
    free(r->ly);
    free(r->lm);
    free(r->lax);
    free(r->lay);
    free(r->lg);
    free(r->lkind);
    free(r->sbuf);
    free(r->rbuf);
    free(r->scnt);
    free(r->rcnt);
    free(r->at);
    free(r->tcnt);
    free(r->pos);
    free(r->end);
    free(r->runs);
    free(r->trail);
    free(r->ord);
    bf_particles_free(&r->blk);
    free(r);
}

/* The arrays of the own particles to capacity n (>= their number). */
static int own_resize(g72 *m, size_t n)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    RESIZE(p->x, n);
    RESIZE(p->y, n);
    RESIZE(p->vx, n);
    RESIZE(p->vy, n);
    RESIZE(p->m, n);
    RESIZE(p->tag, n);
    RESIZE(p->flags, n);
    RESIZE(m->ax, n);
    RESIZE(m->ay, n);
    RESIZE(m->g, n);
    RESIZE(m->x0, n);
    RESIZE(m->y0, n);
    RESIZE(m->kind, n);
    RESIZE(r->gid, n);
    RESIZE(r->col, n);
    RESIZE(r->lown, n);
    r->cap = n;
    return 0;
}

static int own_reserve(g72 *m, size_t need)
{
    return need <= m->ranks->cap ? 0 : own_resize(m, bf_g72r_roomy(need));
}

static int local_reserve(g72_ranks *r, size_t need)
{
    if (need <= r->lcap)
        return 0;
    const size_t n = bf_g72r_roomy(need);
    RESIZE(r->lid, n);
    RESIZE(r->lx, n);
    RESIZE(r->ly, n);
    RESIZE(r->lm, n);
    RESIZE(r->lax, n);
    RESIZE(r->lay, n);
    RESIZE(r->lg, n);
    RESIZE(r->lkind, n);
    r->lcap = n;
    return 0;
}

int bf_g72r_send_reserve(g72_ranks *r, size_t need)
{
    if (need > r->scap) {
        RESIZE(r->sbuf, bf_g72r_roomy(need));
        r->scap = bf_g72r_roomy(need);
    }
    return 0;
}

static int ord_reserve(g72_ranks *r, size_t need)
{
    if (need > r->ocap) {
        RESIZE(r->ord, bf_g72r_roomy(need));
        r->ocap = bf_g72r_roomy(need);
    }
    return 0;
}

bf_status bf_g72r_oom(bf_err *err, const char *what)
{
    return bf_fail(err, BF_EINTERNAL, "out of memory (%s of a run over "
                   "ranks)", what);
}

bf_status bf_g72r_exchange_failed(bf_err *err)
{
    return bf_fail(err, BF_EIO, "the exchange between ranks failed");
}

/* The cell list, the support's and the repulsion's work for `need`
 * particles of the local set: made again when the set outgrows them (the
 * same geometry as g72_create's). */
static bf_status work_reserve(g72 *m, size_t need, bf_err *err)
{
    g72_ranks *r = m->ranks;
    if (need <= r->wcap)
        return BF_OK;
    const size_t cap = bf_g72r_roomy(need);
    const double side = m->rep.cell > 0 ? m->rep.cell : m->rep.cutoff;
    bf_cells c;
    bf_support *s = NULL;
    bf_repulsion_work w;
    memset(&w, 0, sizeof w);
    bf_status st = bf_cells_init(&c, 0.0, 0.0, m->width, m->height, side,
                                 cap, err);
    if (st)
        return st;
    if ((st = bf_support_create(&s, bf_support_params_of(m->sup), cap,
                                err)) ||
        (st = bf_repulsion_work_init(&w, cap, m->threads, err))) {
        bf_cells_free(&c);
        bf_support_free(s);
        return st;
    }
    bf_cells_free(&m->cells);
    m->cells = c;
    bf_support_free(m->sup);
    m->sup = s;
    bf_repulsion_work_free(&m->rw);
    m->rw = w;
    r->wcap = cap;
    return BF_OK;
}

/* The halo in columns of the cell list: the repulsion's reach exactly
 * (the columns it reads), the support's distance rounded up, plus one. */
static void halo_columns(const g72 *m, int *hl, int *hr)
{
    const double ih = m->cells.inv_h;
    const int reach = (int)ceil(m->rep.cutoff * ih * (1.0 - 1e-12));
    double left, right;
    bf_support_reach(m->sup, &left, &right);
    int sl = (int)ceil(left * ih) + 1, sr = (int)ceil(right * ih) + 1;
    *hl = sl > reach ? sl : reach;
    *hr = sr > reach ? sr : reach;
}

static bf_status refuse(g72 *m, bf_err *err)
{
    if (m->ode)
        return bf_fail_key(err, BF_EINPUT, "greenspan72", "integrator",
                           "integrator arkode does not run over ranks (its "
                           "error norms are sums over all particles); use "
                           "leapfrog or one rank");
    if (m->hertz_on)
        return bf_fail_key(err, BF_EINPUT, "hertz", "enabled",
                           "[hertz] does not run over ranks; disable it or "
                           "use one rank");
    if (!m->rep.use_cells)
        return bf_fail_key(err, BF_EINPUT, "repulsion",
                           m->rep.cutoff > 0 ? "method" : "cutoff",
                           "a run over ranks needs the repulsion's cell list "
                           "(a cutoff > 0 and method auto or cells): without "
                           "it every particle acts on every other");
    if (bf_support_params_of(m->sup)->method == BF_SUPPORT_NAIVE)
        return bf_fail_key(err, BF_EINPUT, "support", "method",
                           "method naive reads every particle and does not "
                           "run over ranks; use cell or fast");
    return BF_OK;
}

bf_status bf_greenspan72_ranks_refuse(void *model, bf_err *err)
{
    return refuse(model, err);
}

const uint32_t *bf_greenspan72_ids(void *model)
{
    const g72 *m = model;
    return m->ranks ? m->ranks->gid : NULL;
}

size_t bf_g72_total(const g72 *m)
{
    return m->ranks ? m->ranks->total : m->p.n;
}

/* Keep the particles of this rank's columns (all particles are here, in
 * index order) and shrink every per-particle array to them. */
static bf_status keep_own(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    const size_t n = p->n;
    int32_t *col = malloc((n ? n : 1) * sizeof *col);
    if (!col)
        return bf_g72r_oom(err, "the columns");
    for (size_t i = 0; i < n; i++)
        col[i] = bf_cells_col(&m->cells, p->x[i]);
    bf_slabs_balance(&r->sl, col, n);
    const int me = r->comm.rank;
    const size_t own = r->sl.own[me];
    r->gid = malloc(bf_g72r_roomy(own) * sizeof *r->gid);
    r->col = malloc(bf_g72r_roomy(own) * sizeof *r->col);
    r->lown = malloc(bf_g72r_roomy(own) * sizeof *r->lown);
    if (!r->gid || !r->col || !r->lown) {
        free(col);
        return bf_g72r_oom(err, "the particle numbers");
    }
    r->cap = bf_g72r_roomy(own);
    size_t j = 0;
    for (size_t i = 0; i < n; i++) {
        if (r->sl.rank_of[col[i]] != me)
            continue;
        p->x[j] = p->x[i];
        p->y[j] = p->y[i];
        p->vx[j] = p->vx[i];
        p->vy[j] = p->vy[i];
        p->m[j] = p->m[i];
        p->tag[j] = p->tag[i];
        p->flags[j] = p->flags[i];
        r->gid[j] = (uint32_t)i;
        r->col[j] = col[i];
        j++;
    }
    free(col);
    p->n = j;
    if (own_resize(m, r->cap))
        return bf_g72r_oom(err, "the own particles");
    /* the cell list and work for the local set (own and halo) of these
     * cuts; they grow with it */
    int c0, c1;
    size_t local = 0;
    bf_slabs_reads(&r->sl, me, &c0, &c1);
    for (int c = c0; c < c1; c++)
        local += r->sl.cnt[c];
    r->wcap = 0;
    return work_reserve(m, local, err);
}

/* A split that failed on one rank (memory) fails on every rank before
 * the first exchange of particles. */
static bf_status split_agreed(const bf_ranks *comm, bf_status st,
                              bf_err *err)
{
    double failed = st != BF_OK;
    if (comm->allsum(comm->ctx, &failed, 1))
        return st ? st : bf_g72r_exchange_failed(err);
    if (failed > 0 && !st)
        st = bf_fail(err, BF_EINTERNAL, "another rank could not take its "
                     "share of the particles (out of memory)");
    return st;
}

int bf_greenspan72_failed_together(void *model)
{
    const g72 *m = model;
    return m->ranks && m->ranks->failed_together;
}

bf_status bf_greenspan72_over_ranks(void *model, const bf_ranks *comm,
                                    bf_err *err)
{
    g72 *m = model;
    bf_status st = refuse(m, err);
    if (st)
        return st;
    if (m->ranks)
        return bf_fail(err, BF_EINTERNAL, "greenspan72: already split over "
                       "ranks");
    const size_t n = m->p.n, size = (size_t)comm->size;
    /* the exchanges' counts and displacements are ints (MPI): a gather to
     * rank 0 receives n doubles, a migration up to MIG n */
    if (comm->size < 1 || size > (size_t)INT32_MAX / MSGD ||
        n > (size_t)INT32_MAX / MIG)
        return bf_fail_key(err, BF_EINPUT, "greenspan72", "grid_nx",
                           "%zu particles are too many for a run over ranks",
                           n);
    g72_ranks *r = calloc(1, sizeof *r);
    if (!r) {
        st = bf_g72r_oom(err, "the split");
        return split_agreed(comm, st, err);
    }
    r->comm = *comm;
    r->total = n;
    int hl, hr;
    halo_columns(m, &hl, &hr);
    if ((st = bf_slabs_init(&r->sl, comm->size, m->cells.nx, hl, hr, err))) {
        free(r);
        return split_agreed(comm, st, err);
    }
    r->scnt = calloc(size, sizeof *r->scnt);
    r->rcnt = calloc(size, sizeof *r->rcnt);
    r->at = calloc(size, sizeof *r->at);
    r->tcnt = calloc(size, sizeof *r->tcnt);
    r->pos = calloc(size, sizeof *r->pos);
    r->end = calloc(size, sizeof *r->end);
    r->runs = calloc(size, sizeof *r->runs);
    r->trail = calloc(MSGD * size, sizeof *r->trail);
    m->ranks = r;
    if (!r->scnt || !r->rcnt || !r->at || !r->tcnt || !r->pos || !r->end ||
        !r->runs || !r->trail)
        st = bf_g72r_oom(err, "the split");
    if (!st)
        st = keep_own(m, err);
    if ((st = split_agreed(comm, st, err)))
        return st;
    /* a(x) at t = 0 (or, after a restart, the one the checkpoint had)
     * over ranks; one of a model built whole is computed again, and not
     * counted twice */
    if (m->acc_valid) {
        m->acc_valid = 0;
        m->acc_replay = 1;
    }
    if ((st = bf_g72_accel(m, err)) && m->steps == 0) {
        /* particles that coincide at the start are the scene's fault */
        bf_err_prefix(err, "at t = 0");
        err->status = st = BF_EINPUT;
        bf_err_set_key(err, "greenspan72", "positions");
    }
    return st;
}

/* The cuts placed again by the particles per column of every rank. */
static bf_status recut(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    const int nx = r->sl.nx;
    if (bf_g72r_send_reserve(r, (size_t)nx))
        return bf_g72r_oom(err, "the cuts");
    double *c = r->sbuf;
    memset(c, 0, (size_t)nx * sizeof *c);
    for (size_t i = 0; i < m->p.n; i++)
        c[r->col[i]] += 1.0;
    if (r->comm.allsum(r->comm.ctx, c, (size_t)nx))
        return bf_g72r_exchange_failed(err);
    for (int k = 0; k < nx; k++)
        r->sl.cnt[k] = (size_t)c[k];
    bf_slabs_cut(&r->sl, r->total);
    return BF_OK;
}

/* Offsets of the parts of the send buffer (scnt) into at; their sum. */
static size_t offsets(g72_ranks *r)
{
    size_t off = 0;
    for (int q = 0; q < r->comm.size; q++) {
        r->at[q] = off;
        off += r->scnt[q];
    }
    return off;
}

/* The received records (rcnt[q] doubles from rank q, w doubles each, each
 * part in increasing particle number, the first double) in increasing
 * particle number: ord[k] is the k-th record's index in rbuf.  Returns
 * their number. */
static size_t merge_received(g72_ranks *r, size_t w)
{
    size_t off = 0, nrec = 0;
    int nr = 0;
    for (int q = 0; q < r->comm.size; q++) {
        if (r->rcnt[q]) {
            r->pos[nr] = off / w;
            r->end[nr] = (off + r->rcnt[q]) / w;
            r->runs[nr++] = q;
        }
        off += r->rcnt[q];
    }
    nrec = off / w;
    for (size_t k = 0; k < nrec; k++) {
        int best = -1;
        double bg = 0;
        for (int s = 0; s < nr; s++)
            if (r->pos[s] < r->end[s]) {
                const double g = r->rbuf[r->pos[s] * w];
                if (best < 0 || g < bg) {
                    best = s;
                    bg = g;
                }
            }
        r->ord[k] = (uint32_t)r->pos[best]++;
    }
    return nrec;
}

/* Move own particle a to slot b (b <= a, or b past the kept ones). */
static void own_move(g72 *m, size_t a, size_t b)
{
    bf_particles *p = &m->p;
    g72_ranks *r = m->ranks;
    p->x[b] = p->x[a];
    p->y[b] = p->y[a];
    p->vx[b] = p->vx[a];
    p->vy[b] = p->vy[a];
    p->m[b] = p->m[a];
    p->tag[b] = p->tag[a];
    p->flags[b] = p->flags[a];
    r->gid[b] = r->gid[a];
    r->col[b] = r->col[a];
}

/* The particles in another rank's columns go to it; those arriving are
 * merged in index order. */
static bf_status migrate(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    const int me = r->comm.rank;
    const int *owner = r->sl.rank_of;
    memset(r->scnt, 0, (size_t)r->comm.size * sizeof *r->scnt);
    for (size_t i = 0; i < p->n; i++) {
        const int q = owner[r->col[i]];
        if (q != me)
            r->scnt[q] += MIG;
    }
    if (bf_g72r_send_reserve(r, offsets(r)))
        return bf_g72r_oom(err, "a migration");
    size_t keep = 0;
    for (size_t i = 0; i < p->n; i++) {
        const int q = owner[r->col[i]];
        if (q == me) {
            if (keep != i)
                own_move(m, i, keep);
            keep++;
            continue;
        }
        bf_g72r_pack(p, i, r->gid[i], r->sbuf + r->at[q]);
        r->at[q] += MIG;
    }
    p->n = keep;
    if (r->comm.alltoallv(r->comm.ctx, r->sbuf, r->scnt, &r->rbuf, &r->rcap,
                          r->rcnt))
        return bf_g72r_exchange_failed(err);
    size_t in = 0;
    for (int q = 0; q < r->comm.size; q++)
        in += r->rcnt[q] / MIG;
    if (!in)
        return BF_OK;
    if (own_reserve(m, keep + in) || ord_reserve(r, in))
        return bf_g72r_oom(err, "a migration");
    merge_received(r, MIG);
    /* merge from the back: own particles and arrivals by particle number */
    size_t a = keep, b = in, w = keep + in;
    while (b > 0) {
        const double *d = r->rbuf + (size_t)r->ord[b - 1] * MIG;
        const uint32_t g = (uint32_t)d[0];
        w--;
        if (a > 0 && r->gid[a - 1] > g) {
            a--;
            own_move(m, a, w);
            continue;
        }
        b--;
        r->gid[w] = g;
        bf_g72r_unpack(d, p, w);
        r->col[w] = bf_cells_col(&m->cells, d[1]);
    }
    p->n = keep + in;
    return BF_OK;
}

/* The ranks [*q0, *q1] whose columns lie within the halo of column c
 * (those that read it). */
static void readers(const g72_ranks *r, int c, int *q0, int *q1)
{
    const bf_slabs *s = &r->sl;
    const int lo = c - s->hr < 0 ? 0 : c - s->hr;
    const int hi = c + s->hl >= s->nx ? s->nx - 1 : c + s->hl;
    *q0 = s->rank_of[lo];
    *q1 = s->rank_of[hi];
}

static int reads(const g72_ranks *r, int q)
{
    return q != r->comm.rank && r->sl.cut[q] < r->sl.cut[q + 1];
}

/* The own particles that other ranks read go to them; the local set is
 * the own particles and those received, merged in index order. */
static bf_status halo(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    const bf_particles *p = &m->p;
    memset(r->scnt, 0, (size_t)r->comm.size * sizeof *r->scnt);
    for (size_t i = 0; i < p->n; i++) {
        int q0, q1;
        readers(r, r->col[i], &q0, &q1);
        for (int q = q0; q <= q1; q++)
            if (reads(r, q))
                r->scnt[q] += HALO;
    }
    if (bf_g72r_send_reserve(r, offsets(r)))
        return bf_g72r_oom(err, "the halo");
    for (size_t i = 0; i < p->n; i++) {
        int q0, q1;
        readers(r, r->col[i], &q0, &q1);
        for (int q = q0; q <= q1; q++)
            if (reads(r, q)) {
                double *d = r->sbuf + r->at[q];
                r->at[q] += HALO;
                d[0] = r->gid[i];
                d[1] = p->x[i];
                d[2] = p->y[i];
                d[3] = p->m[i];
            }
    }
    if (r->comm.alltoallv(r->comm.ctx, r->sbuf, r->scnt, &r->rbuf, &r->rcap,
                          r->rcnt))
        return bf_g72r_exchange_failed(err);
    size_t in = 0;
    for (int q = 0; q < r->comm.size; q++)
        in += r->rcnt[q] / HALO;
    if (local_reserve(r, p->n + in) || ord_reserve(r, in))
        return bf_g72r_oom(err, "the halo");
    merge_received(r, HALO);
    size_t a = 0, b = 0, l = 0;
    while (a < p->n || b < in) {
        const double *d = b < in ? r->rbuf + (size_t)r->ord[b] * HALO : NULL;
        if (a < p->n && (!d || r->gid[a] < (uint32_t)d[0])) {
            r->lid[l] = r->gid[a];
            r->lx[l] = p->x[a];
            r->ly[l] = p->y[a];
            r->lm[l] = p->m[a];
            r->lown[a++] = (uint32_t)l++;
        } else {
            r->lid[l] = (uint32_t)d[0];
            r->lx[l] = d[1];
            r->ly[l] = d[2];
            r->lm[l] = d[3];
            l++;
            b++;
        }
    }
    r->nl = l;
    return BF_OK;
}

/* The trailers of every rank: the counts of the kinds of g (summed); the
 * pair of the lowest rank that found two coincident particles. */
static bf_status read_trailers(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    memset(r->kinds, 0, sizeof r->kinds);
    int bad = -1;
    for (int q = 0; q < r->comm.size; q++) {
        const double *t = r->trail + (size_t)q * TRAIL;
        if (bad < 0 && t[0] != 0)
            bad = q;
        for (int k = 0; k < 4; k++)
            r->kinds[k] += (unsigned long long)t[5 + k];
    }
    if (bad < 0)
        return BF_OK;
    r->failed_together = 1;
    const double *t = r->trail + (size_t)bad * TRAIL;
    return bf_fail(err, BF_EUNSTABLE,
                   "particles %zu and %zu coincide at (%.9g, %.9g) with "
                   "xi = 0: the repulsion has no direction",
                   (size_t)t[1] + 1, (size_t)t[2] + 1, t[3], t[4]);
}

bf_status bf_g72_accel_ranks(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    bf_status st;
    for (size_t i = 0; i < p->n; i++)
        r->col[i] = bf_cells_col(&m->cells, p->x[i]);
    const long every = r->comm.recut_every > 0 ? r->comm.recut_every
                                                : RECUT_EVERY;
    if (r->evals++ % every == every - 1 && (st = recut(m, err)))
        return st;
    if ((st = migrate(m, err)) || (st = halo(m, err)) ||
        (st = work_reserve(m, r->nl, err)))
        return st;
    bf_cells_build(&m->cells, r->lx, r->ly, r->lm, r->nl);
    size_t bi = 0, bj = 0;
    const int bad = bf_repulsion_cells(&m->rep, &m->cells, &m->rw, r->lax,
                                       r->lay, &bi, &bj);
    bf_support_eval(m->sup, r->lx, r->ly, r->nl, &m->cells, r->lg, r->lkind);
    unsigned long long kinds[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < p->n; i++) {
        const uint32_t l = r->lown[i];
        m->ax[i] = r->lax[l];
        m->ay[i] = r->lay[l];
        m->g[i] = r->lg[l];
        m->kind[i] = r->lkind[l];
        kinds[r->lkind[l]]++;
    }
    double t[TRAIL] = {bad,
                       bad ? (double)r->lid[bi] : 0.0,
                       bad ? (double)r->lid[bj] : 0.0,
                       bad ? r->lx[bi] : 0.0,
                       bad ? r->ly[bi] : 0.0,
                       /* below 2^53: exact */
                       (double)kinds[0], (double)kinds[1], (double)kinds[2],
                       (double)kinds[3]};
    for (int q = 0; q < r->comm.size; q++)
        r->tcnt[q] = TRAIL;
    if (r->comm.allgather(r->comm.ctx, t, TRAIL, r->trail, r->tcnt))
        return bf_g72r_exchange_failed(err);
    return read_trailers(m, err);
}

void bf_g72_kind_counts(const g72 *m, unsigned long long kinds[4])
{
    if (m->ranks) {
        memcpy(kinds, m->ranks->kinds, sizeof m->ranks->kinds);
        return;
    }
    kinds[0] = kinds[1] = kinds[2] = kinds[3] = 0;
    for (size_t i = 0; i < m->p.n; i++)
        kinds[m->kind[i]]++;
}

/* The failure one process would report: the wall rule's of the lowest
 * particle number, else the box check's of the lowest (the wall rule
 * runs over every particle before the box is checked); -1: none. */
static int failing_rank(const g72_ranks *r)
{
    int best = -1;
    for (int q = 0; q < r->comm.size; q++) {
        const double *u = r->trail + (size_t)q * WALLT;
        if (u[0] == 0)
            continue;
        const double *b = best < 0 ? NULL : r->trail + (size_t)best * WALLT;
        if (!b || u[2] < b[2] || (u[2] == b[2] && u[3] < b[3]))
            best = q;
    }
    return best;
}

bf_status bf_g72_walls_ranks(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    unsigned long long hits = 0;
    bf_err mine = {0};
    size_t bad = 0;
    bf_status st = bf_walls_apply_ids(&m->walls, p, m->x0, m->y0, r->gid,
                                      &hits, &bad, &mine);
    const int walls_failed = st != BF_OK;
    if (!st && !bf_box_contains_all(&m->walls.box, p, &bad))
        st = bf_fail(&mine, BF_EINTERNAL,
                     "particle %zu left the box: (%.17g, %.17g) (a bug in "
                     "the wall rule)",
                     (size_t)r->gid[bad] + 1, p->x[bad], p->y[bad]);
    /* status, wall hits, 0 for the wall rule's failure (1: the box's),
     * the failing particle's number */
    const double t[WALLT] = {(double)st, (double)hits, walls_failed ? 0 : 1,
                             st ? (double)r->gid[bad] : 0};
    for (int q = 0; q < r->comm.size; q++)
        r->tcnt[q] = WALLT;
    if (r->comm.allgather(r->comm.ctx, t, WALLT, r->trail, r->tcnt))
        return bf_g72r_exchange_failed(err);
    const int first = failing_rank(r);
    if (first < 0) {
        for (int q = 0; q < r->comm.size; q++)
            m->wall_hits += (unsigned long long)r->trail[(size_t)q * WALLT + 1];
        return BF_OK;
    }
    r->failed_together = 1;
    const bf_status fst = (bf_status)r->trail[(size_t)first * WALLT];
    /* one process adds no hits of a step that fails; the message of the
     * rank with the failure it would report, to every rank */
    double msg[MSGD];
    memset(msg, 0, sizeof msg);
    if (st)
        memcpy(msg, mine.msg, strnlen(mine.msg, sizeof msg - 1));
    for (int q = 0; q < r->comm.size; q++)
        r->tcnt[q] = MSGD;
    if (r->comm.allgather(r->comm.ctx, msg, MSGD, r->trail, r->tcnt))
        return bf_g72r_exchange_failed(err);
    char text[sizeof msg];
    memcpy(text, r->trail + (size_t)first * MSGD, sizeof text);
    text[sizeof text - 1] = '\0';
    return bf_fail(err, fst, "%s", text);
}

int bf_g72_rank(const g72 *m) { return m->ranks ? m->ranks->comm.rank : 0; }
