/* mac_bc.c: boundary conditions of the MAC solver (thesis ch. III,
 * "Boundary conditions for the algorithm"; listing labels 200-222,
 * 300-328, 500-517).  A ring of fictitious cells surrounds the fluid; its
 * values come from the condition on the face it shares with the fluid.
 *
 * Material boundary (NOSLIP), fictitious cell g next to fluid cell c:
 *   normal face u = 0; beyond it u_{g-1/2} = u_{c+1/2} (continuity in both
 *   cells); tangential ghost v_g = -v_c; T_g = T_c; rho_g = rho_c;
 *   P_g from the normal momentum equation with du/dt = 0.  We take P_g such
 *   that the update the pressure equation assumes gives exactly u = 0 on
 *   the face:  x_g = x_c - (delta/(dt k)) s (u_b - psi/rho_f), where x = P
 *   and k = 1/rho_f for (3.10), x = P/rho and k = 1 for the consistent
 *   equation.  In the first corrector pass this is the listing's DPX/DPY.
 * Free surface (SUR cells: the empty cells next to the fluid):
 *   P = 2 mu [nx^2 du/dx + nx ny (du/dy + dv/dx) + ny^2 dv/dy] (2.20), the
 *   normal (nx, ny) pointing to the empty neighbours (labels 206-222);
 *   faces between two SUR cells from zero shear (2.21) on the fluid side;
 *   faces towards empty cells from continuity in the SUR cell.
 * IN boundary (left): v_g = -v_c (normal inflow), u_{g-1/2} = u_{c+1/2};
 *   the reservoir copies the face velocity from its right neighbour,
 *   U(2,J) = U(3,J) (thesis p. 35), with the hydrostatic P_g = P0(J); the
 *   uniform-flow check prescribes U(2,J) = u0 with P_g from momentum.
 * OUT boundary (Welch et al. 1966): the fluid is not accelerated, v_g = v_c
 *   tangentially; the normal face velocity from the momentum update;
 *   continuity in the ghost cell; P_g = P_c + (dy/dx)[(rho u v)_R -
 *   (rho u v)_L] (listing lines 2643-2647), with no hydrostatic term: that
 *   missing rho |g| dy is what drains the reservoir through its sink.
 */
#include "mac/mac_bc.h"

#include <math.h>

/* Ring densities mirror the fluid (labels 106-109; the top row added so
 * that a fluid touching the lid also has a face density). */
void bf_mac_mirror_density(bf_mac *m)
{
    double *R = m->r;
    for (int i = 2; i <= m->ni - 1; i++) {
        R[IX(i, 1)] = R[IX(i, 2)];
        R[IX(i, m->nj)] = R[IX(i, m->nj - 1)];
    }
    for (int j = 2; j <= m->nj - 1; j++) {
        R[IX(1, j)] = R[IX(2, j)];
        R[IX(m->ni, j)] = R[IX(m->ni - 1, j)];
    }
}

static int side_of(const bf_mac *m, int ig, int jg)
{
    if (ig == 1)
        return MAC_W;
    if (ig == m->ni)
        return MAC_E;
    return jg == 1 ? MAC_S : MAC_N;
}

/* Welch's OUT pressure offset P_g - P_c (listing lines 2643-2647 for the
 * bottom; the right side is the same rule turned by 90 degrees). */
static double out_offset(const bf_mac *m, int ig, int jg, int ic, int jc)
{
    const double *U = m->u, *V = m->v;
    const double rc = m->r[IX(ic, jc)];
    int d = side_of(m, ig, jg);
    if (d == MAC_S) {
        int i = ic;
        double ruvr = 0.5 * rc * U[IX(i + 1, 2)] * (V[IX(i, 2)] + V[IX(i + 1, 2)]);
        double ruvl = 0.5 * rc * U[IX(i, 2)] * (V[IX(i - 1, 2)] + V[IX(i, 2)]);
        double off = m->dy / m->dx * (ruvr - ruvl);
        if (m->prm.out_gravity)
            off += rc * fabs(m->prm.g) * m->dy;
        return off;
    }
    if (d == MAC_E) {
        int j = jc, i = m->ni;
        double ruvt = 0.5 * rc * V[IX(i - 1, j + 1)] * (U[IX(i, j)] + U[IX(i, j + 1)]);
        double ruvb = 0.5 * rc * V[IX(i - 1, j)] * (U[IX(i, j - 1)] + U[IX(i, j)]);
        return -m->dx / m->dy * (ruvt - ruvb);
    }
    return 0.0; /* no problem puts OUT cells on the left or top */
}

int bf_mac_boundary_face(const bf_mac *m, int ig, int jg, int ic, int jc,
                         double *val)
{
    int flag = m->ic[IX(ig, jg)];
    if (flag == BF_MAC_IN) {
        if (m->prm.problem == BF_MAC_RESERVOIR && !m->prm.inflow_prescribed) {
            *val = m->po[jg];
            return MAC_DIRICHLET;
        }
        *val = m->prm.u0;
        return MAC_FLUX;
    }
    if (flag == BF_MAC_OUT) {
        mac_face f;
        bf_mac_face_of(m, ic, jc, side_of(m, ig, jg), &f);
        double off = out_offset(m, ig, jg, ic, jc);
        *val = f.psi / f.rhof - f.s * m->dt / f.delta * off / m->r[IX(ic, jc)];
        return MAC_FLUX;
    }
    *val = 0.0; /* NOSLIP, FREESLIP */
    return MAC_FLUX;
}

/* Ghost pressure of ring cell g next to interior cell c, from p. */
static void ghost_one(bf_mac *m, double *p, int ig, int jg, int ic, int jc)
{
    size_t g = IX(ig, jg), c = IX(ic, jc);
    double val;
    int kind = bf_mac_boundary_face(m, ig, jg, ic, jc, &val);
    if (kind == MAC_DIRICHLET) {
        p[g] = val;
        return;
    }
    if (!mac_fluidish(m->ic[c])) {
        p[g] = 0.0;
        return;
    }
    mac_face f;
    bf_mac_face_of(m, ic, jc, side_of(m, ig, jg), &f);
    const int K = mac_consistent(m);
    double k = K ? 1.0 : 1.0 / f.rhof;
    double xc = K ? p[c] / m->r[c] : p[c];
    double xg = xc - f.delta / (m->dt * k) * f.s * (val - f.psi / f.rhof);
    p[g] = K ? m->r[g] * xg : xg;
}

void bf_mac_ghost_pressure(bf_mac *m, double *p)
{
    for (int j = 2; j <= m->nj - 1; j++) {
        ghost_one(m, p, 1, j, 2, j);
        ghost_one(m, p, m->ni, j, m->ni - 1, j);
    }
    for (int i = 2; i <= m->ni - 1; i++) {
        ghost_one(m, p, i, 1, i, 2);
        ghost_one(m, p, i, m->nj, i, m->nj - 1);
    }
}

/* Free-surface pressure (2.20) in every SUR cell, labels 205-222.  The
 * normal points to the empty neighbours, tested above, right, left, below;
 * diagonal normals use 1/sqrt(2) (the listing's SQR/SOR).  A SUR cell with
 * no empty neighbour (a void inside the fluid) keeps its pressure. */
void bf_mac_surface_pressure(bf_mac *m)
{
    const double sor = 1.0 / sqrt(2.0);
    const double *U = m->u, *V = m->v;
    const int *F = m->ic;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            if (F[IX(i, j)] != BF_MAC_SUR)
                continue;
            int up = F[IX(i, j + 1)] == BF_MAC_EMP;
            int rt = F[IX(i + 1, j)] == BF_MAC_EMP;
            int lt = F[IX(i - 1, j)] == BF_MAC_EMP;
            int dn = F[IX(i, j - 1)] == BF_MAC_EMP;
            double px, py;
            if (up) {
                if (rt)
                    px = sor, py = sor;
                else if (lt)
                    px = -sor, py = sor;
                else
                    px = 0, py = 1;
            } else if (rt) {
                if (dn)
                    px = sor, py = -sor;
                else
                    px = 1, py = 0;
            } else if (lt) {
                if (dn)
                    px = -sor, py = -sor;
                else
                    px = -1, py = 0;
            } else if (dn) {
                px = 0, py = -1;
            } else {
                continue;
            }
            double dudx = (U[IX(i + 1, j)] - U[IX(i, j)]) / m->dx;
            double dvdy = (V[IX(i, j + 1)] - V[IX(i, j)]) / m->dy;
            double dudy = 0.25 * (U[IX(i + 1, j + 1)] + U[IX(i, j + 1)] -
                                  U[IX(i, j - 1)] - U[IX(i + 1, j - 1)]) / m->dy;
            double dvdx = 0.25 * (V[IX(i + 1, j + 1)] + V[IX(i + 1, j)] -
                                  V[IX(i - 1, j + 1)] - V[IX(i - 1, j)]) / m->dx;
            m->p[IX(i, j)] = 2.0 * m->prm.mu *
                             (px * px * dudx + px * py * (dudy + dvdx) +
                              py * py * dvdy);
        }
}

/* The update the scene selected: (3.11)/(3.12) ("modified": P/rho of each
 * cell) or (3.6)-(3.9) (P difference over the face density).  Face between
 * cell a (lower I or J) and cell b; psi is XI or ZETA on it. */
static double update_face(const bf_mac *m, size_t a, size_t b, double psi,
                          double delta)
{
    const double *R = m->r, *P = m->p;
    double rf = R[a] + R[b];
    if (m->prm.update == BF_MAC_ORIGINAL)
        return 2.0 * psi / rf + m->dt * (P[a] - P[b]) / delta / (0.5 * rf);
    return 2.0 * psi / rf + m->dt * (P[a] / R[a] - P[b] / R[b]) / delta;
}

/* Divergence of SUR cell (i,j) with its current faces. */
static double cell_div(const bf_mac *m, int i, int j)
{
    return (m->u[IX(i + 1, j)] - m->u[IX(i, j)]) / m->dx +
           (m->v[IX(i, j + 1)] - m->v[IX(i, j)]) / m->dy;
}

/* Faces of SUR cells: zero shear between two SUR cells (rule b), then the
 * faces towards empty cells (rule c). */
static void surface_velocities_shear(bf_mac *m)
{
    double *U = m->u, *V = m->v;
    const int *F = m->ic;
    const double rxy = m->dy / m->dx, ryx = m->dx / m->dy;
    for (int i = 3; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            if (F[IX(i - 1, j)] != BF_MAC_SUR || F[IX(i, j)] != BF_MAC_SUR)
                continue;
            if (F[IX(i - 1, j - 1)] == BF_MAC_FULL || F[IX(i, j - 1)] == BF_MAC_FULL)
                U[IX(i, j)] = U[IX(i, j - 1)] - rxy * (V[IX(i, j)] - V[IX(i - 1, j)]);
            else if (F[IX(i - 1, j + 1)] == BF_MAC_FULL ||
                     F[IX(i, j + 1)] == BF_MAC_FULL)
                U[IX(i, j)] = U[IX(i, j + 1)] +
                              rxy * (V[IX(i, j + 1)] - V[IX(i - 1, j + 1)]);
        }
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 3; j <= m->nj - 1; j++) {
            if (F[IX(i, j - 1)] != BF_MAC_SUR || F[IX(i, j)] != BF_MAC_SUR)
                continue;
            if (F[IX(i - 1, j - 1)] == BF_MAC_FULL || F[IX(i - 1, j)] == BF_MAC_FULL)
                V[IX(i, j)] = V[IX(i - 1, j)] - ryx * (U[IX(i, j)] - U[IX(i, j - 1)]);
            else if (F[IX(i + 1, j - 1)] == BF_MAC_FULL ||
                     F[IX(i + 1, j)] == BF_MAC_FULL)
                V[IX(i, j)] = V[IX(i + 1, j)] +
                              ryx * (U[IX(i + 1, j)] - U[IX(i + 1, j - 1)]);
        }
}

static void surface_velocities_empty(bf_mac *m)
{
    double *U = m->u, *V = m->v;
    const int *F = m->ic;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            if (F[IX(i, j)] != BF_MAC_SUR)
                continue;
            /* order of the listing's tests: above, right, left, below */
            int e[4] = {F[IX(i, j + 1)] == BF_MAC_EMP, F[IX(i + 1, j)] == BF_MAC_EMP,
                        F[IX(i - 1, j)] == BF_MAC_EMP, F[IX(i, j - 1)] == BF_MAC_EMP};
            int n = e[0] + e[1] + e[2] + e[3];
            if (!n)
                continue;
            double *face[4] = {&V[IX(i, j + 1)], &U[IX(i + 1, j)], &U[IX(i, j)],
                               &V[IX(i, j)]};
            const double *opp[4] = {&V[IX(i, j)], &U[IX(i, j)], &U[IX(i + 1, j)],
                                    &V[IX(i, j + 1)]};
            /* outward sign and spacing of each face in the divergence */
            const double sg[4] = {1, 1, -1, -1};
            const double h[4] = {m->dy, m->dx, m->dx, m->dy};
            int adjacent_pair = n == 2 && !(e[0] && e[3]) && !(e[1] && e[2]);
            if (adjacent_pair) {
                /* Welch: two empty sides at a corner copy the opposite
                 * faces, which keeps the cell divergence-free */
                for (int k = 0; k < 4; k++)
                    if (e[k])
                        *face[k] = *opp[k];
                continue;
            }
            int first = e[0] ? 0 : e[1] ? 1 : e[2] ? 2 : 3;
            for (int k = 0; k < 4; k++)
                if (e[k])
                    *face[k] = 0.0;
            /* the first empty face absorbs the divergence */
            double d = cell_div(m, i, j);
            *face[first] -= sg[first] * h[first] * d;
        }
}

void bf_mac_velocities(bf_mac *m)
{
    const int ni = m->ni, nj = m->nj;
    double *U = m->u, *V = m->v;
    const int *F = m->ic;
    for (size_t k = 0; k < m->ncell; k++)
        U[k] = V[k] = 0.0; /* labels 300-301 */
    /* (a) faces of FULL cells whose other side is FULL or SUR */
    for (int i = 3; i <= ni - 1; i++)
        for (int j = 2; j <= nj - 1; j++) {
            int fa = F[IX(i - 1, j)], fb = F[IX(i, j)];
            if ((fa == BF_MAC_FULL && mac_fluidish(fb)) ||
                (fb == BF_MAC_FULL && mac_fluidish(fa)))
                U[IX(i, j)] = update_face(m, IX(i - 1, j), IX(i, j),
                                          m->xi[IX(i, j)], m->dx);
        }
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 3; j <= nj - 1; j++) {
            int fa = F[IX(i, j - 1)], fb = F[IX(i, j)];
            if ((fa == BF_MAC_FULL && mac_fluidish(fb)) ||
                (fb == BF_MAC_FULL && mac_fluidish(fa)))
                V[IX(i, j)] = update_face(m, IX(i, j - 1), IX(i, j),
                                          m->zeta[IX(i, j)], m->dy);
        }
    /* normal faces on the ring: walls stay 0; OUT faces from the update
     * with the OUT ghost pressure; a prescribed inflow */
    for (int j = 2; j <= nj - 1; j++) {
        if (!mac_fluidish(F[IX(2, j)]))
            continue;
        if (F[IX(1, j)] == BF_MAC_IN &&
            (m->prm.problem != BF_MAC_RESERVOIR || m->prm.inflow_prescribed))
            U[IX(2, j)] = m->prm.u0;
    }
    for (int j = 2; j <= nj - 1; j++) {
        if (F[IX(ni, j)] != BF_MAC_OUT || !mac_fluidish(F[IX(ni - 1, j)]))
            continue;
        if (F[IX(ni - 1, j)] == BF_MAC_SUR && F[IX(ni - 1, j - 1)] == BF_MAC_FULL)
            /* a SUR cell at the OUT boundary: zero shear (rule b) with the
             * OUT ghost's unaccelerated tangential velocity V(ni,J) =
             * V(ni-1,J) gives U(ni,J) = U(ni,J-1) */
            U[IX(ni, j)] = U[IX(ni, j - 1)];
        else
            U[IX(ni, j)] = update_face(m, IX(ni - 1, j), IX(ni, j),
                                       m->xi[IX(ni, j)], m->dx);
    }
    for (int i = 2; i <= ni - 1; i++)
        if (F[IX(i, 1)] == BF_MAC_OUT && mac_fluidish(F[IX(i, 2)]))
            V[IX(i, 2)] = update_face(m, IX(i, 1), IX(i, 2), m->zeta[IX(i, 2)],
                                      m->dy);
    /* (b) zero shear between SUR cells */
    surface_velocities_shear(m);
    /* the reservoir's inflow copies the face on its right */
    if (m->prm.problem == BF_MAC_RESERVOIR && !m->prm.inflow_prescribed)
        for (int j = 2; j <= nj - 1; j++)
            if (F[IX(1, j)] == BF_MAC_IN && mac_fluidish(F[IX(2, j)]))
                U[IX(2, j)] = U[IX(3, j)];
    /* (c) faces towards empty cells */
    surface_velocities_empty(m);
    /* ghost faces beyond the ring */
    for (int j = 2; j <= nj - 1; j++)
        if (F[IX(ni, j)] != BF_MAC_OUT)
            U[IX(ni + 1, j)] = U[IX(ni - 1, j)];
    for (int j = 2; j <= nj; j++) {
        int jl = j < nj ? j : nj - 1;
        int fl = F[IX(1, jl)], fr = F[IX(ni, jl)];
        V[IX(1, j)] = fl == BF_MAC_FREESLIP ? V[IX(2, j)] : -V[IX(2, j)];
        V[IX(ni, j)] = (fr == BF_MAC_FREESLIP || fr == BF_MAC_OUT)
                           ? V[IX(ni - 1, j)]
                           : -V[IX(ni - 1, j)];
    }
    for (int i = 2; i <= ni; i++) {
        int fa = F[IX(i - 1, 1)], fb = F[IX(i, 1)];
        int slip = fa == BF_MAC_OUT || fb == BF_MAC_OUT ||
                   fa == BF_MAC_FREESLIP || fb == BF_MAC_FREESLIP;
        U[IX(i, 1)] = slip ? U[IX(i, 2)] : -U[IX(i, 2)];
        int ta = F[IX(i - 1, nj)], tb = F[IX(i, nj)];
        int tslip = ta == BF_MAC_FREESLIP || tb == BF_MAC_FREESLIP;
        U[IX(i, nj)] = tslip ? U[IX(i, nj - 1)] : -U[IX(i, nj - 1)];
    }
    /* beyond the left ring, u_{g-1/2} = u_{c+1/2}; the corner rows too,
     * since the IN markers of the lowest row interpolate with U(1,1) */
    for (int j = 1; j <= nj; j++)
        U[IX(1, j)] = U[IX(3, j)];
    for (int i = 2; i <= ni - 1; i++) {
        V[IX(i, nj + 1)] = V[IX(i, nj - 1)];
        if (F[IX(i, 1)] == BF_MAC_OUT) /* continuity in the OUT cell */
            V[IX(i, 1)] = V[IX(i, 2)] +
                          m->dy / m->dx * (U[IX(i + 1, 1)] - U[IX(i, 1)]);
        else
            V[IX(i, 1)] = V[IX(i, 3)];
    }
    for (int j = 2; j <= nj - 1; j++)
        if (F[IX(ni, j)] == BF_MAC_OUT)
            U[IX(ni + 1, j)] = U[IX(ni, j)] -
                               m->dx / m->dy * (V[IX(ni, j + 1)] - V[IX(ni, j)]);
}

/* Temperature boundary conditions and (3.14), labels 500-517: empty cells
 * T = 0; walls and OUT adiabatic (T_g = T_c); the IN column holds the
 * initial profile T0(J); a SUR cell takes T from a FULL neighbour (tested
 * above, right, left, below; the last one found wins).  The update of FULL
 * cells is conservative with centred face values and forward Euler; the
 * conduction coefficient is alpha/rho (thesis) or ALPHA*MU/R (listing). */
void bf_mac_temperature(bf_mac *m)
{
    double *T = m->t;
    const int *F = m->ic;
    const int ni = m->ni, nj = m->nj;
    for (size_t k = 0; k < m->ncell; k++)
        if (F[k] == BF_MAC_EMP)
            T[k] = 0.0;
    for (int i = 2; i <= ni - 1; i++) {
        T[IX(i, 1)] = T[IX(i, 2)];
        T[IX(i, nj)] = T[IX(i, nj - 1)];
    }
    for (int j = 2; j <= nj - 1; j++) {
        T[IX(ni, j)] = T[IX(ni - 1, j)];
        if (F[IX(1, j)] == BF_MAC_IN) {
            if (j <= m->nsur)
                T[IX(1, j)] = m->to[j];
        } else {
            T[IX(1, j)] = T[IX(2, j)];
        }
    }
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 2; j <= nj - 1; j++) {
            if (F[IX(i, j)] != BF_MAC_SUR)
                continue;
            if (F[IX(i, j + 1)] == BF_MAC_FULL)
                T[IX(i, j)] = T[IX(i, j + 1)];
            if (F[IX(i + 1, j)] == BF_MAC_FULL)
                T[IX(i, j)] = T[IX(i + 1, j)];
            if (F[IX(i - 1, j)] == BF_MAC_FULL)
                T[IX(i, j)] = T[IX(i - 1, j)];
            if (F[IX(i, j - 1)] == BF_MAC_FULL)
                T[IX(i, j)] = T[IX(i, j - 1)];
        }
    const double kap = m->prm.kappa_listing ? m->prm.alpha * m->prm.mu : m->prm.alpha;
    const double dx = m->dx, dy = m->dy, dt = m->dt;
    const double *U = m->u, *V = m->v;
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 2; j <= nj - 1; j++) {
            if (F[IX(i, j)] != BF_MAC_FULL)
                continue;
            double tc = T[IX(i, j)];
            double tl = 0.5 * (T[IX(i - 1, j)] + tc);
            double tr = 0.5 * (T[IX(i + 1, j)] + tc);
            double tt = 0.5 * (T[IX(i, j + 1)] + tc);
            double tb = 0.5 * (T[IX(i, j - 1)] + tc);
            double dtx2 = (T[IX(i + 1, j)] - 2.0 * tc + T[IX(i - 1, j)]) / (dx * dx);
            double dty2 = (T[IX(i, j + 1)] - 2.0 * tc + T[IX(i, j - 1)]) / (dy * dy);
            m->tn[IX(i, j)] =
                tc + dt * ((U[IX(i, j)] * tl - U[IX(i + 1, j)] * tr) / dx +
                           (V[IX(i, j)] * tb - V[IX(i, j + 1)] * tt) / dy +
                           kap / m->r[IX(i, j)] * (dtx2 + dty2));
        }
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 2; j <= nj - 1; j++)
            if (F[IX(i, j)] == BF_MAC_FULL)
                T[IX(i, j)] = m->tn[IX(i, j)];
}
