/* ball_steps.h: the specialised steps of an integrator for balls under
 * effects (integrator.h, bf_ball_stepper), generated from the integrator's
 * step kernels (step_kernels.h) with the effects' dispatch point inlined
 * (src/effects/effect_kernels.h).  Private to src/integrators.
 *
 * Same operations in the same order as the generic step through the
 * bf_ode callback, so the same bits (bench/bench_balls.c and
 * tests/test_advance.c compare them), same counters and force cache.
 *
 * Two kinds of instantiation:
 *   any    any effects, any number of balls: only the dispatch is inlined;
 *   fixed  the effect lists of the paper's long runs, with the number of
 *          balls a compile-time constant (gravity + floor with one ball,
 *          gravity + floor + contact with two): the loops unroll and the
 *          state stays in registers.  What the forces read is gathered
 *          into a local object at the start of the step; the effect
 *          kernels are the same inline functions, called in the scene's
 *          order, so every force is computed exactly as in the generic
 *          dispatch.
 * A shape is matched by the effects' descriptors (bf_effect_kernel_of,
 * effect_kernels.h), never by name.  The ball system takes none of these
 * steps for a scene with an effect whose force depends on velocity or
 * explicitly on time (BF_EFFECT_VELOCITY, BF_EFFECT_TIME; ballsys.c): their
 * kernels evaluate forces at predicted positions with the step's initial
 * velocities.
 *
 * Runs of steps (advance): the run kernels of step_kernels.h keep the
 * state, Verlet's carried force and the counters in locals for the whole
 * run, so a step costs what the hand-fused loop of bench_balls.c costs.
 *
 * An integrator with a step kernel KERNEL and a run kernel RUN (the
 * signatures of bf_verlet_kernel and bf_verlet_run) and NWORK vectors of
 * scratch gets its stepper with
 *   BF_BALL_STEPPER(name, KERNEL, RUN, NWORK)
 * which defines `static const bf_ball_stepper name_balls`.
 */
#ifndef BALLFILM_BALL_STEPS_H
#define BALLFILM_BALL_STEPS_H

#include <math.h>
#include <stdio.h>

#include "diag/energy.h"
#include "effects/effect_kernels.h"
#include "step_kernels.h"

/* The attribute keeps GCC from turning the zeroing loop of the dispatch
 * into a memset call (effects.c says why); the specialised steps carry it
 * too so that the dispatch inlines into them. */
#if defined(__GNUC__) && !defined(__clang__)
#define BF_BALL_HOT __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define BF_BALL_HOT
#endif

/* the dispatch of the effects in f, inlined */
BF_ALWAYS_INLINE int bf_ball_accel_any(void *ctx, double t, const double *x,
                                       const double *v, double *acc)
{
    const bf_ball_forces *f = ctx;
    return bf_effects_accel_inline(f->eff, f->neff, f->b, t, x, v, acc, NULL);
}

/* What the forces of a fixed effect list read: the balls with n a
 * compile-time constant (so that the loops unroll) and the effects'
 * parameters.  Nothing is copied: x, v and the scratch are restrict in the
 * kernels, so the compiler knows the step's stores leave these alone. */
typedef struct bf_fixed_forces {
    bf_balls b;
    const bf_gravity *gravity;
    const bf_floor *floor;
    const bf_contact *contact;
} bf_fixed_forces;

BF_ALWAYS_INLINE void bf_fixed_setup(bf_fixed_forces *F, const bf_ball_forces *f,
                                     size_t n)
{
    F->b = *f->b;
    F->b.n = n;
    F->gravity = f->eff[0].self;
    F->floor = f->eff[1].self;
    F->contact = f->neff > 2 ? f->eff[2].self : NULL;
}

/* the dispatch point's zeroing, then the listed kernels in order */
BF_ALWAYS_INLINE int bf_accel_gf(void *ctx, double t, const double *x,
                                 const double *v, double *acc)
{
    (void)t;
    (void)v;
    const bf_fixed_forces *F = ctx;
    BF_UNROLL
    for (size_t i = 0; i < F->b.n; i++)
        acc[i] = 0.0;
    bf_gravity_accel(F->gravity, &F->b, x, acc);
    bf_floor_accel(F->floor, &F->b, x, acc);
    return 0;
}

BF_ALWAYS_INLINE int bf_accel_gfc(void *ctx, double t, const double *x,
                                  const double *v, double *acc)
{
    bf_accel_gf(ctx, t, x, v, acc);
    const bf_fixed_forces *F = ctx;
    bf_contact_accel(F->contact, &F->b, x, acc);
    return 0;
}

/* The fixed shapes: the effects' kernels in order and the number of
 * balls. */
static inline int bf_shape_is(const bf_ball_forces *f, size_t n,
                              const bf_effect_kernel *k, size_t nk)
{
    if (f->b->n != n || f->neff != nk)
        return 0;
    for (size_t j = 0; j < nk; j++)
        if (bf_effect_kernel_of(f->eff[j].type) != k[j])
            return 0;
    return 1;
}

static inline int bf_shape_gf1(const bf_ball_forces *f)
{
    static const bf_effect_kernel k[] = {BF_KERNEL_GRAVITY, BF_KERNEL_FLOOR};
    return bf_shape_is(f, 1, k, 2);
}

static inline int bf_shape_gfc2(const bf_ball_forces *f)
{
    static const bf_effect_kernel k[] = {BF_KERNEL_GRAVITY, BF_KERNEL_FLOOR,
                                         BF_KERNEL_CONTACT};
    return bf_shape_is(f, 2, k, 3);
}

/* all of x and v finite?  y * 0 is 0 for finite y and NaN for inf and
 * NaN, so the sum is 0 exactly when every value is finite (no branch per
 * value) */
BF_ALWAYS_INLINE int bf_vec_finite(const double *x, const double *v, size_t n)
{
    double z = 0.0;
    BF_UNROLL
    for (size_t i = 0; i < n; i++)
        z += x[i] * 0.0 + v[i] * 0.0;
    return z == 0.0;
}

/* the runs of the "any" steppers stop at the first non-finite state */
BF_ALWAYS_INLINE int bf_stop_not_finite(void *ctx, const double *x,
                                        const double *v, size_t n)
{
    (void)ctx;
    return !bf_vec_finite(x, v, n);
}

/* Runs of the fixed steps check finiteness once, at the end of the run,
 * not after every step (that check cost about 3 ns of a 12 ns Verlet step
 * in bench_balls): once a position or velocity is not finite, every later
 * position is not finite either, because both kernels form
 * x^{n+1} = x^n + (dt v^n + ...) and IEEE arithmetic keeps inf and NaN in
 * a sum (inf + finite = inf, inf - inf = NaN, NaN + y = NaN; dt > 0).  So
 * a finite end state means that every state of the run was finite.  If
 * the end state is not finite, the run is undone (the state was worked on
 * in local copies; counters and force cache are restored) and taken again
 * step by step, which stops at the failing step with the state, counters
 * and message of one step at a time. */
BF_ALWAYS_INLINE int bf_never_stop(void *ctx, const double *x,
                                   const double *v, size_t n)
{
    (void)ctx;
    (void)x;
    (void)v;
    (void)n;
    return 0;
}

/* a[i] (0 <= i < n) read without indexing by a variable: with n a
 * compile-time constant the loop unrolls to selects, so that a state kept
 * in registers need not go to memory to be indexed */
BF_ALWAYS_INLINE double bf_vec_pick(const double *a, long i, size_t n)
{
    double r = 0.0;
    BF_UNROLL
    for (size_t k = 0; k < n; k++)
        if ((long)k == i)
            r = a[k];
    return r;
}

/* ---- watched runs (integrator.h, bf_ball_watch) ----
 * After every step of a watched run, the checks of bf_ball_watch on the
 * step's start (xs, vs) and end (x, v): the time loop's energy check, with
 * its arithmetic (K summed over the balls from 0, then K + V; the relative
 * error of diag/energy.h), and the events an analysis waits for (vs: the
 * velocities at the step's start).  Returns the BF_WATCH_* bits that end
 * the run.  The `above` event does not end it: it goes into w->fired and
 * its check is off for the rest of the run (w->above = -1), unless the
 * step is a lowest point, which ends the run with x[above] at the step's
 * end for the observer to see. */
BF_ALWAYS_INLINE unsigned bf_watch_check(bf_ball_watch *w, const double *m,
                                         double pot, double e0d,
                                         const double *vs, const double *x,
                                         const double *v, size_t n)
{
    unsigned fired = 0;
    if (w->energy) {
        double kin = 0.0;
        BF_UNROLL
        for (size_t i = 0; i < n; i++)
            kin += 0.5 * m[i] * v[i] * v[i];
        /* bf_rel_error(kin + pot, w->e0), e0d = bf_rel_divisor(w->e0) */
        const double rel = fabs(kin + pot - w->e0) / e0d;
        if (!(rel <= w->max_rel))
            w->max_rel = isnan(rel) ? INFINITY : rel;
        w->last_rel = rel;
        if (w->bound > 0 && !(rel <= w->bound))
            fired |= BF_WATCH_ENERGY;
    }
    if (w->low >= 0 && bf_vec_pick(vs, w->low, n) < 0 &&
        bf_vec_pick(v, w->low, n) >= 0)
        fired |= BF_WATCH_LOW;
    if (w->above >= 0 && !(fired & BF_WATCH_LOW) &&
        bf_vec_pick(x, w->above, n) >= w->above_x) {
        w->fired |= BF_WATCH_ABOVE;
        w->above = -1;
    }
    return fired;
}

/* A watched run of a fixed shape works on a copy of the watch (and keeps
 * the step's start) in a local object, which the compiler keeps in
 * registers: the watch itself is written back when the run ends
 * (bf_watch_fixed_done). */
typedef struct bf_watch_fixed {
    bf_ball_watch w;
    const bf_fixed_forces *F;
    double xs[2], vs[2];
    double mg[2]; /* m_i g, g cm/s^2: gravity's potential is sum mg_i x_i */
    double e0d;   /* bf_rel_divisor(w.e0), formed once per run */
} bf_watch_fixed;

BF_ALWAYS_INLINE void bf_watch_fixed_begin(bf_watch_fixed *r,
                                          const bf_ball_watch *w,
                                          const bf_fixed_forces *F,
                                          const double *x, const double *v,
                                          size_t n)
{
    r->w = *w;
    r->w.fired = 0;
    r->e0d = bf_rel_divisor(w->e0);
    r->F = F;
    for (size_t i = 0; i < n; i++)
        r->mg[i] = F->b.m[i] * F->gravity->g;
    bf_vec_copy(r->xs, x, n);
    bf_vec_copy(r->vs, v, n);
}

/* the run is over: what it found, into the watch */
BF_ALWAYS_INLINE void bf_watch_fixed_done(const bf_watch_fixed *r,
                                         bf_ball_watch *w, size_t n)
{
    w->max_rel = r->w.max_rel;
    w->last_rel = r->w.last_rel;
    w->fired = r->w.fired;
    if (w->fired) {
        bf_vec_copy(w->x_start, r->xs, n);
        bf_vec_copy(w->v_start, r->vs, n);
    }
}

BF_ALWAYS_INLINE int bf_watch_fixed_end(bf_watch_fixed *r, double pot,
                                        const double *x, const double *v,
                                        size_t n)
{
    unsigned fired =
        bf_watch_check(&r->w, r->F->b.m, pot, r->e0d, r->vs, x, v, n);
    if (fired) {
        r->w.fired |= fired;
        return 1;
    }
    bf_vec_copy(r->xs, x, n);
    bf_vec_copy(r->vs, v, n);
    return 0;
}

/* gravity's potential for a fixed shape: bf_gravity_potential's sum of
 * m_i g x_i, from 0, with the products m_i g formed once per run (the same
 * numbers: m_i g x_i is (m_i g) x_i) so that x is read as scalars (the
 * vectorised form loaded x, just stored as two scalars, as one pair and
 * stalled on the store forwarding) */
BF_ALWAYS_INLINE double bf_watch_gravity(const bf_watch_fixed *r,
                                         const double *x, size_t n)
{
    double u = 0.0;
    for (size_t i = 0; i < n; i++)
        u += r->mg[i] * x[i];
    return u;
}

/* the potentials of the fixed shapes (gravity, floor, and with `contact`
 * the contact), summed as bf_effects_potential_inline sums them (from 0,
 * in the scene's order); contact is a constant at each use */
BF_ALWAYS_INLINE int bf_watch_stop_fixed(void *ctx, const double *x,
                                         const double *v, size_t n,
                                         int contact)
{
    bf_watch_fixed *r = ctx;
    double pot = 0.0;
    if (r->w.energy) {
        pot += bf_watch_gravity(r, x, n);
        pot += bf_floor_potential(r->F->floor, &r->F->b, x);
        if (contact)
            pot += bf_contact_potential(r->F->contact, &r->F->b, x);
    }
    return bf_watch_fixed_end(r, pot, x, v, n);
}

BF_ALWAYS_INLINE int bf_watch_stop_gf(void *ctx, const double *x,
                                      const double *v, size_t n)
{
    return bf_watch_stop_fixed(ctx, x, v, n, 0);
}

BF_ALWAYS_INLINE int bf_watch_stop_gfc(void *ctx, const double *x,
                                       const double *v, size_t n)
{
    return bf_watch_stop_fixed(ctx, x, v, n, 1);
}

/* A watched run of any effects keeps the step's start in the watch's
 * arrays (n values) and the time of the step's end (for the potentials of
 * time-dependent effects). */
typedef struct bf_watch_any {
    bf_ball_watch *w;
    const bf_ball_forces *f;
    long next; /* the step count at the end of the next step */
    double dt;
} bf_watch_any;

/* the watch's check on the state after the step from f's state at the
 * step's start (in w->x_start, w->v_start) at time t of its end; copies
 * the end state in when nothing fired */
static inline unsigned bf_watch_any_end(bf_ball_watch *w,
                                        const bf_ball_forces *f, double t,
                                        const double *x, const double *v,
                                        size_t n)
{
    const double pot = w->energy ? bf_effects_potential_inline(
                                       f->eff, f->neff, f->b, t, x)
                                 : 0.0;
    unsigned fired = bf_watch_check(w, f->b->m, pot, bf_rel_divisor(w->e0),
                                    w->v_start, x, v, n);
    w->fired |= fired;
    if (!fired) {
        bf_vec_copy(w->x_start, x, n);
        bf_vec_copy(w->v_start, v, n);
    }
    return fired;
}

BF_ALWAYS_INLINE int bf_watch_stop_any(void *ctx, const double *x,
                                       const double *v, size_t n)
{
    bf_watch_any *r = ctx;
    if (!bf_vec_finite(x, v, n))
        return 1; /* that step failed (BF_BALL_ADVANCE_ANY) */
    return bf_watch_any_end(r->w, r->f, (double)r->next++ * r->dt, x, v,
                            n) != 0;
}

/* k steps one at a time, each followed by the watch's checks (what a
 * watched advance falls back to) */
static inline bf_status bf_ball_steps_watched(bf_ball_step_fn step,
                                              bf_integrator *it,
                                              const bf_ode *ode,
                                              const bf_ball_forces *f,
                                              long n0, long k, double dt,
                                              bf_ball_watch *w, long *done,
                                              bf_err *err)
{
    const size_t n = f->b->n;
    w->fired = 0;
    for (long j = 0; j < k; j++) {
        bf_vec_copy(w->x_start, f->b->x, n);
        bf_vec_copy(w->v_start, f->b->v, n);
        bf_status st = step(it, ode, f, (double)(n0 + j) * dt, dt, err);
        if (st) {
            *done = j;
            return st;
        }
        const double pot = w->energy
                               ? bf_effects_potential_inline(
                                     f->eff, f->neff, f->b,
                                     (double)(n0 + j + 1) * dt, f->b->x)
                               : 0.0;
        unsigned fired = bf_watch_check(w, f->b->m, pot,
                                        bf_rel_divisor(w->e0), w->v_start,
                                        f->b->x, f->b->v, n);
        if (fired) {
            w->fired |= fired;
            *done = j + 1;
            return BF_OK;
        }
    }
    *done = k;
    return BF_OK;
}

/* what a run changes in the integrator, for undoing it (n <= 2) */
typedef struct bf_run_mark {
    bf_counters count;
    int cache_valid;
    unsigned long cache_epoch;
    double cache_x[2], cache_a[2];
} bf_run_mark;

/* to_mark: copy what a run changes from the integrator into the mark;
 * otherwise back from the mark (undo).  One function for both directions,
 * so the two cannot drift apart; to_mark is a constant at every call. */
BF_ALWAYS_INLINE void bf_run_mark_copy(bf_run_mark *m, bf_integrator *it,
                                       size_t n, int to_mark)
{
    bf_counters *count[2] = {&it->count, &m->count};
    int *valid[2] = {&it->cache_valid, &m->cache_valid};
    unsigned long *epoch[2] = {&it->cache_epoch, &m->cache_epoch};
    double *cx[2] = {it->cache_x, m->cache_x};
    double *ca[2] = {it->cache_a, m->cache_a};
    const int to = to_mark ? 1 : 0, from = 1 - to;
    *count[to] = *count[from];
    *valid[to] = *valid[from];
    *epoch[to] = *epoch[from];
    bf_vec_copy(cx[to], cx[from], n);
    bf_vec_copy(ca[to], ca[from], n);
}

/* k steps one at a time (what every advance falls back to) */
static inline bf_status bf_ball_steps(bf_ball_step_fn step, bf_integrator *it,
                                      const bf_ode *ode,
                                      const bf_ball_forces *f, long n0, long k,
                                      double dt, long *done, bf_err *err)
{
    for (long j = 0; j < k; j++) {
        bf_status st = step(it, ode, f, (double)(n0 + j) * dt, dt, err);
        if (st) {
            *done = j;
            return st;
        }
    }
    *done = k;
    return BF_OK;
}

/* One step of a fixed shape. */
#define BF_BALL_STEP_FIXED(NAME, KERNEL, NWORK, ACCEL, N)                      \
    BF_BALL_HOT static bf_status NAME(bf_integrator *it, const bf_ode *ode,   \
                                      const bf_ball_forces *f, double t,      \
                                      double dt, bf_err *err)                 \
    {                                                                         \
        bf_fixed_forces F;                                                    \
        double w[NWORK * N];                                                  \
        bf_fixed_setup(&F, f, N);                                             \
        bf_status st = KERNEL(it, ode, ACCEL, &F, N, w, t, dt, f->b->x,       \
                              f->b->v, err);                                  \
        if (st || bf_vec_finite(f->b->x, f->b->v, N))                         \
            return st;                                                        \
        return bf_balls_not_finite(f->b, err);                                 \
    }

/* The runs of steps of a fixed shape are also built for AVX-512 and
 * chosen at load time (the film's passes do the same): with its 32 vector
 * registers the state, the constants and the watch stay in registers for
 * the whole run instead of being spilled to the stack in every step
 * (objdump -d of MV2M's run for two balls: 796 stack accesses, 1 in the
 * AVX-512 copy).  The arithmetic is the same scalar IEEE operations in the
 * same order (no fused multiply-adds: -ffp-contract=off), so the same
 * bits; compare_runs.sh checks every scene. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define BF_BALL_RUN_CLONES __attribute__((target_clones("avx512f", "default")))
#else
#define BF_BALL_RUN_CLONES
#endif

/* the signature of every generated advance (bf_ball_advance_fn) */
#define BF_BALL_ADVANCE_SIGNATURE(NAME)                                        \
    BF_BALL_HOT static bf_status NAME(bf_integrator *it, const bf_ode *ode,   \
                                      const bf_ball_forces *f, long n0,       \
                                      long k, double dt, bf_ball_watch *watch,\
                                      long *done, bf_err *err)

/* A run of a fixed shape: in local copies, finiteness at the end (see
 * above); STEP is the shape's one-step function, WATCH_STOP its watched
 * stop.  A run that ends in a state that is not finite is undone (also
 * what the watch recorded) and taken again one step at a time. */
#define BF_BALL_ADVANCE_FIXED(NAME, RUN, NWORK, ACCEL, N, STEP, WATCH_STOP)    \
    /* the run, in its clones; the pickable function below only calls it   \
     * (GCC 12 warns of a dangling pointer where a clone's address is      \
     * taken) */                                                           \
    BF_BALL_HOT BF_BALL_RUN_CLONES static bf_status NAME##_body(             \
        bf_integrator *it, const bf_ode *ode, const bf_ball_forces *f,       \
        long n0, long k, double dt, bf_ball_watch *watch, long *done,        \
        bf_err *err)                                                          \
    {                                                                         \
        if (k == 1 && !watch)                                                 \
            return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err);     \
        bf_fixed_forces F;                                                    \
        bf_run_mark mark;                                                     \
        bf_watch_fixed wf;                                                    \
        double w[NWORK * N] = {0}, x[N], v[N];                                \
        long j;                                                               \
        bf_fixed_setup(&F, f, N);                                             \
        bf_run_mark_copy(&mark, it, N, 1);                                    \
        bf_vec_copy(x, f->b->x, N);                                           \
        bf_vec_copy(v, f->b->v, N);                                           \
        bf_status st;                                                         \
        double max0 = 0, last0 = 0;                                           \
        if (watch) {                                                          \
            max0 = watch->max_rel;                                            \
            last0 = watch->last_rel;                                          \
            bf_watch_fixed_begin(&wf, watch, &F, x, v, N);                    \
            st = RUN(it, ode, ACCEL, &F, WATCH_STOP, &wf, N, w, n0, k, dt, x, \
                     v, &j, err);                                             \
            bf_watch_fixed_done(&wf, watch, N);                               \
        } else {                                                              \
            st = RUN(it, ode, ACCEL, &F, bf_never_stop, NULL, N, w, n0, k,    \
                     dt, x, v, &j, err);                                      \
        }                                                                     \
        if (!bf_vec_finite(x, v, N)) {                                        \
            bf_run_mark_copy(&mark, it, N, 0);                                \
            if (!watch)                                                       \
                return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err); \
            watch->max_rel = max0;                                            \
            watch->last_rel = last0;                                          \
            return bf_ball_steps_watched(STEP, it, ode, f, n0, k, dt, watch,  \
                                         done, err);                          \
        }                                                                     \
        bf_vec_copy(f->b->x, x, N);                                           \
        bf_vec_copy(f->b->v, v, N);                                           \
        *done = j;                                                            \
        return st;                                                            \
    }                                                                         \
    BF_BALL_ADVANCE_SIGNATURE(NAME)                                           \
    {                                                                         \
        return NAME##_body(it, ode, f, n0, k, dt, watch, done, err);          \
    }

/* Any effects, any n: only the dispatch is inlined; the scratch is the
 * integrator's. */
#define BF_BALL_STEP_ANY(NAME, KERNEL)                                         \
    BF_BALL_HOT static bf_status NAME(bf_integrator *it, const bf_ode *ode,   \
                                      const bf_ball_forces *f, double t,      \
                                      double dt, bf_err *err)                 \
    {                                                                         \
        const size_t n = f->b->n;                                             \
        bf_status st = KERNEL(it, ode, bf_ball_accel_any, (void *)f, n,       \
                              it->work, t, dt, f->b->x, f->b->v, err);        \
        if (st || bf_vec_finite(f->b->x, f->b->v, n))                         \
            return st;                                                        \
        return bf_balls_not_finite(f->b, err);                                 \
    }

/* Runs of any effects, any n: in place, finiteness checked after every
 * step (the run stops there; that step failed), and the watch's checks
 * after every step of a watched run. */
#define BF_BALL_ADVANCE_ANY(NAME, RUN, STEP)                                   \
    BF_BALL_ADVANCE_SIGNATURE(NAME)                                           \
    {                                                                         \
        if (k == 1 && !watch)                                                 \
            return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err);     \
        const size_t n = f->b->n;                                             \
        long j;                                                               \
        bf_status st;                                                         \
        if (watch) {                                                          \
            bf_watch_any wa = {watch, f, n0 + 1, dt};                         \
            bf_vec_copy(watch->x_start, f->b->x, n);                          \
            bf_vec_copy(watch->v_start, f->b->v, n);                          \
            watch->fired = 0;                                                 \
            st = RUN(it, ode, bf_ball_accel_any, (void *)f, bf_watch_stop_any,\
                     &wa, n, it->work, n0, k, dt, f->b->x, f->b->v, &j, err); \
        } else {                                                              \
            st = RUN(it, ode, bf_ball_accel_any, (void *)f,                   \
                     bf_stop_not_finite, NULL, n, it->work, n0, k, dt,        \
                     f->b->x, f->b->v, &j, err);                              \
        }                                                                     \
        if (!st && j > 0 && !bf_vec_finite(f->b->x, f->b->v, n)) {            \
            *done = j - 1;                                                    \
            return bf_balls_not_finite(f->b, err);                             \
        }                                                                     \
        *done = j;                                                            \
        return st;                                                            \
    }

/* The stepper of an integrator: every shape instantiated, and pick. */
#define BF_BALL_STEPPER(NAME, KERNEL, RUN, NWORK)                              \
    BF_BALL_STEP_FIXED(NAME##_step_gf1, KERNEL, NWORK, bf_accel_gf, 1)         \
    BF_BALL_STEP_FIXED(NAME##_step_gfc2, KERNEL, NWORK, bf_accel_gfc, 2)       \
    BF_BALL_STEP_ANY(NAME##_step_any, KERNEL)                                  \
    BF_BALL_ADVANCE_FIXED(NAME##_advance_gf1, RUN, NWORK, bf_accel_gf, 1,      \
                          NAME##_step_gf1, bf_watch_stop_gf)                   \
    BF_BALL_ADVANCE_FIXED(NAME##_advance_gfc2, RUN, NWORK, bf_accel_gfc, 2,    \
                          NAME##_step_gfc2, bf_watch_stop_gfc)                 \
    BF_BALL_ADVANCE_ANY(NAME##_advance_any, RUN, NAME##_step_any)              \
    static void NAME##_pick(const bf_ball_forces *f, bf_ball_step_fn *step,    \
                            bf_ball_advance_fn *advance)                      \
    {                                                                         \
        if (bf_shape_gf1(f)) {                                                \
            *step = NAME##_step_gf1;                                          \
            *advance = NAME##_advance_gf1;                                    \
        } else if (bf_shape_gfc2(f)) {                                        \
            *step = NAME##_step_gfc2;                                         \
            *advance = NAME##_advance_gfc2;                                   \
        } else {                                                              \
            *step = NAME##_step_any;                                          \
            *advance = NAME##_advance_any;                                    \
        }                                                                     \
    }                                                                         \
    static const bf_ball_stepper NAME##_balls = {NAME##_pick};

#endif
