/* step_kernels.h: the step formulas of Verlet (Yasuda eqs 2.9-2.11) and
 * MV2M (eqs 2.19-2.21, 2.24) written once, as inline functions of the
 * acceleration callback.
 *
 * Why: verlet.c and mv2m.c call them with the bf_ode's callback (an
 * indirect call per force evaluation, any model).  bf_ballsys (ballsys.c)
 * instantiates them with its own force function, a compile-time constant,
 * so the compiler inlines the effect kernels into the step: no indirect
 * call per evaluation, no call per step, small loops it can see through.
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
 * compile-time n and a local array.  x, v and work are distinct arrays
 * (restrict), which lets the compiler keep values in registers across the
 * stores of a step. */

/* Velocity Verlet with the first-same-as-last force cache (integrator.h);
 * work holds 3n doubles. */
BF_ALWAYS_INLINE bf_status bf_verlet_kernel(bf_integrator *it,
                                            const bf_ode *ode,
                                            bf_accel_fn accel, void *ctx,
                                            size_t n, double *restrict work,
                                            double t, double dt,
                                            double *restrict x,
                                            double *restrict v, bf_err *err)
{
    double *a0 = work, *a1 = work + n, *xn = work + 2 * n;
    if (it->cache_valid && it->cache_epoch == ode->epoch &&
        bf_vec_same(it->cache_x, x, n)) {
        bf_vec_copy(a0, it->cache_a, n);
    } else {
        it->count.evals++;
        if (accel(ctx, t, x, v, a0))
            return bf_ode_eval_failed(err);
    }
    const double h2 = 0.5 * dt * dt;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++)
        xn[i] = x[i] + (dt * v[i] + h2 * a0[i]);
    it->count.evals++;
    if (accel(ctx, t + dt, xn, v, a1))
        return bf_ode_eval_failed(err);
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        x[i] = xn[i];
        v[i] += 0.5 * dt * (a1[i] + a0[i]);
    }
    bf_vec_copy(it->cache_x, x, n);
    bf_vec_copy(it->cache_a, a1, n);
    it->cache_epoch = ode->epoch;
    it->cache_valid = 1;
    it->count.steps++;
    return BF_OK;
}

/* MV2M: three evaluations, increments formed first (see mv2m.c); work
 * holds 5n doubles. */
BF_ALWAYS_INLINE bf_status bf_mv2m_kernel(bf_integrator *it, const bf_ode *ode,
                                          bf_accel_fn accel, void *ctx,
                                          size_t n, double *restrict work,
                                          double t, double dt,
                                          double *restrict x,
                                          double *restrict v, bf_err *err)
{
    (void)ode;
    double *a0 = work, *aV = work + n, *aT = work + 2 * n, *xV = work + 3 * n,
           *xT = work + 4 * n;
    it->count.evals++;
    if (accel(ctx, t, x, v, a0))
        return bf_ode_eval_failed(err);
    const double dt2 = dt * dt, hdt = 0.5 * dt, hdt2 = 0.5 * dt2,
                 edt2 = 0.125 * dt2, dt6 = dt / 6.0, dt26 = dt2 / 6.0;
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        xV[i] = x[i] + (dt * v[i] + hdt2 * a0[i]);
        xT[i] = x[i] + (hdt * v[i] + edt2 * a0[i]);
    }
    /* both predictors: the velocity argument is unused (a = a(x)) */
    it->count.evals++;
    if (accel(ctx, t + dt, xV, v, aV))
        return bf_ode_eval_failed(err);
    it->count.evals++;
    if (accel(ctx, t + hdt, xT, v, aT))
        return bf_ode_eval_failed(err);
    BF_KUNROLL
    for (size_t i = 0; i < n; i++) {
        /* (vV + 2 vT)/3 - v^n = dt/6 (a0 + aV + 4 aT)
         * x^{n+1} - x^n     = dt v^n + dt^2/6 (2 a0 + aV) */
        double dv = dt6 * (a0[i] + aV[i] + 4.0 * aT[i]);
        double dx = dt * v[i] + dt26 * (2.0 * a0[i] + aV[i]);
        x[i] += dx;
        v[i] += dv;
    }
    it->count.steps++;
    return BF_OK;
}

#endif
