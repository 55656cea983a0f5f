/* compare.h: local comparison of two integrators along one trajectory.
 *
 * At every output row, from the state (x, v) of the run at that time, one
 * step of integrator a and one step of integrator b are taken (on copies;
 * the run is not touched) and the difference of the resulting velocities
 * v_a - v_b is written to /compare/dv [rows x balls] (cm/s).  With a =
 * verlet and b = alpha (alpha = 1/8, the default) along an MV2M run this
 * is the difference between the two velocity formulas that MV2M averages,
 * Yasuda eqs 2.19 and 2.20: zero in free fall (both are exact for a
 * constant force), non-zero only during collisions (Fig. 4).  Both use
 * their default parameters.  Costs two steps per output row, nothing per
 * step.
 */
#ifndef BALLFILM_COMPARE_H
#define BALLFILM_COMPARE_H

#include "ballfilm/ballsys.h"
#include "ballfilm/h5out.h"

typedef struct bf_compare bf_compare;

extern const bf_section_spec bf_compare_spec; /* [compare] */

/* *out is NULL when [compare] a is empty. */
bf_status bf_compare_create(bf_compare **out, const bf_scene *sc,
                            const bf_ballsys *sys, bf_err *err);
void bf_compare_free(bf_compare *c);
bf_status bf_compare_output_open(bf_compare *c, bf_out *out, bf_err *err);
/* Append the row for the current state at time t with step dt. */
bf_status bf_compare_output_row(bf_compare *c, const bf_ballsys *sys, double t,
                                double dt, bf_err *err);

#endif
