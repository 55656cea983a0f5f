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
#include <string.h>

/* floor(q) as an int for |q| < 2^30 (the same integer as (int)floor(q),
 * without the call the generic x86-64 build makes for floor); q beyond
 * that (a marker far off the grid) takes floor itself. */
static int ifloor(double q)
{
    if (!(fabs(q) < 1073741824.0))
        return (int)floor(q);
    int t = (int)q; /* truncation towards zero */
    return t - (q < (double)t);
}

/* cell index of coordinate x (listing: I = X/DX + 2, Fortran truncation;
 * floor agrees for every cell of the grid and stays monotone outside) */
static int cell_of(double x, double h)
{
    return ifloor(x / h) + 2;
}

static int clampi(int k, int lo, int hi) { return k < lo ? lo : k > hi ? hi : k; }

/* Bilinear velocities at a marker whose coordinates in cell units are
 * qx = x/dx, qy = y/dy (the same divisions serve both components and the
 * listing's I = X/DX + 2).  *inside is cleared when an index had to be
 * clamped (a marker beyond the ring): only unclamped weights lie in
 * [0, 1] and sum to 1. */
static double interp_u(const bf_mac *m, double qx, double qy, int *inside)
{
    double fx = qx + 2.0, fy = qy + 1.5;
    int i0 = ifloor(fx), j0 = ifloor(fy);
    int i = clampi(i0, 1, m->ni), j = clampi(j0, 1, m->nj - 1);
    *inside &= i == i0 && j == j0;
    double ax = fx - (double)i, ay = fy - (double)j;
    const double *U = m->u;
    return (1 - ax) * (1 - ay) * U[IX(i, j)] + ax * (1 - ay) * U[IX(i + 1, j)] +
           (1 - ax) * ay * U[IX(i, j + 1)] + ax * ay * U[IX(i + 1, j + 1)];
}

static double interp_v(const bf_mac *m, double qx, double qy, int *inside)
{
    double fx = qx + 1.5, fy = qy + 2.0;
    int i0 = ifloor(fx), j0 = ifloor(fy);
    int i = clampi(i0, 1, m->ni - 1), j = clampi(j0, 1, m->nj);
    *inside &= i == i0 && j == j0;
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
 * (i, j) is the cell of (*xn, *yn).  Returns 1 if the move was cut. */
static int hold_on_walls(const bf_mac *m, int i, int j, double *xn, double *yn)
{
    int held = 0;
    int jj = clampi(j, 2, m->nj - 1);
    if (i < 2 && is_wall(m->ic[IX(1, jj)])) {
        *xn = 0.0;
        held = 1;
    } else if (i > m->ni - 1 && is_wall(m->ic[IX(m->ni, jj)])) {
        *xn = inside_of((double)(m->ni - 2) * m->dx, m->dx, m->ni - 1);
        held = 1;
    }
    int ii = clampi(held ? cell_of(*xn, m->dx) : i, 2, m->ni - 1);
    if (j < 2 && is_wall(m->ic[IX(ii, 1)])) {
        *yn = 0.0;
        held = 1;
    } else if (j > m->nj - 1 && is_wall(m->ic[IX(ii, m->nj)])) {
        *yn = inside_of((double)(m->nj - 2) * m->dy, m->dy, m->nj - 1);
        held = 1;
    }
    return held;
}

/* Distance of q >= 0 to the nearest integer (exact: Sterbenz, up to one
 * rounding of 1 - q below q = 1/2). */
static double to_edge(double q)
{
    double f = (double)ifloor(q);
    double below = q - f, above = f + 1.0 - q;
    return below < above ? below : above;
}

/* Move marker k from its position at t = n dt with the current faces
 * (into xn, yn, vx, vy; its cell into mcell).  With `first`, record in
 * slack[k] how far inside its new cell the marker lands (in cells) and in
 * mstart[k] the cell it starts from, or slack -1 where a later pass may
 * not skip it: not a fluid marker, off the interior, clamped weights,
 * held at a wall.  Returns 1 if held at a wall. */
static int move_one(bf_mac *m, size_t k, int first)
{
    bf_particles *pt = &m->part;
    const double dt = m->dt;
    int f = pt->tag[k];
    double x = pt->x[k], y = pt->y[k];
    double vx = 0, vy = 0;
    int inside = 1, held = 0, start = -1;
    if (f == BF_MAC_OUT) {
        int i = clampi(cell_of(x, m->dx), 1, m->ni);
        int j = clampi(cell_of(y, m->dy), 1, m->nj);
        if (j == 1)
            vy = m->v[IX(i, 2)];
        else if (i == m->ni)
            vx = m->u[IX(m->ni, j)];
    } else {
        double qx = x / m->dx, qy = y / m->dy;
        vx = interp_u(m, qx, qy, &inside);
        if (f == BF_MAC_REG) {
            vy = interp_v(m, qx, qy, &inside);
            int i = ifloor(qx) + 2, j = ifloor(qy) + 2;
            if (mac_interior(m, i, j))
                start = (int)IX(i, j);
        }
    }
    pt->vx[k] = vx;
    pt->vy[k] = vy;
    double xn = x + vx * dt, yn = y + vy * dt;
    if (!isfinite(xn) || !isfinite(yn)) {
        if (m->nonfinite < 0)
            m->nonfinite = (long)k;
        m->xn[k] = xn;
        m->yn[k] = yn;
        m->mcell[k] = -1;
        if (first)
            m->slack[k] = -1;
        return 0;
    }
    double qx = xn / m->dx, qy = yn / m->dy;
    int i = ifloor(qx) + 2, j = ifloor(qy) + 2;
    if (f == BF_MAC_REG && !m->prm.wall_remove &&
        (held = hold_on_walls(m, i, j, &xn, &yn))) {
        i = cell_of(xn, m->dx);
        j = cell_of(yn, m->dy);
    }
    m->xn[k] = xn;
    m->yn[k] = yn;
    m->mcell[k] = i >= 1 && i <= m->ni && j >= 1 && j <= m->nj ? (int)IX(i, j)
                                                               : -1;
    if (first) {
        m->mcell1[k] = m->mcell[k];
        m->mstart[k] = start;
        m->slack[k] = start >= 0 && inside && !held && mac_interior(m, i, j)
                          ? fmin(to_edge(qx), to_edge(qy))
                          : -1;
    }
    return held;
}

static double max2(double a, double b) { return a > b ? a : b; }

/* For every interior cell c, how far (in cells) a marker starting in c
 * can land from where it landed in the first pass: dt over the spacing
 * times the largest change since the first pass of the faces its bilinear
 * velocities use (u faces I..I+2, J-1..J+1 and v faces I-1..I+1, J..J+2
 * of a start cell (I,J), one more than the four of each component to
 * cover the rounding of x/dx + 2), widened by 1e-6 of itself and 1e-9
 * cells.  Every face is finite here (check_velocities in mac.c stops the
 * step otherwise).  The 3 x 3 maxima are taken along J, then along I. */
static void move_bounds(bf_mac *m)
{
    double *eu = m->mdu, *ev = m->mdv, *B = m->mbound;
    const int ni = m->ni, nj = m->nj;
    for (size_t c = 0; c < m->ncell; c++) {
        eu[c] = fabs(m->u[c] - m->uref[c]);
        ev[c] = fabs(m->v[c] - m->vref[c]);
    }
    /* in place along J: eu(i,j) = max over j-1..j+1 (prev keeps the
     * overwritten j-1), ev(i,j) = max over j..j+2 */
    for (int i = 1; i <= ni + 1; i++) {
        double prev = eu[IX(i, 1)];
        for (int j = 2; j <= nj - 1; j++) {
            double cur = eu[IX(i, j)];
            eu[IX(i, j)] = max2(max2(prev, cur), eu[IX(i, j + 1)]);
            prev = cur;
            ev[IX(i, j)] = max2(max2(ev[IX(i, j)], ev[IX(i, j + 1)]),
                                ev[IX(i, j + 2)]);
        }
    }
    const double sx = m->dt / m->dx, sy = m->dt / m->dy;
    for (int i = 2; i <= ni - 1; i++)
        for (int j = 2; j <= nj - 1; j++) {
            double du = max2(max2(eu[IX(i, j)], eu[IX(i + 1, j)]),
                             eu[IX(i + 2, j)]);
            double dv = max2(max2(ev[IX(i - 1, j)], ev[IX(i, j)]),
                             ev[IX(i + 1, j)]);
            B[IX(i, j)] = max2(sx * du, sy * dv) * (1.0 + 1e-6) + 1e-9;
        }
}

/* The corrector passes move the markers again from the same positions
 * with slightly changed velocities, and only the cells they land in
 * matter until the final pass (the density correction counts markers per
 * cell).  A bilinear velocity is a convex combination of four faces, so
 * it changes by at most the largest change of those faces since the first
 * pass, and the marker's landing point by dt times that: a fluid marker
 * that landed farther than that inside its cell in the first pass lands
 * in the same cell again and is not moved.  The bound's widening is far
 * beyond the rounding of a move (about 1e-14 cells), so the cells are
 * exactly those a full move gives: the same results to the bit
 * (bench/mac_vs_plain.sh compares every output row with a program that
 * moves every marker in every pass). */
long bf_mac_move_markers(bf_mac *m, bf_mac_move mode)
{
    const size_t n = m->part.n;
    const int *tag = m->part.tag;
    long held = 0;
    m->nonfinite = -1;
    if (mode == BF_MAC_MOVE_CELLS) {
        move_bounds(m);
        for (size_t k = 0; k < n; k++) {
            /* slack >= 0: a fluid marker that started in an interior
             * cell mstart[k] */
            if (m->slack[k] >= 0 && m->slack[k] > m->mbound[m->mstart[k]]) {
                m->mcell[k] = m->mcell1[k];
                m->skipped_moves++;
            } else if (tag[k] != BF_MAC_AVAIL)
                held += move_one(m, k, 0);
            else
                m->mcell[k] = -1;
        }
        return held;
    }
    const int first = mode == BF_MAC_MOVE_FIRST;
    if (first) {
        memcpy(m->uref, m->u, m->ncell * sizeof *m->uref);
        memcpy(m->vref, m->v, m->ncell * sizeof *m->vref);
    }
    for (size_t k = 0; k < n; k++) {
        if (tag[k] != BF_MAC_AVAIL) {
            held += move_one(m, k, first);
        } else {
            m->mcell[k] = -1;
            if (first)
                m->slack[k] = -1;
        }
    }
    return held;
}

bf_status bf_mac_markers_finite(const bf_mac *m, bf_err *err)
{
    if (m->nonfinite >= 0)
        return bf_fail(err, BF_EUNSTABLE, "particle %ld: non-finite "
                       "position after the move", m->nonfinite + 1);
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
    /* the cells of the move (-1: free slot or off the grid), in slot
     * order as before: the same sums */
    const int *cell = m->mcell;
    for (size_t k = 0; k < pt->n; k++) {
        if (cell[k] < 0)
            continue;
        N[cell[k]]++;
        S[cell[k]] += m->dens[k];
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
