/* yoshida.c: a user-defined integrator, registered by the program.
 *
 * Yoshida's fourth-order composition of velocity Verlet (H. Yoshida,
 * Phys. Lett. A 150, 262, 1990): three Verlet steps of w1 dt, w0 dt, w1 dt
 * with w1 = 1 / (2 - 2^(1/3)), w0 = -2^(1/3) w1 (w0 < 0: the middle step
 * goes backwards).  The composition is symmetric and its weights cancel the
 * dt^3 error term of Verlet, so it is of order 4 and, like Verlet,
 * symplectic.
 *
 * It is added to a catalog of this program's own (bf_catalog_new +
 * bf_catalog_add_integrator) and named by the scene like a built-in one.
 * Trust numbers, on the harmonic oscillator x'' = -x (built-in spring,
 * omega = 1), x(0) = 1, to T = 10 s:
 *   - the observed order of the error |x(T) - cos T| between dt and dt/2
 *     (should be 4: the composition's order, against the analytic solution);
 *   - the largest relative energy error, which for a symplectic method
 *     stays bounded (no drift) and falls like dt^4.
 *
 * Build and run: make -C examples yoshida && examples/yoshida
 */
#include <math.h>
#include <stdio.h>

#include <ballfilm/run.h>
#include <ballfilm/sim.h>

/* One velocity Verlet step of length h from (x, v) with a = a(x) in acc
 * (the force at x, kept up to date: first the kick with the old force,
 * then the drift, the new force, the second kick). */
static bf_status verlet(bf_integrator *it, const bf_ode *ode, double t,
                        double h, double *x, double *v, double *acc,
                        bf_err *err)
{
    for (size_t i = 0; i < ode->n; i++) {
        v[i] += 0.5 * h * acc[i];
        x[i] += h * v[i];
    }
    bf_status st = bf_ode_eval(it, ode, t + h, x, v, acc, err);
    for (size_t i = 0; !st && i < ode->n; i++)
        v[i] += 0.5 * h * acc[i];
    return st;
}

static bf_status yoshida_init(bf_integrator *it, const void *params,
                              bf_err *err)
{
    (void)params;                                /* no [integrator] keys */
    return bf_integrator_alloc_work(it, 3, err); /* acc, x0, v0 */
}

static bf_status yoshida_step(bf_integrator *it, const bf_ode *ode, double t,
                              double dt, double *x, double *v, bf_err *err)
{
    const double cbrt2 = cbrt(2.0);
    const double w1 = 1.0 / (2.0 - cbrt2), w0 = -cbrt2 * w1;
    const size_t n = ode->n;
    double *acc = it->work, *x0 = acc + n, *v0 = x0 + n;
    for (size_t i = 0; i < n; i++) {
        x0[i] = x[i];
        v0[i] = v[i];
    }
    bf_status st = bf_ode_eval(it, ode, t, x, v, acc, err);
    if (!st)
        st = verlet(it, ode, t, w1 * dt, x, v, acc, err);
    if (!st)
        st = verlet(it, ode, t + w1 * dt, w0 * dt, x, v, acc, err);
    if (!st)
        st = verlet(it, ode, t + (w1 + w0) * dt, w1 * dt, x, v, acc, err);
    if (st) { /* the interface's promise: x, v as they were at t */
        for (size_t i = 0; i < n; i++) {
            x[i] = x0[i];
            v[i] = v0[i];
        }
        return st;
    }
    it->count.steps++;
    return BF_OK;
}

static const bf_integrator_type yoshida4 = {
    .name = "yoshida4",
    .doc = "Yoshida's fourth-order composition of velocity Verlet",
    .order = 4,
    .evals_per_step = 4,
    .flags = BF_INT_SYMMETRIC | BF_INT_POSITION_ONLY,
    .init = yoshida_init,
    .step = yoshida_step,
};

static const char *const oscillator =
    "[scene]\n"
    "title      = harmonic oscillator, Yoshida's composition\n"
    "integrator = yoshida4\n"
    "effects    = spring\n"
    "t_end      = 10\n"
    "output_every = 0.1 s\n"
    "[spring]\n"
    "stiffness  = 1\n"
    "[ball.1]\n"
    "position   = 1\n";

/* One run at step dt: the error at T = 10 s and the energy error. */
static int run(const bf_catalog *cat, double dt, double *x_err,
               double *e_err)
{
    char set[64];
    snprintf(set, sizeof set, "scene.dt=%.17g", dt);
    const char *sets[] = {set};
    bf_err err = {0};
    bf_run *r;
    if (bf_run_from_text(&r, cat, "oscillator", oscillator, sets, 1, NULL,
                         &err) ||
        bf_sim_run(bf_run_sim(r), &err)) {
        fprintf(stderr, "yoshida: %s\n", err.msg);
        return 1;
    }
    const double *x = bf_sim_get(bf_run_sim(r), "balls/position", NULL);
    *x_err = fabs(x[0] - cos(bf_sim_time(bf_run_sim(r))));
    *e_err = bf_sim_max_energy_error(bf_run_sim(r));
    bf_run_free(r);
    return 0;
}

int main(void)
{
    bf_err err = {0};
    bf_catalog *cat = bf_catalog_new(bf_catalog_builtin());
    if (!cat || bf_catalog_add_integrator(cat, &yoshida4, &err)) {
        fprintf(stderr, "yoshida: %s\n", cat ? err.msg : "out of memory");
        return 1;
    }
    const double dts[3] = {0.1, 0.05, 0.025};
    double xe[3], ee[3];
    printf("%8s %14s %14s %8s\n", "dt (s)", "|x(T) - cos T|", "max |dE/E|",
           "order");
    for (int k = 0; k < 3; k++) {
        if (run(cat, dts[k], &xe[k], &ee[k]))
            return 1;
        if (k)
            printf("%8.4g %14.4e %14.4e %8.3f\n", dts[k], xe[k], ee[k],
                   log(xe[k - 1] / xe[k]) / log(2.0));
        else
            printf("%8.4g %14.4e %14.4e %8s\n", dts[k], xe[k], ee[k], "");
    }
    bf_catalog_free(cat);
    /* the trust numbers */
    const double order = log(xe[1] / xe[2]) / log(2.0);
    printf("observed order %.3f (the composition's: 4)\n", order);
    printf("energy error %.3e at dt = %g s, falling by %.1f per halving "
           "(2^4 = 16)\n",
           ee[2], dts[2], ee[1] / ee[2]);
    return fabs(order - 4.0) < 0.2 ? 0 : 1;
}
