/* integrator.h: one small interface for every ODE time integrator.
 *
 * The system is second order in form: dx/dt = v, dv/dt = a(t, x, v), with n
 * degrees of freedom.  Integrators know nothing of the physics: they ask the
 * bf_ode for accelerations.  Each integrator lives in its own file and
 * exports one constant descriptor (bf_integrator_type); the catalog
 * (src/compose/catalog.c) lists them.  Adding an integrator touches one
 * new file and one catalog line.
 *
 * Fast path: an integrator may also carry specialised steps for balls
 * under effects (bf_ball_stepper), with the effects' force kernels
 * inlined; the ball system takes them through that slot.  They must give
 * the bits of the generic step (Verlet and MV2M do, see
 * src/integrators/ball_steps.h).
 *
 * Methods that, like Verlet, evaluate a at the step's end point keep that
 * value for the next step (first same as last).  The cache is keyed by the
 * positions and by bf_ode.epoch: a model whose force field changes between
 * steps for reasons other than x (the film under the balls) bumps the epoch.
 */
#ifndef BALLFILM_INTEGRATOR_H
#define BALLFILM_INTEGRATOR_H

#include <stddef.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"
#include "ballfilm/effect.h"
#include "ballfilm/params.h"

/* a(t, x, v) -> acc[n].  Returns 0, or non-zero if the force cannot be
 * evaluated (the integrator then fails the step with BF_EUNSTABLE). */
typedef int (*bf_accel_fn)(void *ctx, double t, const double *x,
                           const double *v, double *acc);

/* Discrete-gradient acceleration (optional): for a = -grad V / m,
 * abar(x, xn)[i] = -Dbar_i V(x, xn) / m_i with Dbar V a discrete gradient
 * of V: sum_i Dbar_i V (xn_i - x_i) = V(xn) - V(x), Dbar V(x, x) =
 * grad V(x), and symmetric, Dbar V(x, xn) = Dbar V(xn, x).  Energy-
 * conserving integrators (greenspan73) step with it; the ball system
 * gives it from its effects' potentials (src/effects/effect_kernels.h).
 * Returns 0, or non-zero if it cannot be evaluated. */
typedef int (*bf_daccel_fn)(void *ctx, double t, const double *x,
                            const double *xn, double *abar);

typedef struct bf_ode {
    size_t n;
    bf_accel_fn accel;
    void *ctx;
    int velocity_dependent; /* a depends on v (Verlet-type methods refuse) */
    unsigned long epoch;    /* bumped when the force field changes */
    bf_daccel_fn daccel;    /* NULL: none (integrators that need it fall
                             * back, see greenspan73.c) */
    size_t n_check;         /* the fixed-point iterations (verlet for
                             * velocity-dependent forces, impmid) test the
                             * convergence of the first n_check components
                             * only (0: all n); the rest must follow from
                             * them (the ball system's work components) */
} bf_ode;

/* Events (optional, see bf_integrator_set_events).  g(ctx, t, x, v) ->
 * g[n]; an integrator with BF_INT_ROOTS locates the zeros of g inside its
 * steps (ARKODE rootfinding) and calls hit(ctx, k, t, x, v) with the state
 * at each root, in time order, before the step returns.  dir[k] = +1
 * (only where g increases), -1 (decreases) or 0 (both); dir may be NULL.
 * Integrators without BF_INT_ROOTS ignore events: the caller then locates
 * them from the step's end states. */
typedef int (*bf_root_fn)(void *ctx, double t, const double *x,
                          const double *v, double *g);
typedef void (*bf_root_hit_fn)(void *ctx, int k, double t, const double *x,
                               const double *v);
typedef struct bf_events {
    int n;
    bf_root_fn g;
    const int *dir;
    bf_root_hit_fn hit;
    void *ctx;
} bf_events;

/* Step monitor (optional, see bf_integrator_set_monitor): adaptive
 * integrators call it with the state after each accepted internal step, so
 * that a driver can watch, e.g., the energy inside one long call. */
typedef void (*bf_monitor_fn)(void *ctx, double t, const double *x,
                              const double *v);

typedef struct bf_counters {
    unsigned long long steps;      /* accepted steps */
    unsigned long long evals;      /* force (acceleration) evaluations */
    unsigned long long rejected;   /* rejected steps (adaptive methods) */
    unsigned long long iterations; /* inner iterations (implicit methods) */
} bf_counters;

typedef struct bf_integrator bf_integrator;

enum {
    BF_INT_SYMMETRIC = 1u << 0,     /* time-symmetric (bounded energy error) */
    BF_INT_POSITION_ONLY = 1u << 1, /* needs a(x) independent of v */
    BF_INT_ADAPTIVE = 1u << 2,      /* takes its own internal steps */
    BF_INT_IMPLICIT = 1u << 3,
    BF_INT_ROOTS = 1u << 4, /* locates the events of bf_ode inside its steps */
    BF_INT_POTENTIAL = 1u << 5 /* steps with the discrete gradient of a
                                  potential of x (bf_ode.daccel): refuses
                                  forces of t as well as of v */
};

/* Balls under effects as a specialised ball step sees them: the balls
 * (their state x, v is advanced in place) and the effects whose forces
 * it sums. */
typedef struct bf_ball_forces {
    const bf_balls *b;
    const bf_effect *eff;
    size_t neff;
} bf_ball_forces;

/* One step t -> t + dt, or k steps from t = n0 dt (as bf_model_type's
 * advance), of the balls of f under the sum of their effects' forces:
 * the bits, counters and force cache of the generic step with ode (whose
 * callback computes the same sum).  On a non-finite state the step fails
 * with BF_EUNSTABLE naming the ball. */
typedef bf_status (*bf_ball_step_fn)(bf_integrator *it, const bf_ode *ode,
                                     const bf_ball_forces *f, double t,
                                     double dt, bf_err *err);
/* What a run of ball steps checks after each of its steps, so that the
 * time loop's energy check and the events an analysis waits for need no
 * call per step (NULL: nothing).  The checks are those the loop and the
 * analysis would make after each step, with the same arithmetic: the run
 * gives the same bits as the steps taken one at a time. */
typedef struct bf_ball_watch {
    /* energy: after every step E = K + V (K = sum of m v^2/2, then V =
     * the effects' potentials in order, as bf_ballsys_energy), its
     * relative error against e0 (diag/energy.h: NaN counts as infinite)
     * raises max_rel and sets last_rel; the run ends after a step whose
     * error is not <= bound (bound 0: never). */
    int energy;
    double e0, bound;      /* erg; 1 */
    double max_rel, last_rel; /* in and out */
    /* events: the run ends after a step in which v[low] went from < 0 to
     * >= 0 (low >= 0).  A step that ends with x[above] >= above_x (above
     * >= 0) does not end it: BF_WATCH_ABOVE goes into `fired` and the run
     * goes on without that check (not when the step is also one of `low`:
     * then only BF_WATCH_LOW, and x[above] is the end state's) */
    long low, above;
    double above_x; /* cm */
    /* out: what ended the run or was noted in it (BF_WATCH_* bits, 0:
     * nothing, it took its k steps), and then the state at the start of
     * its last step: n values each in
     * arrays the model provides (bf_ballsys_advance points them at its
     * own); the run also uses them as scratch */
    unsigned fired;
    double *x_start, *v_start;
} bf_ball_watch;
enum { BF_WATCH_ENERGY = 1u, BF_WATCH_LOW = 2u, BF_WATCH_ABOVE = 4u };

typedef bf_status (*bf_ball_advance_fn)(bf_integrator *it, const bf_ode *ode,
                                        const bf_ball_forces *f, long n0,
                                        long k, double dt, bf_ball_watch *w,
                                        long *done, bf_err *err);
typedef struct bf_ball_stepper {
    /* the specialised step and run for these effects and this many balls
     * (fixed shapes where the stepper has them) */
    void (*pick)(const bf_ball_forces *f, bf_ball_step_fn *step,
                 bf_ball_advance_fn *advance);
} bf_ball_stepper;

typedef struct bf_integrator_type {
    const char *name;
    const char *doc;
    int order;          /* nominal global order */
    int evals_per_step; /* nominal; 0 if variable */
    unsigned flags;
    const bf_section_spec *spec; /* keys of [integrator], or NULL */
    /* Allocate it->work etc. for it->n unknowns from the filled struct of
     * `spec` (NULL when there is no spec); a failure that is about a key
     * names it (bf_fail_key). */
    bf_status (*init)(bf_integrator *it, const void *params, bf_err *err);
    /* Advance (x, v) from t to t + dt in place.  On failure x, v are left
     * at their values at t.  Adaptive integrators (BF_INT_ADAPTIVE) take
     * their own internal steps inside [t, t + dt] and end exactly at
     * t + dt. */
    bf_status (*step)(bf_integrator *it, const bf_ode *ode, double t, double dt,
                      double *x, double *v, bf_err *err);
    void (*free)(bf_integrator *it);
    /* Private state needed to continue bit for bit (step-size history,
     * solver memory); optional.  Names must start with `prefix`. */
    bf_status (*save)(const bf_integrator *it, bf_ckpt *ck, const char *prefix,
                      bf_err *err);
    bf_status (*load)(bf_integrator *it, const bf_ckpt *ck, const char *prefix,
                      bf_err *err);
    /* Nominal order when it depends on the parameters (ARKODE tables);
     * optional, `order` is used otherwise. */
    int (*order_of)(const bf_integrator *it);
    /* One-line description with the parameters in use; optional. */
    void (*describe)(const bf_integrator *it, char *buf, size_t cap);
    /* Specialised steps for balls under effects; optional. */
    const bf_ball_stepper *balls;
} bf_integrator_type;

struct bf_integrator {
    const bf_integrator_type *type;
    size_t n;
    double *work; /* scratch owned by the type (allocated by init) */
    void *priv;   /* type-private data */
    bf_counters count;
    /* first-same-as-last cache: acceleration at cache_x */
    double *cache_x, *cache_a;
    int cache_valid;
    unsigned long cache_epoch;
    const bf_events *events; /* NULL: none (bf_integrator_set_events) */
    const bf_events *kinks;  /* NULL: none (bf_integrator_set_kinks) */
    /* [integrator] events = yes: the caller splits each fixed step at the
     * kinks of its right-hand side (the ball system at contact onsets and
     * releases, ballsys.c); adaptive integrators stop and restart at them
     * (bf_integrator_set_kinks).  Set by the type's init. */
    int split_events;
    double split_zone; /* [integrator] events_zone, s (see ballsys.c) */
    bf_monitor_fn monitor;   /* NULL: none (bf_integrator_set_monitor) */
    void *monitor_ctx;
};

/* An integrator of type t for n unknowns with the [integrator] struct
 * `params` (NULL: the defaults of t's spec). */
bf_status bf_integrator_create(bf_integrator **it,
                               const bf_integrator_type *t, size_t n,
                               const void *params, bf_err *err);
void bf_integrator_free(bf_integrator *it);
/* Nominal global order of an instance, and a one-line description of it
 * ("arkode DORMAND_PRINCE_7_4_5 rtol=1e-08 atol=1e-11", or the name). */
int bf_integrator_order(const bf_integrator *it);
void bf_integrator_describe(const bf_integrator *it, char *buf, size_t cap);
/* Register events (kept by pointer; NULL removes them).  Only integrators
 * with BF_INT_ROOTS use them. */
void bf_integrator_set_events(bf_integrator *it, const bf_events *ev);
/* Register the kinks of the right-hand side (kept by pointer; NULL
 * removes them): functions whose zeros are the points where a(t, x, v) is
 * not smooth (a Hertz contact's onset and release).  Integrators with
 * BF_INT_ROOTS locate each zero inside their steps, end an internal step
 * there and restart from it, so that no internal step straddles a kink;
 * `hit` (may be NULL) is called at each.  Independent of the events. */
void bf_integrator_set_kinks(bf_integrator *it, const bf_events *kinks);
/* The [integrator] keys `events` (yes/no) and `events_zone` (s) of every
 * integrator that offers them: two rows for the type's bf_param table
 * (members `events` and `events_zone` of its struct). */
#define BF_EVENTS_PARAMS(type)                                                \
    {"events", BF_AT(type, events, BF_BOOL), "", "no",                        \
     "split every step at the contact onsets and releases inside it (ball "   \
     "systems; docs/accuracy-balls.md); off: the step as it is",              \
     0, 0, 0, NULL},                                                          \
    {"events_zone", BF_AT(type, events_zone, BF_REAL), "s", "1e-3",           \
     "with events: the time after an onset and before a release over which "  \
     "the substeps are graded (about half a contact's duration)",            \
     BF_POS, 0, 0, NULL}
/* Watch the internal steps of adaptive integrators (NULL removes it).
 * Fixed-step integrators do not call it: each of their steps is a call. */
void bf_integrator_set_monitor(bf_integrator *it, bf_monitor_fn fn, void *ctx);
/* Forget cached forces (after the caller changed x or the force field). */
void bf_integrator_reset(bf_integrator *it);
/* Checkpoint: counters, the force cache and the type's private state, under
 * names starting with `prefix`. */
bf_status bf_integrator_save(const bf_integrator *it, bf_ckpt *ck,
                             const char *prefix, bf_err *err);
bf_status bf_integrator_load(bf_integrator *it, const bf_ckpt *ck,
                             const char *prefix, bf_err *err);

static inline bf_status bf_integrator_step(bf_integrator *it, const bf_ode *ode,
                                           double t, double dt, double *x,
                                           double *v, bf_err *err)
{
    return it->type->step(it, ode, t, dt, x, v, err);
}

/* Helpers for integrator implementations. */
bf_status bf_ode_eval_failed(bf_err *err);
/* Evaluate a(t, x, v), count it, and turn a failure into a message.
 * Inline: it sits in every integrator's innermost loop. */
static inline bf_status bf_ode_eval(bf_integrator *it, const bf_ode *ode,
                                    double t, const double *x, const double *v,
                                    double *acc, bf_err *err)
{
    it->count.evals++;
    if (ode->accel(ode->ctx, t, x, v, acc))
        return bf_ode_eval_failed(err);
    return BF_OK;
}
/* a(x) at the step's start, from the cache when x and the epoch match. */
bf_status bf_ode_eval_cached(bf_integrator *it, const bf_ode *ode, double t,
                             const double *x, const double *v, double *acc,
                             bf_err *err);
/* Store a(x) computed at the step's end for the next step. */
void bf_integrator_cache_store(bf_integrator *it, const bf_ode *ode,
                               const double *x, const double *acc);
/* Allocate `nvec` vectors of length n into it->work (zeroed). */
bf_status bf_integrator_alloc_work(bf_integrator *it, size_t nvec, bf_err *err);

#endif
