/* hertz_pairs.h: Hertz contact between 2-D particles of one radius R, an
 * optional pair force of the Greenspan 1972 model ([hertz], off by
 * default).
 *
 * Two particles whose centres are r < 2R apart push each other apart
 * along the line of centres with
 *
 *   f = k x^{3/2},   x = max((2R - r)/2, 0),
 *
 * the law of src/contact/hertz.h (bf_hertz_pair_force with R_i = R_j = R;
 * x is the deformation of one particle), so that the pair's potential is
 * bf_hertz_pair_energy = (4/5) k x^{5/2} and -dE/dr = f.  Particle i gets
 * a_i = f (x_i - x_j)/(r m_i), particle j the opposite force.
 *
 * Units (CGS): k in g cm^{-1/2} s^{-2}, R in cm, accelerations in cm/s^2.
 */
#ifndef BALLFILM_PARTICLES_HERTZ_PAIRS_H
#define BALLFILM_PARTICLES_HERTZ_PAIRS_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"
#include "particles/cells.h"

/* The keys of [hertz] (bf_hertz_spec). */
typedef struct bf_hertz_keys {
    int enabled;
    double k;
    double radius; /* 0: the model's default (greenspan72: d/2) */
} bf_hertz_keys;

extern const bf_section_spec bf_hertz_spec; /* [hertz] */

typedef struct bf_hertz_pairs {
    double k; /* g cm^-1/2 s^-2 */
    double R; /* cm */
} bf_hertz_pairs;

/* Add the accelerations of every pair closer than 2R to ax, ay: all pairs,
 * O(N^2), pair (j, i > j) in the order of j, then i.  Returns 0, or 1 if
 * two particles coincide (no direction; *bi, *bj name the first such
 * pair). */
int bf_hertz_pairs_all(const bf_hertz_pairs *h, const double *x,
                       const double *y, const double *m, size_t n,
                       double *ax, double *ay, size_t *bi, size_t *bj);

/* The same from a cell list built with the masses as weights (any cell
 * side: the search reaches as many cells as 2R needs), in slot order of
 * the list; the same return value. */
int bf_hertz_pairs_cells(const bf_hertz_pairs *h, const bf_cells *c,
                         double *ax, double *ay, size_t *bi, size_t *bj);

#endif
