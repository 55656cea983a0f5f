/* g72_ranks.c: model "greenspan72" split over ranks, with the same bits
 * as one process at any rank count.
 *
 * Why the same bits: the acceleration of a particle is a sum of terms
 * from the particles near it, taken in an order that the serial code
 * fixes by the cell list (repulsion.h: stripes of columns, then column,
 * row and slot; support.h: the columns of the strip in slot order, the
 * sweep in x order from the start of its chunk), and the slot order inside
 * a cell is the particles' index order (cells.h: a stable sort).  A rank
 * builds the cell list of the whole box on its own particles and those of
 * a halo of columns, in index order; every term of its own particles'
 * sums is then there, in the same relative order, and the sums are the
 * same bits.  The halo: the repulsion reads `reach` columns each way
 * (repulsion.c), the support-set gravity the squares within
 * bf_support_reach (one column more for the rounding of a column index).
 *
 * Every rank holds the whole state: after each a(x) the ranks exchange
 * what their own particles got (ax and ay + g) and how many of them got each
 * kind of g, and every rank then takes the same leapfrog step, reading
 * the accelerations straight from the exchange's buffer (no copy into
 * arrays of N), and the same wall rule on every particle, writes the same
 * diagnostics, and the one that writes the output (rank 0) has all of
 * it.  The work of a(x) falls as 1/R (plus the halo); the state, the step
 * and the exchange stay O(N) on every rank.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "models/g72_impl.h"
#include "particles/slabs.h"

struct g72_ranks {
    bf_ranks comm;
    bf_slabs sl;
    int32_t *col;             /* [n]: cell column of each particle */
    uint32_t *lid;            /* [n]: particle of each local index */
    double *lx, *ly, *lm;     /* [n]: local positions and masses */
    double *lax, *lay, *lg;   /* [n]: local results */
    uint8_t *lkind;           /* [n] */
    double *send, *recv;      /* [2 n + 7], [2 n + 7 size] */
    size_t *counts, *at;      /* [size] */
    /* particles of each kind of g (BF_SUP_*) at the last a(x): sums of
     * integers, exact in any order */
    unsigned long long kinds[4];
};

/* doubles a particle (ax, ay + g); the trailer: status, bi, bj and the
 * counts of the four kinds of g of the rank's own particles */
enum { PER = 2, TRAILER = 7 };

void bf_g72_ranks_free(g72_ranks *r)
{
    if (!r)
        return;
    bf_slabs_free(&r->sl);
    free(r->col);
    free(r->lid);
    free(r->lx);
    free(r->ly);
    free(r->lm);
    free(r->lax);
    free(r->lay);
    free(r->lg);
    free(r->lkind);
    free(r->send);
    free(r->recv);
    free(r->counts);
    free(r->at);
    free(r);
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

bf_status bf_greenspan72_over_ranks(void *model, const bf_ranks *comm,
                                    bf_err *err)
{
    g72 *m = model;
    bf_status st = refuse(m, err);
    if (st)
        return st;
    const size_t n = m->p.n, k = n ? n : 1, size = (size_t)comm->size;
    /* the exchange's counts and displacements are ints (MPI): the last
     * displacement is PER n + TRAILER (size - 1) */
    if (size > (size_t)INT32_MAX / TRAILER ||
        n > ((size_t)INT32_MAX - TRAILER * size) / PER)
        return bf_fail_key(err, BF_EINPUT, "greenspan72", "grid_nx",
                           "%zu particles are too many for a run over ranks",
                           n);
    g72_ranks *r = calloc(1, sizeof *r);
    if (!r)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    r->comm = *comm;
    int hl, hr;
    halo_columns(m, &hl, &hr);
    if ((st = bf_slabs_init(&r->sl, comm->size, m->cells.nx, hl, hr, err))) {
        free(r);
        return st;
    }
    r->col = malloc(k * sizeof *r->col);
    r->lid = malloc(k * sizeof *r->lid);
    r->lx = malloc(k * sizeof *r->lx);
    r->ly = malloc(k * sizeof *r->ly);
    r->lm = malloc(k * sizeof *r->lm);
    r->lax = malloc(k * sizeof *r->lax);
    r->lay = malloc(k * sizeof *r->lay);
    r->lg = malloc(k * sizeof *r->lg);
    r->lkind = malloc(k * sizeof *r->lkind);
    r->send = malloc((PER * k + TRAILER) * sizeof *r->send);
    r->recv = malloc((PER * k + TRAILER * size) * sizeof *r->recv);
    r->counts = malloc(size * sizeof *r->counts);
    r->at = malloc(size * sizeof *r->at);
    if (!r->col || !r->lid || !r->lx || !r->ly || !r->lm || !r->lax ||
        !r->lay || !r->lg || !r->lkind || !r->send || !r->recv ||
        !r->counts || !r->at) {
        bf_g72_ranks_free(r);
        return bf_fail(err, BF_EINTERNAL, "out of memory (%zu particles over "
                       "ranks)", n);
    }
    bf_g72_ranks_free(m->ranks);
    m->ranks = r;
    /* the a(x) of the set-up was one process's, in arrays that the steps
     * over ranks do not read: computed again over ranks, and not counted
     * twice */
    if (m->acc_valid) {
        m->acc_valid = 0;
        m->acc_replay = 1;
    }
    return BF_OK;
}

/* This rank's particles and halo into the local arrays, in index order
 * (the order of the serial cell list inside every cell). */
static size_t gather_local(g72_ranks *r, const bf_particles *p)
{
    int c0, c1;
    bf_slabs_reads(&r->sl, r->comm.rank, &c0, &c1);
    size_t nl = 0;
    for (size_t i = 0; i < p->n; i++)
        if (r->col[i] >= c0 && r->col[i] < c1) {
            r->lid[nl] = (uint32_t)i;
            r->lx[nl] = p->x[i];
            r->ly[nl] = p->y[i];
            r->lm[nl] = p->m[i];
            nl++;
        }
    return nl;
}

/* The own particles' results into send (index order), then the trailer:
 * 1 and the pair if two particles coincide, else 0; the counts of the
 * kinds of g. */
static size_t pack_own(g72_ranks *r, size_t nl, int bad, size_t bi,
                       size_t bj)
{
    const int me = r->comm.rank;
    size_t w = 0, kinds[4] = {0, 0, 0, 0};
    for (size_t l = 0; l < nl; l++) {
        if (r->sl.rank_of[r->col[r->lid[l]]] != me)
            continue;
        r->send[w++] = r->lax[l];
        /* the leapfrog's ay + g (eq 2.2), added here as it would add
         * them: the same bits, a third less to exchange */
        r->send[w++] = r->lay[l] + r->lg[l];
        kinds[r->lkind[l]]++;
    }
    r->send[w++] = bad;
    r->send[w++] = bad ? (double)r->lid[bi] : 0.0;
    r->send[w++] = bad ? (double)r->lid[bj] : 0.0;
    for (int k = 0; k < 4; k++) /* below 2^53: exact */
        r->send[w++] = (double)kinds[k];
    return w;
}

/* The trailers of every rank: the counts of the kinds of g (summed), 1
 * and the pair of the lowest rank that found two coincident particles.
 * The results stay in recv, read by bf_g72_leapfrog_ranks. */
static int read_trailers(g72_ranks *r, size_t *bi, size_t *bj)
{
    size_t off = 0;
    int bad = 0;
    memset(r->kinds, 0, sizeof r->kinds);
    for (int q = 0; q < r->comm.size; q++) {
        off += r->counts[q];
        const double *t = r->recv + off - TRAILER;
        if (!bad && t[0] != 0) {
            bad = 1;
            *bi = (size_t)t[1];
            *bj = (size_t)t[2];
        }
        for (int k = 0; k < 4; k++)
            r->kinds[k] += (unsigned long long)t[3 + k];
    }
    return bad;
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

/* Eqs 2.1-2.4 as in g72_leapfrog (greenspan72.c), the same operations in
 * the same order, with a(x) of particle i read from the part of recv of
 * the rank that owns it (its particles in index order). */
void bf_g72_leapfrog_ranks(g72 *m, double h, double dt)
{
    g72_ranks *r = m->ranks;
    bf_particles *p = &m->p;
    size_t off = 0;
    for (int q = 0; q < r->comm.size; q++) {
        r->at[q] = off;
        off += r->counts[q];
    }
    for (size_t i = 0; i < p->n; i++) {
        const int q = r->sl.rank_of[r->col[i]];
        const double *v = r->recv + r->at[q];
        r->at[q] += PER;
        p->vx[i] += h * v[0];
        p->vy[i] += h * v[1];
        m->x0[i] = p->x[i];
        m->y0[i] = p->y[i];
        p->x[i] += dt * p->vx[i];
        p->y[i] += dt * p->vy[i];
    }
}

bf_status bf_g72_accel_ranks(g72 *m, bf_err *err)
{
    g72_ranks *r = m->ranks;
    const bf_particles *p = &m->p;
    for (size_t i = 0; i < p->n; i++)
        r->col[i] = bf_cells_col(&m->cells, p->x[i]);
    bf_slabs_balance(&r->sl, r->col, p->n);
    const size_t nl = gather_local(r, p);
    bf_cells_build(&m->cells, r->lx, r->ly, r->lm, nl);
    size_t bi = 0, bj = 0;
    int bad = bf_repulsion_cells(&m->rep, &m->cells, &m->rw, r->lax, r->lay,
                                 &bi, &bj);
    bf_support_eval(m->sup, r->lx, r->ly, nl, &m->cells, r->lg, r->lkind);
    const size_t w = pack_own(r, nl, bad, bi, bj);
    for (int q = 0; q < r->comm.size; q++)
        r->counts[q] = PER * r->sl.own[q] + TRAILER;
    if (r->comm.allgather(r->comm.ctx, r->send, w, r->recv, r->counts))
        return bf_fail(err, BF_EIO, "the exchange between ranks failed");
    if (read_trailers(r, &bi, &bj))
        return bf_fail(err, BF_EUNSTABLE,
                       "particles %zu and %zu coincide at (%.9g, %.9g) with "
                       "xi = 0: the repulsion has no direction",
                       bi + 1, bj + 1, p->x[bi], p->y[bi]);
    return BF_OK;
}
