/* walls.h: a rectangular container whose walls reflect point particles,
 * with the reflected speed reduced by a factor omega (Greenspan 1972,
 * eq. 2.13: angle of reflection = angle of incidence, |v_r| = omega |v_i|,
 * 0 < omega <= 1).
 *
 * The rule is applied after a position update x^k -> x^{k+1} made with the
 * velocity v (the leapfrog half-step velocity in the 1972 model):
 *
 *   clean   (default, the text): if the straight segment x^k -> x^{k+1}
 *           leaves the box through wall W at the point H, then
 *              x^{k+1} <- H + omega R_W (x^{k+1} - H),  v <- omega R_W v,
 *           R_W negating the normal component; repeated from H until the
 *           particle is inside (corners, several walls in one step).  A
 *           corner hit exactly reflects both components.
 *   fortran (Schubert's WALCOL, literally): impact point and post-impact
 *           displacement from TANTH with the SIGN(EPS, .) guard, the
 *           velocity rebuilt as omega |v| (x2 - x1)/(|x2 - x1| + EPS).  Even
 *           with omega = 1 every hit multiplies the speed by |D|/(|D| + EPS),
 *           and for omega < 1 the outgoing direction is not specular:
 *           the rest of the step is scaled by omega^2 along the wall and
 *           by omega normal to it (docs/models/greenspan72.md, walls).
 *
 * Invariant: after bf_walls_apply every particle is in the closed box
 * [ax, bx] x [ay, by]; a particle that cannot be brought back (non-finite,
 * or more than BF_WALLS_MAX_HITS reflections in one step) fails the step
 * with BF_EUNSTABLE naming it.  Units: cm and cm/s.
 */
#ifndef BALLFILM_PARTICLES_WALLS_H
#define BALLFILM_PARTICLES_WALLS_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/params.h"
#include "ballfilm/particles.h"

#define BF_WALLS_MAX_HITS 10000

typedef struct bf_box {
    double ax, bx, ay, by; /* cm */
} bf_box;

typedef enum bf_wall_rule { BF_WALL_CLEAN = 0, BF_WALL_FORTRAN = 1 } bf_wall_rule;

typedef struct bf_walls {
    bf_box box;
    double omega;      /* speed factor at each hit, (0, 1] */
    bf_wall_rule rule;
    double eps;        /* the listing's EPS (fortran rule only), cm */
} bf_walls;

/* The keys of [walls] (bf_walls_spec). */
typedef struct bf_walls_keys {
    double omega;
    int rule; /* bf_wall_rule */
    double eps;
} bf_walls_keys;

extern const bf_section_spec bf_walls_spec; /* [walls] */

/* The walls of the given box from the filled [walls] keys. */
void bf_walls_from_keys(bf_walls *w, const bf_walls_keys *k, bf_box box);

/* Reflect every particle whose step from (x0[i], y0[i]) to (p->x[i],
 * p->y[i]) left the box; x0 and y0 are scratch (the fortran rule moves
 * them, as WALCOL does).  Adds the number of reflections to *hits. */
bf_status bf_walls_apply(const bf_walls *w, bf_particles *p, double *x0,
                         double *y0, unsigned long long *hits, bf_err *err);
/* The same, naming particle ids[i] + 1 (not i + 1) in the error, for a
 * rank's share of the particles (ids NULL: i), and on failure the index i
 * of the particle in *bad (may be NULL). */
bf_status bf_walls_apply_ids(const bf_walls *w, bf_particles *p, double *x0,
                             double *y0, const uint32_t *ids,
                             unsigned long long *hits, size_t *bad,
                             bf_err *err);

/* 1 if every particle is in the closed box, else 0 with *bad its index. */
int bf_box_contains_all(const bf_box *b, const bf_particles *p, size_t *bad);

#endif
