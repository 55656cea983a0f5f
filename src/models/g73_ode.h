/* g73_ode.h: Greenspan's 1973 particles as an ordinary differential
 * equation, integrated by other methods than the paper's implicit scheme
 * ([greenspan73] integrator = leapfrog or arkode).
 *
 * The ODE is the limit dt -> 0 of the scheme (2.1)-(2.4): dx_i/dt = v_i,
 * mu_i dv_i/dt = F_i(x), with F the continuous pair force of potential
 * (2.17) plus gravity, i.e. the discrete force of dforce.h at x^{k+1} =
 * x^k (where it is -grad V exactly: 2a S_n(a, a) = (n-1)/a^n); fixed
 * particles keep x and v.  Methods:
 *   leapfrog  the 1972 paper's leapfrog (eqs 2.1-2.4 there) in its
 *             kick-drift-kick form with synchronised velocities:
 *             v^{k+1/2} = v^k + dt/2 a(x^k), x^{k+1} = x^k + dt v^{k+1/2},
 *             v^{k+1} = v^{k+1/2} + dt/2 a(x^{k+1}); second order,
 *             symplectic, one force evaluation per step (the last kept);
 *   arkode    ARKODE's adaptive ERK (any table of arkode.c) on
 *             y = (x, y, vx, vy), stopped exactly at every [scene] dt.
 * Private to the library (greenspan73.c). */
#ifndef BALLFILM_MODELS_G73_ODE_H
#define BALLFILM_MODELS_G73_ODE_H

#include "ballfilm/checkpoint.h"
#include "ballfilm/integrator.h"
#include "ballfilm/particles.h"
#include "particles/dforce.h"

enum { BF_G73_IMPLICIT = 0, BF_G73_LEAPFROG = 1, BF_G73_ARKODE = 2 };

typedef struct bf_g73_ode_opts {
    int method; /* BF_G73_LEAPFROG or BF_G73_ARKODE */
    int table;  /* arkode: ERK table (integrators/arkode.h) */
    double rtol, atol, max_step;
    long max_steps;
} bf_g73_ode_opts;

typedef struct bf_g73_ode bf_g73_ode;

/* For the particles p with force f and inertia mu (all kept, not owned). */
bf_status bf_g73_ode_create(bf_g73_ode **out, const bf_dforce *f,
                            const double *mu, bf_particles *p,
                            const bf_g73_ode_opts *o, bf_err *err);
void bf_g73_ode_free(bf_g73_ode *o);

/* One step of dt (leapfrog) or ARKODE's steps from t to t + dt. */
bf_status bf_g73_ode_step(bf_g73_ode *o, double t, double dt, bf_err *err);
/* The particles were changed from outside: forget the kept force. */
void bf_g73_ode_changed(bf_g73_ode *o);

void bf_g73_ode_counters(const bf_g73_ode *o, bf_counters *c);
void bf_g73_ode_describe(const bf_g73_ode *o, char *buf, size_t cap,
                         int *order);
/* Checkpoints (under "g73.ode_*"): the counters, and ARKODE's next
 * initial step; after a load the counters go on as in the run that was
 * not interrupted (the leapfrog's kept force is recomputed, not counted). */
bf_status bf_g73_ode_save(const bf_g73_ode *o, bf_ckpt *ck, bf_err *err);
bf_status bf_g73_ode_load(bf_g73_ode *o, const bf_ckpt *ck, bf_err *err);

#endif
