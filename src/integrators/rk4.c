/* rk4.c: the classical fourth-order Runge-Kutta method (the paper's "RK41",
 * the 1/6 formula of its ref. [1], Yasuda sec. 2.5, Fig. 3C), applied to
 * the first-order system y = (x, v), y' = (v, a(t, x, v)):
 *
 *   k1 = F(t, y)
 *   k2 = F(t + h/2, y + h/2 k1)
 *   k3 = F(t + h/2, y + h/2 k2)
 *   k4 = F(t + h, y + h k3)
 *   y^{n+1} = y^n + h/6 (k1 + 2 k2 + 2 k3 + k4)
 *
 * Order 4, four force evaluations per step, none reusable by the next step.
 * Not symmetric: on a conservative problem its energy error drifts.  The
 * step is erk.c's with this tableau.
 */
#include "erk.h"
#include "fixed_step.h"

static const bf_erk_tableau rk4 = {
    .s = 4,
    .a = {{0}, {0.5}, {0, 0.5}, {0, 0, 1}},
    .b = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6},
    .c = {0, 0.5, 0.5, 1},
};

BF_ERK_INTEGRATOR(rk4, rk4, 4, 4,
                  "classical Runge-Kutta (the paper's RK41), order 4, 4 force "
                  "evaluations per step");
