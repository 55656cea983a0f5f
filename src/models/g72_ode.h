/* g72_ode.h: Greenspan's 1972 particles as an ordinary differential
 * equation for ARKODE ([greenspan72] integrator = arkode), the other
 * method beside the paper's leapfrog (greenspan72.c).
 *
 * The ODE is the limit dt -> 0 of the leapfrog (1972, eqs 2.1-2.4):
 * dx_j/dt = v_j, dv_j/dt = a_j(x) + g_j(x) y^, with a the repulsion
 * (2.11, 2.12; and the Hertz pairs with [hertz] enabled) and g the
 * support-set gravity (2.8, 2.9), both from the model's own routine
 * (given as a callback, so the forces are the leapfrog's bit for bit).
 * ARKODE's adaptive ERK integrates y = (x, y, vx, vy) from t to t + dt
 * and stops exactly there; the walls (eq. 2.13) are applied by the model
 * after that step, as after a leapfrog step.
 *
 * The right-hand side is not smooth: g_j jumps when a particle changes
 * its band K_j or a band under it empties or fills, the support set
 * S(P_j) changes when two particles pass each other in y, the overlap
 * areas have kinks when square edges cross, the repulsion's beta factor
 * has a kink at r = d, and a wall hit inside a step is treated at the
 * step's end (first order).  The adaptive ERK meets the jumps with
 * rejected steps; its error is then no longer proportional to its
 * tolerance.  Private to the library (greenspan72.c). */
#ifndef BALLFILM_MODELS_G72_ODE_H
#define BALLFILM_MODELS_G72_ODE_H

#include "ballfilm/particles.h"
#include "integrators/ark1.h"

/* Fill the accelerations ax, ay (repulsion) and g (gravity, along y; all
 * cm/s^2) at the current positions of the particles. */
typedef bf_status (*bf_g72_accel_fn)(void *model, bf_err *err);

typedef struct bf_g72_ode_opts {
    int table; /* ERK table (integrators/arkode.h) */
    double rtol, atol, max_step;
    long max_steps;
} bf_g72_ode_opts;

typedef struct bf_g72_ode bf_g72_ode;

/* For the particles p, whose accelerations accel(model) writes into ax,
 * ay, g (all kept, not owned). */
bf_status bf_g72_ode_create(bf_g72_ode **out, bf_particles *p,
                            const double *ax, const double *ay,
                            const double *g, bf_g72_accel_fn accel,
                            void *model, const bf_g72_ode_opts *o,
                            bf_err *err);
void bf_g72_ode_free(bf_g72_ode *o);

/* ARKODE's steps from t to t + dt: positions and velocities at t + dt
 * (the velocities synchronised with the positions, unlike the
 * leapfrog's half-step ones); the accelerations are left at some stage's
 * positions.  On failure the particles are those at t. */
bf_status bf_g72_ode_step(bf_g72_ode *o, double t, double dt, bf_err *err);

/* "arkode ERK <table> rtol=..." and the nominal order; o == NULL: the
 * model's leapfrog. */
void bf_g72_ode_describe(const bf_g72_ode *o, char *buf, size_t cap,
                         int *order);
/* The ARKODE integrator: its counters (bf_ark1_counters) are the
 * model's, its checkpoints (bf_ark1_save, bf_ark1_load) the model's
 * (under "g72.ode"). */
bf_ark1 *bf_g72_ode_arkode(const bf_g72_ode *o);

#endif
