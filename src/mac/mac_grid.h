/* mac_grid.h: the state of the MAC solver and the grid helpers every file
 * of src/mac builds on (private).
 *
 * The files of the folder call one another in one direction, bottom to
 * top; each private header declares the functions of one file:
 *   mac_grid.c      the flood over interior cells, the faces of a cell;
 *   mac_bc.c        boundary conditions (on mac_grid.c);
 *   mac_pressure.c  the pressure equation, relaxation and direct solve
 *                   (on mac_bc.c and mac_grid.c);
 *   mac_markers.c   marker particles, cell flags, corrected density (on
 *                   mac_grid.c);
 *   mac.c           set-up, the eight-step time step, views, checkpoints
 *                   (on all of them; its interface is mac.h).
 * The types that mac.h shares are in mac_types.h.
 */
#ifndef BALLFILM_MAC_GRID_H
#define BALLFILM_MAC_GRID_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/particles.h"
#include "mac/mac_types.h"

struct bf_mac {
    bf_mac_params prm;
    int ni, nj;       /* cells including the ring (listing NI, NJ) */
    int st;           /* stride: nj + 2 */
    size_t ncell;     /* (ni + 2) (nj + 2) */
    double dx, dy, dt;
    double depth;     /* (nj - 2) dy: DEPTH of the relaxation test */
    double part_area; /* dx dy / 4: the share of a cell one marker carries */
    int nsur;         /* initial last row holding particles (listing NSUR) */
    int out_lo, out_hi; /* bottom OUT cells I = out_lo..out_hi (reservoir) */

    /* state at t = n dt */
    double *u, *v, *p, *r, *t;
    int *ic;
    /* work arrays, allocated once */
    double *rn;         /* predicted density (3.13) */
    double *xi, *zeta;  /* psi, zeta of (3.3)/(3.4) */
    double *pn, *pold;  /* relaxation */
    double *a, *b1, *b2, *b3, *b4;
    double *tn;
    int *ncnt;          /* particles per cell */
    double *s;          /* sum of particle densities per cell */
    double *po, *to;    /* inflow pressure and temperature per row */
    double *ro;         /* particle densities of the 2 nd rows (RO) */
    int nro;
    /* direct solver: band Cholesky of the interior cells */
    int nunk, bw;
    double *band, *band0, *rhs, *sol, *pex;
    int *mark, *queue;
    /* pressure coefficients (mac_pressure.c): the densities they were
     * last computed from, and per cell the step (nstep) they belong to */
    double *rcoef;
    long *cstamp;
    long nstep; /* steps taken by this object (1 in the first) */
    /* The two shortcuts of the corrector passes (markers that cannot
     * change cell, coefficients whose densities did not change) and how
     * often they were taken; full_passes = 1 turns them off (tests). */
    int full_passes;
    long long skipped_moves, kept_coefficients;

    /* markers: x, y, vx, vy (velocity of the last move), m (mass),
     * tag = particle flag */
    bf_particles part;
    double *dens, *xn, *yn;
    /* marker motion (mac_markers.c): each marker's cell index IX after
     * the move of the current pass (-1: free slot or off the grid); after
     * the first pass its cell, the cell it started from and the margin
     * in cells by which it landed inside (-1: a later pass must move it);
     * the face velocities of the first pass, their changes since and the
     * bound per start cell; the first marker whose move was not finite
     * (-1: none) */
    int *mcell, *mcell1, *mstart;
    double *slack, *uref, *vref, *mdu, *mdv, *mbound;
    long nonfinite;

    bf_mac_counts cnt;
    long voids_filled; /* cells filled by void_fix in the current step */
    int last_passes;
    long last_sweeps;
};

static inline size_t mac_ix(const bf_mac *m, int i, int j)
{
    return (size_t)i * (size_t)m->st + (size_t)j;
}

#define IX(i, j) mac_ix(m, (i), (j))

/* The interior (not ring) cells. */
static inline int mac_interior(const bf_mac *m, int i, int j)
{
    return i >= 2 && i <= m->ni - 1 && j >= 2 && j <= m->nj - 1;
}

/* Cells whose pressure enters the velocity update of a face: FULL and SUR
 * cells. */
static inline int mac_fluidish(int flag)
{
    return flag == BF_MAC_FULL || flag == BF_MAC_SUR;
}

/* Index of interior cell (i,j) among the unknowns of the pressure
 * equation (and in m->mark, m->queue): (I-2)(nj-2) + J-2. */
static inline int mac_unk(const bf_mac *m, int i, int j)
{
    return (i - 2) * (m->nj - 2) + (j - 2);
}

/* The pressure equation and the update in x = P/rho with cell densities
 * (BF_MAC_CONSISTENT) rather than x = P with face densities. */
static inline int mac_consistent(const bf_mac *m)
{
    return m->prm.update == BF_MAC_CONSISTENT;
}

/* Breadth-first flood over interior cells.  The caller has marked the
 * seeds (m->mark, index mac_unk) and queued the first `n` of them in
 * m->queue; every interior cell reachable through cells whose flag
 * satisfies `pass` gets marked. */
void bf_mac_flood(bf_mac *m, int n, int (*pass)(int flag));

/* One face of cell (i,j) towards direction d (MAC_E, MAC_W, MAC_N,
 * MAC_S): the neighbour, the spacing normal to the face, psi or zeta on
 * it, the face density (mean of the two cells) and the sign s of the
 * outward normal (+1 towards larger I or J). */
enum { MAC_E = 0, MAC_W = 1, MAC_N = 2, MAC_S = 3 };
typedef struct mac_face {
    int i, j;
    double delta, psi, rhof, s;
} mac_face;
void bf_mac_face_of(const bf_mac *m, int i, int j, int d, mac_face *f);

#endif
