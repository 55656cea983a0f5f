/* erk.h: explicit Runge-Kutta methods for the second-order system
 * x' = v, v' = a(t, x, v), from a Butcher tableau (private to
 * src/integrators; rk3.c and rk4.c are its tables). */
#ifndef BALLFILM_ERK_H
#define BALLFILM_ERK_H

#include "ballfilm/integrator.h"

enum { BF_ERK_MAXS = 4 };

typedef struct bf_erk_tableau {
    int s;                                /* stages */
    double a[BF_ERK_MAXS][BF_ERK_MAXS];   /* strictly lower triangular */
    double b[BF_ERK_MAXS], c[BF_ERK_MAXS];
} bf_erk_tableau;

/* it->work must hold 3 s n doubles (bf_erk_init); params: the
 * bf_fixed_step_keys of [integrator] (fixed_step.h). */
bf_status bf_erk_init(bf_integrator *it, const void *params, int stages,
                      bf_err *err);
bf_status bf_erk_step(const bf_erk_tableau *tab, bf_integrator *it,
                      const bf_ode *ode, double t, double h, double *x,
                      double *v, bf_err *err);

/* The descriptor `bf_integrator_<id>` of the explicit method with tableau
 * `tab` (a static bf_erk_tableau of the including file): its init and step
 * are erk.c's, its keys fixed_step.h's; order, stages (tab.s, one force
 * evaluation each; a literal, as a static initializer needs) and `doc` as
 * given. */
#define BF_ERK_INTEGRATOR(id, tab, order_, stages_, doc_)                     \
    static bf_status id##_init(bf_integrator *it, const void *params,         \
                               bf_err *err)                                   \
    {                                                                         \
        return bf_erk_init(it, params, (tab).s, err);                         \
    }                                                                         \
    static bf_status id##_step(bf_integrator *it, const bf_ode *ode,          \
                               double t, double h, double *x, double *v,      \
                               bf_err *err)                                   \
    {                                                                         \
        return bf_erk_step(&(tab), it, ode, t, h, x, v, err);                 \
    }                                                                         \
    const bf_integrator_type bf_integrator_##id = {                           \
        .name = #id,                                                          \
        .doc = doc_,                                                          \
        .order = order_,                                                      \
        .evals_per_step = stages_,                                             \
        .flags = 0,                                                           \
        .spec = &bf_fixed_step_spec,                                          \
        .init = id##_init,                                                    \
        .step = id##_step,                                                    \
    }

#endif
