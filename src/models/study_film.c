/* study_film.c: the convergence study of the two-phase film (model film):
 * methods are [film] schemes (invariant, arkode, arkode-imex) with their
 * [film] keys; compared are psi (1), h (cm) and the phase volume fluxes
 * q_k = alpha_k h u_k (cm^2/s) on the nodes; the invariants are the two
 * phase totals (integrals of alpha_k h, cm^2), which the invariant scheme
 * keeps to round-off.
 *
 * Why q_k and not u_k: where a phase is absent (alpha_k < [film] vanish,
 * 1e-8) the scheme gives it the other phase's velocity, a convention
 * switched on and off at a node by round-off-size changes of alpha_k
 * there; the kink with a density jump (runs/kink_converge.ini, rho_d =
 * 1.2, T = 1 s) had u_c differing by 0.53 cm/s between the scheme and
 * the reference at a node with alpha_c = 8e-9, at every dt.  Weighted by
 * alpha_k h, what the phase carries, that has no weight.
 *
 * The reference: the same equations on the same grid in method-of-lines
 * form (src/film/film_mol.c, the limit dt -> 0 of the invariant scheme)
 * integrated by ARKODE's adaptive ERK at a tight tolerance (VERNER_8_5_6,
 * else DORMAND_PRINCE_7_4_5, else CASH_KARP_6_4_5 when compared).  It has
 * the scheme's space error and no time error, so what converge reports
 * for the invariant scheme is its time error alone; its space error is
 * measured by runs at several dx (bench/film_orders.c, make kink-dx2).
 *
 * A start with random grid-scale noise (the kink scene's [film]
 * perturbation) has no smooth limit in dt: the noise excites modes up to
 * the grid scale, whose phase-separation frequencies ~ gamma k^2 are
 * resolved by no step above the stable limit; the errors then do not
 * shrink at the nominal order.  The notes say so and name the key. */
#include <stdio.h>
#include <string.h>

#include "models/filmsys.h"
#include "models/studies.h"

static int film_adaptive(const bf_model_setup *s)
{
    const bf_film_keys *k = bf_setup_get(s, &bf_filmsys_spec, NULL);
    return k && k->scheme != BF_FILM_SCHEME_INVARIANT;
}

double bf_study_film_dx(const bf_model_setup *s)
{
    const bf_film_keys *k = bf_setup_get(s, &bf_filmsys_spec, NULL);
    return k ? k->dx : 0.0;
}

void bf_study_film_groups(bf_filmsys *fs, bf_study_view *v)
{
    const bf_film *f = bf_filmsys_film(fs);
    static const char *const names[4] = {"psi", "h", "q_d", "q_c"};
    static const char *const units[4] = {"1", "cm", "cm^2/s", "cm^2/s"};
    const double *data[4] = {bf_film_psi(f), bf_film_h(f),
                             bf_filmsys_phase_flux(fs, 0),
                             bf_filmsys_phase_flux(fs, 1)};
    for (size_t k = 0; k < 4; k++) {
        size_t g = v->ngroups++;
        v->g[g].name = names[k];
        v->g[g].unit = units[k];
        v->g[g].a = data[k];
        /* out of memory: an empty group, which the driver refuses (the
         * state's size differs from the reference's) */
        v->g[g].n = data[k] ? bf_film_nodes(f) : 0;
    }
    v->ninv = 2;
    bf_film_totals(f, &v->inv[0], &v->inv[1]);
}

static void film_view(void *self, bf_study_view *v)
{
    memset(v, 0, sizeof *v);
    bf_study_film_groups(self, v);
}

static void film_describe(void *self, char *buf, size_t cap, int *order)
{
    bf_filmsys_describe(self, buf, cap, order);
}

static void film_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: the reference is the film's equations on the same grid "
             "(dx = %g cm) in method-of-lines form, so the errors are time "
             "errors only (the space error needs runs at several dx).\n",
             bf_study_film_dx(s));
    bf_study_perturbation_note(s, buf, cap);
}

void bf_study_perturbation_note(const bf_model_setup *s, char *buf,
                                size_t cap)
{
    const bf_film_keys *k = bf_setup_get(s, &bf_filmsys_spec, NULL);
    if (!k || !(k->perturbation > 0))
        return;
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: the start has a random perturbation of the volume "
             "fractions ([film] perturbation = %g): grid-scale noise has no "
             "smooth limit in dt, so the observed orders are not the "
             "methods' orders; --set film.perturbation=0 switches it off.\n",
             k->perturbation);
}

const bf_study_type bf_study_film = {
    .method_key = "film.scheme",
    .param_section = "film",
    .invariant = "phase totals",
    .default_ref_rtol = 1e-10,
    .max_ref_rtol = 1e-8,
    .adaptive = film_adaptive,
    .reference = bf_study_arkode_erk,
    .view = film_view,
    .describe = film_describe,
    .notes = film_notes,
};
