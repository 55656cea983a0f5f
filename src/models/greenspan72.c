/* greenspan72.c: model "greenspan72", Greenspan's particle model of two
 * fluids mixing (Univ. Wisconsin CS TR 153, 1972).
 *
 * Particles of two fluids in the box [0, width] x [0, height]: L1 (the
 * heavy fluid, tag 1) starts above the line y = interface, L2 (tag 2)
 * below.  Leapfrog, eqs 2.1-2.4, with the half step first:
 *
 *   v^{1/2}   = v^0 + (dt/2) a(x^0)
 *   v^{k+1/2} = v^{k-1/2} + dt a(x^k)          (k >= 1)
 *   x^{k+1}   = x^k + dt v^{k+1/2},  then the walls (eq. 2.13, walls.h)
 *
 * a_j = (repulsion 2.11, 2.12 (repulsion.h)) + g_j y^ (support-set gravity
 * 2.8, 2.9 (support.h)), and with [hertz] enabled the Hertz repulsion of
 * the particles closer than 2R (hertz_pairs.h; not in the paper).
 * Initial velocities: the scene's, or uniform in [-V, V] per component
 * from GSL's mt19937 with [greenspan72] seed; an optional uniform
 * perturbation of +-perturb (another seed) for ensembles.
 *
 * The model does not conserve energy (support-set gravity has no potential
 * and no reaction), so it reports no energy to the time loop; the kinetic
 * energy is a diagnostic (dataset diag/kinetic), computed with the half-step
 * velocities v^{k-1/2} that the scheme carries.
 *
 * Invariant: every particle is in the closed box after every step (checked
 * every step in every build; the check costs < 1 % of a step).
 *
 * Output (rows at [scene] output_every): /particles/x, /particles/y and
 * (output = all) /particles/vx, /particles/vy [rows x N] (velocities at
 * t - dt/2), at every particles_every-th row, their steps in
 * /particles/step; diag/... (kinetic energy, mean heights, counts per horizontal
 * quarter, support kinds, settling criteria); /particles/mass and
 * /particles/tag once.
 */
#include <gsl/gsl_rng.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "particles/cells.h"
#include "integrators/arkode.h"
#include "models/g72_ode.h"
#include "models/greenspan.h"
#include "models/studies.h"
#include "particles/hertz_pairs.h"
#include "ballfilm/model.h"
#include "ballfilm/particles.h"
#include "particles/pdiag.h"
#include "particles/repulsion.h"
#include "particles/support.h"
#include "particles/walls.h"
#include "io/dataset_paths.h"
#include "models/g72_impl.h"


/* The keys of [greenspan72]. */
typedef struct g72_keys {
    double width, height, interface, d, m_heavy, m_light;
    int layout; /* LAYOUT_GRID, LAYOUT_LIST */
    long grid_nx, grid_ny;
    bf_reals positions, velocities;
    double v_random;
    long seed;
    bf_reals set_velocity;
    double perturb;
    long perturb_seed;
    double bottom;
    long threads, particles_every;
    int output; /* OUT_ALL, OUT_POSITIONS, OUT_DIAG */
    /* the time integrator: INT_LEAPFROG or INT_ARKODE (g72_ode.h) */
    int integrator, table;
    double rtol, atol, max_step;
    long max_steps;
} g72_keys;

enum { INT_LEAPFROG = 0, INT_ARKODE = 1 };

enum { LAYOUT_GRID = 0, LAYOUT_LIST = 1 };

static const bf_param g72_params[] = {
    {"width", BF_AT(g72_keys, width, BF_REAL), "cm", "100",
     "box width |AB| (x from 0)", BF_POS, 0, 0, NULL},
    {"height", BF_AT(g72_keys, height, BF_REAL), "cm", "100",
     "box height (y from 0)", BF_POS, 0, 0, NULL},
    {"interface", BF_AT(g72_keys, interface, BF_REAL), "cm", "75",
     "b: particles starting above y = b are the heavy fluid L1 (tag 1), the "
     "others L2 (tag 2)",
     0, 0, 0, NULL},
    {"d", BF_AT(g72_keys, d, BF_REAL), "cm", NULL,
     "particle width d: side of its square in the support-set gravity and "
     "the distance below which beta acts",
     BF_POS, 0, 0, NULL},
    {"m_heavy", BF_AT(g72_keys, m_heavy, BF_REAL), "g", NULL,
     "mass m(L1) of a heavy particle", BF_POS, 0, 0, NULL},
    {"m_light", BF_AT(g72_keys, m_light, BF_REAL), "g", NULL,
     "mass m(L2) of a light particle", BF_POS, 0, 0, NULL},
    {"layout", BF_AT(g72_keys, layout, BF_ENUM), "", "grid",
     "grid: grid_nx x grid_ny cell centres in the listing's order (top row "
     "first, left to right); list: the positions key",
     0, 0, 0, "grid|list"},
    {"grid_nx", BF_AT(g72_keys, grid_nx, BF_INT), "1", "16", "grid columns",
     BF_MIN, 1, 0, NULL},
    {"grid_ny", BF_AT(g72_keys, grid_ny, BF_INT), "1", "16", "grid rows",
     BF_MIN, 1, 0, NULL},
    {"positions", BF_AT(g72_keys, positions, BF_REALS), "cm", "",
     "layout = list: x1 y1 x2 y2 ... (particle k is pair k)", 0, 0, 0, NULL},
    {"velocities", BF_AT(g72_keys, velocities, BF_REALS), "cm/s", "",
     "vx1 vy1 vx2 vy2 ... at t = 0 (default: random in [-V, V])", 0, 0, 0,
     NULL},
    {"v_random", BF_AT(g72_keys, v_random, BF_REAL), "cm/s", "0",
     "V: random initial velocity components uniform in [-V, V] (when no "
     "velocities are given)",
     BF_NONNEG, 0, 0, NULL},
    {"seed", BF_AT(g72_keys, seed, BF_INT), "1", "1972",
     "seed of the random velocities (GSL mt19937)", BF_MIN, 0, 0, NULL},
    {"set_velocity", BF_AT(g72_keys, set_velocity, BF_REALS), "1, cm/s", "",
     "triples k vx vy: particle k (1-based) starts with (vx, vy) after the "
     "random draw",
     0, 0, 0, NULL},
    {"perturb", BF_AT(g72_keys, perturb, BF_REAL), "cm/s", "0",
     "add a uniform perturbation in [-perturb, perturb] to every initial "
     "velocity component (ensembles)",
     BF_NONNEG, 0, 0, NULL},
    {"perturb_seed", BF_AT(g72_keys, perturb_seed, BF_INT), "1", "1",
     "seed of the perturbation", BF_MIN, 0, 0, NULL},
    {"bottom", BF_AT(g72_keys, bottom, BF_REAL), "cm", "0",
     "height of 'the bottom' in the settling diagnostics (0: the support "
     "band height dx)",
     BF_NONNEG, 0, 0, NULL},
    {"threads", BF_AT(g72_keys, threads, BF_INT), "1", "0",
     "OpenMP threads for the forces (0: OMP_NUM_THREADS if set, else 1); "
     "the results do not depend on it",
     BF_NONNEG, 0, 0, NULL},
    {"particles_every", BF_AT(g72_keys, particles_every, BF_INT), "1", "1",
     "write the per-particle rows (/particles/x ...) at every N-th output "
     "row only; their steps are in /particles/step",
     BF_MIN, 1, 0, NULL},
    {"output", BF_AT(g72_keys, output, BF_ENUM), "", "all",
     "per-row datasets: all (positions, velocities, diagnostics), positions "
     "(no velocities), diagnostics (none per particle)",
     0, 0, 0, "all|positions|diagnostics"},
    {"integrator", BF_AT(g72_keys, integrator, BF_ENUM), "", "leapfrog",
     "time integrator: leapfrog (the paper's, eqs 2.1-2.4) or arkode "
     "(ARKODE adaptive ERK on the same forces as an ODE, stopped at every "
     "[scene] dt, the walls applied there; its velocities are at t, not "
     "t - dt/2)",
     0, 0, 0, "leapfrog|arkode"},
    BF_PARTICLE_ARKODE_KEYS(g72_keys),
    {0},
};

static const bf_section_spec g72_spec = BF_SECTION(
    "greenspan72",
    "two fluids mixing, Greenspan 1972: box, particles, initial data",
    g72_params, g72_keys);


bf_particles *bf_greenspan72_particles(void *model)
{
    return &((g72 *)model)->p;
}

int bf_greenspan72_adaptive(const bf_model_setup *s)
{
    const g72_keys *k = bf_setup_get(s, &g72_spec, NULL);
    return k && k->integrator == INT_ARKODE;
}

bf_support *bf_greenspan72_support(void *model)
{
    return ((g72 *)model)->sup;
}

static void g72_destroy(void *self)
{
    g72 *m = self;
    if (!m)
        return;
    bf_particles_free(&m->p);
    bf_support_free(m->sup);
    bf_g72_ode_free(m->ode);
    bf_g72_ranks_free(m->ranks);
    bf_cells_free(&m->cells);
    free(m->ax);
    free(m->ay);
    free(m->g);
    bf_repulsion_work_free(&m->rw);
    free(m->x0);
    free(m->y0);
    free(m->kind);
    free(m);
}

/* The number of particles of the keys (a grid's may be refused). */
static double g72_count(const g72_keys *k)
{
    return k->layout == LAYOUT_LIST ? (double)(k->positions.n / 2)
                                    : (double)k->grid_nx * (double)k->grid_ny;
}

/* Doubles per particle: x, y, vx, vy, m and the tag; ax, ay, g and the
 * old positions; the cell list's six arrays and the support sweep's
 * eleven (ints and doubles alike counted as 8 bytes); the buffered rows
 * of the per-particle outputs; 2 more per thread for the repulsion's
 * work arrays.  Measured: the smallest ulimit -v of a two-step run of
 * runs/greenspan72_large.ini grows by 306-319 B (38-40 doubles) per
 * particle from 224^2 to 448^2 particles (docs/reliability.md), before
 * the sweep's query and update lists (issue 21: 52 B = 6.5 doubles more
 * per particle, counted from their allocations); 54 keeps the margin. */
static void g72_memory(const bf_model_setup *setup, bf_mem_need *need)
{
    const g72_keys *k = bf_setup_get(setup, &g72_spec, NULL);
    if (!k)
        return;
    double n = g72_count(k), threads = k->threads > 1 ? (double)k->threads : 1;
    double per = 54.0 + 2.0 * threads;
    /* split over R ranks: the particles (7 doubles) whole until the
     * split, the rest for a rank's share, counted as 2/R of them for the
     * halo's margin */
    const double R = setup->nranks;
    if (R > 2)
        per = 7.0 + (per - 7.0) * 2.0 / R;
    need->bytes = 8.0 * per * n;
    snprintf(need->what, sizeof need->what, "%.3g particles x %.0f doubles",
             n, per);
    snprintf(need->section, sizeof need->section, "greenspan72");
    snprintf(need->key, sizeof need->key,
             k->layout == LAYOUT_LIST ? "positions" : "grid_nx");
}

/* Positions and initial velocities from the keys. */
static bf_status g72_initial(g72 *m, const g72_keys *k72, bf_err *err)
{
    const char *S = "greenspan72";
    size_t n, nv = k72->velocities.n, npos = k72->positions.n;
    const double *pos = k72->positions.v;
    const double *vel = k72->velocities.v;
    int list = k72->layout == LAYOUT_LIST;
    long gx = k72->grid_nx, gy = k72->grid_ny;
    if (list) {
        if (npos == 0 || npos % 2)
            return bf_fail_key(err, BF_EINPUT, S, "positions",
                               "layout = list needs x y pairs (%zu numbers "
                               "given)",
                               npos);
    } else {
        if (npos)
            return bf_fail_key(err, BF_EINPUT, S, "positions",
                               "positions are only used with layout = list");
        if ((double)gx * (double)gy > 5e7)
            return bf_fail_key(err, BF_EINPUT, S, "grid_nx",
                               "%ld x %ld particles is too many", gx, gy);
    }
    n = (size_t)g72_count(k72);
    if (nv && nv != 2 * n)
        return bf_fail_key(err, BF_EINPUT, S, "velocities",
                           "%zu numbers for %zu particles (need %zu)", nv, n,
                           2 * n);
    bf_status st = bf_particles_init(&m->p, n, err);
    if (st)
        return st;
    bf_particles *p = &m->p;
    for (size_t k = 0; k < n; k++) {
        if (list) {
            p->x[k] = pos[2 * k];
            p->y[k] = pos[2 * k + 1];
        } else {
            /* listing INITAL: k = (I-1) NCOL + J, row I = 1 at the top */
            size_t I = k / (size_t)gx, J = k % (size_t)gx;
            double bx = m->width / (double)gx, by = m->height / (double)gy;
            p->x[k] = bx * (double)J + 0.5 * bx;
            p->y[k] = by * (double)((size_t)gy - 1 - I) + 0.5 * by;
        }
        if (!(p->x[k] >= 0 && p->x[k] <= m->width && p->y[k] >= 0 &&
              p->y[k] <= m->height))
            return bf_fail_key(err, BF_EINPUT, S, "positions",
                               "particle %zu at (%g, %g) is outside the box "
                               "[0, %g] x [0, %g]",
                               k + 1, p->x[k], p->y[k], m->width, m->height);
    }
    if (nv) {
        for (size_t k = 0; k < n; k++) {
            p->vx[k] = vel[2 * k];
            p->vy[k] = vel[2 * k + 1];
        }
    } else {
        double V = k72->v_random;
        gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
        if (!r)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        gsl_rng_set(r, (unsigned long)k72->seed);
        for (size_t k = 0; k < n; k++) {
            p->vx[k] = V * (2.0 * gsl_rng_uniform(r) - 1.0);
            p->vy[k] = V * (2.0 * gsl_rng_uniform(r) - 1.0);
        }
        gsl_rng_free(r);
    }
    size_t ns = k72->set_velocity.n;
    const double *set = k72->set_velocity.v;
    if (ns % 3)
        return bf_fail_key(err, BF_EINPUT, S, "set_velocity",
                           "needs triples k vx vy (%zu numbers)", ns);
    for (size_t t = 0; t < ns; t += 3) {
        double k = set[t];
        if (!(k >= 1 && k <= (double)n && k == floor(k)))
            return bf_fail_key(err, BF_EINPUT, S, "set_velocity",
                               "particle number %g is not in 1..%zu", k, n);
        p->vx[(size_t)k - 1] = set[t + 1];
        p->vy[(size_t)k - 1] = set[t + 2];
    }
    double eps = k72->perturb;
    if (eps > 0) {
        gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
        if (!r)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        gsl_rng_set(r, (unsigned long)k72->perturb_seed);
        for (size_t k = 0; k < n; k++) {
            p->vx[k] += eps * (2.0 * gsl_rng_uniform(r) - 1.0);
            p->vy[k] += eps * (2.0 * gsl_rng_uniform(r) - 1.0);
        }
        gsl_rng_free(r);
    }
    double mh = k72->m_heavy, ml = k72->m_light;
    m->n_heavy = 0;
    for (size_t k = 0; k < n; k++) {
        int heavy = p->y[k] > m->interface;
        p->tag[k] = heavy ? TAG_HEAVY : TAG_LIGHT;
        p->m[k] = heavy ? mh : ml;
        m->n_heavy += (size_t)heavy;
    }
    return BF_OK;
}

/* a(x) for the ODE of integrator = arkode (g72_ode.h) */
static bf_status g72_accel_cb(void *m, bf_err *err)
{
    return bf_g72_accel(m, err);
}

static bf_status g72_create(void **self, const bf_model_setup *setup,
                            bf_err *err)
{
    const g72_keys *k72 = bf_setup_get(setup, &g72_spec, NULL);
    const bf_walls_keys *kw = bf_setup_get(setup, &bf_walls_spec, NULL);
    const bf_repulsion_keys *kr = bf_setup_get(setup, &bf_repulsion_spec, NULL);
    const bf_support_keys *ks = bf_setup_get(setup, &bf_support_spec, NULL);
    const bf_hertz_keys *kh = bf_setup_get(setup, &bf_hertz_spec, NULL);
    if (!k72 || !kw || !kr || !ks || !kh)
        return bf_fail(err, BF_EINTERNAL, "greenspan72: sections missing "
                       "from the setup");
    g72 *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_status st;
    m->width = k72->width;
    m->height = k72->height;
    m->interface = k72->interface;
    double d = k72->d;
    m->out_mode = k72->output;
    m->particles_every = k72->particles_every;
    m->threads = (int)k72->threads;
#ifdef _OPENMP
    /* opt-in: spinning threads on a machine whose other cores are busy are
     * slower than one thread */
    if (m->threads == 0)
        m->threads = getenv("OMP_NUM_THREADS") ? omp_get_max_threads() : 1;
    m->nthr = m->threads;
#else
    m->threads = m->nthr = 1;
#endif
    bf_box box = {0.0, m->width, 0.0, m->height};
    bf_support_params sp;
    bf_walls_from_keys(&m->walls, kw, box);
    if ((st = bf_repulsion_from_keys(&m->rep, kr, d, err)) ||
        (st = bf_support_params_from_keys(&sp, ks, box, d, err)) ||
        (st = g72_initial(m, k72, err)))
        goto fail;
    sp.threads = m->threads;
    m->hertz_on = kh->enabled;
    m->hertz.k = kh->k;
    m->hertz.R = kh->radius > 0 ? kh->radius : 0.5 * d;
    m->bottom = k72->bottom;
    if (m->bottom == 0)
        m->bottom = sp.dx;
    const size_t n = m->p.n;
    /* built to be split over ranks (g72_ranks.c): the work for all
     * particles (about 400 of the 450 bytes a particle) is allocated for
     * each rank's share once it is split; the split refuses what it does
     * not support, on a model built whole */
    const int split = setup->nranks > 1 && m->rep.use_cells &&
                      sp.method != BF_SUPPORT_NAIVE && !kh->enabled &&
                      k72->integrator != INT_ARKODE;
    const size_t cap = split ? 1 : n;
    m->split_ready = split;
    if ((st = bf_support_create(&m->sup, &sp, cap, err)))
        goto fail;
    m->need_cells = m->rep.use_cells || sp.method != BF_SUPPORT_NAIVE;
    if (m->need_cells) {
        /* cells of the cutoff (or the requested side) for the repulsion
         * and the support queries alike: cells of half the cutoff test
         * fewer candidates, but at Greenspan's densities (2.6 particles
         * per cutoff^2) they hold 0.6 particles each, and the many short
         * runs cost more in loop overhead and mispredicted loop exits
         * (Example 2: 12 % slower); without a cutoff, cells of dx for the
         * support queries */
        double h = m->rep.use_cells ? (m->rep.cell > 0 ? m->rep.cell
                                                        : m->rep.cutoff)
                                    : sp.dx;
        if ((st = bf_cells_init(&m->cells, 0.0, 0.0, m->width, m->height, h,
                                cap, err)))
            goto fail;
    }
    size_t k = cap ? cap : 1;
    m->ax = malloc(k * sizeof *m->ax);
    m->ay = malloc(k * sizeof *m->ay);
    m->g = malloc(k * sizeof *m->g);
    m->x0 = malloc(k * sizeof *m->x0);
    m->y0 = malloc(k * sizeof *m->y0);
    m->kind = malloc(k * sizeof *m->kind);
    if (!m->ax || !m->ay || !m->g || !m->x0 || !m->y0 || !m->kind) {
        st = bf_fail(err, BF_EINTERNAL, "out of memory (%zu particles)", n);
        goto fail;
    }
    if (m->rep.use_cells &&
        (st = bf_repulsion_work_init(&m->rw, cap, m->threads, err)))
        goto fail;
    for (int c = 0; c < NSETTLE; c++) {
        m->settle_first[c] = -1;
        m->settle_lastfail[c] = -1;
    }
    m->settle_last_row = -1;
    /* a(x) at t = 0, which the first row or step would compute: particles
     * that coincide at the start are the scene's fault, not the run's
     * (over ranks it is computed by the split) */
    if (!split && (st = bf_g72_accel(m, err))) {
        bf_err_prefix(err, "at t = 0");
        err->status = st = BF_EINPUT;
        bf_err_set_key(err, "greenspan72",
                       k72->layout == LAYOUT_LIST ? "positions" : "layout");
        goto fail;
    }
    bf_g72_ode_opts oo = {.table = k72->table, .rtol = k72->rtol,
                          .atol = k72->atol, .max_step = k72->max_step,
                          .max_steps = k72->max_steps};
    if (k72->integrator == INT_ARKODE &&
        (st = bf_g72_ode_create(&m->ode, &m->p, m->ax, m->ay, m->g,
                                g72_accel_cb, m, &oo, err)))
        goto fail;
    *self = m;
    return BF_OK;
fail:
    g72_destroy(m);
    return st;
}

/* The repulsion into ax, ay; 1 if two particles coincide (bi, bj). */
static int g72_repulsion(g72 *m, const bf_cells *c, size_t *bi, size_t *bj)
{
    const bf_particles *p = &m->p;
    if (m->rep.use_cells)
        return bf_repulsion_cells(&m->rep, c, &m->rw, m->ax, m->ay, bi, bj);
    return bf_repulsion_all_pairs(&m->rep, p->x, p->y, p->m, p->n, m->ax,
                                  m->ay, bi, bj);
}

/* a(x): repulsion into ax, ay; support-set gravity into g (and kind).
 * With two or more threads and few particles the two run side by side (they
 * are independent); with many particles each is parallel inside. */
static bf_status g72_forces(g72 *m, bf_err *err)
{
    bf_particles *p = &m->p;
    size_t bi = 0, bj = 0;
    int bad = 0;
    if (m->need_cells)
        bf_cells_build(&m->cells, p->x, p->y, p->m, p->n);
    const bf_cells *c = m->need_cells ? &m->cells : NULL;
    if (m->nthr >= 2 && p->n < 4096) {
#ifdef _OPENMP
#pragma omp parallel sections num_threads(2)
        {
#pragma omp section
            bad = g72_repulsion(m, c, &bi, &bj);
#pragma omp section
            bf_support_eval(m->sup, p->x, p->y, p->n, c, m->g, m->kind);
        }
#endif
    } else {
        /* one thread: no parallel region (libgomp allocates a team for
         * every region, even for one with if (0)) */
        bad = g72_repulsion(m, c, &bi, &bj);
        bf_support_eval(m->sup, p->x, p->y, p->n, c, m->g, m->kind);
    }
    if (bad)
        return bf_fail(err, BF_EUNSTABLE,
                       "particles %zu and %zu coincide at (%.9g, %.9g) with "
                       "xi = 0: the repulsion has no direction",
                       bi + 1, bj + 1, p->x[bi], p->y[bi]);
    /* the Hertz contacts (after the repulsion, which overwrites ax, ay) */
    if (m->hertz_on &&
        (c ? bf_hertz_pairs_cells(&m->hertz, c, m->ax, m->ay, &bi, &bj)
           : bf_hertz_pairs_all(&m->hertz, p->x, p->y, p->m, p->n, m->ax,
                                m->ay, &bi, &bj)))
        return bf_fail(err, BF_EUNSTABLE,
                       "particles %zu and %zu coincide at (%.9g, %.9g): the "
                       "Hertz force has no direction",
                       bi + 1, bj + 1, p->x[bi], p->y[bi]);
    return BF_OK;
}

bf_status bf_g72_accel(g72 *m, bf_err *err)
{
    if (m->split_ready && !m->ranks)
        return bf_fail(err, BF_EINTERNAL, "greenspan72: built to be split "
                       "over ranks (bf_sim_opts nranks) but not split");
    bf_status st = m->ranks ? bf_g72_accel_ranks(m, err) : g72_forces(m, err);
    if (st)
        return st;
    if (m->acc_replay)
        m->acc_replay = 0;
    else
        m->evals++;
    m->acc_valid = 1;
    return BF_OK;
}

/* Eqs 2.1-2.4 for particle i: v += h a, x += dt v (the walls follow). */
static inline void g72_leapfrog(g72 *m, size_t i, double h, double dt)
{
    bf_particles *p = &m->p;
    p->vx[i] += h * m->ax[i];
    p->vy[i] += h * (m->ay[i] + m->g[i]);
    m->x0[i] = p->x[i];
    m->y0[i] = p->y[i];
    p->x[i] += dt * p->vx[i];
    p->y[i] += dt * p->vy[i];
}

static bf_status g72_step(void *self, long n, double t, double dt, bf_err *err)
{
    g72 *m = self;
    bf_particles *p = &m->p;
    bf_status st;
    if (!m->acc_valid && (st = bf_g72_accel(m, err)))
        return st;
    unsigned long long kinds[4];
    bf_g72_kind_counts(m, kinds);
    for (int k = 0; k < 4; k++)
        m->kind_total[k] += kinds[k];
    const double h = n == 0 ? 0.5 * dt : dt; /* eqs 2.1-2.2: half step first */
    const size_t np = p->n;
    if (m->ode) {
        memcpy(m->x0, p->x, np * sizeof *p->x);
        memcpy(m->y0, p->y, np * sizeof *p->y);
        m->acc_valid = 0;
        if ((st = bf_g72_ode_step(m->ode, t, dt, err)))
            return st;
    } else if (m->nthr > 1 && np >= 16384) {
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(m->nthr)
        for (size_t i = 0; i < np; i++)
            g72_leapfrog(m, i, h, dt);
#endif
    } else {
        for (size_t i = 0; i < np; i++)
            g72_leapfrog(m, i, h, dt);
    }
    m->acc_valid = 0;
    if (m->ranks) {
        /* over ranks (np: this rank's particles): the walls and the box
         * checked on each rank, their failures agreed */
        if ((st = bf_g72_walls_ranks(m, err)))
            return st;
        m->steps++;
        return bf_g72_accel(m, err);
    }
    if ((st = bf_walls_apply(&m->walls, p, m->x0, m->y0, &m->wall_hits, err)))
        return st;
    /* the invariant (a non-finite position would fail it too: the wall
     * rule refuses non-finite particles) */
    size_t bad;
    if (!bf_box_contains_all(&m->walls.box, p, &bad))
        return bf_fail(err, BF_EINTERNAL,
                       "particle %zu left the box: (%.17g, %.17g) (a bug in "
                       "the wall rule)",
                       bad + 1, p->x[bad], p->y[bad]);
    m->steps++;
    return bf_g72_accel(m, err);
}

static void g72_counters(const void *self, bf_counters *c)
{
    const g72 *m = self;
    if (m->ode) {
        memset(c, 0, sizeof *c);
        bf_ark1_counters(bf_g72_ode_arkode(m->ode), c);
        return;
    }
    c->steps = m->steps;
    c->evals = m->evals;
}

void bf_greenspan72_describe(void *model, char *buf, size_t cap, int *order)
{
    bf_g72_ode_describe(((g72 *)model)->ode, buf, cap, order);
}

static void g72_report(const void *self, FILE *f)
{
    const g72 *m = self;
    unsigned long long tot = 0;
    for (int k = 0; k < 4; k++)
        tot += m->kind_total[k];
    fprintf(f, "particles:         %zu (%zu heavy), wall hits %llu\n",
            bf_g72_total(m), m->n_heavy, m->wall_hits);
    if (tot)
        fprintf(f, "support gravity:   resting %.3f, partial %.3f, free fall "
                   "%.3f, antigravity %.3f (fractions of particle-steps)\n",
                (double)m->kind_total[0] / (double)tot,
                (double)m->kind_total[1] / (double)tot,
                (double)m->kind_total[2] / (double)tot,
                (double)m->kind_total[3] / (double)tot);
    static const char *what[NSETTLE] = {
        "(a) every heavy particle below every light one",
        "(b) every heavy particle below 'bottom'",
        "(c) all heavy but at most one below 'bottom'",
        "(d) mean height of heavy below that of light"};
    if (m->settle_last_row >= 0)
        for (int c = 0; c < NSETTLE; c++) {
            long from = m->settle_lastfail[c] == m->settle_last_row
                            ? -1
                            : m->settle_lastfail[c] + 1;
            fprintf(f, "settling %s: first at step %ld, ", what[c],
                    m->settle_first[c]);
            if (from < 0)
                fprintf(f, "not at the end\n");
            else
                fprintf(f, "holds at every output row from step %ld on\n",
                        from);
        }
}

/* The state beyond the particles (the accelerations are recomputed from
 * the restored positions). */
static const bf_field g72_state[] = {
    BF_FIELD_ARRAY(g72, kind_total, BF_F_ULL, "particle-steps"),
    BF_FIELD(g72, steps, BF_F_ULL, "1"),
    BF_FIELD(g72, evals, BF_F_ULL, "1"),
    BF_FIELD(g72, wall_hits, BF_F_ULL, "1"),
    BF_FIELD_ARRAY(g72, settle_first, BF_F_LONG, "step"),
    BF_FIELD_ARRAY(g72, settle_lastfail, BF_F_LONG, "step"),
    BF_FIELD(g72, settle_last_row, BF_F_LONG, "step"),
    BF_FIELD(g72, rows, BF_F_LONG, "1"),
    BF_FIELD(g72, acc_valid, BF_F_INT, "1"),
};

/* Over ranks every rank takes the checkpoint (bf_sim_opts follower; ck
 * NULL but on rank 0): rank 0 gathers the whole state and saves it in
 * index order, which any number of ranks continues. */
static bf_status g72_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    g72 *m = (g72 *)self; /* over ranks: the exchange's buffers */
    bf_particles all;
    const bf_particles *p = &m->p;
    bf_status st;
    if (m->ranks) {
        if ((st = bf_g72_gather(m, &all, err)))
            return st;
        if (bf_g72_rank(m) != 0 || !ck) {
            bf_particles_free(&all);
            return BF_OK;
        }
        p = &all;
    }
    st = bf_particles_save(p, ck, "g72.p", err);
    if (p == &all)
        bf_particles_free(&all);
    if (!st)
        st = bf_ckpt_put_fields(ck, "g72", g72_state, BF_NFIELDS(g72_state),
                                m, err);
    if (!st && m->ode)
        st = bf_ark1_save(bf_g72_ode_arkode(m->ode), ck, "g72.ode", err);
    return st;
}

static bf_status g72_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    g72 *m = self;
    bf_status st = bf_particles_load(&m->p, ck, "g72.p", err);
    if (!st)
        st = bf_ckpt_get_fields(ck, "g72", g72_state, BF_NFIELDS(g72_state),
                                m, err);
    /* one output row per step at most, the initial one included (the
     * count is incremented at each row: an edited one could overflow) */
    if (!st && (m->rows < 0 || (unsigned long long)m->rows > m->steps + 1 ||
                m->rows == LONG_MAX))
        st = bf_fail(err, BF_EINPUT, "checkpoint: g72.rows = %ld output rows "
                     "after %llu steps", m->rows, (unsigned long long)m->steps);
    if (!st && m->ode)
        st = bf_ark1_load(bf_g72_ode_arkode(m->ode), ck, "g72.ode", err);
    /* a(x) is recomputed from the restored positions; if the run had it,
     * that is no new evaluation (the counters stay the uninterrupted
     * run's) */
    m->acc_replay = m->acc_valid;
    m->acc_valid = 0;
    return st;
}

static size_t g72_state_vars(void *self, bf_state_var *vars, size_t cap)
{
    return bf_particles_state_vars(&((g72 *)self)->p, vars, cap);
}

static bf_status g72_set_state(void *self, const char *name, const double *v,
                               size_t n, bf_err *err)
{
    g72 *m = self;
    if (m->ranks)
        return bf_fail(err, BF_EINPUT, "the state of a run over ranks is "
                       "split between them: set %s before the split", name);
    m->acc_valid = 0; /* the forces of the new positions */
    return bf_particles_set_var(&m->p, &m->walls.box, name, v, n, err);
}

static const bf_section_spec *const g72_specs[] = {
    &g72_spec,     &bf_repulsion_spec, &bf_support_spec,
    &bf_walls_spec, &bf_hertz_spec,    NULL};

const bf_model_type bf_model_greenspan72 = {
    .name = "greenspan72",
    .series = bf_g72_tables,
    .doc = "two fluids mixing: support-set gravity, repulsion, damped walls "
           "(Greenspan 1972)",
    .flags = 0,
    .specs = g72_specs,
    .create = g72_create,
    .destroy = g72_destroy,
    .memory = g72_memory,
    .step = g72_step,
    .output_open = bf_g72_output_open,
    .output_row = bf_g72_output_row,
    .output_close = bf_g72_output_close,
    .counters = g72_counters,
    .report = g72_report,
    .checkpoint_save = g72_save,
    .checkpoint_load = g72_load,
    .state = g72_state_vars,
    .set_state = g72_set_state,
    .study = &bf_study_greenspan72,
};
