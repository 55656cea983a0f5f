/* mac_pressure.h: the pressure equation of the MAC solver and its two
 * solvers (mac_pressure.c; private).  Built on mac_bc.c and mac_grid.c. */
#ifndef BALLFILM_MAC_PRESSURE_H
#define BALLFILM_MAC_PRESSURE_H

#include "mac/mac_grid.h"

/* A, B1..B4 of (3.10) (or of the consistent equation) in the FULL cells. */
void bf_mac_pressure_coefficients(bf_mac *m);
/* Gauss-Seidel in m->p with the crude (fine = 0) or fine test; *sweeps
 * receives the sweeps made.  BF_ENOCONV after max_sweeps. */
bf_status bf_mac_relax(bf_mac *m, int fine, long *sweeps, bf_err *err);
/* The exact solution of the same equations into pout (m->p or another
 * array of ncell values).  BF_ENOCONV if singular or not accurate. */
bf_status bf_mac_direct(bf_mac *m, double *pout, bf_err *err);

#endif
