/* mac_markers.c: the marker particles of the MAC solver (thesis ch. III,
 * steps 4-5 and Figure 2; listing labels 400-459 and 432-448).
 *
 * Velocity of a particle (Fig. 2): a dx x dy rectangle centred on the
 * particle overlaps the dx x dy rectangles centred on the four nearest u
 * (or v) points; each velocity's weight is the overlapped fraction.  That
 * is bilinear interpolation.  Motion is forward Euler from the position at
 * t = n dt with the provisional velocities of the current corrector pass:
 * x_new = x + u_k dt, y_new = y + v_k dt (results in XN, YN; X = XN only
 * after the final pass).  IN particles move horizontally only; OUT
 * particles move along the outward normal with the OUT face velocity.
 * Fluid markers whose move would cross a wall stop on it (wall_markers =
 * hold); the listing instead deletes them after the final pass.
 *
 * Density correction (step 5, label 426): rho_ij = sum_k rho_k / N_ij over
 * the particles in the cell.  A cell is FULL if it holds particles, SUR if
 * it is empty but a neighbour (ring cells included) holds particles, else
 * EMP (label 418).  SUR cells take the density of the cell below (label
 * 459); where that is not FULL we use the mean density of the neighbours
 * holding particles (the listing would divide by R = 0 in (3.11)).
 *
 * Particle flags after the final pass (labels 432-448): an IN particle
 * that crossed into the fluid becomes REG and a new IN particle of the same
 * density goes half a cell to its left ("OUT OF PARTICLES" if no slot is
 * free); a REG particle in an OUT cell becomes OUT; an OUT particle that
 * left its OUT cell frees its slot; a REG particle anywhere else outside
 * the fluid cells is removed (counted as backflow in the IN column, lost
 * otherwise).
 */
#include "mac/mac_markers.h"

#include <math.h>

/* cell index of coordinate x (listing: I = X/DX + 2, Fortran truncation;
 * floor agrees for every cell of the grid and stays monotone outside) */
static int cell_of(double x, double h)
{
    return (int)floor(x / h) + 2;
}

static int clampi(int k, int lo, int hi) { return k < lo ? lo : k > hi ? hi : k; }

static double interp_u(const bf_mac *m, double x, double y)
{
    double fx = x / m->dx + 2.0, fy = y / m->dy + 1.5;
    int i = clampi((int)floor(fx), 1, m->ni);
    int j = clampi((int)floor(fy), 1, m->nj - 1);
    double ax = fx - (double)i, ay = fy - (double)j;
    const double *U = m->u;
    return (1 - ax) * (1 - ay) * U[IX(i, j)] + ax * (1 - ay) * U[IX(i + 1, j)] +
           (1 - ax) * ay * U[IX(i, j + 1)] + ax * ay * U[IX(i + 1, j + 1)];
}

static double interp_v(const bf_mac *m, double x, double y)
{
    double fx = x / m->dx + 1.5, fy = y / m->dy + 2.0;
    int i = clampi((int)floor(fx), 1, m->ni - 1);
    int j = clampi((int)floor(fy), 1, m->nj);
    double bx = fx - (double)i, by = fy - (double)j;
    const double *V = m->v;
    return (1 - bx) * (1 - by) * V[IX(i, j)] + bx * (1 - by) * V[IX(i + 1, j)] +
           (1 - bx) * by * V[IX(i, j + 1)] + bx * by * V[IX(i + 1, j + 1)];
}

static int is_wall(int flag)
{
    return flag == BF_MAC_NOSLIP || flag == BF_MAC_FREESLIP;
}

/* The largest coordinate below the wall at w that still lies in cell
 * `cell`. */
static double inside_of(double w, double h, int cell)
{
    double x = w;
    while (cell_of(x, h) > cell)
        x = nextafter(x, -INFINITY);
    return x;
}

/* wall_markers = hold [not in the listing]: a fluid marker whose move ends
 * beyond a wall (interpolation mixes the wall's zero normal velocity with
 * the sink's next to it) stops on the wall instead of being deleted.
 * Returns 1 if the move was cut. */
static int hold_on_walls(const bf_mac *m, double *xn, double *yn)
{
    int held = 0;
    int i = cell_of(*xn, m->dx), j = cell_of(*yn, m->dy);
    int jj = clampi(j, 2, m->nj - 1);
    if (i < 2 && is_wall(m->ic[IX(1, jj)])) {
        *xn = 0.0;
        held = 1;
    } else if (i > m->ni - 1 && is_wall(m->ic[IX(m->ni, jj)])) {
        *xn = inside_of((double)(m->ni - 2) * m->dx, m->dx, m->ni - 1);
        held = 1;
    }
    int ii = clampi(cell_of(*xn, m->dx), 2, m->ni - 1);
    if (j < 2 && is_wall(m->ic[IX(ii, 1)])) {
        *yn = 0.0;
        held = 1;
    } else if (j > m->nj - 1 && is_wall(m->ic[IX(ii, m->nj)])) {
        *yn = inside_of((double)(m->nj - 2) * m->dy, m->dy, m->nj - 1);
        held = 1;
    }
    return held;
}

long bf_mac_move_markers(bf_mac *m)
{
    bf_particles *pt = &m->part;
    const double dt = m->dt;
    long held = 0;
    for (size_t k = 0; k < pt->n; k++) {
        int f = pt->tag[k];
        double x = pt->x[k], y = pt->y[k];
        double vx = 0, vy = 0;
        if (f == BF_MAC_AVAIL)
            continue;
        if (f == BF_MAC_OUT) {
            int i = clampi(cell_of(x, m->dx), 1, m->ni);
            int j = clampi(cell_of(y, m->dy), 1, m->nj);
            if (j == 1)
                vy = m->v[IX(i, 2)];
            else if (i == m->ni)
                vx = m->u[IX(m->ni, j)];
        } else {
            vx = interp_u(m, x, y);
            if (f == BF_MAC_REG)
                vy = interp_v(m, x, y);
        }
        pt->vx[k] = vx;
        pt->vy[k] = vy;
        m->xn[k] = x + vx * dt;
        m->yn[k] = y + vy * dt;
        if (f == BF_MAC_REG && !m->prm.wall_remove)
            held += hold_on_walls(m, &m->xn[k], &m->yn[k]);
    }
    return held;
}

bf_status bf_mac_markers_finite(const bf_mac *m, bf_err *err)
{
    for (size_t k = 0; k < m->part.n; k++)
        if (m->part.tag[k] != BF_MAC_AVAIL &&
            (!isfinite(m->xn[k]) || !isfinite(m->yn[k])))
            return bf_fail(err, BF_EUNSTABLE, "particle %zu: non-finite "
                           "position after the move", k + 1);
    return BF_OK;
}

/* void_fix [not in the thesis]: empty cells that no chain of empty cells
 * connects to an EMP cell are a hole inside the fluid (the listing makes
 * them SUR cells that keep an old pressure, a Dirichlet value inside the
 * fluid).  Fill them: FULL, with the mean density of the neighbours that
 * hold particles (or, deeper inside a large hole, of filled neighbours).
 * Returns the number of cells filled. */
static int not_full(int flag) { return flag != BF_MAC_FULL; }

static void flood_from_empty(bf_mac *m)
{
    int n = 0;
    for (int k = 0; k < m->nunk; k++)
        m->mark[k] = 0;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            if (m->ic[IX(i, j)] == BF_MAC_EMP) {
                m->mark[mac_unk(m, i, j)] = 1;
                m->queue[n++] = mac_unk(m, i, j);
            }
    bf_mac_flood(m, n, not_full);
}

int bf_mac_find_void(bf_mac *m, int *vi, int *vj)
{
    int n = 0;
    flood_from_empty(m);
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++)
            if (m->ic[IX(i, j)] != BF_MAC_FULL && !m->mark[mac_unk(m, i, j)] &&
                !n++) {
                *vi = i;
                *vj = j;
            }
    return n;
}

static int fill_voids(bf_mac *m)
{
    int filled = 0;
    flood_from_empty(m);
    /* fill the unreached ones, repeating while a hole's inside has no
     * filled neighbour yet */
    for (int again = 1; again;) {
        again = 0;
        for (int i = 2; i <= m->ni - 1; i++)
            for (int j = 2; j <= m->nj - 1; j++) {
                size_t c = IX(i, j);
                if (m->ic[c] == BF_MAC_FULL || m->mark[mac_unk(m, i, j)])
                    continue;
                size_t nb[4] = {IX(i, j - 1), IX(i + 1, j), IX(i - 1, j),
                                IX(i, j + 1)};
                double s = 0;
                int cnt = 0;
                for (int d = 0; d < 4; d++) {
                    if (m->ncnt[nb[d]]) {
                        s += m->s[nb[d]] / m->ncnt[nb[d]];
                        cnt++;
                    } else if (m->ic[nb[d]] == BF_MAC_FULL && m->r[nb[d]] > 0) {
                        s += m->r[nb[d]];
                        cnt++;
                    }
                }
                if (!cnt) {
                    again = 1;
                    continue;
                }
                m->ic[c] = BF_MAC_FULL;
                m->r[c] = s / cnt;
                filled++;
            }
    }
    return filled;
}

int bf_mac_correct_density(bf_mac *m)
{
    const bf_particles *pt = &m->part;
    int *N = m->ncnt;
    double *S = m->s, *R = m->r;
    for (size_t c = 0; c < m->ncell; c++) {
        N[c] = 0;
        S[c] = 0.0;
    }
    for (size_t k = 0; k < pt->n; k++) {
        if (pt->tag[k] == BF_MAC_AVAIL)
            continue;
        int i = cell_of(m->xn[k], m->dx), j = cell_of(m->yn[k], m->dy);
        if (i < 1 || i > m->ni || j < 1 || j > m->nj)
            continue;
        N[IX(i, j)]++;
        S[IX(i, j)] += m->dens[k];
    }
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            size_t c = IX(i, j);
            if (N[c])
                m->ic[c] = BF_MAC_FULL;
            else if (N[IX(i, j + 1)] || N[IX(i, j - 1)] || N[IX(i + 1, j)] ||
                     N[IX(i - 1, j)])
                m->ic[c] = BF_MAC_SUR;
            else
                m->ic[c] = BF_MAC_EMP;
        }
    int changed = 0;
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            size_t c = IX(i, j);
            if (!N[c]) {
                R[c] = 0.0;
                continue;
            }
            double q = S[c] / N[c];
            if (q != R[c]) {
                R[c] = q;
                changed = 1;
            }
        }
    if (m->prm.void_fix)
        m->voids_filled += fill_voids(m);
    for (int i = 2; i <= m->ni - 1; i++)
        for (int j = 2; j <= m->nj - 1; j++) {
            size_t c = IX(i, j);
            if (m->ic[c] != BF_MAC_SUR)
                continue;
            if (m->ic[IX(i, j - 1)] == BF_MAC_FULL) {
                R[c] = R[IX(i, j - 1)];
                continue;
            }
            size_t nb[4] = {IX(i, j - 1), IX(i + 1, j), IX(i - 1, j), IX(i, j + 1)};
            double s = 0;
            int cnt = 0;
            for (int d = 0; d < 4; d++)
                if (N[nb[d]]) {
                    s += S[nb[d]] / N[nb[d]];
                    cnt++;
                }
            R[c] = cnt ? s / cnt : R[IX(i, j - 1)];
        }
    return changed;
}

bf_status bf_mac_reflag_markers(bf_mac *m, bf_err *err)
{
    bf_particles *pt = &m->part;
    const double a = m->part_area;
    for (size_t k = 0; k < pt->n; k++) {
        int f = pt->tag[k];
        if (f == BF_MAC_AVAIL)
            continue;
        int i = cell_of(m->xn[k], m->dx), j = cell_of(m->yn[k], m->dy);
        int inside = i >= 1 && i <= m->ni && j >= 1 && j <= m->nj;
        if (f == BF_MAC_PIN) {
            if (i < 2) {
                if (m->xn[k] < -m->dx) {
                    /* backflow pushed it past the ring: hold it at the
                     * ring's outer edge (the reservoir continues there) */
                    m->xn[k] = -m->dx;
                    m->cnt.in_clamped++;
                }
                continue;
            }
            pt->tag[k] = BF_MAC_REG;
            m->cnt.entered++;
            m->cnt.mass_in += m->dens[k] * a;
            size_t kk;
            for (kk = 0; kk < pt->n; kk++)
                if (pt->tag[kk] == BF_MAC_AVAIL)
                    break;
            if (kk == pt->n)
                return bf_fail(err, BF_EUNSTABLE, "out of particles: all %zu "
                               "slots are in use when particle %zu enters; "
                               "raise [mac] slots", pt->n, k + 1);
            pt->tag[kk] = BF_MAC_PIN;
            m->xn[kk] = m->xn[k] - 0.5 * m->dx;
            m->yn[kk] = m->yn[k];
            m->dens[kk] = m->dens[k];
            pt->m[kk] = pt->m[k];
            pt->vx[kk] = pt->vx[k];
            pt->vy[kk] = 0.0;
            continue;
        }
        int in_out_cell = inside && m->ic[IX(i, j)] == BF_MAC_OUT;
        if (f == BF_MAC_OUT) {
            if (!in_out_cell) {
                pt->tag[k] = BF_MAC_AVAIL;
                m->cnt.freed++;
            }
            continue;
        }
        /* REG */
        if (in_out_cell) {
            pt->tag[k] = BF_MAC_OUT;
            m->cnt.left_out++;
            m->cnt.mass_out += m->dens[k] * a;
        } else if (!mac_interior(m, i, j)) {
            pt->tag[k] = BF_MAC_AVAIL;
            if (i == 1 && j >= 2 && j <= m->nj - 1 &&
                m->ic[IX(1, j)] == BF_MAC_IN) {
                m->cnt.backflow++;
                m->cnt.mass_back += m->dens[k] * a;
            } else {
                m->cnt.lost++;
                m->cnt.mass_lost += m->dens[k] * a;
            }
        }
    }
    for (size_t k = 0; k < pt->n; k++) {
        if (pt->tag[k] == BF_MAC_AVAIL) {
            pt->x[k] = pt->y[k] = pt->vx[k] = pt->vy[k] = 0.0;
            pt->m[k] = m->dens[k] = m->xn[k] = m->yn[k] = 0.0;
        } else {
            pt->x[k] = m->xn[k];
            pt->y[k] = m->yn[k];
        }
    }
    return BF_OK;
}
