/* coupled_multirate.c: [coupled] film_every = auto, the film's step chosen
 * from an estimate of the coupling error (coupled_impl.h; beyond the
 * paper).
 *
 * In a multirate window the balls take K steps of dt in the film frozen at
 * the window's start, and the film then takes one step of H = K dt with
 * mu_cpl (3.11) of the balls at the start.  The balls' coupling
 * acceleration a = -M dF/dr (3.12) therefore lags behind the one of the
 * film they would see single rate: at the window's end by
 *
 *   lag = max_p |a_p(x_p; film after the step) - a_p(x_p; film before)|
 *
 * (both at the balls' end positions x_p, cm/s^2), and in between by about
 * lag s/H at a time s into the window (the film changes smoothly over a
 * step).  The lag is first order in H, so the next window takes
 *
 *   K' = K min(2, max(1/5, 0.9 tol / lag)),  1 <= K' <= kmax,
 *
 * and no more than 90 % of the film's stable limit (K' dt <=
 * 0.9 bf_film_stable_dt, of the film's state at most STABLE_EVERY ball
 * steps ago) or the steps left in the run.  A rule of cost caps it too:
 * K' dt <= taylor_radius / max_p |v_p|, the time the fastest ball takes to
 * leave the Taylor anchor of its coupling integral (coupling.h); a longer
 * film step makes every later force evaluation of the window an exact
 * quadrature, which costs more than the film steps it saves (measured on
 * the Fig. 8 scene, bench_coupled).  A window is not
 * repeated when its lag exceeded the tolerance (it is counted in the
 * report): the lag changes slowly from window to window.
 *
 * What a tolerance promises: an acceleration error of at most tol moves a
 * ball by at most tol t^2 / 2 in a time t (cm, t in s), unless the
 * dynamics amplifies differences (collisions; the Fig. 8 scene is chaotic,
 * its separations grow as exp(4 t/s), docs/models/coupled.md).  The
 * estimate covers the balls' side of the lag only: the film's side (mu_cpl
 * frozen over the film step) is not estimated; on the Fig. 8 scene it is
 * the smaller part (tests/test_coupling.c measures the whole error).
 *
 * A Lyapunov shadow ([lyapunov] enabled) takes the film steps its run
 * chooses (coupled_impl.h, leader).
 */
#include <math.h>
#include <stdlib.h>

#include "models/coupled_impl.h"

static const double PI = 3.14159265358979323846;

/* ball steps between two evaluations of the film's stable limit */
enum { STABLE_EVERY = 1000 };

enum { ST_WIN, ST_KSUM, ST_KMIN, ST_KMAX, ST_LAG, ST_OVER };

bf_status bf_coupled_mr_init(coupled_model *m, double tol, long kmax,
                             long nsteps, bf_err *err)
{
    m->adaptive = 1;
    m->mr_tol = tol;
    m->mr_kmax = kmax;
    m->nsteps = nsteps;
    m->win_start = 0;
    m->win_k = 1;
    m->mr_stat[ST_KMIN] = INFINITY;
    m->acc_old = calloc(2 * m->nb, sizeof(double));
    if (!m->acc_old)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

int bf_coupled_window_starts(const coupled_model *m, long n)
{
    return m->adaptive ? n == m->win_start : n % m->every == 0;
}

long bf_coupled_window_ends(const coupled_model *m, long n)
{
    if (m->adaptive)
        return n + 1 == m->win_start + m->win_k ? m->win_k : 0;
    return (n + 1) % m->every == 0 ? m->every : 0;
}

/* the coupling acceleration -M dF_p/dr (3.10, 3.12) of each ball at its
 * position, in the coupling's current film level, cm/s^2 (the exact
 * quadrature: no Taylor anchor is used or moved) */
static void coupling_acc(coupled_model *m, double *a)
{
    const bf_coupling_params *p = bf_coupling_params_of(m->cpl);
    const double k = 4.0 * PI * p->V0 * p->M;
    const bf_balls *b = &m->sys->b;
    for (size_t i = 0; i < m->nb; i++) {
        double I, dI;
        bf_coupling_integral(m->cpl, b->x[i], &I, &dI);
        a[i] = -k * b->R[i] * b->R[i] * dI;
    }
}

void bf_coupled_mr_before(coupled_model *m)
{
    if (!m->leader)
        coupling_acc(m, m->acc_old);
}

void bf_coupled_mr_after(coupled_model *m, long n, double dt)
{
    if (m->leader) {
        /* a Lyapunov shadow takes the run's film steps (the run has just
         * chosen its next one at this step): the two systems then differ
         * by their states only */
        m->win_start = m->leader->win_start;
        m->win_k = m->leader->win_k;
        return;
    }
    double lag = 0, *a = m->acc_old + m->nb;
    coupling_acc(m, a);
    for (size_t i = 0; i < m->nb; i++)
        lag = fmax(lag, fabs(a[i] - m->acc_old[i]));
    double *st = m->mr_stat;
    const double K = (double)m->win_k;
    st[ST_WIN] += 1;
    st[ST_KSUM] += K;
    st[ST_KMIN] = fmin(st[ST_KMIN], K);
    st[ST_KMAX] = fmax(st[ST_KMAX], K);
    st[ST_LAG] = fmax(st[ST_LAG], lag);
    if (lag > m->mr_tol)
        st[ST_OVER] += 1;
    /* first order: lag proportional to K */
    double f = lag > 0 ? fmax(0.2, fmin(2.0, 0.9 * m->mr_tol / lag)) : 2.0;
    double next = floor(K * f);
    /* the film's stable limit (s), of its state at most STABLE_EVERY ball
     * steps ago (it costs a pass over the film, as much as a film step,
     * and changes slowly): 90 % of it */
    if (n + 1 >= m->mr_stable_at) {
        m->mr_stable = bf_film_stable_dt(bf_filmsys_film(m->fs), NULL, 0);
        m->mr_stable_at = n + 1 + STABLE_EVERY;
    }
    const double L = m->mr_stable;
    if (L > 0 && L < INFINITY)
        next = fmin(next, fmax(1.0, floor(0.9 * L / dt)));
    next = fmin(next, (double)m->mr_kmax);
    /* cost: no longer than the fastest ball takes to leave its Taylor
     * anchor (coupling.h; beyond, every force evaluation is the exact
     * quadrature, and that costs more than the film steps saved) */
    const double rT = bf_coupling_params_of(m->cpl)->taylor_radius;
    double v = 0;
    for (size_t i = 0; i < m->nb; i++)
        v = fmax(v, fabs(m->sys->b.v[i]));
    if (rT > 0 && v > 0)
        next = fmin(next, fmax(1.0, floor(rT / (v * dt))));
    long left = m->nsteps - (n + 1);
    if (left > 0)
        next = fmin(next, (double)left);
    m->win_start = n + 1;
    m->win_k = next < 1 ? 1 : (long)next;
}

int bf_coupled_mr_output_row(coupled_model *m)
{
    if (!m->adaptive)
        return 0;
    double k = (double)m->win_k;
    return bf_series_append(m->kser, &k);
}

void bf_coupled_mr_report(const coupled_model *m, FILE *f)
{
    if (!m->adaptive)
        return;
    const double *st = m->mr_stat;
    fprintf(f,
            "multirate: film_every = auto, multirate_tol %g cm/s^2: %.0f film "
            "steps of K = %.0f to %.0f ball steps (mean %.1f); largest "
            "coupling-acceleration lag %.3g cm/s^2, %.0f film steps above "
            "the tolerance\n",
            m->mr_tol, st[ST_WIN], st[ST_WIN] > 0 ? st[ST_KMIN] : 0,
            st[ST_KMAX], st[ST_WIN] > 0 ? st[ST_KSUM] / st[ST_WIN] : 0,
            st[ST_LAG], st[ST_OVER]);
}

static const bf_field mr_fields[] = {
    BF_FIELD(coupled_model, win_start, BF_F_LONG, "1"),
    BF_FIELD(coupled_model, win_k, BF_F_LONG, "1"),
    BF_FIELD(coupled_model, mr_stable_at, BF_F_LONG, "1"),
    BF_FIELD(coupled_model, mr_stable, BF_F_DOUBLE, "s"),
    BF_FIELD_ARRAY(coupled_model, mr_stat, BF_F_DOUBLE, "1"),
};

bf_status bf_coupled_mr_save(const coupled_model *m, bf_ckpt *ck,
                             const char *name, bf_err *err)
{
    if (!m->adaptive)
        return BF_OK;
    return bf_ckpt_put_fields(ck, name, mr_fields, BF_NFIELDS(mr_fields), m,
                              err);
}

bf_status bf_coupled_mr_load(coupled_model *m, const bf_ckpt *ck,
                             const char *name, bf_err *err)
{
    if (!m->adaptive)
        return BF_OK;
    return bf_ckpt_get_fields(ck, name, mr_fields, BF_NFIELDS(mr_fields), m,
                              err);
}
