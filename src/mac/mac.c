/* mac.c: set-up and time step of the thesis's predictor-corrector MAC
 * solver (see mac.h for the eight steps and the indexing; mac_grid.h for
 * how the files of src/mac build on one another).
 *
 * Momentum without pressure, (3.3)/(3.4), as coded in the listing (labels
 * 101-122; psi = XI on u faces, zeta = ZETA on v faces):
 *   XI(I,J) = RL U(I,J) - dt [ (R(I,J) UR^2 - R(I-1,J) UL^2)/dx
 *             + (RUVT - RUVB)/dy - mu (d2u/dx2 + d2u/dy2) ]
 *   ZETA(I,J) = RB V(I,J) - dt [ (R(I,J) VT^2 - R(I,J-1) VB^2)/dy
 *             + (RUVR - RUVL)/dx - mu (d2v/dx2 + d2v/dy2) - RB G ]
 * with RL, RB the face densities (mean of the two cells), UR, UL, VT, VB
 * the cell-centre velocities, and the corner fluxes rho u v taken donor
 * cell: the transverse velocity averaged to the corner, rho and the
 * transported velocity from the upwind side.  They are computed once per
 * time step from u^n and rho^n.
 *
 * Density predictor (3.13), forward one-sided differences (label 103):
 *   RN(I,J) = R - dt [ ubar (R(I+1,J) - R)/dx + vbar (R(I,J+1) - R)/dy ].
 *
 * The corrector loop (labels 106-451): pressure (mac_pressure.c), velocities
 * and boundary conditions (mac_bc.c), markers moved and the density
 * recomputed from them (mac_markers.c), repeated until no cell density
 * changes; the pass after that uses the fine relaxation test and is final.
 */
#include "mac/mac.h"

#include "mac/mac_bc.h"
#include "mac/mac_grid.h"
#include "mac/mac_markers.h"
#include "mac/mac_pressure.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param mac_params[] = {
    {"problem", BF_AT(bf_mac_params, problem, BF_ENUM), "", "reservoir",
     "reservoir: PROGRAM STRATRES (IN left, point sink in the bottom); rest: "
     "the same fluid in a closed tank; uniform: a uniform stream (IN left, "
     "OUT right, slip bottom)",
     0, 0, 0, "reservoir|rest|uniform"},
    {"refine", BF_AT(bf_mac_params, refine, BF_INT), "1", "1",
     "grid refinement r: (14 r + 2)^2 cells, dx = dy = 0.1/r, same physical "
     "set-up (scale [scene] dt by 1/r too)",
     BF_MIN | BF_MAX, 1, 8, NULL},
    {"update", BF_AT(bf_mac_params, update, BF_ENUM), "", "printed",
     "printed: (3.11)/(3.12) with (3.10) as printed (thesis, listing); "
     "consistent: (3.11)/(3.12) with the pressure equation derived from them; "
     "original: (3.6)-(3.9) with (3.10)",
     0, 0, 0, "printed|consistent|original"},
    {"pressure_solver", BF_AT(bf_mac_params, solver, BF_ENUM), "", "relax",
     "relax: the listing's Gauss-Seidel with crude/fine tests; direct: band "
     "Cholesky checked to direct_tol",
     0, 0, 0, "relax|direct"},
    {"compare", BF_AT(bf_mac_params, compare, BF_BOOL), "", "false",
     "with relax: also solve the final pass exactly and record the largest "
     "pressure and velocity differences",
     0, 0, 0, NULL},
    {"crude_tol", BF_AT(bf_mac_params, crude_tol, BF_REAL), "1", "3e-4",
     "crude test: |dP| per sweep / |rho g DEPTH| (listing .0003)", BF_POS, 0,
     0, NULL},
    {"fine_tol", BF_AT(bf_mac_params, fine_tol, BF_REAL), "1", "2e-4",
     "fine test of the last pass (listing .0002)", BF_POS, 0, 0, NULL},
    {"max_sweeps", BF_AT(bf_mac_params, max_sweeps, BF_INT), "1", "500",
     "sweeps per relaxation before 'too many iterations' (listing 500)",
     BF_MIN, 1, 0, NULL},
    {"omega", BF_AT(bf_mac_params, omega, BF_REAL), "1", "1",
     "over-relaxation factor (the listing has none: 1)", BF_POS | BF_MAX, 0,
     1.99, NULL},
    {"direct_tol", BF_AT(bf_mac_params, direct_tol, BF_REAL), "1", "1e-10",
     "largest relative residual accepted from the direct solve", BF_POS, 0, 0,
     NULL},
    {"max_passes", BF_AT(bf_mac_params, max_passes, BF_INT), "1", "10",
     "corrector passes before the fine pass is forced (listing ITNUM 10)",
     BF_MIN, 1, 0, NULL},
    {"oscillation", BF_AT(bf_mac_params, stop_on_oscillation, BF_ENUM), "",
     "continue",
     "when the density still changes after max_passes: continue with the "
     "fine pass (listing, counted in /mac/diag) or stop (exit 4)",
     0, 0, 0, "continue|stop"},
    {"predict", BF_AT(bf_mac_params, predict, BF_BOOL), "", "true",
     "use the predicted density (3.13) in the first pass (thesis); false: "
     "the OCR'd listing, which never copies RN into R",
     0, 0, 0, NULL},
    {"mu", BF_AT(bf_mac_params, mu, BF_REAL), "1 (scaled)", "1.14e-4",
     "viscosity mu' (listing MU)", BF_NONNEG, 0, 0, NULL},
    {"alpha", BF_AT(bf_mac_params, alpha, BF_REAL), "1 (scaled)", "1.41e-5",
     "conductivity alpha' = k/(R L W C_v) (listing ALPHA)", BF_NONNEG, 0, 0,
     NULL},
    {"g", BF_AT(bf_mac_params, g, BF_REAL), "W^2/L", "-0.98",
     "body force per unit mass, y component (listing G)", 0, 0, 0, NULL},
    {"rho_mean", BF_AT(bf_mac_params, rho_mean, BF_REAL), "R", "0.9985",
     "density profile rho = rho_mean - rho_amp tanh(y - D/2)/tanh(D/2)",
     BF_POS, 0, 0, NULL},
    {"rho_amp", BF_AT(bf_mac_params, rho_amp, BF_REAL), "R", "0.0015",
     "density amplitude (0: homogeneous fluid)", BF_NONNEG, 0, 0, NULL},
    {"t_mean", BF_AT(bf_mac_params, t_mean, BF_REAL), "dT", "15",
     "temperature T = t_mean + t_amp tanh(...)", 0, 0, 0, NULL},
    {"t_amp", BF_AT(bf_mac_params, t_amp, BF_REAL), "dT", "10",
     "temperature amplitude", 0, 0, 0, NULL},
    {"conduction", BF_AT(bf_mac_params, kappa_listing, BF_ENUM), "", "thesis",
     "heat conduction coefficient in (3.14): alpha/rho (thesis) or "
     "ALPHA*MU/R (listing line 3304)",
     0, 0, 0, "thesis|listing"},
    {"out_first", BF_AT(bf_mac_params, out_first, BF_INT), "1", "13",
     "I of the first of the two OUT cells on the 16 x 16 grid: 13 (IC flags, "
     "velocity and pressure blocks) or 14 (the particle test NI-1, NI-2)",
     BF_MIN | BF_MAX, 2, 14, NULL},
    {"out_gravity", BF_AT(bf_mac_params, out_gravity, BF_BOOL), "", "false",
     "add the hydrostatic rho |g| dy to the OUT ghost pressure (not in the "
     "listing; the sink then barely draws)",
     0, 0, 0, NULL},
    {"inflow", BF_AT(bf_mac_params, inflow_prescribed, BF_ENUM), "", "copy",
     "reservoir IN boundary: copy U(2,J) = U(3,J) with P = P0 (thesis) or "
     "prescribed u0 with P from momentum",
     0, 0, 0, "copy|prescribed"},
    {"u0", BF_AT(bf_mac_params, u0, BF_REAL), "W", "0.1",
     "stream speed of the uniform problem (and of a prescribed inflow)", 0, 0,
     0, NULL},
    {"void_fix", BF_AT(bf_mac_params, void_fix, BF_BOOL), "", "false",
     "fill empty cells enclosed by the fluid (no chain of empty cells to an "
     "EMP cell): FULL with the neighbours' density (not in the listing, "
     "which makes them SUR cells with a frozen pressure)",
     0, 0, 0, NULL},
    {"wall_markers", BF_AT(bf_mac_params, wall_remove, BF_ENUM), "", "hold",
     "a fluid marker whose move would cross a wall: hold it on the wall, or "
     "remove it and count it lost (the listing)",
     0, 0, 0, "hold|remove"},
    {"slots", BF_AT(bf_mac_params, slots, BF_INT), "1", "0",
     "particle slots (listing NK = 800); 0: 800 refine^2",
     BF_NONNEG | BF_MAX, 0, 1e7, NULL},
    {"max_cfl", BF_AT(bf_mac_params, max_cfl, BF_REAL), "1", "1",
     "stop (exit 3) when |u| dt/dx or |v| dt/dy exceeds this", BF_POS, 0, 0,
     NULL},
    {0},
};

const bf_section_spec bf_mac_spec =
    BF_SECTION("mac", "the thesis's predictor-corrector MAC solver "
               "(docs/models/mac.md)", mac_params, bf_mac_params);

void bf_mac_params_default(bf_mac_params *p)
{
    /* cannot fail: every key has a valid default (tests/test_mac.c) */
    bf_params_defaults(&bf_mac_spec, p, NULL);
}

void bf_mac_free(bf_mac *m)
{
    if (!m)
        return;
    double **d[] = {&m->u,  &m->v,  &m->p,  &m->r,    &m->t,  &m->rn,
                    &m->xi, &m->zeta, &m->pn, &m->pold, &m->a, &m->b1,
                    &m->b2, &m->b3, &m->b4, &m->tn,   &m->s,  &m->po,
                    &m->to, &m->ro, &m->band, &m->rhs, &m->sol, &m->pex,
                    &m->dens, &m->xn, &m->yn, &m->band0, &m->slack,
                    &m->uref, &m->vref, &m->mdu, &m->mdv, &m->mbound,
                    &m->rcoef};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        free(*d[k]);
    free(m->ic);
    free(m->ncnt);
    free(m->mark);
    free(m->queue);
    free(m->mcell);
    free(m->mcell1);
    free(m->mstart);
    free(m->cstamp);
    bf_particles_free(&m->part);
    free(m);
}

static bf_status check_params(const bf_mac_params *p, double dt, bf_err *err)
{
    if (p->refine < 1 || p->refine > 8)
        return bf_fail(err, BF_EINPUT, "refine = %ld: must be 1..8", p->refine);
    if (p->slots < 0 || p->slots > 10000000)
        return bf_fail(err, BF_EINPUT, "slots = %ld: must be 0..1e7", p->slots);
    if (p->out_first < 2 || p->out_first > 14)
        return bf_fail(err, BF_EINPUT, "out_first = %ld: the two OUT cells "
                       "must lie under the fluid (2..14)", p->out_first);
    if (!(p->rho_mean > p->rho_amp && p->rho_amp >= 0))
        return bf_fail(err, BF_EINPUT, "rho_mean = %g, rho_amp = %g: the "
                       "density must stay positive", p->rho_mean, p->rho_amp);
    if (!(p->crude_tol > 0 && p->fine_tol > 0 && p->max_sweeps >= 1 &&
          p->omega > 0 && p->omega < 2 && p->max_passes >= 1 &&
          p->direct_tol > 0 && p->max_cfl > 0))
        return bf_fail(err, BF_EINPUT, "bad solver tolerances");
    if (!(dt > 0))
        return bf_fail(err, BF_EINPUT, "dt must be positive");
    return BF_OK;
}

/* Allocate every array once: nothing is allocated while stepping. */
static bf_status alloc_all(bf_mac *m, size_t nslots, bf_err *err)
{
    size_t n = m->ncell;
    double **d[] = {&m->u,  &m->v,  &m->p,  &m->r,    &m->t,  &m->rn,
                    &m->xi, &m->zeta, &m->pn, &m->pold, &m->a, &m->b1,
                    &m->b2, &m->b3, &m->b4, &m->tn,   &m->s,  &m->pex,
                    &m->uref, &m->vref, &m->mdu, &m->mdv, &m->mbound,
                    &m->rcoef};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        if (!(*d[k] = calloc(n, sizeof(double))))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->ic = calloc(n, sizeof *m->ic);
    m->ncnt = calloc(n, sizeof *m->ncnt);
    m->cstamp = calloc(n, sizeof *m->cstamp);
    m->po = calloc((size_t)m->nj + 2, sizeof(double));
    m->to = calloc((size_t)m->nj + 2, sizeof(double));
    m->ro = calloc((size_t)m->nro + 1, sizeof(double));
    m->nunk = (m->ni - 2) * (m->nj - 2);
    m->bw = m->nj - 2;
    /* the band matrix only when an exact solve is asked for */
    int exact = m->prm.solver == BF_MAC_DIRECT || m->prm.compare;
    size_t nb = exact ? (size_t)m->nunk * (size_t)(m->bw + 1) : 1;
    m->band = calloc(nb, sizeof(double));
    m->band0 = calloc(nb, sizeof(double));
    m->rhs = calloc((size_t)m->nunk, sizeof(double));
    m->sol = calloc((size_t)m->nunk, sizeof(double));
    m->mark = calloc((size_t)m->nunk, sizeof(int));
    m->queue = calloc((size_t)m->nunk, sizeof(int));
    m->dens = calloc(nslots, sizeof(double));
    m->xn = calloc(nslots, sizeof(double));
    m->yn = calloc(nslots, sizeof(double));
    m->slack = calloc(nslots, sizeof(double));
    m->mcell = calloc(nslots, sizeof *m->mcell);
    m->mcell1 = calloc(nslots, sizeof *m->mcell1);
    m->mstart = calloc(nslots, sizeof *m->mstart);
    if (!m->ic || !m->ncnt || !m->cstamp || !m->po || !m->to || !m->ro ||
        !m->band || !m->band0 || !m->rhs || !m->sol || !m->mark ||
        !m->queue || !m->dens || !m->xn || !m->yn || !m->slack ||
        !m->mcell || !m->mcell1 || !m->mstart)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return bf_particles_init(&m->part, nslots, err);
}

/* Cell flags of the listing (lines 2339-2372), generalised to refine r:
 * the fluid fills rows 2..NSUR, the row above is the free surface (SUR),
 * the rest is empty; the ring depends on the problem. */
static void setup_flags(bf_mac *m)
{
    const int ni = m->ni, nj = m->nj;
    for (int i = 1; i <= ni; i++)
        for (int j = 1; j <= nj; j++) {
            int f;
            if (i == 1 || i == ni || j == 1 || j == nj)
                f = BF_MAC_NOSLIP;
            else if (j <= m->nsur)
                f = BF_MAC_FULL;
            else if (j == m->nsur + 1)
                f = BF_MAC_SUR;
            else
                f = BF_MAC_EMP;
            m->ic[IX(i, j)] = f;
        }
    if (m->prm.problem != BF_MAC_REST)
        for (int j = 2; j <= nj - 1; j++)
            m->ic[IX(1, j)] = BF_MAC_IN;
    if (m->prm.problem == BF_MAC_RESERVOIR)
        for (int i = m->out_lo; i <= m->out_hi; i++)
            m->ic[IX(i, 1)] = BF_MAC_OUT;
    if (m->prm.problem == BF_MAC_UNIFORM) {
        for (int j = 2; j <= nj - 1; j++)
            m->ic[IX(ni, j)] = BF_MAC_OUT;
        for (int i = 2; i <= ni - 1; i++)
            m->ic[IX(i, 1)] = BF_MAC_FREESLIP;
    }
}

/* Density, temperature and pressure profiles (listing lines 2373-2405):
 * tanh profiles over the fluid depth DEEP, and the exact hydrostatic
 * pressure of the density profile at each cell's bottom, which equals the
 * pressure at the cell centre with the surface half a cell above the
 * particles (P = 0 in the SUR row). */
static void setup_fields(bf_mac *m)
{
    const bf_mac_params *p = &m->prm;
    const int ni = m->ni, nsur = m->nsur;
    const double deep = (double)(nsur - 1) * m->dy;
    const double th = tanh(0.5 * deep), gabs = fabs(p->g);
    for (int l = 1; l <= m->nro; l++) {
        double y = (0.5 * (double)l - 0.25) * m->dy;
        m->ro[l] = p->rho_mean - p->rho_amp * tanh(y - 0.5 * deep) / th;
    }
    for (int j = 2; j <= nsur; j++) {
        double yc = ((double)j - 1.5) * m->dy, yb = (double)(j - 2) * m->dy;
        m->to[j] = p->t_mean + p->t_amp * tanh(yc - 0.5 * deep) / th;
        m->po[j] = gabs * (p->rho_mean * (deep - yb) -
                           p->rho_amp / th *
                               log(cosh(0.5 * deep) / cosh(yb - 0.5 * deep)));
    }
    for (int i = 1; i <= ni - 1; i++)
        for (int j = 2; j <= nsur; j++) {
            m->r[IX(i, j)] = 0.5 * (m->ro[2 * j - 3] + m->ro[2 * j - 2]);
            m->t[IX(i, j)] = m->to[j];
            m->p[IX(i, j)] = m->po[j];
        }
    for (int i = 2; i <= ni - 1; i++)
        m->r[IX(i, nsur + 1)] = m->r[IX(i, nsur)];
    if (p->problem == BF_MAC_UNIFORM) {
        /* a uniform stream on every face of the fluid and SUR rows,
         * ghosts included (the slip bottom mirrors u) */
        for (int i = 1; i <= ni + 1; i++)
            for (int j = 1; j <= nsur + 1; j++)
                m->u[IX(i, j)] = p->u0;
    }
}

/* Markers (listing lines 2406-2440): two IN particles per row of the IN
 * column, 2 x 2 fluid particles per cell, the rest of the slots free. */
static bf_status setup_markers(bf_mac *m, bf_err *err)
{
    bf_particles *pt = &m->part;
    const int nd2 = m->nro; /* 2 ND rows of particles */
    const int ncol = 2 * (m->ni - 2);
    size_t k = 0;
    size_t need = (size_t)nd2 * (size_t)ncol +
                  (m->prm.problem != BF_MAC_REST ? (size_t)nd2 : 0);
    if (need > pt->n)
        return bf_fail(err, BF_EINPUT, "slots = %zu: the initial fluid "
                       "needs %zu particles", pt->n, need);
    if (m->prm.problem != BF_MAC_REST)
        for (int l = 1; l <= nd2; l++, k++) {
            pt->tag[k] = BF_MAC_PIN;
            pt->x[k] = -0.25 * m->dx;
            pt->y[k] = (0.5 * (double)l - 0.25) * m->dy;
            m->dens[k] = m->ro[l];
        }
    for (int row = 1; row <= nd2; row++)
        for (int col = 1; col <= ncol; col++, k++) {
            pt->tag[k] = BF_MAC_REG;
            pt->x[k] = (0.5 * (double)col - 0.25) * m->dx;
            pt->y[k] = (0.5 * (double)row - 0.25) * m->dy;
            m->dens[k] = m->ro[row];
        }
    for (; k < pt->n; k++)
        pt->tag[k] = BF_MAC_AVAIL;
    for (k = 0; k < pt->n; k++) {
        pt->m[k] = m->dens[k] * m->part_area;
        if (m->prm.problem == BF_MAC_UNIFORM && pt->tag[k] != BF_MAC_AVAIL)
            pt->vx[k] = m->prm.u0;
    }
    return BF_OK;
}

bf_status bf_mac_create(bf_mac **out, const bf_mac_params *p, double dt,
                        bf_err *err)
{
    *out = NULL;
    bf_status st = check_params(p, dt, err);
    if (st)
        return st;
    bf_mac *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    m->prm = *p;
    const int r = (int)p->refine;
    m->ni = m->nj = 14 * r + 2;
    m->st = m->nj + 2;
    m->ncell = (size_t)(m->ni + 2) * (size_t)m->st;
    m->dx = m->dy = 0.1 / (double)r;
    m->dt = dt;
    m->depth = (double)(m->nj - 2) * m->dy;
    m->part_area = 0.25 * m->dx * m->dy;
    m->nsur = 12 * r + 1;
    m->nro = 2 * (m->nsur - 1);
    m->out_lo = (int)(p->out_first - 2) * r + 2;
    m->out_hi = m->out_lo + 2 * r - 1;
    if (m->out_hi > m->ni - 1) {
        bf_mac_free(m);
        return bf_fail(err, BF_EINPUT, "out_first = %ld puts OUT cells under "
                       "the right wall", p->out_first);
    }
    size_t nslots = p->slots > 0 ? (size_t)p->slots : (size_t)(800 * r * r);
    if ((st = alloc_all(m, nslots, err))) {
        bf_mac_free(m);
        return st;
    }
    setup_flags(m);
    setup_fields(m);
    if ((st = setup_markers(m, err))) {
        bf_mac_free(m);
        return st;
    }
    *out = m;
    return BF_OK;
}

/* ------------------------------------------------------------ the step */

/* psi (XI) and zeta (ZETA) of (3.3)/(3.4), listing labels 101-122. */
static void momentum(bf_mac *m)
{
    const int ni = m->ni, nj = m->nj;
    const double dx = m->dx, dy = m->dy, dt = m->dt, mu = m->prm.mu;
    const double g = m->prm.g;
    const double *U = m->u, *V = m->v, *R = m->r;
    for (int i = 2; i <= ni; i++)
        for (int j = 2; j <= nj - 1; j++) {
            double rl = 0.5 * (R[IX(i - 1, j)] + R[IX(i, j)]);
            double ur = 0.5 * (U[IX(i + 1, j)] + U[IX(i, j)]);
            double ul = 0.5 * (U[IX(i - 1, j)] + U[IX(i, j)]);
            double vb = 0.5 * (V[IX(i - 1, j)] + V[IX(i, j)]);
            double ruvb, ruvt;
            if (vb >= 0)
                ruvb = 0.5 * (R[IX(i, j - 1)] + R[IX(i - 1, j - 1)]) *
                       U[IX(i, j - 1)] * vb;
            else
                ruvb = 0.5 * (R[IX(i, j)] + R[IX(i - 1, j)]) * U[IX(i, j)] * vb;
            double vt = 0.5 * (V[IX(i - 1, j + 1)] + V[IX(i, j + 1)]);
            if (vt >= 0)
                ruvt = 0.5 * (R[IX(i, j)] + R[IX(i - 1, j)]) * U[IX(i, j)] * vt;
            else
                ruvt = 0.5 * (R[IX(i, j + 1)] + R[IX(i - 1, j + 1)]) *
                       U[IX(i, j + 1)] * vt;
            double dux2 = (U[IX(i + 1, j)] - 2.0 * U[IX(i, j)] +
                           U[IX(i - 1, j)]) / (dx * dx);
            double duy2 = (U[IX(i, j + 1)] - 2.0 * U[IX(i, j)] +
                           U[IX(i, j - 1)]) / (dy * dy);
            m->xi[IX(i, j)] =
                rl * U[IX(i, j)] -
                dt * ((R[IX(i, j)] * ur * ur - R[IX(i - 1, j)] * ul * ul) / dx +
                      (ruvt - ruvb) / dy - mu * (dux2 + duy2));
        }
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 2; j <= nj; j++) {
            double rb = 0.5 * (R[IX(i, j - 1)] + R[IX(i, j)]);
            double vt = 0.5 * (V[IX(i, j + 1)] + V[IX(i, j)]);
            double vb = 0.5 * (V[IX(i, j - 1)] + V[IX(i, j)]);
            double ur = 0.5 * (U[IX(i + 1, j)] + U[IX(i + 1, j - 1)]);
            double ruvr, ruvl;
            if (ur >= 0)
                ruvr = 0.5 * (R[IX(i, j)] + R[IX(i, j - 1)]) * ur * V[IX(i, j)];
            else
                ruvr = 0.5 * (R[IX(i + 1, j)] + R[IX(i + 1, j - 1)]) * ur *
                       V[IX(i + 1, j)];
            double ul = 0.5 * (U[IX(i, j)] + U[IX(i, j - 1)]);
            if (ul >= 0)
                ruvl = 0.5 * (R[IX(i - 1, j)] + R[IX(i - 1, j - 1)]) * ul *
                       V[IX(i - 1, j)];
            else
                ruvl = 0.5 * (R[IX(i, j)] + R[IX(i, j - 1)]) * ul * V[IX(i, j)];
            double dvx2 = (V[IX(i + 1, j)] - 2.0 * V[IX(i, j)] +
                           V[IX(i - 1, j)]) / (dx * dx);
            double dvy2 = (V[IX(i, j + 1)] - 2.0 * V[IX(i, j)] +
                           V[IX(i, j - 1)]) / (dy * dy);
            m->zeta[IX(i, j)] =
                rb * V[IX(i, j)] -
                dt * ((R[IX(i, j)] * vt * vt - R[IX(i, j - 1)] * vb * vb) / dy +
                      (ruvr - ruvl) / dx - mu * (dvx2 + dvy2) - rb * g);
        }
}

/* (3.13), label 103; with `predict` the prediction replaces R in FULL
 * cells (thesis steps 1-2; the OCR'd listing never copies RN into R). */
static void predict_density(bf_mac *m)
{
    const double *U = m->u, *V = m->v, *R = m->r;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            double rr = R[IX(i, j)];
            m->rn[IX(i, j)] =
                rr - m->dt * (0.5 * (U[IX(i, j)] + U[IX(i + 1, j)]) *
                                  (R[IX(i + 1, j)] - rr) / m->dx +
                              0.5 * (V[IX(i, j)] + V[IX(i, j + 1)]) *
                                  (R[IX(i, j + 1)] - rr) / m->dy);
        }
    if (m->prm.predict)
        for (int i = 2; i <= m->ni - 1; i++)
            for (int j = 2; j <= m->nj - 1; j++)
                if (m->ic[IX(i, j)] == BF_MAC_FULL)
                    m->r[IX(i, j)] = m->rn[IX(i, j)];
}

/* Every face velocity finite, and within the CFL limit on the faces of
 * interior cells: a marker must not jump over a cell (the listing has no
 * such check).  The message names the face and says whether empty cells
 * are enclosed by the fluid (the usual cause). */
static bf_status check_velocities(bf_mac *m, int pass, bf_err *err)
{
    double worst = 0;
    int wi = 0, wj = 0, wv = 0;
    for (int i = 1; i <= m->ni + 1; i++)
        for (int j = 1; j <= m->nj + 1; j++) {
            double u = j <= m->nj ? m->u[IX(i, j)] : 0;
            double v = i <= m->ni ? m->v[IX(i, j)] : 0;
            if (!isfinite(u) || !isfinite(v))
                return bf_fail(err, BF_EUNSTABLE, "non-finite velocity on "
                               "the %s face of cell (%d,%d) in corrector "
                               "pass %d", isfinite(u) ? "bottom (v)" :
                               "left (u)", i, j, pass);
            double cu = fabs(u) * m->dt / m->dx, cv = fabs(v) * m->dt / m->dy;
            if (i >= 2 && i <= m->ni && j >= 2 && j <= m->nj - 1 && cu > worst)
                worst = cu, wi = i, wj = j, wv = 0;
            if (i >= 2 && i <= m->ni - 1 && j >= 2 && j <= m->nj && cv > worst)
                worst = cv, wi = i, wj = j, wv = 1;
        }
    if (worst > m->prm.max_cfl) {
        char hint[256] = "";
        int vi = 0, vj = 0, nv = bf_mac_find_void(m, &vi, &vj);
        if (nv)
            snprintf(hint, sizeof hint, "; %d empty cell%s enclosed by the "
                     "fluid (first: cell (%d,%d), flagged SUR with a frozen "
                     "pressure); [mac] void_fix = true fills them",
                     nv, nv > 1 ? "s are" : " is", vi, vj);
        return bf_fail(err, BF_EUNSTABLE, "CFL number %.3g on the %s face of "
                       "cell (%d,%d) (%s = %.4g) exceeds [mac] max_cfl = %g in "
                       "corrector pass %d%s",
                       worst, wv ? "bottom" : "left", wi, wj, wv ? "v" : "u",
                       wv ? m->v[IX(wi, wj)] : m->u[IX(wi, wj)], m->prm.max_cfl,
                       pass, nv ? hint : "; reduce dt");
    }
    return BF_OK;
}

/* Largest differences between the relaxed pressure (m->p) and the exact
 * solution of the same system (m->pex): pressure relative to |rho g
 * DEPTH|, and the face velocities of the interior faces they give. */
static void compare_solutions(bf_mac *m)
{
    double dp = 0, du = 0;
    const double gd = fabs(m->prm.g) * m->depth;
    const int modified = m->prm.update != BF_MAC_ORIGINAL;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            if (m->ic[IX(i, j)] == BF_MAC_FULL) {
                double d = fabs(m->p[IX(i, j)] - m->pex[IX(i, j)]) /
                           fabs(m->r[IX(i, j)] * gd);
                if (d > dp)
                    dp = d;
            }
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            for (int d = 0; d < 2; d++) {
                int i2 = d == 0 ? i + 1 : i, j2 = d == 0 ? j : j + 1;
                if (!mac_interior(m, i2, j2))
                    continue;
                int fa = m->ic[IX(i, j)], fb = m->ic[IX(i2, j2)];
                if (!((fa == BF_MAC_FULL && mac_fluidish(fb)) ||
                      (fb == BF_MAC_FULL && mac_fluidish(fa))))
                    continue;
                double ra = m->r[IX(i, j)], rb = m->r[IX(i2, j2)];
                double qa = m->p[IX(i, j)] - m->pex[IX(i, j)];
                double qb = m->p[IX(i2, j2)] - m->pex[IX(i2, j2)];
                double h = d == 0 ? m->dx : m->dy;
                double diff = modified ? m->dt * (qa / ra - qb / rb) / h
                                       : m->dt * (qa - qb) / h / (0.5 * (ra + rb));
                if (fabs(diff) > du)
                    du = fabs(diff);
            }
    if (dp > m->cnt.max_gs_dp)
        m->cnt.max_gs_dp = dp;
    if (du > m->cnt.max_gs_du)
        m->cnt.max_gs_du = du;
}

bf_status bf_mac_step(bf_mac *m, double dt, bf_err *err)
{
    bf_status st;
    m->dt = dt;
    m->nstep++; /* psi, zeta and dt are new: no coefficient is current */
    bf_mac_mirror_density(m);
    momentum(m);
    predict_density(m);
    int fine = 0, itnum = 0, passes = 0;
    long sweeps = 0;
    for (;;) {
        passes++;
        m->voids_filled = 0;
        bf_mac_mirror_density(m);
        bf_mac_pressure_coefficients(m);
        bf_mac_surface_pressure(m);
        if (m->prm.solver == BF_MAC_RELAX) {
            long sw = 0;
            st = bf_mac_relax(m, fine, &sw, err);
            sweeps += sw;
            if (sw > m->cnt.max_sweeps_step)
                m->cnt.max_sweeps_step = sw;
            if (st) {
                bf_err_prefix(err, "corrector pass %d", passes);
                return st;
            }
            if (fine && m->prm.compare) {
                if ((st = bf_mac_direct(m, m->pex, err))) {
                    bf_err_prefix(err, "comparison solve");
                    return st;
                }
                compare_solutions(m);
            }
        } else if ((st = bf_mac_direct(m, m->p, err))) {
            bf_err_prefix(err, "corrector pass %d", passes);
            return st;
        }
        bf_mac_ghost_pressure(m, m->p);
        bf_mac_velocities(m);
        if ((st = check_velocities(m, passes, err)))
            return st;
        long held = bf_mac_move_markers(
            m, passes == 1                  ? BF_MAC_MOVE_FIRST
               : fine || m->full_passes ? BF_MAC_MOVE_ALL
                                            : BF_MAC_MOVE_CELLS);
        if ((st = bf_mac_markers_finite(m, err)))
            return st;
        int changed = bf_mac_correct_density(m);
        if (fine) {
            m->cnt.held += held;
            m->cnt.voids += m->voids_filled;
            break;
        }
        itnum++;
        if (!changed) {
            fine = 1; /* "NO DENSITY CHANGE" */
        } else if (itnum >= m->prm.max_passes) {
            /* "OSCILLATING PARTICLE": the listing forces the fine pass */
            m->cnt.oscillations++;
            if (m->prm.stop_on_oscillation)
                return bf_fail(err, BF_ENOCONV, "the corrector loop did not "
                               "converge: cell densities still change after "
                               "%d passes (oscillating particle)", itnum);
            fine = 1;
        }
    }
    if ((st = bf_mac_reflag_markers(m, err)))
        return st;
    bf_mac_temperature(m);
    m->cnt.passes += passes;
    m->cnt.sweeps += sweeps;
    m->last_passes = passes;
    m->last_sweeps = sweeps;
    return BF_OK;
}

/* ------------------------------------------------------------ views */

void bf_mac_dims(const bf_mac *m, int *ni, int *nj, double *dx, double *dy)
{
    if (ni) *ni = m->ni;
    if (nj) *nj = m->nj;
    if (dx) *dx = m->dx;
    if (dy) *dy = m->dy;
}

size_t bf_mac_index(const bf_mac *m, int i, int j) { return IX(i, j); }
const double *bf_mac_u(const bf_mac *m) { return m->u; }
const double *bf_mac_v(const bf_mac *m) { return m->v; }
const double *bf_mac_p(const bf_mac *m) { return m->p; }
const double *bf_mac_rho(const bf_mac *m) { return m->r; }
const double *bf_mac_temp(const bf_mac *m) { return m->t; }
const int *bf_mac_flags(const bf_mac *m) { return m->ic; }
const bf_particles *bf_mac_particles(const bf_mac *m) { return &m->part; }
const double *bf_mac_particle_density(const bf_mac *m) { return m->dens; }
const bf_mac_counts *bf_mac_get_counts(const bf_mac *m) { return &m->cnt; }

void bf_mac_last_step(const bf_mac *m, int *passes, long *sweeps)
{
    *passes = m->last_passes;
    *sweeps = m->last_sweeps;
}

void bf_mac_extremes(const bf_mac *m, double *umax, double *vmax,
                     double *divmax, int *ic, int *jc)
{
    double um = 0, vm = 0, dm = 0;
    int bi = 0, bj = 0;
    for (int i = 2; i <= m->ni; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            int a = m->ic[IX(i - 1, j)], b = m->ic[IX(i, j)];
            if (mac_fluidish(a) || mac_fluidish(b))
                um = fmax(um, fabs(m->u[IX(i, j)]));
        }
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj; j++) {
            int a = m->ic[IX(i, j - 1)], b = m->ic[IX(i, j)];
            if (mac_fluidish(a) || mac_fluidish(b))
                vm = fmax(vm, fabs(m->v[IX(i, j)]));
        }
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            if (m->ic[IX(i, j)] == BF_MAC_FULL) {
                double d = fabs((m->u[IX(i + 1, j)] - m->u[IX(i, j)]) / m->dx +
                                (m->v[IX(i, j + 1)] - m->v[IX(i, j)]) / m->dy);
                if (d > dm)
                    dm = d, bi = i, bj = j;
            }
    if (umax) *umax = um;
    if (vmax) *vmax = vm;
    if (divmax) *divmax = dm;
    if (ic) *ic = bi;
    if (jc) *jc = bj;
}

void bf_mac_flag_counts(const bf_mac *m, int64_t count[5])
{
    for (int k = 0; k < 5; k++)
        count[k] = 0;
    for (size_t k = 0; k < m->part.n; k++) {
        int f = m->part.tag[k];
        if (f >= 1 && f <= 4)
            count[f]++;
    }
}

double bf_mac_fluid_mass(const bf_mac *m)
{
    double s = 0;
    for (size_t k = 0; k < m->part.n; k++)
        if (m->part.tag[k] == BF_MAC_REG)
            s += m->dens[k] * m->part_area;
    return s;
}

/* ------------------------------------------------------------ checkpoints */

/* The state at t = n dt (the work arrays are recomputed by every step),
 * stored as PREFIX.NAME; the markers as PREFIX.markers (particles.h). */
static const bf_field mac_state[] = {
    BF_FIELD_PTR(bf_mac, u, BF_F_DOUBLE, ncell, "W"),
    BF_FIELD_PTR(bf_mac, v, BF_F_DOUBLE, ncell, "W"),
    BF_FIELD_PTR(bf_mac, p, BF_F_DOUBLE, ncell, "R W^2"),
    BF_FIELD_PTR(bf_mac, r, BF_F_DOUBLE, ncell, "R"),
    BF_FIELD_PTR(bf_mac, t, BF_F_DOUBLE, ncell, "dT"),
    BF_FIELD_PTR(bf_mac, ic, BF_F_INT, ncell, "1"),
    BF_FIELD_PTR(bf_mac, dens, BF_F_DOUBLE, part.n, "R"),
    BF_FIELD(bf_mac, last_passes, BF_F_INT, "1"),
    BF_FIELD(bf_mac, last_sweeps, BF_F_LONG, "1"),
};

/* The counters, as PREFIX.counts.NAME. */
static const bf_field mac_counts[] = {
    BF_FIELD(bf_mac_counts, entered, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, left_out, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, freed, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, backflow, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, lost, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, in_clamped, BF_F_I64, "particles"),
    BF_FIELD(bf_mac_counts, held, BF_F_I64, "moves"),
    BF_FIELD(bf_mac_counts, voids, BF_F_I64, "cells"),
    BF_FIELD(bf_mac_counts, oscillations, BF_F_I64, "steps"),
    BF_FIELD(bf_mac_counts, passes, BF_F_I64, "1"),
    BF_FIELD(bf_mac_counts, sweeps, BF_F_I64, "1"),
    BF_FIELD(bf_mac_counts, max_sweeps_step, BF_F_I64, "1"),
    BF_FIELD(bf_mac_counts, mass_in, BF_F_DOUBLE, "R L^2"),
    BF_FIELD(bf_mac_counts, mass_out, BF_F_DOUBLE, "R L^2"),
    BF_FIELD(bf_mac_counts, mass_back, BF_F_DOUBLE, "R L^2"),
    BF_FIELD(bf_mac_counts, mass_lost, BF_F_DOUBLE, "R L^2"),
    BF_FIELD(bf_mac_counts, max_gs_dp, BF_F_DOUBLE, "1"),
    BF_FIELD(bf_mac_counts, max_gs_du, BF_F_DOUBLE, "W"),
};

/* The state, its counters and the markers under prefix, prefix.counts and
 * prefix.markers: written (save) or read back, one list for both. */
static bf_status mac_ckpt(bf_mac *m, bf_ckpt *ck, const char *prefix,
                          int save, bf_err *err)
{
    const struct {
        const char *suffix;
        const bf_field *fields;
        size_t nfields;
        void *obj;
    } parts[] = {
        {"", mac_state, BF_NFIELDS(mac_state), m},
        {".counts", mac_counts, BF_NFIELDS(mac_counts), &m->cnt},
    };
    char name[256];
    bf_status st = BF_OK;
    for (size_t k = 0; k < sizeof parts / sizeof parts[0] && !st; k++) {
        snprintf(name, sizeof name, "%s%s", prefix, parts[k].suffix);
        st = save ? bf_ckpt_put_fields(ck, name, parts[k].fields,
                                       parts[k].nfields, parts[k].obj, err)
                  : bf_ckpt_get_fields(ck, name, parts[k].fields,
                                       parts[k].nfields, parts[k].obj, err);
    }
    snprintf(name, sizeof name, "%s.markers", prefix);
    if (st)
        return st;
    return save ? bf_particles_save(&m->part, ck, name, err)
                : bf_particles_load(&m->part, ck, name, err);
}

bf_status bf_mac_save(const bf_mac *m, bf_ckpt *ck, const char *prefix,
                      bf_err *err)
{
    /* saving reads m only */
    return mac_ckpt((bf_mac *)m, ck, prefix, 1, err);
}

bf_status bf_mac_load(bf_mac *m, const bf_ckpt *ck, const char *prefix,
                      bf_err *err)
{
    /* loading reads ck only */
    return mac_ckpt(m, (bf_ckpt *)ck, prefix, 0, err);
}
