/* mac_internal.h: the state of the MAC solver, shared by the files of
 * src/mac/ (mac.c: set-up and the time step; mac_bc.c: boundary
 * conditions; mac_pressure.c: relaxation and direct solve; mac_markers.c:
 * marker particles, cell flags, corrected density).  Not a public header.
 */
#ifndef BALLFILM_MAC_INTERNAL_H
#define BALLFILM_MAC_INTERNAL_H

#include "mac/mac.h"

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

    /* markers: x, y, vx, vy (velocity of the last move), m (mass),
     * tag = particle flag */
    bf_particles part;
    double *dens, *xn, *yn;

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

/* mac.c: breadth-first flood over interior cells.  The caller has marked
 * the seeds (m->mark, index (I-2)(nj-2) + J-2) and queued the first `n` of
 * them in m->queue; every interior cell reachable through cells whose flag
 * satisfies `pass` gets marked. */
void bf_mac_flood(bf_mac *m, int n, int (*pass)(int flag));
static inline int mac_unk(const bf_mac *m, int i, int j)
{
    return (i - 2) * (m->nj - 2) + (j - 2);
}

/* mac_bc.c */
void bf_mac_mirror_density(bf_mac *m);
void bf_mac_surface_pressure(bf_mac *m);
void bf_mac_ghost_pressure(bf_mac *m, double *p);
void bf_mac_velocities(bf_mac *m);
void bf_mac_temperature(bf_mac *m);
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

/* The condition on the face between interior cell (ic,jc) and its ring
 * neighbour g = (ig,jg): MAC_DIRICHLET with *val = the ghost pressure (the
 * IN boundary's hydrostatic P0), or MAC_FLUX with *val = the normal face
 * velocity it imposes (0 on walls, u0 at a prescribed inflow, the
 * momentum update with Welch's ghost pressure at an OUT boundary). */
enum { MAC_DIRICHLET = 0, MAC_FLUX = 1 };
int bf_mac_boundary_face(const bf_mac *m, int ig, int jg, int ic, int jc,
                      double *val);

/* mac_pressure.c */
void bf_mac_pressure_coefficients(bf_mac *m);
bf_status bf_mac_relax(bf_mac *m, int fine, long *sweeps, bf_err *err);
bf_status bf_mac_direct(bf_mac *m, double *pout, bf_err *err);

/* mac_markers.c */
long bf_mac_move_markers(bf_mac *m); /* returns the moves held at a wall */
int bf_mac_correct_density(bf_mac *m);
bf_status bf_mac_reflag_markers(bf_mac *m, bf_err *err);
bf_status bf_mac_markers_finite(const bf_mac *m, bf_err *err);
int bf_mac_fill_voids(bf_mac *m);
/* Number of empty cells enclosed by fluid, and the first of them. */
int bf_mac_find_void(bf_mac *m, int *vi, int *vj);

#endif
