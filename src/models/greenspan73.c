/* greenspan73.c: model "greenspan73", Greenspan's arithmetic particle
 * theory of fluids (Univ. Wisconsin CS TR 171, 1973): the implicit,
 * exactly energy-conserving scheme (2.1)-(2.4) (implicit.h, dforce.h).
 *
 * Layouts (the paper's examples; docs/models/greenspan73.md, layouts):
 *   hexagon  P1-P11 at ((i+1/2) r0, h), P12-P23 at (i r0, 0), P24-P34 at
 *            ((i+1/2) r0, -h), r0 the pair equilibrium distance, h = r0
 *            sqrt(3)/2; v_i = (V + e_i1, e_i2), the 68 numbers e drawn once
 *            (GSL mt19937, seed) uniform in (-1, 1) and scaled so that
 *            max |e| = J V / 100.
 *   wall     P2..P9 at x = 0, BX, ..., 7 BX (BX = r0), y = 0; the fluid
 *            particle P1 at (1.5 BX, BY) (hollow, the reconstruction of the
 *            text's (0.1717, 0.9914)), at the text's numbers literally, or
 *            at (3.5 BX, BY) (centre, the penetration example), BY = r0
 *            sqrt(3)/2, with speed |v| at angle theta below (or, the
 *            listing's sign, above) the horizontal; P10 at (3.5 BX, -BY)
 *            if below = true.
 *   list     positions, velocities, masses from the scene.
 * The readings where the text and Jones's listing differ are options: the
 * inertia of the update (mass = paper: a = F/m; fortran: v += dt F), the
 * wall mass, who feels gravity (listed particles or all free ones), the
 * fixed particles, the start of P1, the sign of theta.
 *
 * A step that the solver cannot do is retried as two half steps (up to
 * max_halvings times, counted and reported) when on_failure = halve, or
 * stops the run with BF_ENOCONV (on_failure = stop); never a silent
 * continue.  Every (sub)step conserves K + V to the solver tolerance.
 *
 * Energy to the time loop: K = sum mu |v|^2/2 over free particles,
 * V = pair potential (2.17) + gravity.  Output: /particles/x, y, vx, vy
 * [rows x n]; diag/energy [rows x 5]: K, V pair, V gravity, E, E - K_cm;
 * diag/energy_drift [rows x 2]: (E - E_0)/|E_0| and the same for E - K_cm;
 * diag/iterations and diag/substeps of the step ending at the row.
 */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/arkode.h"
#include "models/g73_ode.h"
#include "particles/dforce.h"
#include "models/greenspan.h"
#include "models/studies.h"
#include "particles/implicit.h"
#include "ballfilm/model.h"
#include "ballfilm/particles.h"
#include "particles/pdiag.h"
#include "io/dataset_paths.h"

/* The keys of [greenspan73]. */
typedef struct g73_keys {
    int layout; /* LAYOUT_HEXAGON, LAYOUT_WALL, LAYOUT_LIST */
    long alpha, beta;
    double p, q;
    bf_reals pairs;
    double g;
    int gravity; /* GRAVITY_LISTED, GRAVITY_ALL */
    bf_reals gravity_on, fixed;
    int mass; /* MASS_PAPER, MASS_FORTRAN */
    double speed, jitter;
    long seed;
    double theta;
    int theta_dir; /* 0: down, 1: up */
    int start;     /* START_HOLLOW, START_TEXT, START_CENTRE */
    int below;
    double fluid_mass, wall_mass;
    bf_reals positions, velocities, masses;
    int solver; /* bf_implicit_method */
    double omega, tol;
    long max_iter;
    int jacobian; /* 0: dense, 1: sparse */
    double jacobian_cutoff;
    int on_failure; /* 0: stop, 1: halve */
    long max_halvings, watch;
    /* the time integrator (g73_ode.h) */
    int integrator; /* BF_G73_* */
    int table;
    double rtol, atol, max_step;
    long max_steps;
} g73_keys;

enum { LAYOUT_HEXAGON = 0, LAYOUT_WALL = 1, LAYOUT_LIST = 2 };
enum { GRAVITY_LISTED = 0, GRAVITY_ALL = 1 };
enum { MASS_PAPER = 0, MASS_FORTRAN = 1 };
enum { START_HOLLOW = 0, START_TEXT = 1, START_CENTRE = 2 };
/* the choices of `start`, for the summary */
static const char *const start_names[] = {"hollow", "text", "centre"};

static const bf_param g73_params[] = {
    {"layout", BF_AT(g73_keys, layout, BF_ENUM), "", "hexagon",
     "hexagon: the 34-particle flow; wall: a fluid particle and the wall "
     "particles P2-P9 (and P10); list: positions/velocities/masses",
     0, 0, 0, "hexagon|wall|list"},
    {"alpha", BF_AT(g73_keys, alpha, BF_INT), "1", "7",
     "attraction exponent alpha (p / r^alpha)", BF_MIN | BF_MAX, 2, 60, NULL},
    {"beta", BF_AT(g73_keys, beta, BF_INT), "1", "10",
     "repulsion exponent beta (q / r^beta)", BF_MIN | BF_MAX, 2, 60, NULL},
    {"p", BF_AT(g73_keys, p, BF_REAL), "1", "1",
     "attraction constant p_ij of every pair", BF_NONNEG, 0, 0, NULL},
    {"q", BF_AT(g73_keys, q, BF_REAL), "1", "1",
     "repulsion constant q_ij of every pair", BF_NONNEG, 0, 0, NULL},
    {"pairs", BF_AT(g73_keys, pairs, BF_REALS), "1", "",
     "quadruples i j p q: other constants for the pair (i, j), 1-based", 0, 0,
     0, NULL},
    {"g", BF_AT(g73_keys, g, BF_REAL), "cm/s^2", "0", "gravity (along -y)",
     BF_NONNEG, 0, 0, NULL},
    {"gravity", BF_AT(g73_keys, gravity, BF_ENUM), "", "listed",
     "who feels gravity: the particles in gravity_on (the listing: P1), or "
     "all free particles (the text's eq. 2.4)",
     0, 0, 0, "listed|all"},
    {"gravity_on", BF_AT(g73_keys, gravity_on, BF_REALS), "1", "1",
     "particle numbers that feel gravity", BF_MIN, 1, 0, NULL},
    {"fixed", BF_AT(g73_keys, fixed, BF_REALS), "1", "",
     "particle numbers held fixed (the listing: 2 9; the text: 2 8)", BF_MIN, 1,
     0, NULL},
    {"mass", BF_AT(g73_keys, mass, BF_ENUM), "", "paper",
     "inertia of the update: paper (F = m a, v += dt F/m) or fortran (the "
     "listing: v += dt F, i.e. inertia 1)",
     0, 0, 0, "paper|fortran"},
    {"speed", BF_AT(g73_keys, speed, BF_REAL), "cm/s", "50",
     "hexagon: the drift V; wall: the speed |v| of P1", BF_NONNEG, 0, 0, NULL},
    {"jitter", BF_AT(g73_keys, jitter, BF_REAL), "%", "1",
     "hexagon: J, the largest random velocity component is J V / 100",
     BF_NONNEG, 0, 0, NULL},
    {"seed", BF_AT(g73_keys, seed, BF_INT), "1", "1973",
     "hexagon: seed of the random components", BF_MIN, 0, 0, NULL},
    {"theta", BF_AT(g73_keys, theta, BF_REAL), "deg", "30",
     "wall: angle of P1's velocity to the horizontal", 0, 0, 0, NULL},
    {"theta_dir", BF_AT(g73_keys, theta_dir, BF_ENUM), "", "down",
     "wall: down: v = |v| (cos, -sin) towards the wall (the text); up: "
     "(cos, sin) (the listing's VY0 = VEL sin)",
     0, 0, 0, "down|up"},
    {"start", BF_AT(g73_keys, start, BF_ENUM), "", "hollow",
     "wall: P1 at (1.5 BX, BY) (hollow), the text's (0.1717, 0.9914) "
     "(text), or (3.5 BX, BY) (centre)",
     0, 0, 0, "hollow|text|centre"},
    {"below", BF_AT(g73_keys, below, BF_BOOL), "", "false",
     "wall: add P10 at (3.5 BX, -BY)", 0, 0, 0, NULL},
    {"fluid_mass", BF_AT(g73_keys, fluid_mass, BF_REAL), "g", "0.1",
     "wall: mass of P1", BF_POS, 0, 0, NULL},
    {"wall_mass", BF_AT(g73_keys, wall_mass, BF_REAL), "g", "10",
     "wall: mass of the wall particles (the text: 10)", BF_POS, 0, 0, NULL},
    {"positions", BF_AT(g73_keys, positions, BF_REALS), "cm", "",
     "list: x1 y1 x2 y2 ...", 0, 0, 0, NULL},
    {"velocities", BF_AT(g73_keys, velocities, BF_REALS), "cm/s", "",
     "list: vx1 vy1 ... (default 0)", 0, 0, 0, NULL},
    {"masses", BF_AT(g73_keys, masses, BF_REALS), "g", "",
     "list: m1 m2 ... (default 1)", BF_POS, 0, 0, NULL},
    {"solver", BF_AT(g73_keys, solver, BF_ENUM), "", "fixed_point",
     "fixed_point: the listing's relaxed iteration; newton: the text's "
     "Newton method",
     0, 0, 0, "fixed_point|newton"},
    {"omega", BF_AT(g73_keys, omega, BF_REAL), "1", "1",
     "relaxation of the fixed-point iteration", BF_POS | BF_MAX, 0, 1, NULL},
    {"tol", BF_AT(g73_keys, tol, BF_REAL), "cm, cm/s", "1e-10",
     "stop iterating when no x or v changes by more than this", BF_POS, 0, 0,
     NULL},
    {"max_iter", BF_AT(g73_keys, max_iter, BF_INT), "1", "500",
     "iterations before a step fails", BF_MIN, 1, 0, NULL},
    {"jacobian", BF_AT(g73_keys, jacobian, BF_ENUM), "", "dense",
     "Newton: dense (LU) or sparse (GMRES, pairs beyond jacobian_cutoff "
     "left out)",
     0, 0, 0, "dense|sparse"},
    {"jacobian_cutoff", BF_AT(g73_keys, jacobian_cutoff, BF_REAL), "cm", "0",
     "sparse Jacobian: leave out pairs farther apart (0: keep all)", BF_NONNEG,
     0, 0, NULL},
    {"on_failure", BF_AT(g73_keys, on_failure, BF_ENUM), "", "stop",
     "when the solver fails: stop the run (exit 4) or halve the step "
     "(repeatedly, up to max_halvings)",
     0, 0, 0, "stop|halve"},
    {"max_halvings", BF_AT(g73_keys, max_halvings, BF_INT), "1", "12",
     "most halvings of one step", BF_MIN | BF_MAX, 0, 40, NULL},
    {"watch", BF_AT(g73_keys, watch, BF_INT), "1", "1",
     "particle whose final position the summary prints", BF_MIN, 1, 0, NULL},
    {"integrator", BF_AT(g73_keys, integrator, BF_ENUM), "", "greenspan73",
     "time integrator: greenspan73 (the paper's implicit energy-conserving "
     "scheme), leapfrog (the 1972 leapfrog, kick-drift-kick, on the "
     "continuous force) or arkode (ARKODE adaptive ERK on the same ODE, "
     "stopped at every [scene] dt)",
     0, 0, 0, "greenspan73|leapfrog|arkode"},
    BF_PARTICLE_ARKODE_KEYS(g73_keys),
    {0},
};

static const bf_section_spec g73_spec =
    BF_SECTION("greenspan73",
               "the implicit energy-conserving particle scheme, Greenspan 1973",
               g73_params, g73_keys);

typedef struct g73 {
    bf_particles p;
    bf_dforce f;
    bf_implicit *solver;
    bf_g73_ode *ode; /* integrator = leapfrog, arkode (NULL: the scheme) */
    double *mu, *r;
    int halve, max_halvings, watch;
    char reading[256];
    unsigned long long steps, substeps, iterations, failed;
    int depth_max;  /* most halvings in one step */
    long last_iter, last_sub;
    double e0, eint0; /* E and E - K_cm of the initial state */
    bf_particle_out po;
    bf_series *s_e, *s_drift, *s_it, *s_sub;
} g73;

static void g73_destroy(void *self)
{
    g73 *m = self;
    if (!m)
        return;
    bf_particles_free(&m->p);
    bf_dforce_free(&m->f);
    bf_implicit_free(m->solver);
    bf_g73_ode_free(m->ode);
    free(m->mu);
    free(m->r);
    free(m);
}

bf_particles *bf_greenspan73_particles(void *model)
{
    return &((g73 *)model)->p;
}

int bf_greenspan73_adaptive(const bf_model_setup *s)
{
    const g73_keys *k = bf_setup_get(s, &g73_spec, NULL);
    return k && k->integrator == BF_G73_ARKODE;
}

/* A particle-number list (key `key` of [greenspan73]) into flags (1-based
 * numbers). */
static bf_status number_list(bf_reals v, const char *key, size_t n,
                             uint8_t *flag, bf_err *err)
{
    for (size_t a = 0; a < v.n; a++) {
        if (!(v.v[a] == floor(v.v[a]) && v.v[a] >= 1 && v.v[a] <= (double)n))
            return bf_fail_key(err, BF_EINPUT, "greenspan73", key,
                               "%g is not a particle number 1..%zu", v.v[a],
                               n);
        flag[(size_t)v.v[a] - 1] = 1;
    }
    return BF_OK;
}

static bf_status g73_layout(g73 *m, const g73_keys *k, bf_err *err)
{
    const char *S = "greenspan73";
    const int layout = k->layout;
    const int alpha = (int)k->alpha, beta = (int)k->beta;
    const double p = k->p, q = k->q;
    if (alpha == beta)
        return bf_fail_key(err, BF_EINPUT, S, "beta",
                           "alpha = beta = %d: no equilibrium distance",
                           alpha);
    double r0 = layout == LAYOUT_LIST ? 1.0 : bf_dforce_r0(alpha, beta, p, q);
    if (layout != LAYOUT_LIST && !(r0 > 0 && isfinite(r0)))
        return bf_fail_key(err, BF_EINPUT, S, "p",
                           "p = %g, q = %g give no equilibrium distance", p,
                           q);
    size_t n;
    bf_status st;
    if (layout == LAYOUT_HEXAGON) {
        n = 34;
    } else if (layout == LAYOUT_WALL) {
        n = k->below ? 10 : 9;
    } else {
        size_t np = k->positions.n;
        if (np == 0 || np % 2)
            return bf_fail_key(err, BF_EINPUT, S, "positions",
                               "layout = list needs x y pairs (%zu numbers)",
                               np);
        n = np / 2;
    }
    if ((st = bf_particles_init(&m->p, n, err)) ||
        (st = bf_dforce_init(&m->f, n, alpha, beta, err)))
        return st;
    bf_particles *P = &m->p;
    const double V = k->speed;
    if (layout == LAYOUT_HEXAGON) {
        const double h = r0 * sqrt(3.0) / 2.0;
        size_t j = 0;
        for (int i = 0; i < 11; i++, j++) {
            P->x[j] = (i + 0.5) * r0;
            P->y[j] = h;
        }
        for (int i = 0; i < 12; i++, j++) {
            P->x[j] = i * r0;
            P->y[j] = 0.0;
        }
        for (int i = 0; i < 11; i++, j++) {
            P->x[j] = (i + 0.5) * r0;
            P->y[j] = -h;
        }
        /* one set of 68 random numbers, scaled for each V */
        double e[68], emax = 0.0;
        gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
        if (!r)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        gsl_rng_set(r, (unsigned long)k->seed);
        for (int a = 0; a < 68; a++) {
            e[a] = 2.0 * gsl_rng_uniform(r) - 1.0;
            emax = fmax(emax, fabs(e[a]));
        }
        gsl_rng_free(r);
        const double scale = k->jitter * V / 100.0 / emax;
        for (size_t i = 0; i < 34; i++) {
            P->vx[i] = V + scale * e[2 * i];
            P->vy[i] = scale * e[2 * i + 1];
            P->m[i] = 1.0;
        }
    } else if (layout == LAYOUT_WALL) {
        /* Jones's SUBROUTINE INP: the wall particles P2..P9 a distance
         * BX = r0 apart on y = 0, P1 (and P10) at the height BY of an
         * equilateral triangle of side BX above (below) them
         * (docs/models/greenspan73.md, wall layout) */
        const double BX = r0, BY = sqrt(BX * BX - 0.25 * BX * BX);
        const double wm = k->wall_mass;
        for (size_t i = 1; i < 9; i++) {
            P->x[i] = (double)(i - 1) * BX;
            P->y[i] = 0.0;
            P->m[i] = wm;
        }
        int start = k->start;
        P->x[0] = start == START_HOLLOW ? 1.5 * BX
                  : start == START_TEXT ? 0.1717
                                        : 3.5 * BX;
        P->y[0] = start == START_TEXT ? 0.9914 : BY;
        P->m[0] = k->fluid_mass;
        double th = k->theta * (3.14159265358979323846 / 180.0);
        double sgn = k->theta_dir == 0 ? -1.0 : 1.0;
        P->vx[0] = V * cos(th);
        P->vy[0] = sgn * V * sin(th);
        if (n == 10) {
            P->x[9] = 3.5 * BX;
            P->y[9] = -BY;
            P->m[9] = wm;
        }
    } else {
        size_t nv = k->velocities.n, nm = k->masses.n;
        const double *pos = k->positions.v;
        const double *vel = k->velocities.v;
        const double *mas = k->masses.v;
        if (nv && nv != 2 * n)
            return bf_fail_key(err, BF_EINPUT, S, "velocities",
                               "%zu numbers for %zu particles", nv, n);
        if (nm && nm != n)
            return bf_fail_key(err, BF_EINPUT, S, "masses",
                               "%zu numbers for %zu particles", nm, n);
        for (size_t i = 0; i < n; i++) {
            P->x[i] = pos[2 * i];
            P->y[i] = pos[2 * i + 1];
            P->vx[i] = nv ? vel[2 * i] : 0.0;
            P->vy[i] = nv ? vel[2 * i + 1] : 0.0;
            P->m[i] = nm ? mas[i] : 1.0;
        }
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (P->x[i] == P->x[j] && P->y[i] == P->y[j])
                return bf_fail_key(err, BF_EINPUT, S, "positions",
                                   "particles %zu and %zu coincide", i + 1,
                                   j + 1);
    return BF_OK;
}

static void g73_energy(const void *self, double t, double *kin, double *pot);

/* The solver's readings for the summary (and the output's "reading"). */
static void g73_reading(g73 *m, const g73_keys *k)
{
    const size_t nfx = k->fixed.n;
    const double *fx = k->fixed.v;
    char fixed[64] = "";
    for (size_t a = 0; a < nfx && a < 6; a++)
        snprintf(fixed + strlen(fixed), sizeof fixed - strlen(fixed), "%s%g",
                 a ? " " : "", fx[a]);
    snprintf(m->reading, sizeof m->reading,
             "mass = %s, gravity = %s, fixed = %s%s%s",
             k->mass == MASS_FORTRAN ? "fortran (v += dt F)"
                                     : "paper (a = F/m)",
             k->gravity == GRAVITY_ALL ? "all free particles" : "listed",
             nfx ? fixed : "none",
             k->layout == LAYOUT_WALL ? ", wall_mass = " : "", "");
    if (k->layout == LAYOUT_WALL)
        snprintf(m->reading + strlen(m->reading),
                 sizeof m->reading - strlen(m->reading), "%g, start = %s",
                 k->wall_mass, start_names[k->start]);
}

/* The memory of the scheme's N x N arrays, per pair of particles (B):
 * the pair constants p, q and the distances of the model, the solver's
 * old and new distances (5 doubles, 6 with the outputs' rows and the
 * per-particle arrays of a small N); Newton adds the full Jacobian and
 * GSL's dense matrix of (2N)^2 (8 doubles), its sparse form a COO and a
 * CSC copy of (2N)^2 entries of 16 and 12 bytes.  Measured: the smallest
 * ulimit -v of a two-step run grows by 42 B (fixed point) and 106 B
 * (Newton) per N^2 from N = 500 to 1000 (docs/reliability.md). */
static void g73_memory(const bf_model_setup *setup, bf_mem_need *need)
{
    const g73_keys *k = bf_setup_get(setup, &g73_spec, NULL);
    if (!k)
        return;
    double n = k->layout == LAYOUT_HEXAGON ? 34
               : k->layout == LAYOUT_WALL  ? (k->below ? 10 : 9)
                                           : (double)(k->positions.n / 2);
    double per = 48.0;
    if (k->solver == BF_IMPLICIT_NEWTON)
        per += k->jacobian == 1 ? 64.0 + 4.0 * (16.0 + 12.0) : 64.0;
    need->bytes = per * n * n;
    snprintf(need->what, sizeof need->what,
             "%.0f particles x %.0f particles x %.0f bytes (the N^2 arrays "
             "of the %s)",
             n, n, per,
             k->solver == BF_IMPLICIT_NEWTON ? "Newton solver" : "scheme");
    snprintf(need->section, sizeof need->section, "greenspan73");
    snprintf(need->key, sizeof need->key,
             k->layout == LAYOUT_LIST ? "positions" : "layout");
}

static bf_status g73_create(void **self, const bf_model_setup *setup,
                            bf_err *err)
{
    const char *S = "greenspan73";
    const g73_keys *k = bf_setup_get(setup, &g73_spec, NULL);
    if (!k)
        return bf_fail(err, BF_EINTERNAL, "greenspan73: [greenspan73] "
                       "missing from the setup");
    g73 *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_status st = g73_layout(m, k, err);
    if (st)
        goto fail;
    const size_t n = m->p.n;
    bf_dforce *f = &m->f;
    f->g = k->g;
    for (size_t i = 0; i < n; i++) {
        f->m[i] = m->p.m[i];
        for (size_t j = 0; j < n; j++) {
            f->p[i * n + j] = k->p;
            f->q[i * n + j] = k->q;
        }
    }
    const size_t np = k->pairs.n;
    const double *pr = k->pairs.v;
    if (np % 4) {
        st = bf_fail_key(err, BF_EINPUT, S, "pairs",
                         "needs quadruples i j p q");
        goto fail;
    }
    for (size_t a = 0; a < np; a += 4) {
        double i = pr[a], j = pr[a + 1];
        if (!(i >= 1 && j >= 1 && i <= (double)n && j <= (double)n &&
              i == floor(i) && j == floor(j) && i != j && pr[a + 2] >= 0 &&
              pr[a + 3] >= 0)) {
            st = bf_fail_key(err, BF_EINPUT, S, "pairs", "bad pair %g %g", i,
                             j);
            goto fail;
        }
        size_t ii = (size_t)i - 1, jj = (size_t)j - 1;
        f->p[ii * n + jj] = f->p[jj * n + ii] = pr[a + 2];
        f->q[ii * n + jj] = f->q[jj * n + ii] = pr[a + 3];
    }
    if ((st = number_list(k->fixed, "fixed", n, f->fixed, err)))
        goto fail;
    if (k->gravity == GRAVITY_ALL) {
        for (size_t i = 0; i < n; i++)
            f->gravity[i] = !f->fixed[i];
    } else if ((st = number_list(k->gravity_on, "gravity_on", n, f->gravity,
                                 err))) {
        goto fail;
    }
    for (size_t i = 0; i < n; i++) {
        if (f->fixed[i]) {
            m->p.flags[i] |= BF_PART_FIXED;
            m->p.vx[i] = m->p.vy[i] = 0.0;
        }
        m->p.tag[i] = f->gravity[i];
    }
    m->mu = malloc((n ? n : 1) * sizeof *m->mu);
    m->r = malloc((n ? n * n : 1) * sizeof *m->r);
    if (!m->mu || !m->r) {
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
        goto fail;
    }
    int fortran = k->mass == MASS_FORTRAN;
    for (size_t i = 0; i < n; i++)
        m->mu[i] = fortran ? 1.0 : m->p.m[i];
    bf_implicit_opts o = {
        .method = (bf_implicit_method)k->solver,
        .omega = k->omega,
        .tol = k->tol,
        .max_iter = (int)k->max_iter,
        .sparse = k->jacobian == 1,
        .jac_cutoff = k->jacobian_cutoff,
    };
    if ((st = bf_implicit_create(&m->solver, f, &o, err)))
        goto fail;
    if (k->integrator != BF_G73_IMPLICIT) {
        bf_g73_ode_opts oo = {.method = k->integrator,
                              .table = k->table,
                              .rtol = k->rtol,
                              .atol = k->atol,
                              .max_step = k->max_step,
                              .max_steps = k->max_steps};
        if ((st = bf_g73_ode_create(&m->ode, f, m->mu, &m->p, &oo, err)))
            goto fail;
    }
    m->halve = k->on_failure == 1;
    m->max_halvings = (int)k->max_halvings;
    m->watch = (int)k->watch;
    if ((size_t)m->watch > n) {
        st = bf_fail_key(err, BF_EINPUT, S, "watch", "particle %d of %zu",
                         m->watch, n);
        goto fail;
    }
    g73_reading(m, k);
    double K, V;
    g73_energy(m, 0.0, &K, &V);
    m->e0 = K + V;
    m->eint0 = m->e0 - bf_pdiag_cm_kinetic(&m->p, m->mu);
    *self = m;
    return BF_OK;
fail:
    g73_destroy(m);
    return st;
}

/* One step of dt, or (on_failure = halve) two of dt/2, recursively. */
static bf_status advance(g73 *m, double dt, int depth, bf_err *err)
{
    bf_particles *p = &m->p;
    int it = 0;
    bf_status st = bf_implicit_step(m->solver, &m->f, m->mu, p->x, p->y,
                                    p->vx, p->vy, dt, &it, err);
    m->iterations += (unsigned long long)it;
    m->last_iter += it;
    if (st == BF_OK) {
        m->substeps++;
        m->last_sub++;
        return BF_OK;
    }
    if (st != BF_ENOCONV)
        return st;
    m->failed++;
    if (!m->halve || depth >= m->max_halvings) {
        bf_err_prefix(err, "dt = %g%s", dt,
                      !m->halve ? " (on_failure = stop)"
                                : " (the most halvings allowed)");
        return st;
    }
    if (depth + 1 > m->depth_max)
        m->depth_max = depth + 1;
    if ((st = advance(m, 0.5 * dt, depth + 1, err)) ||
        (st = advance(m, 0.5 * dt, depth + 1, err)))
        return st;
    return BF_OK;
}

static bf_status g73_step(void *self, long n, double t, double dt, bf_err *err)
{
    (void)n;
    g73 *m = self;
    m->last_iter = m->last_sub = 0;
    bf_status st = m->ode ? bf_g73_ode_step(m->ode, t, dt, err)
                          : advance(m, dt, 0, err);
    if (st)
        return st;
    m->steps++;
    return BF_OK;
}

static void g73_energy(const void *self, double t, double *kin, double *pot)
{
    (void)t;
    const g73 *m = self;
    bf_dforce_distances(&m->f, m->p.x, m->p.y, m->r);
    *kin = bf_pdiag_kinetic(&m->p, m->mu);
    *pot = bf_dforce_pair_energy(&m->f, m->r) +
           bf_dforce_gravity_energy(&m->f, m->p.y);
}

/* The scheme conserves E = K + V exactly in exact arithmetic (the
 * discrete gradient of eq. 2.17); what is left is the iteration's
 * tolerance and rounding, below 1e-14 in every scene of runs/.  A drift
 * of 1e-6 means that the iteration did not do its job. */
static double g73_energy_bound(const void *self)
{
    /* the leapfrog and ARKODE conserve it only to their order: no bound */
    return ((const g73 *)self)->ode ? 0.0 : 1e-6;
}

void bf_greenspan73_describe(void *model, char *buf, size_t cap, int *order)
{
    const g73 *m = model;
    if (m->ode) {
        bf_g73_ode_describe(m->ode, buf, cap, order);
        return;
    }
    snprintf(buf, cap, "greenspan73 (implicit, energy-conserving)");
    *order = 2;
}

static const bf_series_spec g73_series[] = {
    {.path = "/diag/energy", .unit = "erg", .ncols = 5,
     .columns = "K, V pair, V gravity, E, E - K_cm",
     .doc = "K (inertia of the update), V pair (2.17), V gravity, E = K + V, "
            "E - K of the centre of mass",
     .slot = BF_SLOT(g73, s_e)},
    {.path = "/diag/energy_drift", .unit = "1", .ncols = 2,
     .columns = "E, E - K_cm",
     .doc = "relative change since t = 0 of E and of E - K_cm",
     .slot = BF_SLOT(g73, s_drift)},
    {.path = "/diag/iterations", .unit = "1", .is_int = 1,
     .doc = "solver iterations of the step ending at the row (all substeps)",
     .slot = BF_SLOT(g73, s_it)},
    {.path = "/diag/substeps", .unit = "1", .is_int = 1,
     .doc = "substeps of the step ending at the row (> 1 after halvings)",
     .slot = BF_SLOT(g73, s_sub)},
    {.path = BF_DS_PARTICLES_INERTIA, .unit = "g", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "particle",
     .doc = "inertia of the update (mass, or 1 for mass = fortran)"},
    {.path = BF_DS_PARTICLES_FIXED, .unit = "1", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "particle", .doc = "1: held fixed"},
    {.path = BF_DS_PARTICLES_GRAVITY, .unit = "1", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "particle", .doc = "1: feels gravity"},
};
enum { G73_INERTIA = 4, G73_FIXED, G73_GRAVITY };
static const bf_series_table g73_table = {"greenspan73", g73_series,
                                          BF_NSERIES(g73_series)};
static const bf_series_table *const g73_tables[] = {&bf_particle_series,
                                                    &g73_table, NULL};

static bf_status g73_output_open(void *self, bf_out *out, bf_err *err)
{
    g73 *m = self;
    const size_t n = m->p.n;
    const bf_series_extent ext[] = {{"particle", n}};
    bf_status st = bf_particles_output_open(&m->po, out, &m->p,
                                            BF_PO_POS | BF_PO_VEL, err);
    if (!st)
        st = bf_out_open_table(out, g73_series, BF_NSERIES(g73_series), m,
                               ext, 1, 0, err);
    if (st)
        return st;
    double *tmp = malloc((n ? n : 1) * sizeof *tmp);
    if (!tmp)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    st = bf_out_table_array(out, &g73_series[G73_INERTIA], m->mu, n, err);
    for (size_t i = 0; i < n; i++)
        tmp[i] = m->f.fixed[i];
    if (!st)
        st = bf_out_table_array(out, &g73_series[G73_FIXED], tmp, n, err);
    for (size_t i = 0; i < n; i++)
        tmp[i] = m->f.gravity[i];
    if (!st)
        st = bf_out_table_array(out, &g73_series[G73_GRAVITY], tmp, n, err);
    free(tmp);
    if (!st)
        st = bf_out_attr_str(out, "/", "reading", m->reading, err);
    return st;
}

static bf_status g73_output_row(void *self, long n, double t, bf_err *err)
{
    (void)n;
    g73 *m = self;
    double K, V;
    g73_energy(m, t, &K, &V);
    double vp = bf_dforce_pair_energy(&m->f, m->r);
    double e[5] = {K, vp, V - vp, K + V,
                   K + V - bf_pdiag_cm_kinetic(&m->p, m->mu)};
    double drift[2] = {(e[3] - m->e0) / fabs(m->e0),
                       (e[4] - m->eint0) / fabs(m->eint0)};
    int64_t it = m->last_iter, sub = m->last_sub;
    if (bf_series_append(m->s_drift, drift) ||
        bf_particles_output_row(&m->po, &m->p, 0) ||
        bf_series_append(m->s_e, e) ||
        bf_series_append_i64(m->s_it, &it) ||
        bf_series_append_i64(m->s_sub, &sub))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

static void g73_counters(const void *self, bf_counters *c)
{
    const g73 *m = self;
    if (m->ode) {
        bf_g73_ode_counters(m->ode, c);
        return;
    }
    c->steps = m->steps;
    c->evals = m->iterations;
    c->iterations = m->iterations;
    c->rejected = m->failed;
}

static void g73_report(const void *self, FILE *f)
{
    const g73 *m = self;
    const size_t w = (size_t)m->watch - 1;
    if (m->ode) {
        char d[256];
        int q;
        bf_counters c;
        bf_g73_ode_describe(m->ode, d, sizeof d, &q);
        bf_g73_ode_counters(m->ode, &c);
        fprintf(f, "integrator:        %s: %llu steps, %llu force "
                   "evaluations, %llu rejected\n",
                d, c.steps, c.evals, c.rejected);
    } else
        fprintf(f, "implicit solver:   %llu substeps, %llu iterations (%.2f per "
               "substep), %llu failed solves, most halvings of a step %d\n",
            m->substeps, m->iterations,
            m->substeps ? (double)m->iterations / (double)m->substeps : 0.0,
            m->failed, m->depth_max);
    fprintf(f, "particle %zu at the end: (%.5f, %.5f), v = (%.4g, %.4g)\n",
            w + 1, m->p.x[w], m->p.y[w], m->p.vx[w], m->p.vy[w]);
    fprintf(f, "reading:           %s\n", m->reading);
}

static const bf_field g73_state[] = {
    BF_FIELD(g73, steps, BF_F_ULL, "1"),
    BF_FIELD(g73, substeps, BF_F_ULL, "1"),
    BF_FIELD(g73, iterations, BF_F_ULL, "1"),
    BF_FIELD(g73, failed, BF_F_ULL, "1"),
    BF_FIELD(g73, depth_max, BF_F_INT, "1"),
    BF_FIELD(g73, last_iter, BF_F_LONG, "1"),
    BF_FIELD(g73, last_sub, BF_F_LONG, "1"),
};

static bf_status g73_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const g73 *m = self;
    bf_status st = bf_particles_save(&m->p, ck, "g73.p", err);
    if (!st)
        st = bf_ckpt_put_fields(ck, "g73", g73_state, BF_NFIELDS(g73_state),
                                m, err);
    /* the leapfrog's or ARKODE's own state (nothing for the scheme) */
    if (!st && m->ode)
        st = bf_g73_ode_save(m->ode, ck, err);
    return st;
}

static bf_status g73_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    g73 *m = self;
    bf_status st = bf_particles_load(&m->p, ck, "g73.p", err);
    if (!st)
        st = bf_ckpt_get_fields(ck, "g73", g73_state, BF_NFIELDS(g73_state),
                                m, err);
    if (!st && m->ode)
        st = bf_g73_ode_load(m->ode, ck, err);
    return st;
}

static const bf_section_spec *const g73_specs[] = {&g73_spec, NULL};

static size_t g73_state_vars(void *self, bf_state_var *vars, size_t cap)
{
    return bf_particles_state_vars(&((g73 *)self)->p, vars, cap);
}

/* New positions or velocities; the energy of t = 0 is theirs. */
static bf_status g73_set_state(void *self, const char *name, const double *v,
                               size_t n, bf_err *err)
{
    g73 *m = self;
    bf_status st = bf_particles_set_var(&m->p, NULL, name, v, n, err);
    if (m->ode)
        bf_g73_ode_changed(m->ode);
    double K, V;
    g73_energy(m, 0.0, &K, &V);
    m->e0 = K + V;
    m->eint0 = m->e0 - bf_pdiag_cm_kinetic(&m->p, m->mu);
    return st;
}

const bf_model_type bf_model_greenspan73 = {
    .name = "greenspan73",
    .series = g73_tables,
    .doc = "implicit, exactly energy-conserving particle scheme (Greenspan "
           "1973)",
    .flags = 0,
    .specs = g73_specs,
    .create = g73_create,
    .destroy = g73_destroy,
    .memory = g73_memory,
    .step = g73_step,
    .energy = g73_energy,
    .energy_bound = g73_energy_bound,
    .output_open = g73_output_open,
    .output_row = g73_output_row,
    .counters = g73_counters,
    .report = g73_report,
    .checkpoint_save = g73_save,
    .checkpoint_load = g73_load,
    .state = g73_state_vars,
    .set_state = g73_set_state,
    .study = &bf_study_greenspan73,
};
