/* ballsys.c: balls + effects + integrator (see ballsys.h).
 *
 * Speed: with Verlet or MV2M (the methods of the long runs) a step does not
 * go through the integrator descriptor and the bf_ode callback but through
 * a specialised step: the integrator's kernel (step_kernels.h)
 * instantiated here with the effects' dispatch point inlined
 * (effect_kernels.h).  Same operations in the same order, so the same bits
 * as the generic path (bench/bench_balls.c compares them), same counters.
 * Any other integrator takes the generic path, and so does every step
 * when a caller has replaced s->ode.accel by its own force function.
 *
 * Runs of steps (bf_ballsys_advance, used by the core loop between its
 * events): the run kernels of step_kernels.h keep the state, Verlet's
 * carried force and the counters in locals for the whole run, so a step
 * costs what the hand-fused loop of bench_balls.c costs; same bits,
 * counters and force cache as one call per step (tests/test_advance.c).
 */
#include "ballfilm/ballsys.h"

#include <float.h>
#include <string.h>

#include "ballfilm/effect_kernels.h"
#include "ballfilm/step_kernels.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const bf_param ball_params[] = {
    {"position", BF_REAL, 0, "cm", NULL,
     "centre position at t = 0 (height above the floor, or x in the film)", 0,
     0, 0, NULL},
    {"velocity", BF_REAL, 0, "cm/s", "0", "velocity at t = 0", 0, 0, 0, NULL},
    {"mass", BF_REAL, 0, "g", "1", "mass", BF_POS, 0, 0, NULL},
    {"radius", BF_REAL, 0, "cm", "0.1", "radius", BF_POS, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_ballsys_ball_spec = {
    "ball.N", "one section per ball, N = 1, 2, ... in increasing position",
    ball_params, 0};

/* The acceleration callback handed to the integrator: the effects' dispatch
 * point, inlined here (see effect_kernels.h for why).  The attribute keeps
 * GCC from turning the zeroing loop into a memset call; the specialised
 * steps below carry it too so that this function inlines into them. */
#if defined(__GNUC__) && !defined(__clang__)
#define BALLSYS_HOT __attribute__((optimize("no-tree-loop-distribute-patterns")))
#else
#define BALLSYS_HOT
#endif
BALLSYS_HOT
static int ballsys_accel(void *ctx, double t, const double *x, const double *v,
                         double *acc)
{
    (void)v;
    const bf_ballsys *s = ctx;
    return bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, acc);
}

/* ---- specialised steps ----
 * The kernels of step_kernels.h instantiated with the effects' dispatch
 * inlined.  For the two scenes of the paper's long runs the effect list and
 * the number of balls are also fixed at compile time (gravity + floor with
 * one ball, gravity + floor + contact with two): what the forces read is
 * copied into a local object at the start of the step, so the compiler
 * knows n, sees that the step's stores cannot change it and keeps it in
 * registers.  The effect kernels are the same inline functions, called in
 * the scene's order, so every force is computed exactly as in the generic
 * dispatch. */

BF_ALWAYS_INLINE int ballsys_accel_inl(void *ctx, double t, const double *x,
                                       const double *v, double *acc)
{
    (void)v;
    const bf_ballsys *s = ctx;
    return bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, acc);
}

/* What the forces of a fixed effect list read: the balls with n a
 * compile-time constant (so that the loops unroll) and the effects'
 * parameters.  Nothing is copied: x, v and the scratch are restrict in the
 * kernels, so the compiler knows the step's stores leave these alone. */
typedef struct fixed_forces {
    bf_balls b;
    const bf_gravity *gravity;
    const bf_floor *floor;
    const bf_contact *contact;
} fixed_forces;

BF_ALWAYS_INLINE void fixed_setup(fixed_forces *F, const bf_ballsys *s,
                                  size_t n)
{
    F->b = s->b;
    F->b.n = n;
    F->gravity = s->eff[0].self;
    F->floor = s->eff[1].self;
    F->contact = s->neff > 2 ? s->eff[2].self : NULL;
}

/* the dispatch point's zeroing, then the listed kernels in order */
BF_ALWAYS_INLINE int gf_accel(void *ctx, double t, const double *x,
                              const double *v, double *acc)
{
    (void)t;
    (void)v;
    const fixed_forces *F = ctx;
    BF_UNROLL
    for (size_t i = 0; i < F->b.n; i++)
        acc[i] = 0.0;
    bf_gravity_accel(F->gravity, &F->b, x, acc);
    bf_floor_accel(F->floor, &F->b, x, acc);
    return 0;
}

BF_ALWAYS_INLINE int gfc_accel(void *ctx, double t, const double *x,
                               const double *v, double *acc)
{
    gf_accel(ctx, t, x, v, acc);
    const fixed_forces *F = ctx;
    bf_contact_accel(F->contact, &F->b, x, acc);
    return 0;
}

/* all of x and v finite?  y * 0 is 0 for finite y and NaN for inf and
 * NaN, so the sum is 0 exactly when every value is finite (no branch per
 * value) */
BF_ALWAYS_INLINE int vec_finite(const double *x, const double *v, size_t n)
{
    double z = 0.0;
    BF_UNROLL
    for (size_t i = 0; i < n; i++)
        z += x[i] * 0.0 + v[i] * 0.0;
    return z == 0.0;
}

BF_ALWAYS_INLINE int state_finite(const bf_ballsys *s, size_t n)
{
    return vec_finite(s->b.x, s->b.v, n);
}

/* the runs of step_kernels.h stop at the first non-finite state */
BF_ALWAYS_INLINE int stop_not_finite(const double *x, const double *v,
                                     size_t n)
{
    return !vec_finite(x, v, n);
}

static bf_status not_finite(const bf_ballsys *s, bf_err *err);

/* any integrator through its descriptor; also used when a caller replaced
 * ode.accel (tests plug their own force in this way) */
static bf_status step_generic(bf_ballsys *s, double t, double dt, bf_err *err)
{
    bf_status st = bf_integrator_step(s->it, &s->ode, t, dt, s->b.x, s->b.v,
                                      err);
    if (st || state_finite(s, s->b.n))
        return st;
    return not_finite(s, err);
}

/* k calls of s->step: what every advance falls back to */
static bf_status advance_steps(bf_ballsys *s, long n0, long k, double dt,
                               long *done, bf_err *err)
{
    for (long j = 0; j < k; j++) {
        bf_status st = s->step(s, (double)(n0 + j) * dt, dt, err);
        if (st) {
            *done = j;
            return st;
        }
    }
    *done = k;
    return BF_OK;
}

/* After a run kernel took j steps: a force failure, or the state after
 * the j-th step is not finite (the run stopped there; that step failed),
 * or all went well. */
static bf_status run_end(bf_ballsys *s, bf_status st, long j, long *done,
                         bf_err *err)
{
    if (!st && j > 0 && !state_finite(s, s->b.n)) {
        *done = j - 1;
        return not_finite(s, err);
    }
    *done = j;
    return st;
}

#define BALLSYS_STEP_FIXED(NAME, KERNEL, NWORK, ACCEL, N)                      \
    BALLSYS_HOT static bf_status NAME(bf_ballsys *s, double t, double dt,     \
                                      bf_err *err)                            \
    {                                                                         \
        if (s->ode.accel != ballsys_accel)                                    \
            return step_generic(s, t, dt, err);                               \
        fixed_forces F;                                                       \
        double w[NWORK * N];                                                  \
        fixed_setup(&F, s, N);                                                \
        bf_status st = KERNEL(s->it, &s->ode, ACCEL, &F, N, w, t, dt, s->b.x, \
                              s->b.v, err);                                   \
        if (st || state_finite(s, N))                                         \
            return st;                                                        \
        return not_finite(s, err);                                            \
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
 * and message of bf_ballsys_step.  The state is copied into local arrays
 * for the run: nothing the loop stores can then alias it, and it stays in
 * registers. */
BF_ALWAYS_INLINE int never_stop(const double *x, const double *v, size_t n)
{
    (void)x;
    (void)v;
    (void)n;
    return 0;
}

/* what a run changes in the integrator, for undoing it (n <= 2) */
typedef struct run_mark {
    bf_counters count;
    int cache_valid;
    unsigned long cache_epoch;
    double cache_x[2], cache_a[2];
} run_mark;

BF_ALWAYS_INLINE void run_mark_set(run_mark *m, const bf_integrator *it,
                                   size_t n)
{
    m->count = it->count;
    m->cache_valid = it->cache_valid;
    m->cache_epoch = it->cache_epoch;
    bf_vec_copy(m->cache_x, it->cache_x, n);
    bf_vec_copy(m->cache_a, it->cache_a, n);
}

static void run_mark_undo(const run_mark *m, bf_integrator *it, size_t n)
{
    it->count = m->count;
    it->cache_valid = m->cache_valid;
    it->cache_epoch = m->cache_epoch;
    bf_vec_copy(it->cache_x, m->cache_x, n);
    bf_vec_copy(it->cache_a, m->cache_a, n);
}

#define BALLSYS_ADVANCE_FIXED(NAME, RUN, NWORK, ACCEL, N)                      \
    BALLSYS_HOT static bf_status NAME(bf_ballsys *s, long n0, long k,         \
                                      double dt, long *done, bf_err *err)     \
    {                                                                         \
        if (s->ode.accel != ballsys_accel || k == 1)                          \
            return advance_steps(s, n0, k, dt, done, err);                    \
        fixed_forces F;                                                       \
        run_mark mark;                                                        \
        double w[NWORK * N] = {0}, x[N], v[N];                                \
        long j;                                                               \
        fixed_setup(&F, s, N);                                                \
        run_mark_set(&mark, s->it, N);                                        \
        bf_vec_copy(x, s->b.x, N);                                            \
        bf_vec_copy(v, s->b.v, N);                                            \
        bf_status st = RUN(s->it, &s->ode, ACCEL, &F, never_stop, N, w, n0,   \
                           k, dt, x, v, &j, err);                             \
        if (!vec_finite(x, v, N)) {                                           \
            run_mark_undo(&mark, s->it, N);                                   \
            return advance_steps(s, n0, k, dt, done, err);                    \
        }                                                                     \
        bf_vec_copy(s->b.x, x, N);                                            \
        bf_vec_copy(s->b.v, v, N);                                            \
        *done = j;                                                            \
        return st;                                                            \
    }

BALLSYS_STEP_FIXED(step_mv2m_gf1, bf_mv2m_kernel, 5, gf_accel, 1)
BALLSYS_STEP_FIXED(step_mv2m_gfc2, bf_mv2m_kernel, 5, gfc_accel, 2)
BALLSYS_STEP_FIXED(step_verlet_gf1, bf_verlet_kernel, 3, gf_accel, 1)
BALLSYS_STEP_FIXED(step_verlet_gfc2, bf_verlet_kernel, 3, gfc_accel, 2)
BALLSYS_ADVANCE_FIXED(advance_mv2m_gf1, bf_mv2m_run, 5, gf_accel, 1)
BALLSYS_ADVANCE_FIXED(advance_mv2m_gfc2, bf_mv2m_run, 5, gfc_accel, 2)
BALLSYS_ADVANCE_FIXED(advance_verlet_gf1, bf_verlet_run, 3, gf_accel, 1)
BALLSYS_ADVANCE_FIXED(advance_verlet_gfc2, bf_verlet_run, 3, gfc_accel, 2)

/* any effects, any n: only the dispatch is inlined */
BALLSYS_HOT
static bf_status step_mv2m_any(bf_ballsys *s, double t, double dt, bf_err *err)
{
    if (s->ode.accel != ballsys_accel)
        return step_generic(s, t, dt, err);
    bf_status st = bf_mv2m_kernel(s->it, &s->ode, ballsys_accel_inl, s, s->b.n,
                                  s->it->work, t, dt, s->b.x, s->b.v, err);
    if (st || state_finite(s, s->b.n))
        return st;
    return not_finite(s, err);
}

BALLSYS_HOT
static bf_status step_verlet_any(bf_ballsys *s, double t, double dt,
                                 bf_err *err)
{
    if (s->ode.accel != ballsys_accel)
        return step_generic(s, t, dt, err);
    bf_status st = bf_verlet_kernel(s->it, &s->ode, ballsys_accel_inl, s,
                                    s->b.n, s->it->work, t, dt, s->b.x, s->b.v,
                                    err);
    if (st || state_finite(s, s->b.n))
        return st;
    return not_finite(s, err);
}

/* runs of any effects, any n: in place, finiteness checked after every
 * step */
#define BALLSYS_ADVANCE_ANY(NAME, RUN)                                         \
    BALLSYS_HOT static bf_status NAME(bf_ballsys *s, long n0, long k,         \
                                      double dt, long *done, bf_err *err)     \
    {                                                                         \
        if (s->ode.accel != ballsys_accel || k == 1)                          \
            return advance_steps(s, n0, k, dt, done, err);                    \
        long j;                                                               \
        bf_status st = RUN(s->it, &s->ode, ballsys_accel_inl, s,              \
                           stop_not_finite, s->b.n, s->it->work, n0, k, dt,   \
                           s->b.x, s->b.v, &j, err);                          \
        return run_end(s, st, j, done, err);                                  \
    }

BALLSYS_ADVANCE_ANY(advance_mv2m_any, bf_mv2m_run)
BALLSYS_ADVANCE_ANY(advance_verlet_any, bf_verlet_run)

/* Is the effect list exactly these kinds, in this order? */
static int effects_are(const bf_ballsys *s, const bf_effect_kind *k, size_t nk)
{
    if (s->neff != nk)
        return 0;
    for (size_t j = 0; j < nk; j++)
        if (s->eff[j].type->kind != k[j])
            return 0;
    return 1;
}

static void choose_step(bf_ballsys *s)
{
    static const bf_effect_kind gfc[] = {BF_EFFECT_GRAVITY, BF_EFFECT_FLOOR,
                                         BF_EFFECT_CONTACT};
    const char *iname = s->it->type->name;
    const int mv2m = !strcmp(iname, "mv2m"), verlet = !strcmp(iname, "verlet");
    const int gf1 = s->b.n == 1 && effects_are(s, gfc, 2);
    const int gfc2 = s->b.n == 2 && effects_are(s, gfc, 3);
    if (mv2m) {
        s->step = gf1 ? step_mv2m_gf1 : gfc2 ? step_mv2m_gfc2 : step_mv2m_any;
        s->advance = gf1    ? advance_mv2m_gf1
                     : gfc2 ? advance_mv2m_gfc2
                            : advance_mv2m_any;
    } else if (verlet) {
        s->step = gf1    ? step_verlet_gf1
                  : gfc2 ? step_verlet_gfc2
                         : step_verlet_any;
        s->advance = gf1    ? advance_verlet_gf1
                     : gfc2 ? advance_verlet_gfc2
                            : advance_verlet_any;
    } else {
        s->step = step_generic;
        s->advance = advance_steps;
    }
}

void bf_ballsys_free(bf_ballsys *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->neff; k++)
        if (s->eff[k].type->destroy && s->eff[k].self)
            s->eff[k].type->destroy(s->eff[k].self);
    free(s->eff);
    bf_integrator_free(s->it);
    free(s->b.x);
    free(s->b.v);
    free(s->b.m);
    free(s->b.inv_m);
    free(s->b.R);
    free(s);
}

bf_status bf_ballsys_create(bf_ballsys **out, const bf_scene *sc,
                            const bf_effect_env *env, bf_err *err)
{
    *out = NULL;
    int n = bf_scene_count(sc, "ball");
    if (n < 1)
        return bf_scene_fail(sc, err, "scene", NULL,
                             "no balls: add a [ball.1] section with a "
                             "position");
    bf_ballsys *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    size_t nb = (size_t)n;
    s->b.n = nb;
    s->b.x = calloc(nb, sizeof(double));
    s->b.v = calloc(nb, sizeof(double));
    s->b.m = calloc(nb, sizeof(double));
    s->b.inv_m = calloc(nb, sizeof(double));
    s->b.R = calloc(nb, sizeof(double));
    if (!s->b.x || !s->b.v || !s->b.m || !s->b.inv_m || !s->b.R) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    char sec[32];
    for (size_t i = 0; i < nb; i++) {
        snprintf(sec, sizeof sec, "ball.%zu", i + 1);
        s->b.x[i] = bf_scene_real(sc, sec, "position");
        s->b.v[i] = bf_scene_real(sc, sec, "velocity");
        s->b.m[i] = bf_scene_real(sc, sec, "mass");
        s->b.inv_m[i] = 1.0 / s->b.m[i];
        s->b.R[i] = bf_scene_real(sc, sec, "radius");
    }
    for (size_t i = 0; i + 1 < nb; i++) {
        double d = s->b.x[i + 1] - s->b.x[i];
        if (d < s->b.R[i] + s->b.R[i + 1]) {
            snprintf(sec, sizeof sec, "ball.%zu", i + 2);
            bf_status st;
            if (d < 0)
                st = bf_scene_fail(sc, err, sec, "position",
                                   "balls must be numbered in increasing "
                                   "position: ball %zu at %g cm lies below "
                                   "ball %zu at %g cm",
                                   i + 2, s->b.x[i + 1], i + 1, s->b.x[i]);
            else
                st = bf_scene_fail(sc, err, sec, "position",
                                   "balls %zu and %zu overlap at t = 0 "
                                   "(centres %g cm apart, radii sum %g cm)",
                                   i + 1, i + 2, d, s->b.R[i] + s->b.R[i + 1]);
            bf_ballsys_free(s);
            return st;
        }
    }
    /* effects, in the order the scene lists them */
    size_t ne;
    const char *const *names = bf_scene_names(sc, "scene", "effects", &ne);
    s->eff = calloc(ne ? ne : 1, sizeof *s->eff);
    if (!s->eff) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t k = 0; k < ne; k++) {
        const bf_effect_type *t = bf_effect_find(names[k]);
        if (!t) { /* the registry has already checked the names */
            bf_ballsys_free(s);
            return bf_fail(err, BF_EINTERNAL, "unknown effect %s", names[k]);
        }
        s->eff[k].type = t;
        s->neff = k + 1;
        bf_status st = t->create(&s->eff[k].self, sc, &s->b, env, err);
        if (st) {
            bf_ballsys_free(s);
            return st;
        }
    }
    bf_status st = bf_integrator_create(&s->it, bf_scene_str(sc, "scene",
                                                              "integrator"),
                                        nb, sc, err);
    if (st) {
        bf_ballsys_free(s);
        return st;
    }
    s->ode.n = nb;
    s->ode.accel = ballsys_accel;
    s->ode.ctx = s;
    s->ode.velocity_dependent = 0;
    s->ode.epoch = 0;
    choose_step(s);
    *out = s;
    return BF_OK;
}

static bf_status not_finite(const bf_ballsys *s, bf_err *err)
{
    for (size_t i = 0; i < s->b.n; i++)
        if (!isfinite(s->b.x[i]) || !isfinite(s->b.v[i]))
            return bf_fail(err, BF_EUNSTABLE,
                           "ball %zu: non-finite state (position %g cm, "
                           "velocity %g cm/s); the step is too large for "
                           "this integrator",
                           i + 1, s->b.x[i], s->b.v[i]);
    return bf_fail(err, BF_EUNSTABLE, "non-finite state");
}

void bf_ballsys_energy(const bf_ballsys *s, double t, double *kin, double *pot)
{
    double k = 0.0;
    for (size_t i = 0; i < s->b.n; i++)
        k += 0.5 * s->b.m[i] * s->b.v[i] * s->b.v[i];
    *kin = k;
    *pot = bf_effects_potential_inline(s->eff, s->neff, &s->b, t, s->b.x);
}

bf_status bf_ballsys_save(const bf_ballsys *s, bf_ckpt *ck, const char *prefix,
                          bf_err *err)
{
    char name[256];
    bf_status st;
    snprintf(name, sizeof name, "%s.x", prefix);
    if ((st = bf_ckpt_put(ck, name, s->b.x, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.v", prefix);
    if ((st = bf_ckpt_put(ck, name, s->b.v, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.integrator", prefix);
    return bf_integrator_save(s->it, ck, name, err);
}

bf_status bf_ballsys_load(bf_ballsys *s, const bf_ckpt *ck, const char *prefix,
                          bf_err *err)
{
    char name[256];
    bf_status st;
    snprintf(name, sizeof name, "%s.x", prefix);
    if ((st = bf_ckpt_get(ck, name, s->b.x, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.v", prefix);
    if ((st = bf_ckpt_get(ck, name, s->b.v, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.integrator", prefix);
    return bf_integrator_load(s->it, ck, name, err);
}
