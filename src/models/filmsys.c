/* filmsys.c: a film from a scene's [film] section, its initial state,
 * output and diagnostics (see filmsys.h).
 *
 * Initial state (Yasuda sec. 3.4): h = h0, u = 0, and psi from
 *   kink     psi = sqrt(a/b) tanh((x - x0)/(sqrt(2) xi)), xi = sqrt(gamma/a)
 *            (eq. 3.17 with the width corrected: the print's
 *            tanh(x/sqrt(2 xi)) has mu = 0 only for xi = 1);
 *   uniform  psi = psi0;
 *   file     the last profile row (/film/h, /film/psi, /film/u_d, /film/u_c)
 *            of an earlier run's output.
 * The paper adds "a perturbation of less than 0.0001 randomly to the
 * volume fractions" without saying how alpha_d + alpha_c = 1 is kept:
 *   positive  alpha_k += eps_k, eps_k uniform in [0, amplitude), then both
 *             divided by their sum: the fractions stay in [0, 1];
 *   signed    alpha_d += eps, eps uniform in [-amplitude, amplitude),
 *             alpha_c = 1 - alpha_d, clipped to [0, 1] (without the clip the
 *             far field of the kink, alpha ~ 1e-16, would start negative,
 *             where the model is ill-posed).
 * The random numbers come from GSL's mt19937 seeded with [film] seed, drawn
 * node by node (eps_d then eps_c): same seed, same bits.
 */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "film/film_mol.h"
#include "integrators/ark1.h"
#include "integrators/arkode.h"
#include "models/filmsys.h"
#include "models/state_names.h"
#include "io/dataset_paths.h"

/* The film's profiles: datasets (series.h), the state's names (without
 * the slash) and what initial = file reads. */
#define FILM_H BF_DS_FILM_H
#define FILM_PSI BF_DS_FILM_PSI
#define FILM_UD BF_DS_FILM_U_D
#define FILM_UC BF_DS_FILM_U_C
#define FILM_X BF_DS_FILM_X

enum { INIT_KINK, INIT_UNIFORM, INIT_FILE };
enum { PERT_POSITIVE, PERT_SIGNED };

static const bf_param film_params[] = {
    {"length", BF_AT(bf_film_keys, length, BF_REAL), "cm", "50",
     "film length L (walls at -L/2 and L/2)", BF_POS, 0, 0, NULL},
    {"dx", BF_AT(bf_film_keys, dx, BF_REAL), "cm", "0.1",
     "node spacing; L/dx must be a whole number", BF_POS, 0, 0, NULL},
    {"h0", BF_AT(bf_film_keys, h0, BF_REAL), "cm", "1",
     "initial height (kink and uniform)", BF_POS, 0, 0, NULL},
    {"rho_d", BF_AT(bf_film_keys, rho_d, BF_REAL), "g/cm^3", "1",
     "density of the minor phase d", BF_POS, 0, 0, NULL},
    {"rho_c", BF_AT(bf_film_keys, rho_c, BF_REAL), "g/cm^3", "1",
     "density of the major phase c", BF_POS, 0, 0, NULL},
    {"nu", BF_AT(bf_film_keys, nu, BF_REAL), "cm^2/s", "0.01",
     "lateral viscosity (sec. 3.4)", BF_NONNEG, 0, 0, NULL},
    {"g", BF_AT(bf_film_keys, g, BF_REAL), "cm/s^2", "980",
     "gravitational acceleration", BF_NONNEG, 0, 0, NULL},
    {"a", BF_AT(bf_film_keys, a, BF_REAL), "g/(cm s^2)", "1",
     "Ginzburg-Landau constant a", BF_POS, 0, 0, NULL},
    {"b", BF_AT(bf_film_keys, b, BF_REAL), "g/(cm s^2)", "1",
     "Ginzburg-Landau constant b (b >= a keeps |psi_e| <= 1)", BF_POS, 0, 0,
     NULL},
    {"gamma", BF_AT(bf_film_keys, gamma, BF_REAL), "g cm/s^2", "1",
     "Ginzburg-Landau gradient constant", BF_POS, 0, 0, NULL},
    {"initial", BF_AT(bf_film_keys, initial, BF_ENUM), "", "kink",
     "initial psi: kink (eq. 3.17), uniform (psi0), or file (last profile "
     "of an earlier run's output)",
     0, 0, 0, "kink|uniform|file"},
    {"center", BF_AT(bf_film_keys, center, BF_REAL), "cm", "0",
     "kink centre x0", 0, 0, 0, NULL},
    {"psi0", BF_AT(bf_film_keys, psi0, BF_REAL), "1", "0",
     "order parameter of the uniform film", BF_MIN | BF_MAX, -1, 1, NULL},
    {"file", BF_AT(bf_film_keys, file, BF_STR), "", "",
     "HDF5 output of an earlier run (initial = file)", 0, 0, 0, NULL},
    {"perturbation", BF_AT(bf_film_keys, perturbation, BF_REAL), "1", "0",
     "amplitude of the random perturbation of the volume fractions",
     BF_MIN | BF_MAX, 0, 0.5, NULL},
    {"perturbation_mode", BF_AT(bf_film_keys, perturbation_mode, BF_ENUM), "",
     "positive",
     "positive: alpha_k += [0, amp) then renormalised; signed: alpha_d += "
     "[-amp, amp), clipped to [0, 1]",
     0, 0, 0, "positive|signed"},
    {"seed", BF_AT(bf_film_keys, seed, BF_INT), "", "1",
     "seed of the GSL mt19937 generator", BF_NONNEG, 0, 0, NULL},
    {"mu_taylor", BF_AT(bf_film_keys, mu_taylor, BF_ENUM), "", "midpoint",
     "how mu enters the dt^2/2 term of (3.16): midpoint (consistent, "
     "2nd order), um (as printed: W = (P +- mu) u_m), uk (W = (P +- mu) u_k)",
     0, 0, 0, "midpoint|um|uk"},
    {"positivity", BF_AT(bf_film_keys, positivity, BF_ENUM), "", "limit",
     "negative volume fractions: limit (flux limiter keeps alpha >= 0, "
     "conservative) or stop (the run stops at the first one)",
     0, 0, 0, "limit|stop"},
    {"vanish", BF_AT(bf_film_keys, vanish, BF_REAL), "1", "1e-8",
     "where a volume fraction is below this, that phase's velocity is set to "
     "the mixture velocity after each step (0: never)",
     BF_MIN | BF_MAX, 0, 0.5, NULL},
    {"force_dt", BF_AT(bf_film_keys, force_dt, BF_BOOL), "", "false",
     "run even if [scene] dt exceeds the stable limit (stops at the first "
     "bad value)",
     0, 0, 0, NULL},
    {"profile_every", BF_AT(bf_film_keys, profile_every, BF_INTERVAL),
     "steps | s", "0",
     "interval of the profile output /film/h, /film/psi, ... ('N' steps or "
     "'T s'; 0: at every [scene] output_every row); the first and last "
     "states are always written",
     0, 0, 0, NULL},
    {"scheme", BF_AT(bf_film_keys, scheme, BF_ENUM), "", "invariant",
     "time integrator: invariant (the paper's scheme 3.15-3.16), arkode "
     "(ARKODE adaptive ERK on the same grid in method-of-lines form) or "
     "arkode-imex (ARKODE IMEX, the stiff terms implicit: imex_implicit); "
     "the ARKODE schemes step adaptively inside each [scene] dt "
     "(docs/models/film.md)",
     0, 0, 0, "invariant|arkode|arkode-imex"},
    {"table", BF_AT(bf_film_keys, table, BF_ENUM), "",
     "ARKODE_DORMAND_PRINCE_7_4_5", "scheme = arkode: ERK Butcher table", 0,
     0, 0, BF_ARKODE_TABLE_CHOICES},
    {"imex_order", BF_AT(bf_film_keys, imex_order, BF_INT), "1", "4",
     "scheme = arkode-imex: order of ARKStep's ARK pair (3: ARK324L2SA, 4: "
     "ARK436L2SA, 5: ARK548L2SA)",
     BF_MIN | BF_MAX, 3, 5, NULL},
    {"imex_implicit", BF_AT(bf_film_keys, imex_implicit, BF_ENUM), "",
     "waves",
     "scheme = arkode-imex: waves (implicit: phase fluxes, pressure and mu "
     "gradients, viscosity; explicit: the self-advection u u_x) or capillary "
     "(implicit: the gamma psi_xx part of mu and the viscosity)",
     0, 0, 0, "waves|capillary"},
    {"rtol", BF_AT(bf_film_keys, rtol, BF_REAL), "1", "1e-6",
     "ARKODE schemes: relative tolerance of the local error", BF_POS, 0, 0,
     NULL},
    {"atol", BF_AT(bf_film_keys, atol, BF_REAL), "cm, cm/s", "1e-8",
     "ARKODE schemes: absolute tolerance (alpha_k h and u_k)", BF_POS, 0, 0,
     NULL},
    {"max_step", BF_AT(bf_film_keys, max_step, BF_REAL), "s", "0",
     "ARKODE schemes: largest internal step (0: none)", BF_NONNEG, 0, 0,
     NULL},
    {"max_steps", BF_AT(bf_film_keys, max_steps, BF_INT), "1", "1000000",
     "ARKODE schemes: internal steps allowed per [scene] dt", BF_MIN, 1, 0,
     NULL},
    {0},
};

const bf_section_spec bf_filmsys_spec = BF_SECTION(
    "film",
    "two-phase shallow-water film with Ginzburg-Landau phase separation "
    "(Yasuda sec. 3.1-3.4)",
    film_params, bf_film_keys);

struct bf_filmsys {
    bf_film *film;
    size_t n;
    double dt, film_dt; /* [scene] dt; the film's own step (0: static) */
    int step_varies;    /* film_dt is the first of steps chosen as it runs */
    long every;         /* film steps every `every` steps (0: static) */
    int force_dt;       /* [film] force_dt: no stable-step limit */
    long prof_every, last_step;
    int kink;
    double x0;
    double m0[2];
    double drift; /* largest relative change of the totals seen */
    double *tmp;  /* one profile row */
    double *given; /* the initial h, psi, u_d, u_c as handed to the film
                      (4 x n): set_state replaces one of them */
    double *kink0; /* the analytic kink on the nodes (initial = kink) */
    double *flux;  /* 2 x n: bf_filmsys_phase_flux (allocated on demand) */
    /* ARKODE schemes: the method-of-lines right-hand side, the
     * integrator, the state vector, the coupling's mu_cpl of this step */
    int scheme, split;
    bf_film_mol *mol;
    bf_ark1 *ark;
    double *y;
    const double *mu_cpl;
    double t_film;                /* s, sum of the film steps taken */
    unsigned long long inv_steps; /* invariant scheme: steps taken */
    bf_series *s_time, *s_h, *s_psi, *s_ud, *s_uc;
    bf_series *s_md, *s_mc, *s_umax, *s_amin, *s_kerr, *s_lim;
};

bf_film *bf_filmsys_film(bf_filmsys *fs) { return fs->film; }

int bf_filmsys_has_kink(const bf_filmsys *fs, double *x0)
{
    if (x0)
        *x0 = fs->x0;
    return fs->kink;
}

void bf_filmsys_free(bf_filmsys *fs)
{
    if (!fs)
        return;
    bf_film_free(fs->film);
    free(fs->tmp);
    free(fs->kink0);
    free(fs->given);
    free(fs->flux);
    bf_ark1_free(fs->ark);
    bf_film_mol_free(fs->mol);
    free(fs->y);
    free(fs);
}

/* The last profile row of an earlier run. */
static bf_status read_file(bf_filmsys *fs, const char *path, double *h,
                           double *psi, double *ud, double *uc, bf_err *err)
{
    if (!*path)
        return bf_fail_key(err, BF_EINPUT, "film", "file",
                           "initial = file needs the HDF5 file of an "
                           "earlier run");
    const char *names[4] = {FILM_H, FILM_PSI, FILM_UD, FILM_UC};
    double *dst[4] = {h, psi, ud, uc};
    for (int k = 0; k < 4; k++) {
        double *d;
        size_t n0, n1;
        bf_err e2 = {0};
        if (bf_h5_read(path, names[k], &d, &n0, &n1, &e2))
            return bf_fail_key(err, BF_EINPUT, "film", "file", "%s", e2.msg);
        if (n1 != fs->n || n0 < 1) {
            free(d);
            return bf_fail_key(err, BF_EINPUT, "film", "file",
                               "%s: %s has %zu x %zu values; this film has "
                               "%zu nodes (same length and dx needed)",
                               path, names[k], n0, n1, fs->n);
        }
        memcpy(dst[k], d + (n0 - 1) * n1, fs->n * sizeof(double));
        free(d);
    }
    return BF_OK;
}

static bf_status initial_state(bf_filmsys *fs, const bf_film_keys *k,
                               bf_err *err)
{
    bf_film *f = fs->film;
    const bf_film_params *p = bf_film_params_of(f);
    const size_t n = fs->n;
    const double *x = bf_film_x(f);
    double *buf = calloc(4 * n, sizeof(double));
    if (!buf)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    double *h = buf, *psi = buf + n, *ud = buf + 2 * n, *uc = buf + 3 * n;
    bf_status st = BF_OK;
    fs->kink = k->initial == INIT_KINK;
    fs->x0 = k->center;
    if (k->initial == INIT_FILE) {
        st = read_file(fs, k->file, h, psi, ud, uc, err);
    } else {
        for (size_t i = 0; i < n; i++) {
            h[i] = k->h0;
            psi[i] = k->initial == INIT_KINK ? bf_film_kink(p, fs->x0, x[i])
                                             : k->psi0;
        }
    }
    double amp = k->perturbation;
    if (!st && amp > 0) {
        gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
        if (!r) {
            free(buf);
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        }
        gsl_rng_set(r, (unsigned long)k->seed);
        for (size_t i = 0; i < n; i++) {
            double ad = 0.5 * (1.0 + psi[i]), ac = 0.5 * (1.0 - psi[i]);
            if (k->perturbation_mode == PERT_POSITIVE) {
                ad += amp * gsl_rng_uniform(r);
                ac += amp * gsl_rng_uniform(r);
                double s = ad + ac;
                ad /= s;
                ac /= s;
            } else {
                ad += amp * (2.0 * gsl_rng_uniform(r) - 1.0);
                ad = fmin(fmax(ad, 0.0), 1.0);
                ac = 1.0 - ad;
            }
            psi[i] = ad - ac;
        }
        gsl_rng_free(r);
    }
    if (!st) {
        bf_err e2 = {0};
        if (bf_film_set_state(f, h, psi, ud, uc, &e2))
            st = bf_fail_key(err, BF_EINPUT, "film", "initial", "%s", e2.msg);
    }
    if (st)
        free(buf);
    else
        fs->given = buf;
    return st;
}

/* Doubles per node a film takes at its peak: the 25 arrays of the
 * scheme (film_impl.h), the zero mu_cpl, tmp and kink0 here, and 8 more
 * for the larger of the initial state's 4 (freed after create), two
 * buffered profile rows of the 4 profiles, or a checkpoint's copy of the
 * 6 arrays of the state.  Measured: the smallest ulimit -v under which
 * runs/kink_steady.ini (3 steps) ends grows by 228 B = 28.5 doubles per
 * node from 4e5 to 8e5 nodes (docs/reliability.md). */
#define FILM_DOUBLES_PER_NODE 36.0
/* What the ARKODE schemes add per node: the state vector and scratch of
 * film_mol.c (11), ARKODE's vectors (4 unknowns per node each) and, for
 * IMEX, the band matrix and its saved copy (2 x 4 columns x 34 rows of
 * half-bandwidth 11).  Measured as above with runs/kink_converge.ini at
 * length 5000 and 10000 cm (5e4 more nodes, 3 steps): the peak resident
 * size grows by 38 doubles per node with the invariant scheme, 112 with
 * scheme = arkode (the default DORMAND_PRINCE_7_4_5: 74 more; a 13-stage
 * table adds 4 per extra stage, hence 100) and 432 with arkode-imex. */
#define FILM_ARKODE_DOUBLES_PER_NODE 100.0
#define FILM_IMEX_DOUBLES_PER_NODE 396.0

void bf_filmsys_memory(const bf_film_keys *k, double extra, int copies,
                       bf_mem_need *need)
{
    double nodes = floor(k->length / k->dx + 0.5) + 1.0;
    double per = FILM_DOUBLES_PER_NODE + extra;
    if (k->scheme == BF_FILM_SCHEME_ARKODE)
        per += FILM_ARKODE_DOUBLES_PER_NODE;
    else if (k->scheme == BF_FILM_SCHEME_IMEX)
        per += FILM_IMEX_DOUBLES_PER_NODE;
    need->bytes = (double)copies * nodes * per * 8.0;
    snprintf(need->what, sizeof need->what,
             "%.3g nodes (length %g cm / dx %g cm) x %.0f doubles%s", nodes,
             k->length, k->dx, per,
             copies > 1 ? ", twice (the Lyapunov shadow)" : "");
    snprintf(need->section, sizeof need->section, "film");
    snprintf(need->key, sizeof need->key, "dx");
}

/* The right-hand sides of the ARKODE schemes (film_mol.h). */
static int rhs_all(void *ctx, double t, const double *y, double *ydot)
{
    (void)t;
    bf_filmsys *fs = ctx;
    return bf_film_mol_rhs(fs->mol, y, fs->mu_cpl, BF_FILM_MOL_ALL,
                           (bf_film_mol_split)fs->split, ydot);
}

static int rhs_explicit(void *ctx, double t, const double *y, double *ydot)
{
    (void)t;
    bf_filmsys *fs = ctx;
    return bf_film_mol_rhs(fs->mol, y, fs->mu_cpl, BF_FILM_MOL_EXPLICIT,
                           (bf_film_mol_split)fs->split, ydot);
}

static int rhs_implicit(void *ctx, double t, const double *y, double *ydot)
{
    (void)t;
    bf_filmsys *fs = ctx;
    return bf_film_mol_rhs(fs->mol, y, fs->mu_cpl, BF_FILM_MOL_IMPLICIT,
                           (bf_film_mol_split)fs->split, ydot);
}

static bf_status arkode_scheme(bf_filmsys *fs, const bf_film_keys *k,
                               bf_err *err)
{
    bf_status st = bf_film_mol_create(&fs->mol, fs->film, err);
    if (st)
        return st;
    const size_t n = bf_film_mol_size(fs->mol);
    fs->y = calloc(n, sizeof *fs->y);
    if (!fs->y)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    fs->split = k->imex_implicit;
    const int imex = k->scheme == BF_FILM_SCHEME_IMEX;
    bf_ark1_opts o = {
        .kind = imex ? BF_ARK1_IMEX : BF_ARK1_ERK,
        .table = k->table,
        .order = (int)k->imex_order,
        .rtol = k->rtol,
        .atol = k->atol,
        .max_step = k->max_step,
        .max_steps = k->max_steps,
        .band = bf_film_mol_bandwidth(),
        .work_around_311 = 1,
    };
    st = bf_ark1_create(&fs->ark, n, imex ? rhs_explicit : rhs_all,
                        imex ? rhs_implicit : NULL, fs, &o, err);
    if (st == BF_EINPUT)
        bf_err_prefix(err, "[film] table");
    return st;
}

bf_status bf_filmsys_create(bf_filmsys **out, const bf_film_keys *k,
                            const bf_run_ctx *run, long film_every,
                            bf_err *err)
{
    *out = NULL;
    static const bf_film_mu_taylor mt[] = {BF_FILM_MU_MIDPOINT, BF_FILM_MU_UM,
                                           BF_FILM_MU_UK};
    bf_film_params p = {
        .length = k->length,
        .dx = k->dx,
        .rho_d = k->rho_d,
        .rho_c = k->rho_c,
        .nu = k->nu,
        .g = k->g,
        .a = k->a,
        .b = k->b,
        .gamma = k->gamma,
        .mu_taylor = mt[k->mu_taylor],
        .limit_positive = k->positivity == 0,
        .vanish = k->vanish,
    };
    if (k->initial == INIT_KINK && p.a > p.b)
        return bf_fail_key(err, BF_EINPUT, "film", "b",
                           "the kink's far field psi_e = sqrt(a/b) = %g "
                           "exceeds 1 (volume fractions outside [0, 1]): "
                           "use b >= a",
                           sqrt(p.a / p.b));
    bf_filmsys *fs = calloc(1, sizeof *fs);
    if (!fs)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_err e2 = {0};
    if (bf_film_create(&fs->film, &p, &e2)) {
        free(fs);
        if (e2.status != BF_EINPUT)
            return bf_fail(err, e2.status, "film: %s", e2.msg);
        return bf_fail_key(err, BF_EINPUT, "film", "dx", "%s", e2.msg);
    }
    fs->n = bf_film_nodes(fs->film);
    fs->tmp = calloc(fs->n, sizeof(double));
    fs->kink0 = calloc(fs->n, sizeof(double));
    bf_status st = fs->tmp && fs->kink0
                       ? initial_state(fs, k, err)
                       : bf_fail(err, BF_EINTERNAL, "out of memory");
    for (size_t i = 0; !st && i < fs->n; i++)
        fs->kink0[i] = bf_film_kink(&p, fs->x0, bf_film_x(fs->film)[i]);
    if (st) {
        bf_filmsys_free(fs);
        return st;
    }
    fs->dt = run->dt;
    fs->every = film_every;
    fs->film_dt = (double)film_every * fs->dt;
    fs->force_dt = k->force_dt;
    fs->last_step = run->nsteps;
    fs->prof_every = bf_interval_steps(k->profile_every, fs->dt);
    if (fs->prof_every < 1)
        fs->prof_every = run->output_every;
    if (fs->prof_every < 1)
        fs->prof_every = 1;
    bf_film_totals(fs->film, &fs->m0[0], &fs->m0[1]);
    fs->scheme = k->scheme;
    if (fs->scheme != BF_FILM_SCHEME_INVARIANT &&
        (st = arkode_scheme(fs, k, err))) {
        bf_filmsys_free(fs);
        return st;
    }
    *out = fs;
    return BF_OK;
}

/* The largest dt whose film step K dt (in floating point) does not exceed
 * lim, so that refusing dt > it is refusing K dt > lim exactly. */
static double largest_dt(double lim, long K)
{
    double d = lim / (double)K;
    while ((double)K * d > lim)
        d = nextafter(d, 0.0);
    for (double up = nextafter(d, INFINITY); (double)K * up <= lim;
         up = nextafter(d, INFINITY))
        d = up;
    return d;
}

void bf_filmsys_stable_dt(const bf_filmsys *fs, bf_dt_limit *lim)
{
    char why[256];
    /* the ARKODE schemes choose their own steps inside dt */
    if (fs->every < 1 || fs->force_dt ||
        fs->scheme != BF_FILM_SCHEME_INVARIANT)
        return;
    double L = bf_film_stable_dt(fs->film, why, sizeof why);
    if (!(L > 0 && L < INFINITY))
        return; /* nothing limits it (a film at rest without gravity) */
    lim->dt_max = largest_dt(L, fs->every);
    if (fs->every == 1) {
        snprintf(lim->why, sizeof lim->why,
                 "the film's stable limit %.4g s (%s)", L, why);
        snprintf(lim->advice, sizeof lim->advice,
                 "use a smaller dt, or set [film] force_dt = true to run "
                 "anyway");
        return;
    }
    snprintf(lim->why, sizeof lim->why,
             "%.4g s = 1/%ld of the film's stable limit: the film step %ld x "
             "dt = %g s exceeds the film's stable limit %.4g s (%s)",
             lim->dt_max, fs->every, fs->every, fs->film_dt, L, why);
    snprintf(lim->advice, sizeof lim->advice,
             "use a smaller film_every, or set [film] force_dt = true to run "
             "anyway");
    snprintf(lim->section, sizeof lim->section, "coupled");
    snprintf(lim->key, sizeof lim->key, "film_every");
}

static const char *const state_names[5] = {FILM_H + 1, FILM_PSI + 1,
                                           FILM_UD + 1, FILM_UC + 1,
                                           FILM_X + 1};

size_t bf_filmsys_state(bf_filmsys *fs, bf_state_var *vars, size_t cap,
                        int settable)
{
    static const char *const units[5] = {"cm", "1", "cm/s", "cm/s", "cm"};
    const double *data[5] = {bf_film_h(fs->film), bf_film_psi(fs->film),
                             bf_film_u_d(fs->film), bf_film_u_c(fs->film),
                             bf_film_x(fs->film)};
    for (size_t k = 0; k < 5 && k < cap; k++)
        vars[k] = (bf_state_var){state_names[k], units[k], fs->n, data[k],
                                 settable && k < 4};
    return 5;
}

bf_status bf_filmsys_set(bf_filmsys *fs, const char *name, const double *v,
                         size_t n, bf_err *err)
{
    const size_t k = bf_state_index(state_names, 4, name);
    if (k == 4 || n != fs->n)
        return bf_fail(err, BF_EINPUT, "%s: not an array of the film's %zu "
                       "nodes", name, fs->n);
    double *old = malloc(n * sizeof *old), *g = fs->given;
    if (!old)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    memcpy(old, g + k * n, n * sizeof *old);
    memcpy(g + k * n, v, n * sizeof *old);
    bf_status st = bf_film_set_state(fs->film, g, g + n, g + 2 * n, g + 3 * n,
                                     err);
    if (st) {
        memcpy(g + k * n, old, n * sizeof *old);
        bf_film_set_state(fs->film, g, g + n, g + 2 * n, g + 3 * n, NULL);
        bf_err_prefix(err, "%s", name);
    }
    free(old);
    bf_film_totals(fs->film, &fs->m0[0], &fs->m0[1]);
    fs->drift = 0.0;
    return st;
}

bf_status bf_filmsys_step(bf_filmsys *fs, double dt, const double *mu_cpl,
                          bf_err *err)
{
    if (fs->scheme == BF_FILM_SCHEME_INVARIANT) {
        fs->inv_steps++;
        return bf_film_step_invariant(fs->film, dt, mu_cpl, err);
    }
    fs->mu_cpl = mu_cpl;
    bf_film_mol_pack(fs->film, fs->y);
    bf_status st = bf_ark1_evolve(fs->ark, fs->t_film, fs->t_film + dt, fs->y,
                                  err);
    if (!st)
        st = bf_film_mol_check(fs->mol, fs->y, err);
    if (!st) {
        bf_film_mol_vanish(fs->mol, fs->y);
        bf_film_mol_unpack(fs->film, fs->y);
        fs->t_film += dt;
    }
    return st;
}

int bf_filmsys_scheme(const bf_filmsys *fs) { return fs->scheme; }

const double *bf_filmsys_phase_flux(bf_filmsys *fs, int k)
{
    if (!fs->flux && !(fs->flux = malloc(2 * fs->n * sizeof *fs->flux)))
        return NULL;
    const double *a = k ? bf_film_ah_c(fs->film) : bf_film_ah_d(fs->film);
    const double *u = k ? bf_film_u_c(fs->film) : bf_film_u_d(fs->film);
    double *q = fs->flux + (size_t)k * fs->n;
    for (size_t i = 0; i < fs->n; i++)
        q[i] = a[i] * u[i];
    return q;
}

void bf_filmsys_describe(const bf_filmsys *fs, char *buf, size_t cap,
                         int *order)
{
    static const char *const mt[] = {"midpoint", "um", "uk"};
    if (fs->scheme == BF_FILM_SCHEME_INVARIANT) {
        snprintf(buf, cap, "film invariant (mu_taylor %s)",
                 mt[bf_film_params_of(fs->film)->mu_taylor]);
        *order = 1;
        return;
    }
    char a[160];
    bf_ark1_describe(fs->ark, a, sizeof a);
    snprintf(buf, cap, "film arkode %s%s", a,
             fs->scheme == BF_FILM_SCHEME_IMEX
                 ? (fs->split == BF_FILM_MOL_WAVES ? " (implicit: waves)"
                                                   : " (implicit: capillary)")
                 : "");
    *order = bf_ark1_order(fs->ark);
}

void bf_filmsys_counters(const bf_filmsys *fs, bf_counters *c)
{
    memset(c, 0, sizeof *c);
    if (fs->ark)
        bf_ark1_counters(fs->ark, c);
    else
        c->steps = c->evals = fs->inv_steps;
}

double bf_filmsys_kink_error(const bf_filmsys *fs)
{
    if (!fs->kink)
        return NAN;
    const double *psi = bf_film_psi(fs->film);
    double e = 0.0;
    for (size_t i = 0; i < fs->n; i++)
        e = fmax(e, fabs(psi[i] - fs->kink0[i]));
    return e;
}

static double rel_change(double m, double m0)
{
    return m0 != 0.0 ? fabs(m - m0) / fabs(m0) : fabs(m - m0);
}

double bf_filmsys_mass_drift(const bf_filmsys *fs)
{
    double md, mc;
    bf_film_totals(fs->film, &md, &mc);
    return fmax(fs->drift,
                fmax(rel_change(md, fs->m0[0]), rel_change(mc, fs->m0[1])));
}

enum { ON_KINK = 1u << 0 };
#define PROFILE(m, path_, unit_, doc_)                                         \
    {.path = path_, .unit = unit_, .doc = doc_, .kind = BF_SK_SNAPSHOT,        \
     .role = BF_SR_FIELD, .per = "node", .slot = BF_SLOT(bf_filmsys, m)}
static const bf_series_spec film_series[] = {
    {.path = FILM_X, .unit = "cm", .kind = BF_SK_STATIC, .role = BF_SR_GRID,
     .per = "node", .doc = "node positions x_i = -L/2 + i dx"},
    {.path = BF_DS_FILM_TIME, .unit = "s", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_TIME, .doc = "time of each profile row",
     .slot = BF_SLOT(bf_filmsys, s_time)},
    PROFILE(s_h, FILM_H, "cm", "film height h on the nodes"),
    PROFILE(s_psi, FILM_PSI, "1", "order parameter alpha_d - alpha_c"),
    PROFILE(s_ud, FILM_UD, "cm/s", "velocity of phase d"),
    PROFILE(s_uc, FILM_UC, "cm/s", "velocity of phase c"),
    {.path = "/film/mass_d", .unit = "cm^2",
     .doc = "integral of alpha_d h dx (trapezoid), at every output row",
     .slot = BF_SLOT(bf_filmsys, s_md)},
    {.path = "/film/mass_c", .unit = "cm^2",
     .doc = "integral of alpha_c h dx (trapezoid), at every output row",
     .slot = BF_SLOT(bf_filmsys, s_mc)},
    {.path = "/film/max_u", .unit = "cm/s",
     .doc = "max |u_d|, |u_c| over nodes", .slot = BF_SLOT(bf_filmsys, s_umax)},
    {.path = "/film/min_alpha", .unit = "1",
     .doc = "smallest volume fraction of either phase over the nodes",
     .slot = BF_SLOT(bf_filmsys, s_amin)},
    {.path = "/film/limited_faces", .unit = "1", .is_int = 1,
     .doc = "cumulative number of face fluxes changed by the positivity "
            "limiter",
     .slot = BF_SLOT(bf_filmsys, s_lim)},
    {.path = "/film/kink_error", .unit = "1", .when = ON_KINK,
     .doc = "max |psi - tanh((x - x0)/(sqrt(2) xi))| over nodes",
     .slot = BF_SLOT(bf_filmsys, s_kerr)},
};
#undef PROFILE

const bf_series_table bf_filmsys_series = {"film", film_series,
                                           BF_NSERIES(film_series)};

bf_status bf_filmsys_output_open(bf_filmsys *fs, bf_out *out, bf_err *err)
{
    const bf_series_extent ext[] = {{"node", fs->n}};
    bf_status st = bf_out_table_array(out, &film_series[0],
                                      bf_film_x(fs->film), fs->n, err);
    return st ? st
              : bf_out_open_table(out, film_series, BF_NSERIES(film_series),
                                  fs, ext, 1, fs->kink ? ON_KINK : 0, err);
}

bf_status bf_filmsys_output_row(bf_filmsys *fs, long n, double t, bf_err *err)
{
    bf_film *f = fs->film;
    double md, mc;
    bf_film_totals(f, &md, &mc);
    fs->drift = fmax(fs->drift, fmax(rel_change(md, fs->m0[0]),
                                     rel_change(mc, fs->m0[1])));
    double umax = bf_film_max_speed(f), amin = bf_film_min_alpha(f);
    unsigned long long ls, lf;
    bf_film_limiter_counts(f, &ls, &lf);
    int64_t lim = (int64_t)lf;
    if (bf_series_append(fs->s_md, &md) || bf_series_append(fs->s_mc, &mc) ||
        bf_series_append(fs->s_umax, &umax) ||
        bf_series_append(fs->s_amin, &amin) ||
        bf_series_append_i64(fs->s_lim, &lim))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (fs->kink) {
        double e = bf_filmsys_kink_error(fs);
        if (bf_series_append(fs->s_kerr, &e))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (n % fs->prof_every == 0 || n >= fs->last_step) {
        if (bf_series_append(fs->s_time, &t) ||
            bf_series_append(fs->s_h, bf_film_h(f)) ||
            bf_series_append(fs->s_psi, bf_film_psi(f)) ||
            bf_series_append(fs->s_ud, bf_film_u_d(f)) ||
            bf_series_append(fs->s_uc, bf_film_u_c(f)))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    return BF_OK;
}

void bf_filmsys_step_varies(bf_filmsys *fs) { fs->step_varies = 1; }

void bf_filmsys_report(const bf_filmsys *fs, FILE *out)
{
    bf_film *f = fs->film;
    double md, mc;
    bf_film_totals(f, &md, &mc);
    char why[256];
    double lim = bf_film_stable_dt(f, why, sizeof why);
    unsigned long long ls, lf;
    bf_film_limiter_counts(f, &ls, &lf);
    fprintf(out, "film: %zu nodes; phase totals d %.15g, c %.15g cm^2 "
                 "(relative change %.2e, %.2e)\n",
            fs->n, md, mc, rel_change(md, fs->m0[0]),
            rel_change(mc, fs->m0[1]));
    fprintf(out, "film: max |u| %.3e cm/s, min volume fraction %.3e, "
                 "positivity limiter acted in %llu steps (%llu faces)\n",
            bf_film_max_speed(f), bf_film_min_alpha(f), ls, lf);
    if (fs->ark) {
        char d[256];
        int q;
        bf_counters c;
        bf_filmsys_describe(fs, d, sizeof d, &q);
        bf_filmsys_counters(fs, &c);
        fprintf(out, "film: %s: %llu steps, %llu right-hand-side "
                     "evaluations, %llu rejected, %llu Newton iterations\n",
                d, c.steps, c.evals, c.rejected, c.iterations);
    } else if (fs->film_dt > 0 && fs->step_varies)
        fprintf(out, "film: stable dt now %.4g s (film steps chosen as the "
                     "run goes: the multirate line)\n", lim);
    else if (fs->film_dt > 0)
        fprintf(out, "film: stable dt now %.4g s (film step %g s)\n", lim,
                fs->film_dt);
    else if (fs->step_varies)
        fprintf(out, "film: integrated with the balls as one system (the "
                     "scheme lines)\n");
    else
        fprintf(out, "film: static (never stepped)\n");
    if (fs->kink)
        fprintf(out, "film: kink error max|psi - kink| = %.6e\n",
                bf_filmsys_kink_error(fs));
}

/* Checkpoint: the film's arrays (film_state.c) and the totals at t = 0 and
 * the drift seen, all under prefix + "film" (entries film.ah_d, ...,
 * film.m0, film.drift). */
static const bf_field filmsys_fields[] = {
    BF_FIELD_ARRAY(bf_filmsys, m0, BF_F_DOUBLE, "cm^2"),
    BF_FIELD(bf_filmsys, drift, BF_F_DOUBLE, "1"),
};

/* The ARKODE schemes' own state in checkpoints: the next initial step,
 * the counters and the film's time (nothing for the invariant scheme,
 * whose checkpoints stay as they were). */
static bf_status ark_save(const bf_filmsys *fs, bf_ckpt *ck,
                          const char *name, bf_err *err)
{
    char t[128];
    snprintf(t, sizeof t, "%s.arkode_t", name);
    bf_status st = bf_ark1_save(fs->ark, ck, name, err);
    return st ? st : bf_ckpt_put_real(ck, t, fs->t_film, err);
}

static bf_status ark_load(bf_filmsys *fs, const bf_ckpt *ck,
                          const char *name, bf_err *err)
{
    char t[128];
    snprintf(t, sizeof t, "%s.arkode_t", name);
    bf_status st = bf_ark1_load(fs->ark, ck, name, err);
    return st ? st : bf_ckpt_get_real(ck, t, &fs->t_film, err);
}

bf_status bf_filmsys_save(const bf_filmsys *fs, bf_ckpt *ck,
                          const char *prefix, bf_err *err)
{
    char name[96];
    snprintf(name, sizeof name, "%sfilm", prefix);
    bf_status st = bf_film_save(fs->film, ck, name, err);
    if (!st)
        st = bf_ckpt_put_fields(ck, name, filmsys_fields,
                                BF_NFIELDS(filmsys_fields), fs, err);
    return st || !fs->ark ? st : ark_save(fs, ck, name, err);
}

bf_status bf_filmsys_load(bf_filmsys *fs, const bf_ckpt *ck,
                          const char *prefix, bf_err *err)
{
    char name[96];
    snprintf(name, sizeof name, "%sfilm", prefix);
    bf_status st = bf_film_load(fs->film, ck, name, err);
    if (!st)
        st = bf_ckpt_get_fields(ck, name, filmsys_fields,
                                BF_NFIELDS(filmsys_fields), fs, err);
    return st || !fs->ark ? st : ark_load(fs, ck, name, err);
}
