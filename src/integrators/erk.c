/* erk.c: explicit Runge-Kutta step from a tableau (see erk.h).
 *
 * For y = (x, v), y' = F(t, y) = (v, a(t, x, v)), stage i is
 *   X_i = x + h sum_j a_ij V_j,   V_i = v + h sum_j a_ij A_j,
 *   A_i = a(t + c_i h, X_i, V_i)
 * (the position part of stage j's slope is its velocity V_j), and
 *   x^{n+1} = x + h sum_i b_i V_i,   v^{n+1} = v + h sum_i b_i A_i,
 * with the increments formed first and added once.  Sums run over the
 * non-zero coefficients only, in stage order. */
#include "erk.h"
#include "fixed_step.h"

bf_status bf_erk_init(bf_integrator *it, const void *params, int stages,
                      bf_err *err)
{
    return bf_fixed_step_init(it, params, 3 * (size_t)stages, err);
}

bf_status bf_erk_step(const bf_erk_tableau *tab, bf_integrator *it,
                      const bf_ode *ode, double t, double h, double *x,
                      double *v, bf_err *err)
{
    const size_t n = ode->n;
    const int s = tab->s;
    double *X[BF_ERK_MAXS], *V[BF_ERK_MAXS], *A[BF_ERK_MAXS];
    for (int i = 0; i < s; i++) {
        X[i] = it->work + (size_t)(3 * i) * n;
        V[i] = X[i] + n;
        A[i] = V[i] + n;
    }
    for (int i = 0; i < s; i++) {
        const double *xs = x, *vs = v;
        if (i > 0) {
            for (size_t k = 0; k < n; k++) {
                double dx = 0.0, dv = 0.0;
                for (int j = 0; j < i; j++)
                    if (tab->a[i][j] != 0.0) {
                        dx += tab->a[i][j] * V[j][k];
                        dv += tab->a[i][j] * A[j][k];
                    }
                X[i][k] = x[k] + h * dx;
                V[i][k] = v[k] + h * dv;
            }
            xs = X[i];
            vs = V[i];
        } else {
            for (size_t k = 0; k < n; k++)
                V[0][k] = v[k];
        }
        bf_status st = bf_ode_eval(it, ode, t + tab->c[i] * h, xs, vs, A[i],
                                   err);
        if (st)
            return st;
    }
    for (size_t k = 0; k < n; k++) {
        double dx = 0.0, dv = 0.0;
        for (int i = 0; i < s; i++) {
            dx += tab->b[i] * V[i][k];
            dv += tab->b[i] * A[i][k];
        }
        x[k] += h * dx;
        v[k] += h * dv;
    }
    it->count.steps++;
    return BF_OK;
}
