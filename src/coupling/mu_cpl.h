/* mu_cpl.h: the chemical potential the balls add to the film, Yasuda eq.
 * 3.11 (private to the library):
 *   mu_cpl(x) = sum_p 8 pi R_p^2 V0 exp(-|x - r_p|/r0) (psi(x) - psi_s),
 * on the film's nodes, with the kernel, the film and the constants of a
 * coupling (coupling.h).  The film step takes it as an argument
 * (bf_film_step_invariant); the coupled model owns the array.
 */
#ifndef BALLFILM_COUPLING_MU_CPL_H
#define BALLFILM_COUPLING_MU_CPL_H

#include <stddef.h>

#include "coupling/coupling.h"

/* mu_cpl of nb balls at x (radii R, cm) on the nodes 0..N of the
 * coupling's film at its current level, written to mu (N + 1 values, in
 * the units of mu, g/(cm s^2)). */
void bf_coupling_mu(const bf_coupling *c, size_t nb, const double *x,
                    const double *R, double *mu);

#endif
