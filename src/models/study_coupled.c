/* study_coupled.c: the convergence study of balls in the dynamic film
 * (model coupled).
 *
 * Methods: a ball integrator's name (mv2m, verlet, rk4, ...) is the paper's
 * split scheme ([coupled] scheme = split) with that [scene] integrator;
 * split, arkode and mri name [coupled] scheme itself (arkode: ARKODE's
 * adaptive ERK on the whole system; mri: MRIStep, the film slow at the
 * fixed step dt, the balls fast; coupled_whole.c).  A method's key=value
 * go to [coupled] (film_every=10, table=..., rtol=...); other sections'
 * keys are written section.key=value (integrator.events=yes).
 *
 * Compared: the balls' x (cm) and v (cm/s), and the film's psi (1), h (cm)
 * and phase volume fluxes q_k = alpha_k h u_k (cm^2/s; why not u_k: see
 * study_film.c); the invariants are the film's phase totals (the ball
 * energy is not conserved: the film takes and gives it).
 *
 * The reference: [coupled] scheme = arkode at rtol 1e-12 (VERNER_8_5_6,
 * else DORMAND_PRINCE_7_4_5, else CASH_KARP_6_4_5 when compared), the
 * balls and the film in method-of-lines form on the same grid as one ODE,
 * restarted at every contact onset and release: the limit dt -> 0 of the
 * split scheme, so the errors are time errors (the coupling's lag and the
 * film scheme's), not the film's space error.  Its estimated error on
 * runs/coupled_fig8.ini over 0.25 s (four contacts): x 5e-11 cm at rtol
 * 1e-12 (the difference to 1e-13), 4e-9 cm at 1e-10, 1.6e-7 at 1e-8.
 * Its largest internal step is 10 x [scene] dt with Hertz contacts, as
 * for the balls (bf_study_hertz_max_step): in a free flight the balls'
 * error estimate is small and a step could jump over a contact. */
#include <stdio.h>
#include <string.h>

#include "models/coupled.h"
#include "models/coupled_impl.h"
#include "models/filmsys.h"
#include "models/studies.h"

static int coupled_scheme_name(const char *name)
{
    return !strcmp(name, "split") || !strcmp(name, "arkode") ||
           !strcmp(name, "mri");
}

static size_t coupled_method_sets(const char *name, char sets[2][96])
{
    if (coupled_scheme_name(name)) {
        snprintf(sets[0], sizeof sets[0], "coupled.scheme=%s", name);
        return 1;
    }
    snprintf(sets[0], sizeof sets[0], "coupled.scheme=split");
    snprintf(sets[1], sizeof sets[1], "scene.integrator=%s", name);
    return 2;
}

static int coupled_adaptive(const bf_model_setup *s)
{
    const coupled_keys *k = bf_setup_get(s, &bf_coupled_spec, NULL);
    return k && k->whole.scheme == BF_COUPLED_ARKODE;
}

static void coupled_view(void *self, bf_study_view *v)
{
    bf_coupled_parts p;
    bf_coupled_model_parts(self, &p);
    memset(v, 0, sizeof *v);
    bf_study_balls_groups(&p.sys->b, v);
    bf_study_film_groups(bf_coupled_model_filmsys(self), v);
}

static void coupled_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    const coupled_keys *k = bf_setup_get(s, &bf_coupled_spec, NULL);
    size_t l = strlen(buf);
    snprintf(buf + l, cap - l,
             "note: the reference is ARKODE on the whole system, the balls "
             "and the film (dx = %g cm) in method-of-lines form as one ODE, "
             "so the errors are time errors only.  The split scheme's "
             "coupling lag and its film scheme are first order in dt: "
             "observed orders near 1 whatever the ball integrator.\n",
             bf_study_film_dx(s));
    if (k && k->film != 0) { /* film = static */
        l = strlen(buf);
        snprintf(buf + l, cap - l,
                 "note: the film is static: every method is the ball "
                 "integrator alone (the arkode and mri schemes refuse a "
                 "static film).\n");
    }
    bf_study_perturbation_note(s, buf, cap);
}

const bf_study_type bf_study_coupled = {
    .method_key = "coupled.scheme",
    .param_section = "coupled",
    .invariant = "phase totals",
    .default_ref_rtol = 1e-12,
    .max_ref_rtol = 1e-8,
    .method_sets = coupled_method_sets,
    .adaptive = coupled_adaptive,
    .reference = bf_study_arkode_erk,
    .max_step = bf_study_hertz_max_step,
    .view = coupled_view,
    .describe = bf_coupled_model_describe,
    .notes = coupled_notes,
};
