/* ballsys.h: balls on a line driven by effects and advanced by an
 * integrator.  This is the component shared by the "balls" model (balls in
 * space, Yasuda sec. 2) and the coupled ball-film model (sec. 3).
 *
 * Scene keys: one [ball.N] section per ball (N = 1, 2, ... in increasing
 * position), [scene] effects and [scene] integrator.
 */
#ifndef BALLFILM_BALLSYS_H
#define BALLFILM_BALLSYS_H

#include "ballfilm/effects.h"
#include "ballfilm/integrator.h"
#include "ballfilm/scene.h"

typedef struct bf_ballsys {
    bf_balls b;
    bf_effect *eff;
    size_t neff;
    bf_integrator *it;
    bf_ode ode;
    /* one step: the integrator's generic step, or for Verlet and MV2M the
     * bit-identical specialised one (ballsys.c) */
    bf_status (*step)(struct bf_ballsys *s, double t, double dt, bf_err *err);
    /* k steps (bf_ballsys_advance), chosen with step */
    bf_status (*advance)(struct bf_ballsys *s, long n0, long k, double dt,
                         long *done, bf_err *err);
} bf_ballsys;

extern const bf_section_spec bf_ballsys_ball_spec; /* [ball.N] */

/* Read balls, create effects (env is passed to them) and the integrator.
 * Refuses overlapping or unordered balls, naming the key. */
bf_status bf_ballsys_create(bf_ballsys **out, const bf_scene *sc,
                            const bf_effect_env *env, bf_err *err);
void bf_ballsys_free(bf_ballsys *s);

/* One integrator step; fails with BF_EUNSTABLE, naming the ball, if a
 * position or velocity is not finite afterwards (the state is then that of
 * the failed step; the caller stops).  Inline: it is the body of every
 * long run's loop (s->step is chosen in ballsys.c). */
static inline bf_status bf_ballsys_step(bf_ballsys *s, double t, double dt,
                                        bf_err *err)
{
    return s->step(s, t, dt, err);
}

/* k >= 0 steps, step j from t = (n0 + j) dt to (n0 + j + 1) dt: the same
 * bits, counters and force cache as k calls of bf_ballsys_step with those
 * times, in one call (for Verlet and MV2M the state stays in registers
 * between steps).  *done receives the number of steps that succeeded; on
 * failure the state is that of the failed step, as with bf_ballsys_step. */
static inline bf_status bf_ballsys_advance(bf_ballsys *s, long n0, long k,
                                           double dt, long *done, bf_err *err)
{
    return s->advance(s, n0, k, dt, done, err);
}

/* Checkpoint: positions, velocities and integrator state under names
 * starting with `prefix`. */
bf_status bf_ballsys_save(const bf_ballsys *s, bf_ckpt *ck, const char *prefix,
                          bf_err *err);
bf_status bf_ballsys_load(bf_ballsys *s, const bf_ckpt *ck, const char *prefix,
                          bf_err *err);

/* Kinetic and potential energy (erg). */
void bf_ballsys_energy(const bf_ballsys *s, double t, double *kin,
                       double *pot);

/* The ball system inside a "balls" model instance (for drivers and
 * tests that need the state: convergence studies, return maps). */
bf_ballsys *bf_balls_model_system(void *balls_model);

#endif
