/* film_mol.c: the film in method-of-lines form (film_mol.h).
 *
 * The semi-discrete equations are the terms of first order in dt of the
 * invariant scheme (film.c), i.e. what the scheme tends to as dt -> 0 on
 * its grid: for phase k (s_d = +1, s_c = -1), A = alpha_k h, u = u_k,
 *
 *   dA_i/dt = -(A_{i+1} u_{i+1} - A_{i-1} u_{i-1}) / (2 dx)         (3.15)
 *   du_i/dt = -(u_{i+1} + u_{i-1})/2 (u_{i+1} - u_{i-1}) / (2 dx)
 *             - (Q_{i+1} - Q_{i-1}) / (2 rho_k dx)
 *             + nu (u_{i+1} - 2 u_i + u_{i-1}) / dx^2                 (3.16)
 *
 * with Q = P + s_k mu, P = g (rho_d A_d + rho_c A_c) (= rho_m g h), and
 * mu_i = psi_i (b psi_i^2 - a) - (gamma/dx^2)(psi_{i+1} - 2 psi_i +
 * psi_{i-1}) + mu_cpl_i, psi = (A_d - A_c)/(A_d + A_c).  The dt^2/2
 * terms of the scheme (its Lax-Wendroff part) vanish in the limit; the
 * viscous term of the scheme is its 2 nu/dt part of G, which is this
 * nu u_xx exactly.  Boundaries as in the scheme: mirrored ghost nodes,
 * A and psi even, u odd (so u = 0 on the walls, du/dt = 0 there), the
 * phase equation on the wall nodes, the velocity equation on interior
 * nodes; mu at a ghost reads mu_cpl at its mirror image.  The scheme's
 * vanish rule (an absent phase, alpha_k < vanish, moves with the other)
 * is the same here: its du_k/dt is the other phase's, and after every
 * [scene] dt its u_k is set to the other's (bf_film_mol_vanish), as the
 * scheme does after each of its steps; the scheme and the reference then
 * agree on a phase's velocity where it is absent at the compared rows
 * (where it carries less than vanish h of volume and no meaning).  The scheme's
 * positivity limiter has no counterpart: a negative content is reported
 * after a step (bf_film_mol_check).
 *
 * Stiffness: the gradient of gamma psi_xx makes the phase-separation mode
 * a dispersive wave with frequency ~ sqrt(2 beta gamma / rho) k^2, so an
 * explicit step is limited by dx^2 (the scheme's phase-separation limit);
 * the gravity waves (speed sqrt(g h)) limit it by dx.  The IMEX
 * splittings of film_mol.h put one or both of them into the implicit
 * part. */
#include "film/film_mol.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct bf_film_mol {
    long N;
    double dx;
    bf_film_params p;
    const double *x; /* node positions, for messages (the film's) */
    /* scratch with ghosts: node arrays -2..N+2 */
    double *mem;
    double *ad, *ac, *ud, *uc, *psi, *mloc, *mcap;
};

bf_status bf_film_mol_create(bf_film_mol **out, const bf_film *f,
                             bf_err *err)
{
    *out = NULL;
    bf_film_mol *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->N = (long)bf_film_nodes(f) - 1;
    m->p = *bf_film_params_of(f);
    m->dx = m->p.dx;
    m->x = bf_film_x(f);
    const size_t len = (size_t)m->N + 5;
    m->mem = calloc(7 * len, sizeof *m->mem);
    if (!m->mem) {
        free(m);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    double **arr[7] = {&m->ad, &m->ac, &m->ud, &m->uc,
                       &m->psi, &m->mloc, &m->mcap};
    for (int k = 0; k < 7; k++)
        *arr[k] = m->mem + (size_t)k * len + 2;
    *out = m;
    return BF_OK;
}

void bf_film_mol_free(bf_film_mol *m)
{
    if (!m)
        return;
    free(m->mem);
    free(m);
}

size_t bf_film_mol_size(const bf_film_mol *m)
{
    return 4 * ((size_t)m->N + 1);
}

long bf_film_mol_bandwidth(void)
{
    /* du_c at node i (index 4i + 3) depends on A_d at node i - 2 (index
     * 4i - 8) through mu_{i-1}; A_d at node i + 2 is index 4i + 8, so
     * the widest reach is 11 to either side */
    return 11;
}

void bf_film_mol_pack(const bf_film *f, double *y)
{
    const size_t n = bf_film_nodes(f);
    const double *ad = bf_film_ah_d(f), *ac = bf_film_ah_c(f);
    const double *ud = bf_film_u_d(f), *uc = bf_film_u_c(f);
    for (size_t i = 0; i < n; i++) {
        y[4 * i] = ad[i];
        y[4 * i + 1] = ac[i];
        y[4 * i + 2] = ud[i];
        y[4 * i + 3] = uc[i];
    }
}

void bf_film_mol_unpack(bf_film *f, const double *y)
{
    double *arr[BF_FILM_NSTATE];
    const size_t n = bf_film_state(f, arr);
    for (size_t i = 0; i < n; i++) {
        arr[0][i] = y[4 * i];
        arr[1][i] = y[4 * i + 1];
        arr[2][i] = y[4 * i + 2];
        arr[3][i] = y[4 * i + 3];
        arr[4][i] = arr[5][i] = 0.0; /* no rounding carries */
    }
    bf_film_state_changed(f);
}

int bf_film_mol_rhs(bf_film_mol *m, const double *y, const double *mu_cpl,
                    bf_film_mol_part part, bf_film_mol_split split,
                    double *ydot)
{
    const long N = m->N;
    const bf_film_params *p = &m->p;
    double *ad = m->ad, *ac = m->ac, *ud = m->ud, *uc = m->uc;
    double *psi = m->psi, *ml = m->mloc, *mc = m->mcap;
    int bad = 0;
    for (long i = 0; i <= N; i++) {
        ad[i] = y[4 * i];
        ac[i] = y[4 * i + 1];
        ud[i] = y[4 * i + 2];
        uc[i] = y[4 * i + 3];
        const double h = ad[i] + ac[i];
        psi[i] = (ad[i] - ac[i]) / h;
        bad |= !(h > 0) || !isfinite(psi[i]) || !isfinite(ud[i]) ||
               !isfinite(uc[i]);
    }
    if (bad)
        return 1;
    ud[0] = uc[0] = ud[N] = uc[N] = 0.0;
    /* the ghosts: A and psi even, u odd */
    ad[-1] = ad[1];
    ad[N + 1] = ad[N - 1];
    ac[-1] = ac[1];
    ac[N + 1] = ac[N - 1];
    ud[-1] = -ud[1];
    ud[N + 1] = -ud[N - 1];
    uc[-1] = -uc[1];
    uc[N + 1] = -uc[N - 1];
    psi[-1] = psi[1];
    psi[-2] = psi[2];
    psi[N + 1] = psi[N - 1];
    psi[N + 2] = psi[N - 2];
    /* mu = ml + mc: the local part with the coupling, the capillary part */
    const double gl = p->gamma / (m->dx * m->dx);
    for (long i = -1; i <= N + 1; i++) {
        const double ps = psi[i];
        const long im = i < 0 ? 1 : i > N ? N - 1 : i; /* mirror image */
        ml[i] = ps * (p->b * ps * ps - p->a) + (mu_cpl ? mu_cpl[im] : 0.0);
        mc[i] = -gl * ((psi[i + 1] - ps) - (ps - psi[i - 1]));
    }
    /* which terms this part holds */
    const int all = part == BF_FILM_MOL_ALL;
    const int impl = part == BF_FILM_MOL_IMPLICIT;
    const int waves = split == BF_FILM_MOL_WAVES;
    const int t_flux = all || (waves ? impl : !impl);
    const int t_adv = all || !impl;
    const int t_pres = all || (waves ? impl : !impl); /* P and local mu */
    const int t_cap = all || impl;
    const int t_visc = all || impl;
    const double c1 = 1.0 / (2.0 * m->dx);
    for (long i = 0; i <= N; i++) {
        ydot[4 * i] = t_flux ? -(ad[i + 1] * ud[i + 1] -
                                 ad[i - 1] * ud[i - 1]) * c1
                             : 0.0;
        ydot[4 * i + 1] = t_flux ? -(ac[i + 1] * uc[i + 1] -
                                     ac[i - 1] * uc[i - 1]) * c1
                                 : 0.0;
        ydot[4 * i + 2] = ydot[4 * i + 3] = 0.0;
    }
    const double vis = p->nu / (m->dx * m->dx);
    for (long i = 1; i < N; i++) {
        double fd = 0.0, fc = 0.0;
        if (t_adv) {
            fd -= 0.5 * (ud[i + 1] + ud[i - 1]) * (ud[i + 1] - ud[i - 1]) * c1;
            fc -= 0.5 * (uc[i + 1] + uc[i - 1]) * (uc[i + 1] - uc[i - 1]) * c1;
        }
        double dP = 0.0, dm = 0.0;
        if (t_pres) {
            dP = p->g * (p->rho_d * (ad[i + 1] - ad[i - 1]) +
                         p->rho_c * (ac[i + 1] - ac[i - 1]));
            dm = ml[i + 1] - ml[i - 1];
        }
        if (t_cap)
            dm += mc[i + 1] - mc[i - 1];
        fd -= (dP + dm) * c1 / p->rho_d;
        fc -= (dP - dm) * c1 / p->rho_c;
        if (t_visc) {
            fd += vis * ((ud[i + 1] - ud[i]) - (ud[i] - ud[i - 1]));
            fc += vis * ((uc[i + 1] - uc[i]) - (uc[i] - uc[i - 1]));
        }
        /* the vanish rule: an absent phase moves with the other */
        const double vh = p->vanish * (ad[i] + ac[i]);
        ydot[4 * i + 2] = ad[i] < vh ? fc : fd;
        ydot[4 * i + 3] = ac[i] < vh ? fd : fc;
    }
    return 0;
}

void bf_film_mol_vanish(const bf_film_mol *m, double *y)
{
    const double va = m->p.vanish;
    for (long i = 0; i <= m->N; i++) {
        double *q = y + 4 * i;
        const double vh = va * (q[0] + q[1]);
        if (q[0] < vh)
            q[2] = q[3];
        else if (q[1] < vh)
            q[3] = q[2];
    }
}

bf_status bf_film_mol_check(const bf_film_mol *m, const double *y,
                            bf_err *err)
{
    for (long i = 0; i <= m->N; i++) {
        const double a = y[4 * i], c = y[4 * i + 1];
        const double vd = y[4 * i + 2], vc = y[4 * i + 3];
        if (!isfinite(a) || !isfinite(c) || !isfinite(vd) || !isfinite(vc))
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): non-finite value "
                           "(alpha_d h = %g, alpha_c h = %g, u_d = %g, u_c = "
                           "%g cm/s)",
                           i, m->x[i], a, c, vd, vc);
        if (!(a + c > 0))
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): h = %g <= 0", i,
                           m->x[i], a + c);
        if (a < 0 || c < 0)
            return bf_fail(err, BF_EUNSTABLE,
                           "film node %ld (x = %g cm): volume fraction "
                           "alpha_%c = %.3g outside [0, 1]; the model is "
                           "ill-posed there and the method-of-lines film has "
                           "no positivity limiter (use [film] scheme = "
                           "invariant)",
                           i, m->x[i], a < 0 ? 'd' : 'c',
                           (a < 0 ? a : c) / (a + c));
    }
    return BF_OK;
}
