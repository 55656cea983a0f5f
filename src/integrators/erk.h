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

#endif
