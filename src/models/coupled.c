/* coupled.c: the "coupled" model: balls in the two-phase film (Yasuda
 * sec. 3.4-3.5, Figs 6, 8, 9).
 *
 * The balls are a ball system (ballsys.h) whose effects include
 * "coupling" (coupling.h: -M dF/dr, eqs 3.10-3.12) and "contact" (Hertz,
 * eqs 3.13-3.14); the film is a film system (filmsys.h).
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
 * K = 1 is the paper's single-rate scheme, bit for bit.
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
 * Events are located inside the step: the time by linear interpolation of
 * the velocity's zero, the state there by the cubic Hermite interpolant of
 * the step's end states (and linear for v).
 *
 * Forced mirror symmetry (symmetrize = yes, a test of the README's
 * explanation of Figs 8-9, not part of the paper's scheme).  The set-up
 * is symmetric under x -> -x, psi -> -psi: ball i <-> ball n+1-i with
 * x -> -x, v -> -v, and the film map of bf_film_mirror (A_d(i) <->
 * A_c(N-i), u_d(i) <-> -u_c(N-i)).  The equations map this subspace
 * into itself; only round-off leaves it.  After each step the state is
 * projected back: x_i <- (x_i - x_(n+1-i))/2, x_(n+1-i) <- -x_i, v alike
 * (a middle ball, n odd, gets x = v = 0), and the film by bf_film_mirror
 * after each film step, before the coupling reads it.  The set-up must be
 * symmetric to start with (checked at creation, naming the key), else the
 * projection would change the problem.  The largest relative change the
 * projection makes is stored:
 *   /coupled/sym_correction [rows x 4]  since the previous row: film
 *                           alpha_k h (rel. to max h), film u (rel. to
 *                           max |u_k|), ball x (rel. to max |x|), ball v
 *                           (rel. to max |v|)
 *   /coupled/sym_correction_max [4]     the same over the whole run
 *
 * Largest Lyapunov exponent ([lyapunov] enabled = yes, src/diag/lyapsum.h).  The
 * model keeps a shadow coupled system: a second instance of this model
 * built from the same scene (its own film, balls, coupling and
 * integrator, the same film_every and symmetrize), whose balls start
 * displaced by d0 in the scaled ball phase space (x, tau v) as in the balls
 * model, and whose film starts identical.  With symmetrize = yes the
 * displacement is the mirror-odd one (+ on ball i, - on ball n+1-i, 0 on a
 * middle ball, scaled to length d0): the equal-component direction would be
 * projected away.  The shadow takes the same steps right after the run.
 * Every renormalise_every the distance d is measured on the balls only,
 * and if d > d0 the WHOLE difference is pulled back,
 *   shadow = run + (d0/d) (shadow - run),
 * for every component of the state: ball x and v, the film's alpha_k h,
 * u_k and the rounding carries of alpha_k h (bf_film_state), and mu_cpl,
 * which in multirate holds the balls of the start of the film step until
 * the film takes it.  Caches that are functions of this state (the
 * coupling's g and anchors, the integrator's force) are rebuilt: refresh,
 * prepare, epoch++.  Why a ball norm suffices: the separation vector
 * delta(t) of the full system (balls and film) grows like exp(lambda t)
 * along the most unstable direction, and in a finite dimension all norms
 * are equivalent, c |delta| <= |delta|_balls <= C |delta|, so
 * (1/t) log |delta(t)|_balls has the same limit as with any other norm, as
 * long as the pull-back keeps delta's direction, i.e. scales the full
 * vector; pulling back only the balls would change the direction each time
 * and measure something else.  (Caveat: the equivalence needs a norm of
 * the whole vector; the ball norm is only a semi-norm.  It still gives the
 * largest exponent unless the most unstable direction never reaches the
 * balls, i.e. a film mode the balls do not feel; the estimate is then the
 * largest exponent the balls feel, which is what the survey asks.)
 * Physical film: the factor d0/d is < 1, so each alpha_k h of the shadow
 * becomes the convex combination (1 - f) A_run + f A_shadow of two
 * non-negative values: non-negative (also in floating point: |fl(s - r)|
 * <= r for 0 <= s < r, and f <= 1), so h = A_d + A_c > 0 and alpha_k in
 * [0, 1].  A separation that has shrunk (d <= d0) is left alone (no
 * factor > 1, which could push a small alpha below 0), and the sum
 * accounts for it (lyapsum.h); one that has shrunk below
 * BF_LYAP_RESEED_BELOW d0 is re-seeded (factor 0: the film becomes the
 * run's exactly, the balls are displaced again) before the two merge.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "models/ballsys.h"
#include "ballfilm/coupled.h"
#include "diag/lyapsum.h"
#include "ballfilm/model.h"
#include "coupling/coupling.h"
#include "coupling/force.h"
#include "coupling/mu_cpl.h"
#include "models/filmsys.h"

enum { NSYM = 4 };
static const double sym_levels[NSYM] = {1e-12, 1e-9, 1e-6, 1e-3};

/* The keys of [coupled]. */
typedef struct coupled_keys {
    int film;        /* 0 dynamic, 1 static */
    long film_every; /* steps */
    double probe;    /* cm */
    long map_ball, map_pivot, peak_ball; /* 1-based; 0: the default */
    int symmetrize, timing;
} coupled_keys;

static const bf_param coupled_params[] = {
    {"film", BF_AT(coupled_keys, film, BF_ENUM), "", "dynamic",
     "dynamic: the film is solved and feels the balls (sec. 3.5); static: "
     "the balls move in the potential of the initial film (sec. 3.4)",
     0, 0, 0, "dynamic|static"},
    {"film_every", BF_AT(coupled_keys, film_every, BF_INT), "steps", "1",
     "multirate: the film takes one step of film_every x dt every "
     "film_every ball steps (1: the paper's single rate)",
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
    {"timing", BF_AT(coupled_keys, timing, BF_BOOL), "", "false",
     "measure the wall time of balls, film and coupling separately (bench)",
     BF_HIDDEN, 0, 0, NULL},
    {0},
};

static const bf_section_spec coupled_spec =
    BF_SECTION("coupled", "balls coupled to the film (Yasuda sec. 3.4-3.5)",
               coupled_params, coupled_keys);

typedef struct coupled_model {
    bf_filmsys *fs;
    /* [lyapunov]: the running sum and the shadow system (NULL: off) */
    bf_lyap_sum *ly;
    struct coupled_model *shadow;
    bf_ballsys *sys;
    bf_coupling *cpl;
    int dynamic, timing, sym;
    long every;
    size_t nb, map_ball, map_pivot, peak_ball;
    double probe;
    double *mucpl;          /* mu_cpl (3.11) handed to the film step */
    double *x0, *v0;        /* ball state at the start of the step */
    double sym_t[NSYM];     /* first time the ball symmetry error exceeded */
    double cpu[3];          /* wall s: balls, film, coupling (timing) */
    /* symmetrize: largest relative corrections (film A, film u, ball x,
     * ball v) since the last row [0..3] and over the run [4..7] */
    double symc[8];
    long nmap, npeak;
    bf_series *pos, *vel, *probe_s, *symb, *symf, *map, *peaks, *symc_s;
} coupled_model;

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void coupled_destroy(void *self)
{
    coupled_model *m = self;
    if (!m)
        return;
    coupled_destroy(m->shadow);
    free(m->ly);
    bf_ballsys_free(m->sys);
    bf_coupling_free(m->cpl);
    bf_filmsys_free(m->fs);
    free(m->mucpl);
    free(m->x0);
    free(m->v0);
    free(m);
}

/* ------------------------------------------------------------ symmetry */

/* Relative tolerance of the symmetry check of the set-up: the projection
 * may remove round-off of the input (a file, a computed position), not a
 * real asymmetry. */
static const double sym_tol = 1e-12;

static int differ(double a, double b)
{
    return fabs(a - b) > sym_tol * fmax(fabs(a), fabs(b));
}

/* Refuse symmetrize = yes unless the set-up is mirror symmetric (see the
 * file comment), naming the key that breaks it. */
static bf_status check_symmetric(const coupled_model *m,
                                 const bf_film_keys *fk, bf_err *err)
{
    const bf_ballsys *s = m->sys;
    for (size_t k = 0; k < s->neff; k++)
        if (!(s->eff[k].type->flags & BF_EFFECT_MIRROR_ODD))
            return bf_fail_key(err, BF_EINPUT, "scene", "effects",
                               "[coupled] symmetrize = yes: effect '%s' is "
                               "not known to be mirror symmetric (only "
                               "coupling and contact are)",
                               s->eff[k].type->name);
    if (bf_coupling_params_of(m->cpl)->psi_s != 0)
        return bf_fail_key(err, BF_EINPUT, "coupling", "psi_s",
                           "[coupled] symmetrize = yes needs psi_s = 0 "
                           "(psi -> -psi maps psi_s to -psi_s)");
    const bf_film *f = bf_filmsys_film(m->fs);
    const bf_film_params *fp = bf_film_params_of(f);
    if (fp->rho_d != fp->rho_c)
        return bf_fail_key(err, BF_EINPUT, "film", "rho_c",
                           "[coupled] symmetrize = yes needs rho_d = rho_c "
                           "(the mirror image exchanges the phases)");
    const bf_balls *b = &s->b;
    size_t n = b->n;
    for (size_t i = 0; i < (n + 1) / 2; i++) {
        size_t j = n - 1 - i;
        char sec[32];
        snprintf(sec, sizeof sec, "ball.%zu", j + 1);
        const char *key = differ(b->x[j], -b->x[i])   ? "position"
                          : differ(b->v[j], -b->v[i]) ? "velocity"
                          : differ(b->m[j], b->m[i])  ? "mass"
                          : differ(b->R[j], b->R[i])  ? "radius"
                                                      : NULL;
        if (key)
            return bf_fail_key(err, BF_EINPUT, sec, key,
                               "[coupled] symmetrize = yes: ball %zu is not "
                               "the mirror image of ball %zu (needs x_%zu "
                               "= -x_%zu, v_%zu = -v_%zu, equal masses and "
                               "radii)",
                               j + 1, i + 1, j + 1, i + 1, j + 1, i + 1);
    }
    double c[2];
    bf_film_mirror(bf_filmsys_film(m->fs), 0, c);
    if (c[0] > sym_tol || c[1] > sym_tol) {
        double x0;
        const char *key = fk->perturbation > 0
                              ? "perturbation"
                          : bf_filmsys_has_kink(m->fs, &x0) && x0 != 0
                              ? "center"
                              : "initial";
        return bf_fail_key(err, BF_EINPUT, "film", key,
                           "[coupled] symmetrize = yes: the initial film is "
                           "not mirror symmetric (psi odd, h even, u odd "
                           "needed): relative distance %.3g in alpha h, "
                           "%.3g in u",
                           c[0], c[1]);
    }
    return BF_OK;
}

/* Project n positions (or velocities) onto the odd states, a_(n-1-i) =
 * -a_i; returns the largest change relative to max |a| (0 if all vanish). */
static double mirror_odd(double *a, size_t n)
{
    double d = 0, amax = 0;
    for (size_t i = 0; i < n; i++)
        amax = fmax(amax, fabs(a[i]));
    for (size_t i = 0; i < (n + 1) / 2; i++) {
        size_t j = n - 1 - i;
        double o = 0.5 * (a[i] - a[j]);
        d = fmax(d, 0.5 * fabs(a[i] + a[j]));
        a[i] = o;
        a[j] = -o;
    }
    return amax > 0 ? d / amax : d;
}

static void keep_max(double *acc, const double *c, int k)
{
    for (int q = 0; q < k; q++) {
        acc[q] = fmax(acc[q], c[q]);
        acc[q + 4] = fmax(acc[q + 4], c[q]);
    }
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

/* The shadow's caches after its state was changed from outside: g and the
 * anchors of the coupling, the integrator's force (epoch). */
static void state_changed(coupled_model *m)
{
    bf_coupling_refresh(m->cpl);
    if (m->dynamic)
        bf_coupling_prepare(m->cpl, m->nb, m->sys->b.x);
    m->sys->ode.epoch++;
}

/* The shadow's balls = the run's + the initial displacement of length d0
 * (mirror-odd with symmetrize; file comment).  Its film is not touched. */
static void displace_shadow_balls(coupled_model *m)
{
    coupled_model *sh = m->shadow;
    const double *x = m->sys->b.x, *v = m->sys->b.v;
    double *xs = sh->sys->b.x, *vs = sh->sys->b.v;
    bf_lyap_displace(m->ly, x, v, xs, vs);
    if (m->sym) {
        size_t nb = m->nb, half = nb / 2;
        for (size_t i = 0; i < half; i++) {
            size_t j = nb - 1 - i;
            xs[j] = x[j] - (xs[i] - x[i]);
            vs[j] = v[j] - (vs[i] - v[i]);
        }
        if (nb % 2) {
            xs[half] = x[half];
            vs[half] = v[half];
            double back = sqrt((double)nb / (double)(2 * half));
            bf_lyap_pull(nb, back, x, xs);
            bf_lyap_pull(nb, back, v, vs);
        }
    }
}

/* [lyapunov]: the running sum and the shadow, its balls displaced (see the
 * file comment). */
static bf_status shadow_create(coupled_model *m, const bf_model_setup *setup,
                               bf_err *err)
{
    m->ly = malloc(sizeof *m->ly);
    if (!m->ly)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    const bf_integrator_type *t = m->sys->it->type;
    bf_status st = bf_lyap_sum_init(
        m->ly, bf_setup_get(setup, &bf_lyap_spec, NULL), setup->run.dt, m->nb,
        t->flags & BF_INT_ADAPTIVE ? t->name : NULL, err);
    if (!st)
        st = coupled_build(&m->shadow, setup, 0, err);
    if (st)
        return st;
    displace_shadow_balls(m);
    state_changed(m->shadow);
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
    const coupled_keys *k = bf_setup_get(setup, &coupled_spec, NULL);
    const bf_film_keys *fk = bf_setup_get(setup, &bf_filmsys_spec, NULL);
    coupled_model *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->dynamic = k->film == 0;
    m->every = k->film_every;
    m->timing = k->timing;
    m->sym = k->symmetrize;
    m->probe = k->probe;
    bf_status st = bf_filmsys_create(&m->fs, fk, &setup->run,
                                     m->dynamic ? m->every : 0, err);
    if (st) {
        free(m);
        return st;
    }
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
    bf_effect_env env = {.coupling = m->cpl};
    if ((st = bf_ballsys_create(&m->sys, setup, &env, err))) {
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
    if (m->sym && (st = check_symmetric(m, fk, err))) {
        coupled_destroy(m);
        return st;
    }
    if (m->dynamic)
        bf_coupling_prepare(m->cpl, m->nb, m->sys->b.x);
    m->x0 = calloc(m->nb, sizeof(double));
    m->v0 = calloc(m->nb, sizeof(double));
    /* 64-byte aligned, as the film's arrays (its vector loops read it) */
    size_t bytes = (nn * sizeof(double) + 63) & ~(size_t)63;
    m->mucpl = aligned_alloc(64, bytes);
    if (m->mucpl)
        memset(m->mucpl, 0, bytes);
    if (!m->x0 || !m->v0 || !m->mucpl) {
        coupled_destroy(m);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (int k = 0; k < NSYM; k++)
        m->sym_t[k] = NAN;
    const bf_lyap_keys *lk = bf_setup_get(setup, &bf_lyap_spec, NULL);
    if (with_shadow && lk->enabled &&
        (st = shadow_create(m, setup, err))) {
        coupled_destroy(m);
        return st;
    }
    *self = m;
    return BF_OK;
}

/* ------------------------------------------------------------ events */

/* the cubic Hermite interpolant of (x0, v0) -> (x1, v1) over dt at s */
static double hermite(double x0, double v0, double x1, double v1, double dt,
                      double s)
{
    double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    return h00 * x0 + h10 * dt * v0 + h01 * x1 + h11 * dt * v1;
}

static double symmetry_error(const double *x, size_t n)
{
    double e = 0;
    for (size_t i = 0; i < n / 2; i++)
        e = fmax(e, fabs(x[i] + x[n - 1 - i]));
    return e;
}

static bf_status events(coupled_model *m, double t, double dt, bf_err *err)
{
    const bf_balls *b = &m->sys->b;
    const double *x1 = b->x, *v1 = b->v, *x0 = m->x0, *v0 = m->v0;
    /* peaks: the velocity of peak_ball turns from > 0 to <= 0 */
    size_t q = m->peak_ball;
    if (v0[q] > 0 && v1[q] <= 0) {
        double s = v0[q] / (v0[q] - v1[q]);
        double row[2] = {t + s * dt, hermite(x0[q], v0[q], x1[q], v1[q], dt, s)};
        if (m->peaks && bf_series_append(m->peaks, row))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        m->npeak++;
    }
    /* return map: the pivot's distance from the origin has a minimum
     * while it touches its inner neighbour */
    size_t p = m->map_pivot;
    double sg = x1[p] >= 0 ? 1.0 : -1.0;
    double s0 = sg * v0[p], s1 = sg * v1[p];
    if (s0 < 0 && s1 >= 0) {
        /* the neighbour towards the origin */
        long in = sg > 0 ? (long)p - 1 : (long)p + 1;
        if (in >= 0 && in < (long)m->nb) {
            double rs = b->R[p] + b->R[in];
            int touch = fabs(x0[p] - x0[in]) < rs || fabs(x1[p] - x1[in]) < rs;
            if (touch) {
                double s = s0 / (s0 - s1);
                size_t r = m->map_ball;
                double row[3] = {t + s * dt,
                                 hermite(x0[r], v0[r], x1[r], v1[r], dt, s),
                                 v0[r] + s * (v1[r] - v0[r])};
                if (m->map && bf_series_append(m->map, row))
                    return bf_fail(err, BF_EINTERNAL, "out of memory");
                m->nmap++;
            }
        }
    }
    double se = symmetry_error(x1, m->nb);
    for (int k = 0; k < NSYM; k++)
        if (isnan(m->sym_t[k]) && se > sym_levels[k])
            m->sym_t[k] = t + dt;
    return BF_OK;
}

/* ------------------------------------------------------------ step */

static bf_status coupled_step(void *self, long n, double t, double dt,
                              bf_err *err);

/* shadow = run + factor (shadow - run) for the whole state (file
 * comment); factor 0 re-seeds: the shadow becomes the run, its balls
 * displaced again as at the start. */
static void pull_shadow(coupled_model *m, double factor)
{
    coupled_model *sh = m->shadow;
    const size_t nb = m->nb;
    bf_lyap_pull(nb, factor, m->sys->b.x, sh->sys->b.x);
    bf_lyap_pull(nb, factor, m->sys->b.v, sh->sys->b.v);
    bf_film *f = bf_filmsys_film(m->fs), *fsh = bf_filmsys_film(sh->fs);
    double *run[BF_FILM_NSTATE], *shadow[BF_FILM_NSTATE];
    size_t nodes = bf_film_state(f, run);
    bf_film_state(fsh, shadow);
    for (int k = 0; k < BF_FILM_NSTATE; k++)
        bf_lyap_pull(nodes, factor, run[k], shadow[k]);
    bf_film_state_changed(fsh);
    if (m->dynamic)
        bf_lyap_pull(nodes, factor, m->mucpl, sh->mucpl);
    if (factor == 0.0)
        displace_shadow_balls(m);
    state_changed(sh);
}

/* The shadow's step t -> t + dt (the run has just taken it; n_done = n +
 * 1 steps are done) and, when due, the renormalisation. */
static bf_status shadow_step(coupled_model *m, long n, double t, double dt,
                             bf_err *err)
{
    coupled_model *sh = m->shadow;
    bf_status st = coupled_step(sh, n, t, dt, err);
    if (st) {
        bf_err_prefix(err, "Lyapunov shadow system");
        return st;
    }
    if (!bf_lyap_due(m->ly, n + 1))
        return BF_OK;
    double factor;
    st = bf_lyap_measure(m->ly, m->sys->b.x, m->sys->b.v, sh->sys->b.x,
                         sh->sys->b.v, t + dt, &factor, err);
    if (!st && factor != 1.0)
        pull_shadow(m, factor);
    return st;
}

static bf_status coupled_step(void *self, long n, double t, double dt,
                              bf_err *err)
{
    coupled_model *m = self;
    bf_ballsys *s = m->sys;
    double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
    memcpy(m->x0, s->b.x, m->nb * sizeof(double));
    memcpy(m->v0, s->b.v, m->nb * sizeof(double));
    if (m->timing)
        c0 = wall_now();
    /* mu_cpl from the balls at level n (at the start of a film step) */
    if (m->dynamic && n % m->every == 0)
        bf_coupling_mu(m->cpl, m->nb, s->b.x, s->b.R, m->mucpl);
    if (m->timing)
        c1 = wall_now();
    /* the balls in the film frozen at its last level */
    bf_status st = bf_ballsys_step(s, t, dt, err);
    if (st)
        return st;
    if (m->sym) {
        /* before the coupling's prepare reads the positions */
        double c[2] = {mirror_odd(s->b.x, m->nb), mirror_odd(s->b.v, m->nb)};
        keep_max(m->symc + 2, c, 2);
    }
    if (m->timing)
        c2 = wall_now();
    if (m->dynamic && (n + 1) % m->every == 0) {
        if ((st = bf_filmsys_step(m->fs, (double)m->every * dt, m->mucpl,
                                   err)))
            return st;
        if (m->sym) {
            /* before the coupling's refresh reads the film */
            double c[2];
            bf_film_mirror(bf_filmsys_film(m->fs), 1, c);
            keep_max(m->symc, c, 2);
        }
        if (m->timing)
            c3 = wall_now();
        bf_coupling_refresh(m->cpl);
        bf_coupling_prepare(m->cpl, m->nb, s->b.x);
        s->ode.epoch++;
    } else if (m->timing) {
        c3 = c2;
    }
    if (m->timing) {
        double c4 = wall_now();
        m->cpu[0] += c2 - c1;
        m->cpu[1] += c3 - c2;
        m->cpu[2] += (c1 - c0) + (c4 - c3);
    }
    st = events(m, t, dt, err);
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

static bf_status coupled_output_open(void *self, bf_out *out, bf_err *err)
{
    coupled_model *m = self;
    bf_status st = bf_filmsys_output_open(m->fs, out, err);
    if (st)
        return st;
#define SER(var, path, cols, unit, doc)                                        \
    do {                                                                       \
        m->var = bf_out_series(out, path, cols, 0, unit, doc, err);           \
        if (!m->var)                                                           \
            return err->status;                                                \
    } while (0)
    SER(pos, "/balls/position", m->nb, "cm",
        "ball centre positions, one column per ball");
    SER(vel, "/balls/velocity", m->nb, "cm/s",
        "ball velocities, one column per ball");
    SER(probe_s, "/coupled/psi_probe", 0, "1",
        "psi at [coupled] probe, linear between nodes");
    SER(symb, "/coupled/sym_balls", 0, "cm",
        "left/right symmetry error of the balls max_i |x_i + x_(n+1-i)|");
    SER(symf, "/coupled/sym_film", 0, "1",
        "left/right symmetry error of the film max_i |psi_i + psi_(N-i)|");
    SER(map, "/coupled/return_map", 3, "s, cm, cm/s",
        "t, x, v of map_ball when map_pivot is closest to the origin while "
        "touching its inner neighbour (Fig. 8A)");
    SER(peaks, "/coupled/peaks", 2, "s, cm",
        "t, x of the maxima of peak_ball's position (Fig. 6C)");
    if (m->sym)
        SER(symc_s, "/coupled/sym_correction", 4, "1",
            "symmetrize: largest relative change of the projection since the "
            "previous row: film alpha_k h (/ max h), film u (/ max |u_k|), "
            "ball x (/ max |x|), ball v (/ max |v|)");
#undef SER
    if (m->ly && (st = bf_lyap_sum_output_open(m->ly, out, err)))
        return st;
    const bf_balls *b = &m->sys->b;
    if ((st = bf_out_array(out, "/balls/mass", b->m, b->n, 0, "g",
                           "ball masses", err)))
        return st;
    return bf_out_array(out, "/balls/radius", b->R, b->n, 0, "cm",
                        "ball radii", err);
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
    double pr = probe_psi(m), sb = symmetry_error(m->sys->b.x, m->nb);
    if (bf_series_append(m->pos, m->sys->b.x) ||
        bf_series_append(m->vel, m->sys->b.v) ||
        bf_series_append(m->probe_s, &pr) || bf_series_append(m->symb, &sb) ||
        bf_series_append(m->symf, &sf) ||
        (m->sym && bf_series_append(m->symc_s, m->symc)))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    for (int q = 0; q < 4; q++)
        m->symc[q] = 0;
    return BF_OK;
}

static bf_status coupled_output_close(void *self, bf_out *out, bf_err *err)
{
    coupled_model *m = self;
    double rows[NSYM * 2];
    for (int k = 0; k < NSYM; k++) {
        rows[2 * k] = sym_levels[k];
        rows[2 * k + 1] = m->sym_t[k];
    }
    bf_status st = bf_out_array(out, "/coupled/symmetry_break", rows, NSYM, 2,
                                "cm, s",
                                "first time the ball symmetry error exceeded "
                                "each level (NaN: never)",
                                err);
    if (!st && m->sym)
        st = bf_out_array(out, "/coupled/sym_correction_max", m->symc + 4, 4,
                          0, "1",
                          "symmetrize: largest relative change of the "
                          "projection over the run (columns as "
                          "/coupled/sym_correction)",
                          err);
    if (!st && m->ly)
        st = bf_lyap_sum_output_close(m->ly, out, err);
    return st;
}

static void coupled_counters(const void *self, bf_counters *c)
{
    const coupled_model *m = self;
    *c = m->sys->it->count;
}

static void coupled_report(const void *self, FILE *f)
{
    const coupled_model *m = self;
    bf_filmsys_report(m->fs, f);
    unsigned long long ex, ta;
    bf_coupling_counts(m->cpl, &ex, &ta);
    fprintf(f, "coupling: %llu exact and %llu Taylor evaluations of F; "
               "%ld return-map points, %ld peaks\n",
            ex, ta, m->nmap, m->npeak);
    fprintf(f, "symmetry: ball error first above");
    for (int k = 0; k < NSYM; k++)
        fprintf(f, " %g cm at t = %.4g s%s", sym_levels[k], m->sym_t[k],
                k + 1 < NSYM ? "," : "\n");
    if (m->sym)
        fprintf(f, "symmetrize: largest relative change of one projection: "
                   "film alpha h %.3g, film u %.3g, ball x %.3g, ball v "
                   "%.3g\n",
                m->symc[4], m->symc[5], m->symc[6], m->symc[7]);
    if (m->timing)
        fprintf(f, "time: balls %.3f s, film %.3f s, coupling (mu_cpl, "
                   "refresh) %.3f s\n",
                m->cpu[0], m->cpu[1], m->cpu[2]);
    if (m->ly)
        bf_lyap_sum_report(m->ly, m->shadow->sys->it->count.evals, f);
}

/* ------------------------------------------------------------ checkpoint */

/* prefix + name, for the run (prefix "") and its shadow ("lyapunov.") */
static const char *pname(char *buf, size_t cap, const char *prefix,
                         const char *name)
{
    snprintf(buf, cap, "%s%s", prefix, name);
    return buf;
}

static bf_status save_state(const coupled_model *m, bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char nm[128];
    const size_t cap = sizeof nm;
    bf_status st = bf_filmsys_save(m->fs, ck, prefix, err);
    if (!st)
        st = bf_ballsys_save(m->sys, ck, pname(nm, cap, prefix, "balls"), err);
    int64_t meta[3] = {(int64_t)m->sys->ode.epoch, m->nmap, m->npeak};
    if (!st)
        st = bf_ckpt_put_i64(ck, pname(nm, cap, prefix, "coupled.meta"), meta,
                             3, err);
    if (!st)
        st = bf_ckpt_put(ck, pname(nm, cap, prefix, "coupled.sym_t"), m->sym_t,
                         NSYM, err);
    if (!st)
        st = bf_ckpt_put(ck, pname(nm, cap, prefix, "coupled.mucpl"), m->mucpl,
                         bf_film_nodes(bf_filmsys_film(m->fs)), err);
    if (!st)
        st = bf_coupling_save(m->cpl, ck, prefix, err);
    if (!st && m->sym)
        st = bf_ckpt_put(ck, pname(nm, cap, prefix, "coupled.sym_correction"),
                         m->symc, 8, err);
    return st;
}

static bf_status load_state(coupled_model *m, const bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char nm[128];
    const size_t cap = sizeof nm;
    int64_t meta[3];
    bf_status st = bf_filmsys_load(m->fs, ck, prefix, err);
    if (!st)
        st = bf_ballsys_load(m->sys, ck, pname(nm, cap, prefix, "balls"), err);
    if (!st)
        st = bf_ckpt_get_i64(ck, pname(nm, cap, prefix, "coupled.meta"), meta,
                             3, err);
    if (!st)
        st = bf_ckpt_get(ck, pname(nm, cap, prefix, "coupled.sym_t"), m->sym_t,
                         NSYM, err);
    if (!st)
        st = bf_ckpt_get(ck, pname(nm, cap, prefix, "coupled.mucpl"), m->mucpl,
                         bf_film_nodes(bf_filmsys_film(m->fs)), err);
    if (!st) /* after the film */
        st = bf_coupling_load(m->cpl, ck, prefix, err);
    if (!st && m->sym)
        st = bf_ckpt_get(ck, pname(nm, cap, prefix, "coupled.sym_correction"),
                         m->symc, 8, err);
    if (!st) {
        m->sys->ode.epoch = (unsigned long)meta[0];
        m->nmap = (long)meta[1];
        m->npeak = (long)meta[2];
    }
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
    &coupled_spec, &bf_filmsys_spec, &bf_ballsys_ball_spec, &bf_lyap_spec,
    NULL};

const bf_model_type bf_model_coupled = {
    .name = "coupled",
    .doc = "balls coupled to the two-phase film, static kink or dynamic "
           "film (Yasuda sec. 3.4-3.5)",
    .flags = BF_MODEL_INTEGRATOR | BF_MODEL_EFFECTS,
    .specs = coupled_specs,
    .create = coupled_create,
    .destroy = coupled_destroy,
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
};

/* ------------------------------------------------------------ drivers */

/* The return map is /coupled/return_map (no multi-minimum count, the
 * points are not kept in memory). */
static void coupled_results(const void *self, bf_results *r)
{
    const coupled_model *m = self;
    r->has_return_map = 1;
    r->map_points = (size_t)m->nmap;
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
