/* step_kernels.h: the step formulas of Verlet (Yasuda eqs 2.9-2.11),
 * MV2M (eqs 2.19-2.21, 2.24) and RKN6 (rkn6.c) written once, as inline functions of the
 * acceleration callback.
 *
 * Why: verlet.c and mv2m.c call them with the bf_ode's callback (an
 * indirect call per force evaluation, any model).  bf_ballsys (ballsys.c)
 * instantiates them with its own force function, a compile-time constant,
 * so the compiler inlines the effect kernels into the step: no indirect
 * call per evaluation, small loops it can see through, and with the run
 * kernels no call per step either.
 * Both instantiations execute the same floating-point operations in the
 * same order, so they give bit-identical results (bench/bench_balls.c
 * checks it), and the counters and the Verlet force cache behave the same.
 * See verlet.c and mv2m.c for the methods themselves.
 */
#ifndef BALLFILM_STEP_KERNELS_H
#define BALLFILM_STEP_KERNELS_H

#include <stdint.h>
#include <string.h>

#include "ballfilm/integrator.h"

#if defined(__GNUC__) && !defined(__clang__)
#define BF_KUNROLL _Pragma("GCC unroll 4")
#else
#define BF_KUNROLL
#endif

#if defined(__GNUC__)
#define BF_ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define BF_ALWAYS_INLINE static inline
#endif

/* bitwise equality and copy of short vectors (memcmp/memcpy semantics,
 * without a library call for n = 2) */
BF_ALWAYS_INLINE int bf_vec_same(const double *a, const double *b, size_t n)
{
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        uint64_t ua, ub;
        memcpy(&ua, &a[i], sizeof ua);
        memcpy(&ub, &b[i], sizeof ub);
        if (ua != ub)
            return 0;
    }
    return 1;
}

BF_ALWAYS_INLINE void bf_vec_copy(double *dst, const double *src, size_t n)
{
    BF_KUNROLL
    for (size_t i = 0; i < n; i++)
        dst[i] = src[i];
}

/* The kernels take the size n and the scratch `work` explicitly: the
 * generic callers pass ode->n and it->work, a specialised caller a
 * compile-time n and local arrays.  x, v and work are distinct arrays
 * (restrict), which lets the compiler keep values in registers across the
 * stores of a step.
 *
 * Each method has a core (the formulas of one step, no bookkeeping), a
 * one-step kernel (core + counters + force cache: what verlet.c and mv2m.c
 * run) and a run kernel: k steps in one call, with step j going from
 * t = (n0 + j) dt to (n0 + j + 1) dt (t = n dt as in the core loop), the
 * same bits, counters and cache as k calls of the one-step kernel.  A run
 * keeps the state, the carried force and the counters in locals (registers
 * when n is a compile-time constant and x, v are local arrays) and touches
 * the integrator's memory only at its ends.  After every step it asks
 * `stop(stop_ctx, x, v, n)` whether to end the run there (the general runs
 * of the ball system stop at a non-finite state, watched runs at what they
 * watch, ball_steps.h; the fixed runs check finiteness once at the
 * end, see ballsys.c). */
typedef int (*bf_stop_fn)(void *ctx, const double *x, const double *v,
                          size_t n);

/* The parameters every one-step kernel and every run kernel takes (the
 * same for all methods, so that ball_steps.h instantiates them alike). */
#define BF_STEP_KERNEL_PARAMS                                                 \
    bf_integrator *it, const bf_ode *ode, bf_accel_fn accel, void *ctx,       \
        size_t n, double *restrict work, double t, double dt,                 \
        double *restrict x, double *restrict v, bf_err *err
#define BF_RUN_KERNEL_PARAMS                                                  \
    bf_integrator *it, const bf_ode *ode, bf_accel_fn accel, void *ctx,       \
        bf_stop_fn stop, void *stop_ctx, size_t n, double *restrict work,     \
        long n0, long k, double dt, double *restrict x, double *restrict v,   \
        long *done, bf_err *err

/* ---- velocity Verlet ---- */

/* a0 = a(x) from the first-same-as-last cache (integrator.h); 1 if found */
BF_ALWAYS_INLINE int bf_verlet_cache_get(const bf_integrator *it,
                                         const bf_ode *ode, size_t n,
                                         const double *x, double *a0)
{
    if (it->cache_valid && it->cache_epoch == ode->epoch &&
        bf_vec_same(it->cache_x, x, n)) {
        bf_vec_copy(a0, it->cache_a, n);
        return 1;
    }
    return 0;
}

BF_ALWAYS_INLINE void bf_verlet_cache_put(bf_integrator *it, const bf_ode *ode,
                                          size_t n, const double *x,
                                          const double *a)
{
    bf_vec_copy(it->cache_x, x, n);
    bf_vec_copy(it->cache_a, a, n);
    it->cache_epoch = ode->epoch;
    it->cache_valid = 1;
}

/* One step (eqs 2.9-2.11) with a0 = a(x^n) given: x, v advanced in place,
 * a1 = a(x^{n+1}).  Non-zero if the force fails (x, v unchanged then).
 * xn: n doubles of scratch. */
BF_ALWAYS_INLINE int bf_verlet_core(bf_accel_fn accel, void *ctx, size_t n,
                                    double t, double dt, double *restrict x,
                                    double *restrict v,
                                    const double *restrict a0,
                                    double *restrict a1, double *restrict xn)
{
    const double h2 = 0.5 * dt * dt;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++)
        xn[i] = x[i] + (dt * v[i] + h2 * a0[i]);
    if (accel(ctx, t + dt, xn, v, a1))
        return 1;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        x[i] = xn[i];
        v[i] += 0.5 * dt * (a1[i] + a0[i]);
    }
    return 0;
}

/* One step with the force cache; work holds 3n doubles. */
BF_ALWAYS_INLINE bf_status bf_verlet_kernel(BF_STEP_KERNEL_PARAMS)
{
    double *a0 = work, *a1 = work + n, *xn = work + 2 * n;
    if (!bf_verlet_cache_get(it, ode, n, x, a0)) {
        it->count.evals++;
        if (accel(ctx, t, x, v, a0))
            return bf_ode_eval_failed(err);
    }
    it->count.evals++;
    if (bf_verlet_core(accel, ctx, n, t, dt, x, v, a0, a1, xn))
        return bf_ode_eval_failed(err);
    bf_verlet_cache_put(it, ode, n, x, a1);
    it->count.steps++;
    return BF_OK;
}

/* k >= 0 steps from t = n0 dt (see above); work holds 3n doubles.  *done:
 * steps taken, the one after which `stop` ended the run included.  If the
 * force fails in step j, *done = j and x, v are those after step j - 1. */
BF_ALWAYS_INLINE bf_status bf_verlet_run(BF_RUN_KERNEL_PARAMS)
{
    double *a0 = work, *a1 = work + n, *xn = work + 2 * n;
    unsigned long long evals = 0;
    long j = 0;
    bf_status st = BF_OK;
    if (k > 0 && !bf_verlet_cache_get(it, ode, n, x, a0)) {
        evals++;
        if (accel(ctx, (double)n0 * dt, x, v, a0))
            st = bf_ode_eval_failed(err);
    }
    while (!st && j < k) {
        evals++;
        if (bf_verlet_core(accel, ctx, n, (double)(n0 + j) * dt, dt, x, v, a0,
                           a1, xn)) {
            st = bf_ode_eval_failed(err);
            break;
        }
        j++;
        bf_vec_copy(a0, a1, n); /* the next step's a(x^n) */
        if (stop(stop_ctx, x, v, n))
            break;
    }
    it->count.evals += evals;
    it->count.steps += (unsigned long long)j;
    if (j > 0)
        bf_verlet_cache_put(it, ode, n, x, a0);
    *done = j;
    return st;
}

/* The loop of a run kernel whose core takes (accel, ctx, n, t, STEP, x, v,
 * work, &evals), STEP dt or what the core forms from dt once per run, and
 * counts its own evaluations (MV2M, RKN6): steps j = 0..k-1
 * from t = (n0 + j) dt while st is BF_OK, ending after a step that `stop`
 * flags; then the counters.  A macro, not a function of a core pointer,
 * so that the core is inlined for certain. */
#define BF_CORE_RUN_LOOP(CORE, STEP)                                          \
    do {                                                                      \
        while (!st && j < k) {                                                \
            if (CORE(accel, ctx, n, (double)(n0 + j) * dt, STEP, x, v, work,  \
                     &evals)) {                                               \
                st = bf_ode_eval_failed(err);                                 \
                break;                                                        \
            }                                                                 \
            j++;                                                              \
            if (stop(stop_ctx, x, v, n))                                      \
                break;                                                        \
        }                                                                     \
        it->count.evals += evals;                                             \
        it->count.steps += (unsigned long long)j;                             \
    } while (0)

/* ---- MV2M ---- */

/* The step's multiples of dt, formed once per run: the compiler does not
 * move them out of a run's loop by itself (a division may trap, and the
 * loop may take no step), and two divisions per step cost more than the
 * step's sums (the same values however often they are formed). */
typedef struct bf_mv2m_coef {
    double dt, hdt, hdt2, edt2, dt6, dt26;
} bf_mv2m_coef;

BF_ALWAYS_INLINE bf_mv2m_coef bf_mv2m_coefs(double dt)
{
    const double dt2 = dt * dt;
    bf_mv2m_coef c;
    c.dt = dt;
    c.hdt = 0.5 * dt;
    c.hdt2 = 0.5 * dt2;
    c.edt2 = 0.125 * dt2;
    c.dt6 = dt / 6.0;
    c.dt26 = dt2 / 6.0;
    return c;
}

/* One step (eqs 2.19-2.21, 2.24; increments formed first, see mv2m.c)
 * with the multiples of dt in c: three evaluations, each counted in *evals
 * before it is made.  Non-zero if the force fails (x, v unchanged then).
 * work holds 5n doubles. */
BF_ALWAYS_INLINE int bf_mv2m_core_c(bf_accel_fn accel, void *ctx, size_t n,
                                    double t, const bf_mv2m_coef *c,
                                    double *restrict x, double *restrict v,
                                    double *restrict work,
                                    unsigned long long *evals)
{
    double *a0 = work, *aV = work + n, *aT = work + 2 * n, *xV = work + 3 * n,
           *xT = work + 4 * n;
    const double dt = c->dt, hdt = c->hdt, hdt2 = c->hdt2, edt2 = c->edt2,
                 dt6 = c->dt6, dt26 = c->dt26;
    ++*evals;
    if (accel(ctx, t, x, v, a0))
        return 1;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        xV[i] = x[i] + (dt * v[i] + hdt2 * a0[i]);
        xT[i] = x[i] + (hdt * v[i] + edt2 * a0[i]);
    }
    /* both predictors: the velocity argument is unused (a = a(x)) */
    ++*evals;
    if (accel(ctx, t + dt, xV, v, aV))
        return 1;
    ++*evals;
    if (accel(ctx, t + hdt, xT, v, aT))
        return 1;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        /* (vV + 2 vT)/3 - v^n = dt/6 (a0 + aV + 4 aT)
         * x^{n+1} - x^n     = dt v^n + dt^2/6 (2 a0 + aV) */
        double dv = dt6 * (a0[i] + aV[i] + 4.0 * aT[i]);
        double dx = dt * v[i] + dt26 * (2.0 * a0[i] + aV[i]);
        x[i] += dx;
        v[i] += dv;
    }
    return 0;
}

/* one step from dt itself */
BF_ALWAYS_INLINE int bf_mv2m_core(bf_accel_fn accel, void *ctx, size_t n,
                                  double t, double dt, double *restrict x,
                                  double *restrict v, double *restrict work,
                                  unsigned long long *evals)
{
    const bf_mv2m_coef c = bf_mv2m_coefs(dt);
    return bf_mv2m_core_c(accel, ctx, n, t, &c, x, v, work, evals);
}

/* One step; work holds 5n doubles. */
BF_ALWAYS_INLINE bf_status bf_mv2m_kernel(BF_STEP_KERNEL_PARAMS)
{
    (void)ode;
    unsigned long long evals = 0;
    int fail = bf_mv2m_core(accel, ctx, n, t, dt, x, v, work, &evals);
    it->count.evals += evals;
    if (fail)
        return bf_ode_eval_failed(err);
    it->count.steps++;
    return BF_OK;
}

/* k >= 0 steps from t = n0 dt, as bf_verlet_run (no cache: MV2M evaluates
 * no force at x^{n+1}); work holds 5n doubles. */
BF_ALWAYS_INLINE bf_status bf_mv2m_run(BF_RUN_KERNEL_PARAMS)
{
    (void)ode;
    unsigned long long evals = 0;
    long j = 0;
    bf_status st = BF_OK;
    const bf_mv2m_coef c = bf_mv2m_coefs(dt);
    BF_CORE_RUN_LOOP(bf_mv2m_core_c, &c);
    *done = j;
    return st;
}

/* ---- RKN6: Dormand, El-Mikkawy & Prince's RKN6(4)6FD (see rkn6.c) ---- */

enum { BF_RKN6_S = 6 };
/* nodes c_i, position coefficients a_ij (multiplying dt^2; the last row is
 * the position weights b_j, so stage 6 is at x^{n+1}) and velocity
 * weights bv_j, from the exact values in sqrt(8581) of the paper (rkn6.c),
 * rounded to double */
static const double bf_rkn6_c[BF_RKN6_S] = {
    0.0, 0.12929590313670442, 0.25859180627340883, 0.67029708261548, 0.9,
    1.0};
static const double bf_rkn6_a[BF_RKN6_S][BF_RKN6_S - 1] = {
    {0},
    {0.008358715283968025},
    {0.011144953711957367, 0.022289907423914734},
    {0.1454747428010918, -0.22986064052264749, 0.3090349872029675},
    {-0.20766826295078997, 0.6863667842925143, -0.19954927787234925,
     0.12585075653062489},
    {0.07811016144349478, 0.0, 0.2882917411897668, 0.12242553717457041,
     0.011172560192168035},
};
static const double bf_rkn6_bv[BF_RKN6_S] = {
    0.07811016144349478, 0.0, 0.3888434787059826, 0.3713207579288423,
    0.11172560192168035, 0.05};

/* One step with k_1 = a(x^n) in work[0..n): x, v advanced in place and
 * work[0..n) = a(x^{n+1}) (the last stage, first same as last).  Five
 * evaluations, each counted in *evals before it is made; non-zero if the
 * force fails (x, v unchanged then).  work holds 7n doubles: the six
 * stages k_1..k_6 and the stage position X. */
BF_ALWAYS_INLINE int bf_rkn6_core(bf_accel_fn accel, void *ctx, size_t n,
                                  double t, double dt, double *restrict x,
                                  double *restrict v, double *restrict work,
                                  unsigned long long *evals)
{
    double *k = work, *X = work + BF_RKN6_S * n;
    const double h2 = dt * dt;
    for (int s = 1; s < BF_RKN6_S; s++) {
        const double ch = bf_rkn6_c[s] * dt;
        BF_KUNROLL
        for (size_t i = 0; i < n; i++) {
            double sum = 0.0;
            for (int j = 0; j < s; j++)
                sum += bf_rkn6_a[s][j] * k[(size_t)j * n + i];
            X[i] = x[i] + (ch * v[i] + h2 * sum);
        }
        ++*evals;
        if (accel(ctx, t + ch, X, v, k + (size_t)s * n))
            return 1;
    }
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        double sum = 0.0;
        for (int j = 0; j < BF_RKN6_S; j++)
            sum += bf_rkn6_bv[j] * k[(size_t)j * n + i];
        x[i] = X[i];
        v[i] += dt * sum;
        k[i] = k[(size_t)(BF_RKN6_S - 1) * n + i];
    }
    return 0;
}

/* One step with the force cache; work holds 7n doubles. */
BF_ALWAYS_INLINE bf_status bf_rkn6_kernel(BF_STEP_KERNEL_PARAMS)
{
    unsigned long long evals = 0;
    if (!bf_verlet_cache_get(it, ode, n, x, work)) {
        evals++;
        if (accel(ctx, t, x, v, work)) {
            it->count.evals += evals;
            return bf_ode_eval_failed(err);
        }
    }
    int fail = bf_rkn6_core(accel, ctx, n, t, dt, x, v, work, &evals);
    it->count.evals += evals;
    if (fail)
        return bf_ode_eval_failed(err);
    bf_verlet_cache_put(it, ode, n, x, work);
    it->count.steps++;
    return BF_OK;
}

/* k >= 0 steps from t = n0 dt, as bf_verlet_run; work holds 7n doubles. */
BF_ALWAYS_INLINE bf_status bf_rkn6_run(BF_RUN_KERNEL_PARAMS)
{
    unsigned long long evals = 0;
    long j = 0;
    bf_status st = BF_OK;
    if (k > 0 && !bf_verlet_cache_get(it, ode, n, x, work)) {
        evals++;
        if (accel(ctx, (double)n0 * dt, x, v, work))
            st = bf_ode_eval_failed(err);
    }
    BF_CORE_RUN_LOOP(bf_rkn6_core, dt);
    if (j > 0)
        bf_verlet_cache_put(it, ode, n, x, work);
    *done = j;
    return st;
}

#endif
