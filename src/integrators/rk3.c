/* rk3.c: Kutta's third-order method (the paper's "RK32", Yasuda sec. 2.5,
 * Fig. 3D), applied to the first-order system y = (x, v),
 * y' = F(t, y) = (v, a(t, x, v)):
 *
 *   k1 = F(t, y)
 *   k2 = F(t + h/2, y + h/2 k1)
 *   k3 = F(t + h, y - h k1 + 2h k2)
 *   y^{n+1} = y^n + h/6 (k1 + 4 k2 + k3)
 *
 * Order 3, three force evaluations per step (as many as MV2M), none
 * reusable.  Not symmetric: its energy error drifts.  The step is erk.c's
 * with this tableau.
 */
#include "erk.h"
#include "fixed_step.h"

static const bf_erk_tableau rk3 = {
    .s = 3,
    .a = {{0}, {0.5}, {-1, 2}},
    .b = {1.0 / 6, 2.0 / 3, 1.0 / 6},
    .c = {0, 0.5, 1},
};

BF_ERK_INTEGRATOR(rk3, rk3, 3, 3,
                  "Kutta's third-order Runge-Kutta (the paper's RK32), order 3, 3 "
                  "force evaluations per step");
