/* coupled_lyapunov.c: the Lyapunov shadow of the coupled model
 * (coupled_impl.h): the seeding of the shadow system, and after each
 * step the renormalisation when it is due.  coupled.c builds the shadow
 * (another instance of the model) and steps it.
 *
 * Largest Lyapunov exponent ([lyapunov] enabled = yes,
 * src/diag/lyapsum.h).  The model keeps a shadow coupled system: a second
 * instance of this model built from the same setup (its own film, balls,
 * coupling and integrator, the same film_every and symmetrize), whose
 * balls start
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
#include <stdlib.h>

#include "models/coupled_impl.h"

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

bf_status bf_coupled_lyap_init(coupled_model *m, const bf_model_setup *setup,
                               bf_err *err)
{
    m->ly = malloc(sizeof *m->ly);
    if (!m->ly)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    const bf_integrator_type *t = m->sys->it->type;
    return bf_lyap_sum_init(m->ly, bf_setup_get(setup, &bf_lyap_spec, NULL),
                            setup->run.dt, m->nb,
                            t->flags & BF_INT_ADAPTIVE ? t->name : NULL, err);
}

void bf_coupled_lyap_seed(coupled_model *m)
{
    displace_shadow_balls(m);
    state_changed(m->shadow);
}

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

bf_status bf_coupled_lyap_renormalise(coupled_model *m, long n, double t,
                                      double dt, bf_err *err)
{
    coupled_model *sh = m->shadow;
    if (!bf_lyap_due(m->ly, n + 1))
        return BF_OK;
    double factor;
    bf_status st = bf_lyap_measure(m->ly, m->sys->b.x, m->sys->b.v,
                                   sh->sys->b.x, sh->sys->b.v, t + dt,
                                   &factor, err);
    if (!st && factor != 1.0)
        pull_shadow(m, factor);
    return st;
}
