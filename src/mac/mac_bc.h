/* mac_bc.h: boundary conditions of the MAC solver (mac_bc.c; private).
 * Built on mac_grid.c. */
#ifndef BALLFILM_MAC_BC_H
#define BALLFILM_MAC_BC_H

#include "mac/mac_grid.h"

/* Ring densities mirror the fluid. */
void bf_mac_mirror_density(bf_mac *m);
/* Free-surface pressure (2.20) in every SUR cell. */
void bf_mac_surface_pressure(bf_mac *m);
/* Ghost pressures of the ring cells in p from the interior of p. */
void bf_mac_ghost_pressure(bf_mac *m, double *p);
/* Face velocities from the pressure, and every boundary rule. */
void bf_mac_velocities(bf_mac *m);
/* Temperature boundary conditions and (3.14). */
void bf_mac_temperature(bf_mac *m);

/* The condition on the face between interior cell (ic,jc) and its ring
 * neighbour g = (ig,jg): MAC_DIRICHLET with *val = the ghost pressure (the
 * IN boundary's hydrostatic P0), or MAC_FLUX with *val = the normal face
 * velocity it imposes (0 on walls, u0 at a prescribed inflow, the
 * momentum update with Welch's ghost pressure at an OUT boundary). */
enum { MAC_DIRICHLET = 0, MAC_FLUX = 1 };
int bf_mac_boundary_face(const bf_mac *m, int ig, int jg, int ic, int jc,
                         double *val);

#endif
