/* coupled_symmetry.c: the mirror symmetry of the coupled model
 * (coupled_impl.h): the check of the set-up, the projections of the balls
 * and the symmetry error of the balls.
 *
 * Forced mirror symmetry ([coupled] symmetrize = yes, a test of the
 * explanation of Figs 8-9 in docs/models/coupled.md, not part of the paper's scheme).  The
 * set-up is symmetric under x -> -x, psi -> -psi: ball i <-> ball n+1-i
 * with x -> -x, v -> -v, and the film map of bf_film_mirror (A_d(i) <->
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
 */
#include <math.h>
#include <stdio.h>

#include "models/coupled_impl.h"

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
bf_status bf_coupled_check_symmetric(const coupled_model *m,
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
double bf_coupled_mirror_odd(double *a, size_t n)
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

/* acc[q] and acc[q + 4] (since the last row, over the run) take the
 * larger of themselves and c[q], q < k */
void bf_coupled_keep_max(double *acc, const double *c, int k)
{
    for (int q = 0; q < k; q++) {
        acc[q] = fmax(acc[q], c[q]);
        acc[q + 4] = fmax(acc[q + 4], c[q]);
    }
}

/* max_i |x_i + x_(n-1-i)| (cm): how far the balls are from the mirror
 * symmetry */
double bf_coupled_symmetry_error(const double *x, size_t n)
{
    double e = 0;
    for (size_t i = 0; i < n / 2; i++)
        e = fmax(e, fabs(x[i] + x[n - 1 - i]));
    return e;
}
