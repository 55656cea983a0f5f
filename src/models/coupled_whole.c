/* coupled_whole.c: [coupled] scheme = arkode | mri, ARKODE on the whole
 * coupled system (coupled_impl.h; beyond the paper).
 *
 * The paper's scheme (scheme = split) advances the balls in the film
 * frozen at its level n and then the film with mu_cpl of the balls at
 * level n: a coupling error of first order in dt on top of the film
 * scheme's own first-order time error.  Here balls and film are one ODE
 *
 *   y = (x_1..x_nb, v_1..v_nb, film in method-of-lines form, film_mol.h)
 *   dx_p/dt = v_p
 *   dv_p/dt = -M dF_p/dr_p + contact and other effects       (3.12)
 *   dy_film/dt = f_MOL(y_film; mu_cpl(x, psi))       (3.15)-(3.16), (3.11)
 *
 * with every term at the same time: the balls feel the film of the stage
 * and the film the balls of the stage.  This is the limit dt -> 0 of the
 * split scheme on the same grid (the film's invariant scheme tends to
 * f_MOL, film_mol.c), so at a tight tolerance it is the reference that
 * the split runs converge to, with the same space error.
 *
 *   arkode  ERKStep on all of y, adaptive, inside each [scene] dt;
 *   mri     MRIStep: the slow part is the film (its f_MOL, the balls'
 *           entries zero) at the fixed slow step [scene] dt, the fast part
 *           the balls (v and the accelerations in the film of the fast
 *           stage, the film's entries zero) by an adaptive inner ERK
 *           ([coupled] table, rtol, atol, max_step).  MRIStep moves the
 *           film inside the slow step by its slow stages, so the balls see
 *           it change smoothly: a second multirate method beside
 *           film_every.
 *
 * Each evaluation puts the film part of its y into the model's film (h and
 * psi derived) and rebuilds the coupling from it (bf_coupling_refresh),
 * unless that film is the one of the previous evaluation: O(nodes) per
 * evaluation, which is what makes this a reference and not a fast path.
 * After each [scene] dt the film's vanish rule is applied (film_mol.h) and
 * its state is checked (a non-finite value, h <= 0 or a negative phase
 * content stops the run as unstable, naming the node).  The Hertz force is
 * C^1 but not C^2 at a contact onset: arkode finds every onset and
 * release (the gaps' roots) and restarts there (bf_ark1_set_kinks), as
 * the balls' ARKODE reference does; mri does not (its inner ERK steps
 * across them, at the cost of smaller steps).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coupling/mu_cpl.h"
#include "film/film_mol.h"
#include "integrators/ark1.h"
#include "models/coupled_impl.h"

struct bf_coupled_whole {
    int scheme;
    coupled_model *m;
    bf_film_mol *mol;
    bf_ark1 *ark;
    size_t nb, nf, n;
    double *y;      /* [x, v, film] */
    double *mu;     /* mu_cpl of a stage (nodes) */
    double *synced; /* the film part last put into the film (nf) */
    double *film0;  /* the film part at the step's start (nf) */
    int have_synced;
    unsigned long long refreshes;
};

/* the model's film and coupling at the film part yf of a stage */
static void sync_film(bf_coupled_whole *w, const double *yf)
{
    if (w->have_synced && !memcmp(yf, w->synced, w->nf * sizeof *yf))
        return;
    bf_film_mol_unpack(bf_filmsys_film(w->m->fs), yf);
    bf_coupling_refresh(w->m->cpl);
    memcpy(w->synced, yf, w->nf * sizeof *yf);
    w->have_synced = 1;
    w->refreshes++;
}

/* the balls' part of a stage: 1 (retry a smaller step) if a value is not
 * finite or two balls changed places (the coupling's sums take the balls
 * in increasing order) */
static int balls_bad(const bf_coupled_whole *w, const double *y)
{
    for (size_t p = 0; p < 2 * w->nb; p++)
        if (!isfinite(y[p]))
            return 1;
    for (size_t p = 1; p < w->nb; p++)
        if (!(y[p] > y[p - 1]))
            return 1;
    return 0;
}

/* which parts an evaluation fills: balls, film, or both */
enum { PART_BALLS = 1, PART_FILM = 2 };

static int rhs_parts(bf_coupled_whole *w, double t, const double *y,
                     double *ydot, int parts)
{
    const size_t nb = w->nb;
    const double *x = y, *v = y + nb, *yf = y + 2 * nb;
    if (balls_bad(w, y))
        return 1;
    sync_film(w, yf);
    if (parts & PART_BALLS) {
        memcpy(ydot, v, nb * sizeof *v);
        int r = bf_ballsys_accel(w->m->sys, t, x, v, ydot + nb);
        if (r)
            return r;
        for (size_t p = 0; p < nb; p++)
            if (!isfinite(ydot[nb + p]))
                return 1;
    } else {
        memset(ydot, 0, 2 * nb * sizeof *ydot);
    }
    if (parts & PART_FILM) {
        bf_coupling_mu(w->m->cpl, nb, x, w->m->sys->b.R, w->mu);
        return bf_film_mol_rhs(w->mol, yf, w->mu, BF_FILM_MOL_ALL,
                               BF_FILM_MOL_WAVES, ydot + 2 * nb);
    }
    memset(ydot + 2 * nb, 0, w->nf * sizeof *ydot);
    return 0;
}

/* The contact gaps of the balls of y (bf_ballsys_gaps_fn, cm): the Hertz
 * force is C^1 but not C^2 where one crosses 0; ERKStep restarts there
 * (bf_ark1_set_kinks), so that its steps keep their order. */
static int gaps(void *ctx, double t, const double *y, double *g)
{
    const bf_coupled_whole *w = ctx;
    return bf_ballsys_gaps_fn(w->m->sys, t, y, NULL, g);
}

static int rhs_all(void *ctx, double t, const double *y, double *ydot)
{
    return rhs_parts(ctx, t, y, ydot, PART_BALLS | PART_FILM);
}

static int rhs_slow(void *ctx, double t, const double *y, double *ydot)
{
    return rhs_parts(ctx, t, y, ydot, PART_FILM);
}

static int rhs_fast(void *ctx, double t, const double *y, double *ydot)
{
    return rhs_parts(ctx, t, y, ydot, PART_BALLS);
}

bf_status bf_coupled_whole_create(coupled_model *m,
                                  const bf_coupled_whole_keys *k,
                                  const char *film_every, int film_scheme,
                                  double dt, bf_err *err)
{
    const char *name = k->scheme == BF_COUPLED_MRI ? "mri" : "arkode";
    if (!m->dynamic)
        return bf_fail_key(err, BF_EINPUT, "coupled", "scheme",
                           "scheme = %s needs film = dynamic (a static film "
                           "is not integrated: use [scene] integrator = "
                           "arkode for ARKODE on the balls)", name);
    if (m->sym)
        return bf_fail_key(err, BF_EINPUT, "coupled", "symmetrize",
                           "symmetrize works with scheme = split only");
    if (strcmp(film_every, "1"))
        return bf_fail_key(err, BF_EINPUT, "coupled", "film_every",
                           "'%s' with scheme = %s: the ARKODE schemes choose "
                           "their own steps (mri: the slow step is [scene] "
                           "dt); film_every needs scheme = split",
                           film_every, name);
    if (film_scheme != BF_FILM_SCHEME_INVARIANT)
        return bf_fail_key(err, BF_EINPUT, "film", "scheme",
                           "with [coupled] scheme = %s the film is part of "
                           "the whole system's ODE; its own scheme must stay "
                           "invariant (the default)", name);
    bf_coupled_whole *w = calloc(1, sizeof *w);
    if (!w)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->whole = w;
    w->m = m;
    w->scheme = k->scheme;
    bf_film *f = bf_filmsys_film(m->fs);
    bf_status st = bf_film_mol_create(&w->mol, f, err);
    if (st)
        return st;
    w->nb = m->nb;
    w->nf = bf_film_mol_size(w->mol);
    w->n = 2 * w->nb + w->nf;
    w->y = calloc(w->n, sizeof *w->y);
    w->mu = calloc(bf_film_nodes(f), sizeof *w->mu);
    w->synced = calloc(w->nf, sizeof *w->synced);
    w->film0 = calloc(w->nf, sizeof *w->film0);
    if (!w->y || !w->mu || !w->synced || !w->film0)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    const int mri = k->scheme == BF_COUPLED_MRI;
    bf_ark1_opts o = {
        .kind = mri ? BF_ARK1_MRI : BF_ARK1_ERK,
        .table = k->table,
        .order = (int)k->mri_order,
        .rtol = k->rtol,
        .atol = k->atol,
        .max_step = k->max_step,
        .max_steps = k->max_steps,
        .budget_dt = dt,
        .max_steps_key = "[coupled] max_steps",
        .slow_step = dt, /* mri: one slow step per [scene] dt */
        .work_around_311 = 1,
    };
    st = bf_ark1_create(&w->ark, w->n, mri ? rhs_slow : rhs_all,
                        mri ? rhs_fast : NULL, w, &o, err);
    if (st == BF_EINPUT)
        bf_err_prefix(err, "[coupled] table");
    if (st || mri || m->sys->ngaps == 0)
        return st;
    return bf_ark1_set_kinks(w->ark, m->sys->ngaps, gaps, err);
}

void bf_coupled_whole_free(bf_coupled_whole *w)
{
    if (!w)
        return;
    bf_ark1_free(w->ark);
    bf_film_mol_free(w->mol);
    free(w->y);
    free(w->mu);
    free(w->synced);
    free(w->film0);
    free(w);
}

bf_status bf_coupled_whole_step(coupled_model *m, double t, double dt,
                                bf_err *err)
{
    bf_coupled_whole *w = m->whole;
    bf_ballsys *s = m->sys;
    bf_film *f = bf_filmsys_film(m->fs);
    const size_t nb = w->nb;
    double *yf = w->y + 2 * nb;
    memcpy(w->y, s->b.x, nb * sizeof *w->y);
    memcpy(w->y + nb, s->b.v, nb * sizeof *w->y);
    bf_film_mol_pack(f, yf);
    memcpy(w->film0, yf, w->nf * sizeof *yf);
    /* A fresh coupling at every step's start: its Taylor anchors
     * (coupling.h) are then those of this step's evaluations only, as in
     * a run continued from a checkpoint, which refreshes after the load. */
    w->have_synced = 0;
    bf_status st = bf_ark1_evolve(w->ark, t, t + dt, w->y, err);
    if (!st)
        st = bf_film_mol_check(w->mol, yf, err);
    if (st) {
        /* the stages left a trial film in the model's: back to the film
         * at the step's start (the balls were not touched) */
        w->have_synced = 0;
        sync_film(w, w->film0);
        return st;
    }
    bf_film_mol_vanish(w->mol, yf);
    memcpy(s->b.x, w->y, nb * sizeof *w->y);
    memcpy(s->b.v, w->y + nb, nb * sizeof *w->y);
    sync_film(w, yf);
    /* (m->mucpl, the split scheme's mu_cpl for its next film step, is not
     * used here: each stage forms its own) */
    return BF_OK;
}

void bf_coupled_whole_counters(const bf_coupled_whole *w, bf_counters *c)
{
    bf_ark1_counters(w->ark, c);
}

void bf_coupled_whole_describe(const bf_coupled_whole *w, char *buf,
                               size_t cap, int *order)
{
    char a[200];
    bf_ark1_describe(w->ark, a, sizeof a);
    snprintf(buf, cap, "%s %s (whole system: balls + method-of-lines film)",
             w->scheme == BF_COUPLED_MRI ? "mri" : "arkode", a);
    *order = bf_ark1_order(w->ark);
}

void bf_coupled_whole_report(const bf_coupled_whole *w, FILE *f)
{
    char d[320];
    int order;
    bf_coupled_whole_describe(w, d, sizeof d, &order);
    bf_counters c;
    bf_ark1_counters(w->ark, &c);
    fprintf(f, "scheme: %s\n", d);
    fprintf(f, "scheme: %llu steps, %llu evaluations, %llu rejected, %llu "
               "%s; %llu film refreshes of the coupling, %llu restarts at "
               "contact onsets and releases\n",
            c.steps, c.evals, c.rejected, c.iterations,
            w->scheme == BF_COUPLED_MRI ? "fast steps" : "iterations",
            w->refreshes, bf_ark1_restarts(w->ark));
}

bf_status bf_coupled_whole_save(const bf_coupled_whole *w, bf_ckpt *ck,
                                const char *name, bf_err *err)
{
    char n[128];
    snprintf(n, sizeof n, "%s.whole", name);
    return bf_ark1_save(w->ark, ck, n, err);
}

bf_status bf_coupled_whole_load(bf_coupled_whole *w, const bf_ckpt *ck,
                                const char *name, bf_err *err)
{
    char n[128];
    snprintf(n, sizeof n, "%s.whole", name);
    return bf_ark1_load(w->ark, ck, n, err);
}
