/* coupled.c: the "coupled" model: balls in the two-phase film (Yasuda
 * sec. 3.4-3.5, Figs 6, 8, 9).
 *
 * The balls are a ball system (ballsys.h) whose effects include
 * "coupling" (src/coupling: -M dF/dr, eqs 3.10-3.12) and "contact"
 * (Hertz, eqs 3.13-3.14); the film is a film system (filmsys.h).  The
 * model makes the coupling from the [coupling] keys and hands it to its
 * ball system as the coupling effect's instance; it owns mu_cpl and hands it to the
 * film step.
 *
 *   film = static   the film is never stepped (the kink potential of sec.
 *                   3.4): the balls move in F of the initial film, and the
 *                   energy m v^2/2 + contact + m M F is conserved by the
 *                   dynamics, so it checks the integrator;
 *   film = dynamic  explicit coupling as in the paper ("values at n+1 from
 *                   values at n, combined at the n-th step"): at step n
 *                   mu_cpl (3.11) is computed from the balls at level n, the
 *                   balls advance one step in the film frozen at level n, and
 *                   the film advances with mu^n + mu_cpl^n.  The ball
 *                   integrator's force cache is invalidated after every film
 *                   step (bf_ode.epoch).
 *
 * Multirate (film_every = K > 1, beyond the paper): the film takes one
 * step of K dt every K ball steps, with mu_cpl from the balls at the start
 * of that film step, and the balls see the film of the last film level.
 * K = 1 is the paper's single-rate scheme, bit for bit.  film_every =
 * auto chooses K for each film step from the lag of the balls' coupling
 * acceleration behind the film (coupled_multirate.c).
 *
 * Diagnostics (HDF5):
 *   /balls/position, /balls/velocity [rows x balls]
 *   /coupled/psi_probe [rows]       psi at [coupled] probe (linear in x)
 *   /coupled/sym_balls [rows]       max_i |x_i + x_(n+1-i)|, cm
 *   /coupled/sym_film [rows]        max_i |psi_i + psi_(N-i)|
 *   /coupled/return_map [events x 3] t, x, v of map_ball each time the
 *                                   centre of map_pivot is closest to the
 *                                   origin while touching its inner
 *                                   neighbour (Fig. 8A)
 *   /coupled/peaks [events x 2]     t, x of each maximum of peak_ball's
 *                                   position (Fig. 6C)
 *
 * Forced mirror symmetry ([coupled] symmetrize = yes) is in
 * coupled_symmetry.c, the events (peaks, return map) in coupled_events.c,
 * the Lyapunov shadow ([lyapunov] enabled = yes) in coupled_lyapunov.c;
 * what they share is coupled_impl.h.  This file composes the model from
 * its setup and takes its step.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/model.h"
#include "base/clock.h"
#include "coupling/coupling.h"
#include "coupling/force.h"
#include "coupling/mu_cpl.h"
#include "diag/lyapsum.h"
#include "integrators/arkode.h"
#include "models/ballsys.h"
#include "models/coupled.h"
#include "models/coupled_impl.h"
#include "models/filmsys.h"
#include "models/studies.h"
#include "io/dataset_paths.h"

static const bf_param coupled_params[] = {
    {"film", BF_AT(coupled_keys, film, BF_ENUM), "", "dynamic",
     "dynamic: the film is solved and feels the balls (sec. 3.5); static: "
     "the balls move in the potential of the initial film (sec. 3.4)",
     0, 0, 0, "dynamic|static"},
    {"film_every", BF_AT(coupled_keys, film_every, BF_STR), "steps", "1",
     "a positive integer K or auto. K: multirate, the film takes one step "
     "of K x dt every K ball steps (1: the paper's single rate); auto: "
     "each film step as long as the balls' coupling acceleration lags "
     "behind the film's by at most multirate_tol (and the film's stable "
     "limit, film_every_max and the cost allow)",
     0, 0, 0, NULL},
    {"multirate_tol", BF_AT(coupled_keys, multirate_tol, BF_REAL), "cm/s^2",
     "1e-4",
     "film_every = auto: the largest lag of the coupling acceleration -M "
     "dF/dr the balls feel behind the one of the current film, at the end "
     "of each film step (it moves a ball by at most multirate_tol t^2/2 in "
     "a time t, unless the dynamics amplifies it)",
     BF_POS, 0, 0, NULL},
    {"film_every_max", BF_AT(coupled_keys, film_every_max, BF_INT), "steps",
     "1000",
     "film_every = auto: the largest film step in ball steps (also capped "
     "by 90% of the film's stable limit and by the time the fastest ball "
     "takes to leave its [coupling] taylor anchor)",
     BF_MIN, 1, 0, NULL},
    {"probe", BF_AT(coupled_keys, probe, BF_REAL), "cm", "0.3",
     "position of the psi probe /coupled/psi_probe (Fig. 8C)", 0, 0, 0,
     NULL},
    {"map_ball", BF_AT(coupled_keys, map_ball, BF_INT), "", "0",
     "ball recorded in the return map (0: the last)", BF_NONNEG, 0, 0, NULL},
    {"map_pivot", BF_AT(coupled_keys, map_pivot, BF_INT), "", "0",
     "ball whose closest approach to the origin, while touching its inner "
     "neighbour, triggers the return map (0: ball n/2 + 1)",
     BF_NONNEG, 0, 0, NULL},
    {"peak_ball", BF_AT(coupled_keys, peak_ball, BF_INT), "", "0",
     "ball whose position maxima are recorded in /coupled/peaks (0: the "
     "last)",
     BF_NONNEG, 0, 0, NULL},
    {"symmetrize", BF_AT(coupled_keys, symmetrize, BF_BOOL), "", "no",
     "yes: after each step project balls and film onto the mirror-symmetric "
     "states (x -> -x, psi -> -psi; ball i <-> ball n+1-i), removing the "
     "round-off that breaks the symmetry (needs a symmetric set-up); "
     "/coupled/sym_correction records the largest change. no: the paper's "
     "scheme",
     0, 0, 0, NULL},
    {"scheme", BF_AT(coupled_keys, whole.scheme, BF_ENUM), "", "split",
     "time integration. split: the paper's explicit coupling, the balls by "
     "[scene] integrator, the film by [film] scheme every film_every steps; "
     "arkode: ARKODE's adaptive ERK on the whole system (balls and the film "
     "in method-of-lines form, one ODE) inside each [scene] dt, the "
     "reference of the convergence study; mri: ARKODE's MRIStep, the film "
     "the slow part at the fixed step [scene] dt, the balls the fast part "
     "by an adaptive inner ERK (docs/models/coupled.md)",
     0, 0, 0, "split|arkode|mri"},
    {"table", BF_AT(coupled_keys, whole.table, BF_ENUM), "",
     "ARKODE_DORMAND_PRINCE_7_4_5",
     "scheme = arkode: the ERK Butcher table; mri: the inner (fast) ERK's",
     0, 0, 0, BF_ARKODE_TABLE_CHOICES},
    {"mri_order", BF_AT(coupled_keys, whole.mri_order, BF_INT), "1", "3",
     "scheme = mri: order of MRIStep's slow coupling (3 or 4)",
     BF_MIN | BF_MAX, 3, 4, NULL},
    {"rtol", BF_AT(coupled_keys, whole.rtol, BF_REAL), "1", "1e-8",
     "scheme = arkode, mri (its inner ERK): relative tolerance of the local "
     "error", BF_POS, 0, 0, NULL},
    {"atol", BF_AT(coupled_keys, whole.atol, BF_REAL), "cm, cm/s", "1e-11",
     "scheme = arkode, mri (its inner ERK): absolute tolerance of every "
     "component (ball x and v, film alpha_k h and u_k)", BF_POS, 0, 0, NULL},
    {"max_step", BF_AT(coupled_keys, whole.max_step, BF_REAL), "s", "0",
     "scheme = arkode, mri (its inner ERK): largest internal step (0: "
     "none; a contact shorter than the steps between two stages can be "
     "missed in free flight, whose error estimate is small)",
     BF_NONNEG, 0, 0, NULL},
    {"max_steps", BF_AT(coupled_keys, whole.max_steps, BF_INT), "1",
     "10000",
     "scheme = arkode, mri: internal steps allowed per [scene] dt; more end "
     "the run with status 4 (the default keeps one step to seconds: an "
     "internal step of the Fig. 8 film costs about 0.4 ms)", BF_MIN, 1,
     0, NULL},
    {"timing", BF_AT(coupled_keys, timing, BF_BOOL), "", "false",
     "measure the wall time of balls, film and coupling separately (bench)",
     BF_HIDDEN, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_coupled_spec =
    BF_SECTION("coupled", "balls coupled to the film (Yasuda sec. 3.4-3.5)",
               coupled_params, coupled_keys);

static void coupled_destroy(void *self)
{
    coupled_model *m = self;
    if (!m)
        return;
    coupled_destroy(m->shadow);
    bf_coupled_whole_free(m->whole);
    free(m->ly);
    bf_ballsys_free(m->sys);
    bf_coupling_free(m->cpl);
    bf_filmsys_free(m->fs);
    free(m->mucpl);
    free(m->acc_old);
    free(m->x0);
    free(m->v0);
    free(m->map_x);
    free(m->map_v);
    free(m);
}

/* ------------------------------------------------------------ set-up */

/* The film's doubles per node, and the coupling's beside them: g, m, lc,
 * rc, pw, pwr, tl, tw, tmp, the zero row and mu_cpl (11), the pool of 96
 * rows (coupling.c, NROW) and row_of (3); all again for the Lyapunov
 * shadow. */
static void coupled_memory(const bf_model_setup *setup, bf_mem_need *need)
{
    const bf_lyap_keys *lk = bf_setup_get(setup, &bf_lyap_spec, NULL);
    bf_filmsys_memory(bf_setup_get(setup, &bf_filmsys_spec, NULL), 110.0,
                      lk && lk->enabled ? 2 : 1, need);
}

/* [coupled] film_every: a positive integer, or auto (*every = 0) */
static bf_status film_every_key(const char *v, long *every, bf_err *err)
{
    if (strcmp(v, "auto") == 0) {
        *every = 0;
        return BF_OK;
    }
    char *end;
    long k = strtol(v, &end, 10);
    if (end == v || *end || k < 1)
        return bf_fail_key(err, BF_EINPUT, "coupled", "film_every",
                           "'%s' is not a positive integer or auto", v);
    *every = k;
    return BF_OK;
}

/* a 1-based ball index k of [coupled] key (0: default) */
static bf_status ball_key(long k, const char *key, size_t nb, size_t def,
                          size_t *out, bf_err *err)
{
    if (k == 0) {
        *out = def;
        return BF_OK;
    }
    if ((size_t)k > nb)
        return bf_fail_key(err, BF_EINPUT, "coupled", key,
                           "ball %ld does not exist (%zu balls)", k, nb);
    *out = (size_t)k - 1;
    return BF_OK;
}

static bf_status coupled_build(coupled_model **self,
                               const bf_model_setup *setup, int with_shadow,
                               bf_err *err);

/* [lyapunov]: the running sum and the shadow, another instance of this
 * model from the same setup, its balls displaced (coupled_lyapunov.c). */
static bf_status shadow_create(coupled_model *m, const bf_model_setup *setup,
                               bf_err *err)
{
    bf_status st = bf_coupled_lyap_init(m, setup, err);
    if (!st)
        st = coupled_build(&m->shadow, setup, 0, err);
    if (st)
        return st;
    m->shadow->leader = m; /* film_every = auto: the run's film steps */
    bf_coupled_lyap_seed(m);
    return BF_OK;
}

static bf_status coupled_create(void **self, const bf_model_setup *setup,
                                bf_err *err)
{
    coupled_model *m = NULL;
    bf_status st = coupled_build(&m, setup, 1, err);
    *self = m;
    return st;
}

/* The [coupling] keys among the setup's effects (NULL: no coupling). */
static const bf_coupling_keys *coupling_keys(const bf_model_setup *setup)
{
    for (size_t k = 0; k < setup->neffects; k++)
        if (setup->effects[k]->spec == &bf_coupling_spec)
            return setup->effect_params[k];
    return NULL;
}

static bf_status coupled_build(coupled_model **self,
                               const bf_model_setup *setup, int with_shadow,
                               bf_err *err)
{
    const coupled_keys *k = bf_setup_get(setup, &bf_coupled_spec, NULL);
    const bf_film_keys *fk = bf_setup_get(setup, &bf_filmsys_spec, NULL);
    coupled_model *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->dynamic = k->film == 0;
    m->keep_map = with_shadow && setup->run.keep_map; /* not a shadow */
    bf_status st = film_every_key(k->film_every, &m->every, err);
    if (st) {
        free(m);
        return st;
    }
    /* auto: the film steps by 1 to film_every_max ball steps; its stable
     * limit is checked for each step (coupled_multirate.c) */
    int adaptive = m->every == 0;
    if (adaptive)
        m->every = 1;
    m->timing = k->timing;
    m->sym = k->symmetrize;
    m->probe = k->probe;
    /* the whole-system schemes never step the film by its own scheme;
     * mri's slow step is [scene] dt, limited by the film's stable step
     * (that of the invariant scheme, a bound for MRIStep's explicit slow
     * stages too: both are limited by the gravity-wave CFL and the
     * phase-separation dx^2 limit, bf_film_stable_dt), arkode chooses
     * its own steps */
    const int whole = k->whole.scheme != BF_COUPLED_SPLIT;
    const long film_steps = !m->dynamic ? 0
                            : !whole ? m->every
                            : k->whole.scheme == BF_COUPLED_MRI ? 1 : 0;
    st = bf_filmsys_create(&m->fs, fk, &setup->run, film_steps, err);
    if (st) {
        free(m);
        return st;
    }
    if (adaptive || (whole && film_steps == 0))
        bf_filmsys_step_varies(m->fs);
    const bf_coupling_keys *ck = coupling_keys(setup);
    size_t nballs;
    bf_setup_get(setup, &bf_ballsys_ball_spec, &nballs);
    if (!ck) {
        coupled_destroy(m);
        return bf_fail_key(err, BF_EINPUT, "scene", "effects",
                           "model coupled needs the effect 'coupling' (and "
                           "usually 'contact')");
    }
    bf_coupling_params cp = bf_coupling_params_from_keys(ck);
    if ((st = bf_coupling_create(&m->cpl, &cp, bf_filmsys_film(m->fs), nballs,
                                 err))) {
        coupled_destroy(m);
        return st;
    }
    /* the coupling effect's instance is this model's coupling */
    const bf_effect cpl_effect = {&bf_effect_coupling, m->cpl};
    if ((st = bf_ballsys_create(&m->sys, setup, &cpl_effect, 1, err))) {
        coupled_destroy(m);
        return st;
    }
    m->nb = m->sys->b.n;
    const double *x = bf_film_x(bf_filmsys_film(m->fs));
    size_t nn = bf_film_nodes(bf_filmsys_film(m->fs));
    double xa = x[0], xb = x[nn - 1];
    if (m->probe < xa || m->probe > xb) {
        coupled_destroy(m);
        return bf_fail_key(err, BF_EINPUT, "coupled", "probe",
                           "probe at %g cm lies outside the film [%g, %g]",
                           k->probe, xa, xb);
    }
    if ((st = ball_key(k->map_ball, "map_ball", m->nb, m->nb - 1, &m->map_ball,
                       err)) ||
        (st = ball_key(k->map_pivot, "map_pivot", m->nb, m->nb / 2,
                       &m->map_pivot, err)) ||
        (st = ball_key(k->peak_ball, "peak_ball", m->nb, m->nb - 1,
                       &m->peak_ball, err))) {
        coupled_destroy(m);
        return st;
    }
    if (m->sym && (st = bf_coupled_check_symmetric(m, fk, err))) {
        coupled_destroy(m);
        return st;
    }
    if (m->dynamic)
        bf_coupling_prepare(m->cpl, m->nb, m->sys->b.x);
    m->x0 = calloc(m->nb, sizeof(double));
    m->v0 = calloc(m->nb, sizeof(double));
    m->nodes = nn;
    /* 64-byte aligned, as the film's arrays (its vector loops read it) */
    size_t bytes = (nn * sizeof(double) + 63) & ~(size_t)63;
    m->mucpl = aligned_alloc(64, bytes);
    if (m->mucpl)
        memset(m->mucpl, 0, bytes);
    if (!m->x0 || !m->v0 || !m->mucpl) {
        coupled_destroy(m);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (whole && (st = bf_coupled_whole_create(m, &k->whole, k->film_every,
                                               fk->scheme, setup->run.dt,
                                               err))) {
        coupled_destroy(m);
        return st;
    }
    if (adaptive && m->dynamic &&
        (st = bf_coupled_mr_init(m, k->multirate_tol, k->film_every_max,
                                 setup->run.nsteps, err))) {
        coupled_destroy(m);
        return st;
    }
    for (int q = 0; q < BF_COUPLED_NSYM; q++)
        m->sym_t[q] = NAN;
    const bf_lyap_keys *lk = bf_setup_get(setup, &bf_lyap_spec, NULL);
    if (whole && lk->enabled) {
        coupled_destroy(m);
        return bf_fail_key(err, BF_EINPUT, "lyapunov", "enabled",
                           "the Lyapunov shadow works with [coupled] scheme "
                           "= split only");
    }
    if (with_shadow && lk->enabled &&
        (st = shadow_create(m, setup, err))) {
        coupled_destroy(m);
        return st;
    }
    *self = m;
    return BF_OK;
}

/* ------------------------------------------------------------ step */

static bf_status coupled_step(void *self, long n, double t, double dt,
                              bf_err *err);

/* The shadow's step t -> t + dt (the run has just taken it; n_done = n +
 * 1 steps are done) and, when due, the renormalisation. */
static bf_status shadow_step(coupled_model *m, long n, double t, double dt,
                             bf_err *err)
{
    bf_status st = coupled_step(m->shadow, n, t, dt, err);
    if (st) {
        bf_err_prefix(err, "Lyapunov shadow system");
        return st;
    }
    return bf_coupled_lyap_renormalise(m, n, t, dt, err);
}

static bf_status coupled_step(void *self, long n, double t, double dt,
                              bf_err *err)
{
    coupled_model *m = self;
    bf_ballsys *s = m->sys;
    double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
    memcpy(m->x0, s->b.x, m->nb * sizeof(double));
    memcpy(m->v0, s->b.v, m->nb * sizeof(double));
    if (m->whole) {
        bf_status st = bf_coupled_whole_step(m, t, dt, err);
        return st ? st : bf_coupled_events(m, t, dt, err);
    }
    if (m->timing)
        c0 = bf_wall_time();
    /* mu_cpl from the balls at level n (at the start of a film step) */
    if (m->dynamic && bf_coupled_window_starts(m, n))
        bf_coupling_mu(m->cpl, m->nb, s->b.x, s->b.R, m->mucpl);
    if (m->timing)
        c1 = bf_wall_time();
    /* the balls in the film frozen at its last level */
    bf_status st = bf_ballsys_step(s, t, dt, err);
    if (st)
        return st;
    if (m->sym) {
        /* before the coupling's prepare reads the positions */
        double c[2] = {bf_coupled_mirror_odd(s->b.x, m->nb),
                       bf_coupled_mirror_odd(s->b.v, m->nb)};
        bf_coupled_keep_max(m->sym_correction + 2, c, 2);
    }
    if (m->timing)
        c2 = bf_wall_time();
    long K = m->dynamic ? bf_coupled_window_ends(m, n) : 0;
    if (K) {
        if (m->adaptive)
            bf_coupled_mr_before(m);
        if ((st = bf_filmsys_step(m->fs, (double)K * dt, m->mucpl, err)))
            return st;
        if (m->sym) {
            /* before the coupling's refresh reads the film */
            double c[2];
            bf_film_mirror(bf_filmsys_film(m->fs), 1, c);
            bf_coupled_keep_max(m->sym_correction, c, 2);
        }
        if (m->timing)
            c3 = bf_wall_time();
        bf_coupling_refresh(m->cpl);
        bf_coupling_prepare(m->cpl, m->nb, s->b.x);
        s->ode.epoch++;
        if (m->adaptive)
            bf_coupled_mr_after(m, n, dt);
    } else if (m->timing) {
        c3 = c2;
    }
    if (m->timing) {
        double c4 = bf_wall_time();
        m->cpu[0] += c2 - c1;
        m->cpu[1] += c3 - c2;
        m->cpu[2] += (c1 - c0) + (c4 - c3);
    }
    st = bf_coupled_events(m, t, dt, err);
    if (!st && m->ly)
        st = shadow_step(m, n, t, dt, err);
    return st;
}

/* The film's stable step, for its step of film_every x dt (filmsys.h). */
static void coupled_stable_dt(const void *self, bf_dt_limit *lim)
{
    const coupled_model *m = self;
    bf_filmsys_stable_dt(m->fs, lim);
}

static void coupled_energy(const void *self, double t, double *kin,
                           double *pot)
{
    const coupled_model *m = self;
    bf_ballsys_energy(m->sys, t, kin, pot);
}

/* ------------------------------------------------------------ output */

enum { ON_SYM = 1u << 0, ON_ADAPTIVE = 1u << 1 };
static const bf_series_spec coupled_series[] = {
    {.path = "/coupled/psi_probe", .unit = "1",
     .doc = "psi at [coupled] probe, linear between nodes",
     .slot = BF_SLOT(coupled_model, probe_s)},
    {.path = "/coupled/sym_balls", .unit = "cm",
     .doc = "left/right symmetry error of the balls max_i |x_i + x_(n+1-i)|",
     .slot = BF_SLOT(coupled_model, symb)},
    {.path = "/coupled/sym_film", .unit = "1",
     .doc = "left/right symmetry error of the film max_i |psi_i + "
            "psi_(N-i)|",
     .slot = BF_SLOT(coupled_model, symf)},
    {.path = BF_DS_COUPLED_RETURN_MAP, .unit = "1", .kind = BF_SK_EVENTS,
     .ncols = 3, .columns = "t, x, v", .column_units = "s; cm; cm/s",
     .doc = "t, x, v of map_ball when map_pivot is closest to the origin "
            "while touching its inner neighbour (Fig. 8A)",
     .slot = BF_SLOT(coupled_model, map)},
    {.path = "/coupled/peaks", .unit = "1", .kind = BF_SK_EVENTS, .ncols = 2,
     .columns = "t, x", .column_units = "s; cm",
     .doc = "t, x of the maxima of peak_ball's position (Fig. 6C)",
     .slot = BF_SLOT(coupled_model, peaks)},
    {.path = "/coupled/sym_correction", .unit = "1", .ncols = 4,
     .when = ON_SYM, .columns = "film A, film u, ball x, ball v",
     .doc = "symmetrize: largest relative change of the projection since "
            "the previous row: film alpha_k h (/ max h), film u (/ max "
            "|u_k|), ball x (/ max |x|), ball v (/ max |v|)",
     .slot = BF_SLOT(coupled_model, symc_s)},
    {.path = "/coupled/film_every", .unit = "1", .when = ON_ADAPTIVE,
     .doc = "film_every = auto: ball steps K of the film step under way at "
            "each output row",
     .slot = BF_SLOT(coupled_model, kser)},
    {.path = "/coupled/symmetry_break", .unit = "1", .kind = BF_SK_STATIC,
     .per = "level", .ncols = 2, .columns = "level, t",
     .column_units = "cm; s",
     .doc = "first time the ball symmetry error exceeded each level (NaN: "
            "never)"},
    {.path = "/coupled/sym_correction_max", .unit = "1", .kind = BF_SK_STATIC,
     .ncols = 4, .when = ON_SYM, .columns = "film A, film u, ball x, ball v",
     .doc = "symmetrize: largest relative change of the projection over the "
            "run (columns as /coupled/sym_correction)"},
};
enum { CPL_SYMBREAK = BF_NSERIES(coupled_series) - 2, CPL_SYMMAX };
static const bf_series_table coupled_table = {"coupled", coupled_series,
                                              BF_NSERIES(coupled_series)};
static const bf_series_table *const coupled_tables[] = {
    &bf_filmsys_series, &bf_balls_series, &coupled_table, &bf_lyap_series,
    NULL};

static bf_status coupled_output_open(void *self, bf_out *out, bf_err *err)
{
    coupled_model *m = self;
    bf_status st = bf_filmsys_output_open(m->fs, out, err);
    if (!st)
        st = bf_balls_output_open(&m->bo, out, &m->sys->b, err);
    const unsigned on = (m->sym ? ON_SYM : 0) | (m->adaptive ? ON_ADAPTIVE : 0);
    if (!st)
        st = bf_out_open_table(out, coupled_series, BF_NSERIES(coupled_series),
                               m, NULL, 0, on, err);
    if (!st && m->ly)
        st = bf_lyap_sum_output_open(m->ly, out, err);
    return st;
}

static double probe_psi(const coupled_model *m)
{
    const bf_film *f = bf_filmsys_film(m->fs);
    const double *x = bf_film_x(f), *psi = bf_film_psi(f);
    size_t n = bf_film_nodes(f);
    double u = (m->probe - x[0]) / (x[1] - x[0]);
    size_t j = (size_t)floor(u);
    if (j >= n - 1)
        j = n - 2;
    double s = u - (double)j;
    return (1 - s) * psi[j] + s * psi[j + 1];
}

static bf_status coupled_output_row(void *self, long n, double t, bf_err *err)
{
    coupled_model *m = self;
    bf_status st = bf_filmsys_output_row(m->fs, n, t, err);
    if (st)
        return st;
    const bf_film *f = bf_filmsys_film(m->fs);
    const double *psi = bf_film_psi(f);
    size_t nn = bf_film_nodes(f);
    double sf = 0;
    for (size_t i = 0; i < nn; i++)
        sf = fmax(sf, fabs(psi[i] + psi[nn - 1 - i]));
    double pr = probe_psi(m),
           sb = bf_coupled_symmetry_error(m->sys->b.x, m->nb);
    if (bf_balls_output_row(&m->bo, &m->sys->b) ||
        bf_series_append(m->probe_s, &pr) || bf_series_append(m->symb, &sb) ||
        bf_series_append(m->symf, &sf) ||
        (m->sym && bf_series_append(m->symc_s, m->sym_correction)) ||
        bf_coupled_mr_output_row(m))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    for (int q = 0; q < 4; q++)
        m->sym_correction[q] = 0;
    return BF_OK;
}

static bf_status coupled_output_close(void *self, bf_out *out, bf_err *err)
{
    coupled_model *m = self;
    double rows[BF_COUPLED_NSYM * 2];
    for (int k = 0; k < BF_COUPLED_NSYM; k++) {
        rows[2 * k] = bf_coupled_sym_levels[k];
        rows[2 * k + 1] = m->sym_t[k];
    }
    bf_status st = bf_out_table_array(out, &coupled_series[CPL_SYMBREAK], rows,
                                      BF_COUPLED_NSYM, err);
    if (!st && m->sym)
        st = bf_out_table_array(out, &coupled_series[CPL_SYMMAX],
                                m->sym_correction + 4, 4, err);
    if (!st && m->ly)
        st = bf_lyap_sum_output_close(m->ly, out, err);
    return st;
}

static void coupled_counters(const void *self, bf_counters *c)
{
    const coupled_model *m = self;
    if (m->whole)
        bf_coupled_whole_counters(m->whole, c);
    else
        *c = m->sys->it->count;
}

static void coupled_report(const void *self, FILE *f)
{
    const coupled_model *m = self;
    bf_filmsys_report(m->fs, f);
    if (m->whole)
        bf_coupled_whole_report(m->whole, f);
    unsigned long long ex, ta;
    bf_coupling_counts(m->cpl, &ex, &ta);
    fprintf(f, "coupling: %llu exact and %llu Taylor evaluations of F; "
               "%ld return-map points, %ld peaks\n",
            ex, ta, m->nmap, m->npeak);
    fprintf(f, "symmetry: ball error first above");
    /* sym_t is NaN for a level the error never reached */
    for (int k = 0; k < BF_COUPLED_NSYM; k++) {
        fprintf(f, " %g cm ", bf_coupled_sym_levels[k]);
        if (isnan(m->sym_t[k]))
            fprintf(f, "never");
        else
            fprintf(f, "at t = %.4g s", m->sym_t[k]);
        fprintf(f, "%s", k + 1 < BF_COUPLED_NSYM ? "," : "\n");
    }
    if (m->sym)
        fprintf(f,
                "symmetrize: largest relative change of one projection: "
                "film alpha h %.3g, film u %.3g, ball x %.3g, ball v "
                "%.3g\n",
                m->sym_correction[4], m->sym_correction[5],
                m->sym_correction[6], m->sym_correction[7]);
    bf_coupled_mr_report(m, f);
    if (m->timing)
        fprintf(f, "time: balls %.3f s, film %.3f s, coupling (mu_cpl, "
                   "refresh) %.3f s\n",
                m->cpu[0], m->cpu[1], m->cpu[2]);
    if (m->ly)
        bf_lyap_sum_report(m->ly, m->shadow->sys->it->count.evals, f);
}

/* ------------------------------------------------------------ checkpoint */

/* The model's own state (a table of fields, checkpoint.h), under
 * PREFIX + "coupled": the event counts, the first symmetry breaks, the
 * mu_cpl the film's next step takes; the ball integrator's force epoch;
 * with symmetrize, the largest corrections.  The film, the balls and the
 * coupling save theirs under PREFIX + "film", "balls", "coupling". */
static const bf_field coupled_fields[] = {
    BF_FIELD(coupled_model, nmap, BF_F_LONG, "1"),
    BF_FIELD(coupled_model, npeak, BF_F_LONG, "1"),
    BF_FIELD_ARRAY(coupled_model, sym_t, BF_F_DOUBLE, "s"),
    BF_FIELD_PTR(coupled_model, mucpl, BF_F_DOUBLE, nodes, "g/(cm s^2)"),
};
static const bf_field epoch_field[] = {
    BF_FIELD(bf_ode, epoch, BF_F_ULONG, "1")};
static const bf_field sym_fields[] = {
    BF_FIELD_ARRAY(coupled_model, sym_correction, BF_F_DOUBLE, "1"),
};

/* the entry prefixes of one system (prefix "": the run, "lyapunov.": its
 * shadow) */
typedef struct state_names {
    char balls[64], own[64];
} state_names;

static state_names names_of(const char *prefix)
{
    state_names n;
    snprintf(n.balls, sizeof n.balls, "%sballs", prefix);
    snprintf(n.own, sizeof n.own, "%scoupled", prefix);
    return n;
}

static bf_status save_state(const coupled_model *m, bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    state_names n = names_of(prefix);
    bf_status st = bf_filmsys_save(m->fs, ck, prefix, err);
    if (!st)
        st = bf_ballsys_save(m->sys, ck, n.balls, err);
    if (!st)
        st = bf_ckpt_put_fields(ck, n.own, coupled_fields,
                                BF_NFIELDS(coupled_fields), m, err);
    if (!st)
        st = bf_ckpt_put_fields(ck, n.own, epoch_field, 1, &m->sys->ode, err);
    if (!st)
        st = bf_coupling_save(m->cpl, ck, prefix, err);
    if (!st && m->sym)
        st = bf_ckpt_put_fields(ck, n.own, sym_fields, 1, m, err);
    if (!st)
        st = bf_coupled_mr_save(m, ck, n.own, err);
    if (!st && m->whole)
        st = bf_coupled_whole_save(m->whole, ck, n.own, err);
    return st;
}

static bf_status load_state(coupled_model *m, const bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    state_names n = names_of(prefix);
    bf_status st = bf_filmsys_load(m->fs, ck, prefix, err);
    if (!st)
        st = bf_ballsys_load(m->sys, ck, n.balls, err);
    if (!st)
        st = bf_ckpt_get_fields(ck, n.own, coupled_fields,
                                BF_NFIELDS(coupled_fields), m, err);
    if (!st)
        st = bf_ckpt_get_fields(ck, n.own, epoch_field, 1, &m->sys->ode, err);
    if (!st) /* after the film */
        st = bf_coupling_load(m->cpl, ck, prefix, err);
    if (!st && m->sym)
        st = bf_ckpt_get_fields(ck, n.own, sym_fields, 1, m, err);
    if (!st)
        st = bf_coupled_mr_load(m, ck, n.own, err);
    if (!st && m->whole)
        st = bf_coupled_whole_load(m->whole, ck, n.own, err);
    return st;
}

static bf_status coupled_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const coupled_model *m = self;
    bf_status st = save_state(m, ck, "", err);
    if (!st && m->ly)
        st = save_state(m->shadow, ck, "lyapunov.", err);
    if (!st && m->ly)
        st = bf_lyap_sum_save(m->ly, ck, err);
    return st;
}

static bf_status coupled_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    coupled_model *m = self;
    bf_status st = load_state(m, ck, "", err);
    if (!st && m->ly)
        st = load_state(m->shadow, ck, "lyapunov.", err);
    if (!st && m->ly)
        st = bf_lyap_sum_load(m->ly, ck, err);
    return st;
}

static void coupled_results(const void *self, bf_results *r);

static const bf_section_spec *const coupled_specs[] = {
    &bf_coupled_spec, &bf_filmsys_spec, &bf_ballsys_ball_spec, &bf_lyap_spec,
    NULL};

/* The balls' and the film's arrays, to read (the coupling's state
 * follows from both, so setting either is not offered). */
static size_t coupled_state(void *self, bf_state_var *vars, size_t cap)
{
    coupled_model *m = self;
    bf_state_var v[7];
    size_t nb = bf_ballsys_state(m->sys, v, 2);
    for (size_t k = 0; k < nb; k++)
        v[k].settable = 0;
    size_t n = nb + bf_filmsys_state(m->fs, v + nb, 5, 0);
    for (size_t k = 0; k < n && k < cap; k++)
        vars[k] = v[k];
    return n;
}

const bf_model_type bf_model_coupled = {
    .name = "coupled",
    .series = coupled_tables,
    .doc = "balls coupled to the two-phase film, static kink or dynamic "
           "film (Yasuda sec. 3.4-3.5)",
    .flags = BF_MODEL_INTEGRATOR | BF_MODEL_EFFECTS,
    .specs = coupled_specs,
    .create = coupled_create,
    .destroy = coupled_destroy,
    .memory = coupled_memory,
    .stable_dt = coupled_stable_dt,
    .step = coupled_step,
    .energy = coupled_energy,
    .output_open = coupled_output_open,
    .output_row = coupled_output_row,
    .output_close = coupled_output_close,
    .counters = coupled_counters,
    .report = coupled_report,
    .checkpoint_save = coupled_save,
    .checkpoint_load = coupled_load,
    .results = coupled_results,
    .state = coupled_state,
    .study = &bf_study_coupled,
};

/* ------------------------------------------------------------ drivers */

/* The return map is /coupled/return_map (no multi-minimum count); its
 * points are there when the run holds all of them (not continued from a
 * checkpoint). */
static void coupled_results(const void *self, bf_results *r)
{
    const coupled_model *m = self;
    r->has_return_map = 1;
    r->map_points = (size_t)m->nmap;
    if (m->map_kept && m->map_kept == (size_t)m->nmap) {
        r->map_z = m->map_x;
        r->map_v = m->map_v;
    }
    r->has_lyapunov = m->ly != NULL;
    if (m->ly)
        r->lyapunov_exponent = bf_lyap_sum_estimate(m->ly, &r->lyapunov_time);
}

static void parts_of(coupled_model *m, bf_coupled_parts *p)
{
    p->sys = m ? m->sys : NULL;
    p->film = m ? bf_filmsys_film(m->fs) : NULL;
    p->mu_cpl = m ? m->mucpl : NULL;
}

bf_status bf_coupled_sim_parts(bf_sim *sim, bf_coupled_parts *run,
                               bf_coupled_parts *shadow)
{
    if (bf_sim_model_type(sim) != &bf_model_coupled)
        return BF_EINPUT;
    coupled_model *m = bf_sim_model(sim);
    parts_of(m, run);
    parts_of(m->shadow, shadow);
    return BF_OK;
}

void bf_coupled_model_parts(void *model, bf_coupled_parts *p)
{
    parts_of(model, p);
}

bf_filmsys *bf_coupled_model_filmsys(void *model)
{
    return ((coupled_model *)model)->fs;
}

void bf_coupled_model_describe(void *model, char *buf, size_t cap,
                               int *order)
{
    coupled_model *m = model;
    if (m->whole) {
        bf_coupled_whole_describe(m->whole, buf, cap, order);
        return;
    }
    char b[200], f[200];
    int fo = 0;
    bf_integrator_describe(m->sys->it, b, sizeof b);
    bf_filmsys_describe(m->fs, f, sizeof f, &fo);
    *order = bf_integrator_order(m->sys->it);
    if (!m->dynamic) {
        snprintf(buf, cap, "split %s, static film", b);
        return;
    }
    if (m->adaptive)
        snprintf(buf, cap, "split %s, %s every auto steps", b, f);
    else
        snprintf(buf, cap, "split %s, %s every %ld steps", b, f, m->every);
    /* the film's lag behind the balls is first order in dt */
    *order = 1;
}
