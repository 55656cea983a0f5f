/* ballsys.h: balls on a line driven by effects and advanced by an
 * integrator.  This is the component shared by the "balls" model (balls in
 * space, Yasuda sec. 2) and the coupled ball-film model (sec. 3).
 *
 * Its parameters: one [ball.N] section per ball (N = 1, 2, ... in
 * increasing position), the effects and the integrator of the setup
 * (model.h).
 */
#ifndef BALLFILM_MODELS_BALLSYS_H
#define BALLFILM_MODELS_BALLSYS_H

#include "ballfilm/effect.h"
#include "ballfilm/integrator.h"
#include "ballfilm/model.h"

/* The keys of [ball.N]. */
typedef struct bf_ball_keys {
    double position; /* cm */
    double velocity; /* cm/s */
    double mass;     /* g */
    double radius;   /* cm */
} bf_ball_keys;

extern const bf_section_spec bf_ballsys_ball_spec; /* [ball.N] */

typedef struct bf_ballsys {
    bf_balls b;
    bf_effect *eff;
    size_t neff;
    bf_integrator *it;
    void *it_params; /* a copy of the integrator's [integrator] struct */
    const bf_effect_type **effect_types; /* the effects' types (owned) */
    void **effect_params; /* copies of the effects' structs (set_state
                             checks new positions with them) */
    unsigned char *lent;  /* per effect: its self was handed over by the
                             caller (bf_ballsys_create's `given`), not
                             created or destroyed here */
    int no_fast; /* an effect depends on velocity or explicitly on time:
                    no specialised steps (ball_steps.h) */
    int time_dependent; /* an effect depends explicitly on t: ode.epoch is
                           bumped before a step that does not start at
                           t_cached (the force cache is keyed by x,
                           integrator.h) */
    double t_cached; /* the end time of the last generic step, whose
                        force the integrator's cache may hold (NaN: none) */
    bf_ode ode;
    /* what the integrator's specialised steps see (b, eff, neff) */
    bf_ball_forces forces;
    /* the integrator's specialised steps for these effects (NULL: the
     * integrator has none; then its generic step) */
    bf_ball_step_fn fast_step;
    bf_ball_advance_fn fast_advance;
    /* Contact events ([integrator] events = yes; ballsys_events.c, "Event
     * splitting").  The gaps: x_i - R_i per ball with a floor effect,
     * (x_{i+1} - x_i) - (R_i + R_{i+1}) per pair with a contact effect
     * (set for every system: bf_ballsys_gaps_fn serves others too). */
    int split;      /* fixed-step integrator: split each step at them */
    int gap_floor, gap_pair;
    int ngaps;
    const struct bf_floor *floor; /* the floor effect's state, or NULL */
    const struct bf_contact *contact; /* the contact effect's, or NULL */
    /* the release events of the damped contacts (ballsys_events.c,
     * "Releases"): the floor's, one per ball, then the pairs', and the
     * branch of each for the current piece */
    int rel_floor, rel_pair;
    int nrel;
    signed char *branch;
    double kink_power; /* the force grows as delta^kink_power after an
                          onset (graded substeps, ballsys_events.c) */
    double *ev_work; /* scratch of the splitting */
    int *ev_side;
    bf_events kinks; /* adaptive integrator with roots: its kinks */
    /* The work of the non-conservative forces (ballsys.c,
     * bf_ballsys_accel_work): nw = 2 when tracked, then b.x and b.v hold
     * n + 2 values, the last two of b.v being W_diss and W_inj (erg), and
     * the integrator advances ode.n = n + 2 components. */
    size_t nw;
    double *w_acc; /* scratch, n */
    /* the state at the start of the last step of a watched run that fired
     * (bf_ball_watch.x_start; n each) */
    double *x_start, *v_start;
} bf_ballsys;

/* Read the balls of the setup, create its effects and its integrator.
 * An effect of the setup whose type is among the ngiven of `given` is not
 * created: it takes that entry's self, which stays the caller's (the
 * coupled model hands over its coupling this way).  Refuses overlapping or
 * unordered balls, naming the key, and an integrator for a = a(x) with an
 * effect whose force depends on velocity, naming [scene] integrator.  The
 * system keeps what it needs of the setup (the setup may be freed after;
 * strings in the integrator's struct point into the scene). */
bf_status bf_ballsys_create(bf_ballsys **out, const bf_model_setup *setup,
                            const bf_effect *given, size_t ngiven,
                            bf_err *err);
void bf_ballsys_free(bf_ballsys *s);

/* The force callback the ball system installs in ode: the sum of its
 * effects (ctx: the bf_ballsys). */
int bf_ballsys_accel(void *ctx, double t, const double *x, const double *v,
                     double *acc);

/* The discrete-gradient acceleration the ball system installs in ode
 * (integrator.h, bf_daccel_fn): the sum of its effects' (effect_kernels.h). */
int bf_ballsys_daccel(void *ctx, double t, const double *x, const double *xn,
                      double *abar);

/* The same with the powers of the non-conservative forces as the
 * accelerations of components n, n + 1 (what bf_ballsys_accel does when
 * the work is tracked, s->nw = 2). */
int bf_ballsys_accel_work(void *ctx, double t, const double *x,
                          const double *v, double *acc);
/* The work the non-conservative forces did since t = 0 (erg): dissipated
 * (>= 0) and injected by driving; both 0 when not tracked (s->nw = 0). */
void bf_ballsys_work(const bf_ballsys *s, double *diss, double *inj);
/* The s->ngaps gaps of the event splitting at x (bf_root_fn; ctx: the
 * bf_ballsys; v is not read). */
int bf_ballsys_gaps_fn(void *ctx, double t, const double *x, const double *v,
                       double *g);

/* The event splitting's set-up (ballsys_events.c): which gaps the
 * effects make (every system), and for [integrator] events = yes its
 * scratch, the split of fixed steps or the kinks of an adaptive
 * integrator. */
void bf_ballsys_gaps_setup(bf_ballsys *s);
bf_status bf_ballsys_events_setup(bf_ballsys *s, bf_err *err);

/* One step split at the contact onsets and releases inside it (what
 * bf_ballsys_step does with [integrator] events = yes). */
bf_status bf_ballsys_step_split(bf_ballsys *s, double t, double dt,
                                bf_err *err);

/* One step of a twin of the balls (model.h, bf_ball_view's step_twin;
 * ctx: the bf_ballsys) taken as bf_ballsys_step takes the system's own:
 * with events, split at the twin's own onsets and releases. */
bf_status bf_ballsys_step_twin(void *ctx, bf_ball_twin *tw, double t,
                               double dt, bf_err *err);

/* Through the integrator's generic step (what bf_ballsys_step does when
 * there is no specialised one). */
bf_status bf_ballsys_step_generic(bf_ballsys *s, double t, double dt,
                                  bf_err *err);
bf_status bf_ballsys_advance_generic(bf_ballsys *s, long n0, long k,
                                     double dt, bf_ball_watch *w, long *done,
                                     bf_err *err);

/* One integrator step; fails with BF_EUNSTABLE, naming the ball, if a
 * position or velocity is not finite afterwards (the state is then that of
 * the failed step; the caller stops).  Through the integrator's
 * specialised step when it has one and nobody replaced ode.accel (tests
 * plug their own force in this way), else its generic step.  Inline: it
 * is the body of every long run's loop. */
static inline bf_status bf_ballsys_step(bf_ballsys *s, double t, double dt,
                                        bf_err *err)
{
    if (s->split)
        return bf_ballsys_step_split(s, t, dt, err);
    if (s->fast_step && s->ode.accel == bf_ballsys_accel)
        return s->fast_step(s->it, &s->ode, &s->forces, t, dt, err);
    return bf_ballsys_step_generic(s, t, dt, err);
}

/* k >= 0 steps, step j from t = (n0 + j) dt to (n0 + j + 1) dt: the same
 * bits, counters and force cache as k calls of bf_ballsys_step with those
 * times, in one call (for Verlet and MV2M the state stays in registers
 * between steps).  *done receives the number of steps that succeeded; on
 * failure the state is that of the failed step, as with bf_ballsys_step.
 * With a watch (integrator.h, bf_ball_watch; NULL: none) the run also
 * makes the watch's checks after every step and ends after the first step
 * at which one fires (*done counts it); w->x_start, w->v_start point to
 * the system's own arrays. */
static inline bf_status bf_ballsys_advance(bf_ballsys *s, long n0, long k,
                                           double dt, bf_ball_watch *w,
                                           long *done, bf_err *err)
{
    if (w) {
        w->x_start = s->x_start;
        w->v_start = s->v_start;
    }
    if (s->fast_advance && s->ode.accel == bf_ballsys_accel)
        return s->fast_advance(s->it, &s->ode, &s->forces, n0, k, dt, w, done,
                               err);
    return bf_ballsys_advance_generic(s, n0, k, dt, w, done, err);
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

/* The state as arrays (model.h's state and set_state): balls/position
 * (cm) and balls/velocity (cm/s), both settable.  New positions are
 * checked as [ball.N] positions are (order, overlap, and every effect's
 * own check, such as the floor's); on failure the state is unchanged. */
size_t bf_ballsys_state(bf_ballsys *s, bf_state_var *vars, size_t cap);
bf_status bf_ballsys_set(bf_ballsys *s, const char *name, const double *v,
                         size_t n, bf_err *err);

/* The bound on the relative energy error of a ball system whose effects
 * are all conservative (BF_EFFECT_CONSERVATIVE), 0 otherwise
 * (model.h, energy_bound). */
double bf_ballsys_energy_bound(const bf_ballsys *s);

/* The ball view of analyses (model.h). */
void bf_ballsys_view(bf_ballsys *s, bf_ball_view *v);

/* The ball system inside a "balls" model instance (for drivers and
 * tests that need the state: convergence studies, return maps). */
bf_ballsys *bf_balls_model_system(void *balls_model);

#endif
