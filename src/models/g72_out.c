/* g72_out.c: the output of model "greenspan72" (its datasets, the rows of
 * the particles and the diagnostics, the settling criteria), in one
 * process or over ranks (rank 0 writes the whole state it gathers). */
#include <stdio.h>
#include <stdlib.h>

#include "io/dataset_paths.h"
#include "models/g72_impl.h"
#include "particles/pdiag.h"

static const bf_series_spec g72_series[] = {
    {.path = BF_DS_DIAG_KINETIC, .unit = "erg", .ncols = 3,
     .columns = "all, heavy (L1), light (L2)",
     .doc = "kinetic energy sum m|v|^2/2 with the half-step velocities: all, "
            "heavy (L1), light (L2)",
     .slot = BF_SLOT(g72, s_kin)},
    {.path = "/diag/mean_y", .unit = "cm", .ncols = 2,
     .columns = "heavy (L1), light (L2)",
     .doc = "mean height of the heavy (L1) and light (L2) particles",
     .slot = BF_SLOT(g72, s_mean)},
    {.path = "/diag/quarters", .unit = "1", .ncols = 8,
     .columns = "heavy q1, heavy q2, heavy q3, heavy q4, light q1, light q2, "
                "light q3, light q4",
     .doc = "particles per horizontal quarter of the box, bottom to top: "
            "heavy q1..q4, then light q1..q4",
     .slot = BF_SLOT(g72, s_layers)},
    {.path = "/diag/support_kinds", .unit = "1", .ncols = 4,
     .columns = "resting, partial, free fall, antigravity",
     .doc = "particles whose support-set gravity is: resting (g = 0), "
            "partial, free fall (g = -g0), antigravity (g > 0)",
     .slot = BF_SLOT(g72, s_kinds)},
    {.path = "/diag/settle", .unit = "1", .ncols = 4,
     .columns = "a, b, c, d",
     .doc = "(a) 1 if every heavy particle is below every light one; (b) 1 if "
            "every heavy one is below 'bottom'; (c) heavy particles below "
            "'bottom'; (d) 1 if the mean height of the heavy is below that of "
            "the light",
     .slot = BF_SLOT(g72, s_settle)},
    {.path = BF_DS_PARTICLES_TAG, .unit = "1", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "particle",
     .doc = "1: heavy fluid L1 (started above the interface), 2: light fluid "
            "L2"},
};
enum { G72_TAG = BF_NSERIES(g72_series) - 1 };
static const bf_series_table g72_table = {"greenspan72", g72_series,
                                          BF_NSERIES(g72_series)};
const bf_series_table *const bf_g72_tables[] = {&bf_particle_series,
                                                    &g72_table, NULL};

bf_status bf_g72_output_open(void *self, bf_out *out, bf_err *err)
{
    g72 *m = self;
    const size_t n = m->p.n;
    unsigned on = 0;
    if (m->out_mode != OUT_DIAG)
        on |= BF_PO_STEP | BF_PO_POS;
    if (m->out_mode == OUT_ALL)
        on |= m->ode ? BF_PO_VEL : BF_PO_VEL_HALF;
    const bf_series_extent ext[] = {{"particle", n}};
    bf_status st = bf_particles_output_open(&m->po, out, &m->p, on, err);
    if (!st)
        st = bf_out_open_table(out, g72_series, BF_NSERIES(g72_series), m,
                               ext, 1, 0, err);
    if (st)
        return st;
    double *tag = malloc((n ? n : 1) * sizeof *tag);
    if (!tag)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    for (size_t i = 0; i < n; i++)
        tag[i] = m->p.tag[i];
    st = bf_out_table_array(out, &g72_series[G72_TAG], tag, n, err);
    free(tag);
    if (!st)
        st = bf_out_attr_real(out, "/diag", "bottom", m->bottom, err);
    return st;
}

/* The diagnostics of a row, summed over the particles in index order, in
 * one pass or a block at a time (the same sums in the same order). */
typedef struct row_sums {
    bf_pdiag_acc h, l; /* heavy, light */
    double lay[8];     /* per quarter: heavy q1..q4, light q1..q4 */
    size_t below;      /* heavy particles below 'bottom' */
} row_sums;

static row_sums row_start(void)
{
    row_sums a = {bf_pdiag_acc_start(), bf_pdiag_acc_start(), {0}, 0};
    return a;
}

static void row_add(const g72 *m, row_sums *a, const bf_particles *p)
{
    bf_pdiag_acc_add(&a->h, p, TAG_HEAVY);
    bf_pdiag_acc_add(&a->l, p, TAG_LIGHT);
    bf_pdiag_layers_add(p, TAG_HEAVY, 0.0, m->height, 4, a->lay);
    bf_pdiag_layers_add(p, TAG_LIGHT, 0.0, m->height, 4, a->lay + 4);
    for (size_t i = 0; i < p->n; i++)
        a->below += p->tag[i] == TAG_HEAVY && p->y[i] < m->bottom;
}

/* The diagnostics' row of step n from the sums; `fail`: an append of the
 * particles' row failed.  The four settling criteria (how far the heavy
 * fluid has sunk; docs/models/greenspan72.md, settling): (a) 1 if every
 * heavy particle is below every light one, (b) 1 if every heavy one is
 * below 'bottom', (c) the number of heavy ones below 'bottom' (it holds
 * when at most one is above), (d) 1 if the mean height of the heavy is
 * below that of the light. */
static bf_status row_finish(g72 *m, const row_sums *a, long n, int fail,
                            bf_err *err)
{
    const bf_pdiag_group h = bf_pdiag_acc_end(&a->h),
                         l = bf_pdiag_acc_end(&a->l);
    double kin[3] = {h.kin + l.kin, h.kin, l.kin};
    double mean[2] = {h.mean_y, l.mean_y};
    double kinds[4], crit[NSETTLE];
    unsigned long long kc[4];
    bf_g72_kind_counts(m, kc);
    for (int k = 0; k < 4; k++) /* below 2^53: the sum of ones, exactly */
        kinds[k] = (double)kc[k];
    crit[0] = h.max_y < l.min_y;
    crit[1] = a->below == h.count;
    crit[2] = (double)a->below;
    crit[3] = h.mean_y < l.mean_y;
    /* criterion (c) holds when at most one heavy particle is off the
     * bottom ("at least three of the four stay at the bottom") */
    int holds[NSETTLE] = {crit[0] > 0, crit[1] > 0,
                          crit[2] + 1.0 >= (double)m->n_heavy, crit[3] > 0};
    for (int c = 0; c < NSETTLE; c++) {
        if (holds[c] && m->settle_first[c] < 0)
            m->settle_first[c] = n;
        if (!holds[c])
            m->settle_lastfail[c] = n;
    }
    m->settle_last_row = n;
    fail |= bf_series_append(m->s_kin, kin) | bf_series_append(m->s_mean, mean) |
            bf_series_append(m->s_layers, a->lay) |
            bf_series_append(m->s_kinds, kinds) |
            bf_series_append(m->s_settle, crit);
    if (fail)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

/* Over ranks every rank takes the row (bf_sim_opts rank, nranks): rank 0
 * gathers the state a block of particles at a time, in index order, and
 * adds each block to the row of the particles and to the sums; the others
 * send theirs.  Rank 0 holds one block, not the whole state. */
static bf_status row_ranks(g72 *m, long n, bf_err *err)
{
    const int root = bf_g72_rank(m) == 0,
              particles = m->rows++ % m->particles_every == 0;
    const size_t total = bf_g72_total(m);
    row_sums a = row_start();
    int fail = 0;
    for (size_t at = 0; at < total; at += BF_G72_BLOCK) {
        const size_t b = total - at < BF_G72_BLOCK ? total : at + BF_G72_BLOCK;
        const bf_particles *blk;
        bf_status st = bf_g72_gather_block(m, at, b, &blk, err);
        if (st)
            return st;
        if (!root)
            continue;
        if (particles)
            fail |= bf_particles_output_part(&m->po, blk, at == 0,
                                             (int64_t)n);
        row_add(m, &a, blk);
    }
    return root ? row_finish(m, &a, n, fail, err) : BF_OK;
}

bf_status bf_g72_output_row(void *self, long n, double t, bf_err *err)
{
    (void)t;
    g72 *m = self;
    bf_status st;
    if (!m->acc_valid && (st = bf_g72_accel(m, err)))
        return st;
    if (m->ranks)
        return row_ranks(m, n, err);
    int fail = 0;
    if (m->rows++ % m->particles_every == 0)
        fail |= bf_particles_output_row(&m->po, &m->p, (int64_t)n);
    row_sums a = row_start();
    row_add(m, &a, &m->p);
    return row_finish(m, &a, n, fail, err);
}

bf_status bf_g72_output_close(void *self, bf_out *out, bf_err *err)
{
    g72 *m = self;
    static const char *names[NSETTLE] = {"a_heavy_below_light",
                                         "b_all_heavy_at_bottom",
                                         "c_all_but_one_heavy_at_bottom",
                                         "d_mean_heavy_below_light"};
    bf_status st = bf_out_attr_int(out, "/", "wall_hits",
                                   (int64_t)m->wall_hits, err);
    for (int c = 0; !st && c < NSETTLE; c++) {
        char nm[96];
        snprintf(nm, sizeof nm, "settle_%s_first_step", names[c]);
        st = bf_out_attr_int(out, "/diag", nm, m->settle_first[c], err);
        if (!st) {
            /* first step from which it held at every later row (-1: not at
             * the last row) */
            long from = m->settle_lastfail[c] == m->settle_last_row
                            ? -1
                            : m->settle_lastfail[c] + 1;
            snprintf(nm, sizeof nm, "settle_%s_holds_from", names[c]);
            st = bf_out_attr_int(out, "/diag", nm, from, err);
        }
    }
    return st;
}
