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
 * A shape is matched by the kernels the effects declare (effect.h), never
 * by name.
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
    (void)v;
    const bf_ball_forces *f = ctx;
    return bf_effects_accel_inline(f->eff, f->neff, f->b, t, x, acc);
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
        if (f->eff[j].type->kernel != k[j])
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
BF_ALWAYS_INLINE int bf_stop_not_finite(const double *x, const double *v,
                                        size_t n)
{
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
BF_ALWAYS_INLINE int bf_never_stop(const double *x, const double *v, size_t n)
{
    (void)x;
    (void)v;
    (void)n;
    return 0;
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

/* the signature of every generated advance (bf_ball_advance_fn) */
#define BF_BALL_ADVANCE_SIGNATURE(NAME)                                        \
    BF_BALL_HOT static bf_status NAME(bf_integrator *it, const bf_ode *ode,   \
                                      const bf_ball_forces *f, long n0,       \
                                      long k, double dt, long *done,          \
                                      bf_err *err)

/* A run of a fixed shape: in local copies, finiteness at the end (see
 * above); STEP is the shape's one-step function. */
#define BF_BALL_ADVANCE_FIXED(NAME, RUN, NWORK, ACCEL, N, STEP)                \
    BF_BALL_ADVANCE_SIGNATURE(NAME)                                           \
    {                                                                         \
        if (k == 1)                                                           \
            return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err);     \
        bf_fixed_forces F;                                                    \
        bf_run_mark mark;                                                     \
        double w[NWORK * N] = {0}, x[N], v[N];                                \
        long j;                                                               \
        bf_fixed_setup(&F, f, N);                                             \
        bf_run_mark_copy(&mark, it, N, 1);                                    \
        bf_vec_copy(x, f->b->x, N);                                           \
        bf_vec_copy(v, f->b->v, N);                                           \
        bf_status st = RUN(it, ode, ACCEL, &F, bf_never_stop, N, w, n0, k,    \
                           dt, x, v, &j, err);                                \
        if (!bf_vec_finite(x, v, N)) {                                        \
            bf_run_mark_copy(&mark, it, N, 0);                                \
            return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err);     \
        }                                                                     \
        bf_vec_copy(f->b->x, x, N);                                           \
        bf_vec_copy(f->b->v, v, N);                                           \
        *done = j;                                                            \
        return st;                                                            \
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
 * step (the run stops there; that step failed). */
#define BF_BALL_ADVANCE_ANY(NAME, RUN, STEP)                                   \
    BF_BALL_ADVANCE_SIGNATURE(NAME)                                           \
    {                                                                         \
        if (k == 1)                                                           \
            return bf_ball_steps(STEP, it, ode, f, n0, k, dt, done, err);     \
        const size_t n = f->b->n;                                             \
        long j;                                                               \
        bf_status st = RUN(it, ode, bf_ball_accel_any, (void *)f,             \
                           bf_stop_not_finite, n, it->work, n0, k, dt,        \
                           f->b->x, f->b->v, &j, err);                        \
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
                          NAME##_step_gf1)                                     \
    BF_BALL_ADVANCE_FIXED(NAME##_advance_gfc2, RUN, NWORK, bf_accel_gfc, 2,    \
                          NAME##_step_gfc2)                                    \
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
