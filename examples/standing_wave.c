/* standing_wave.c: the film driven from C, from an initial height that the
 * program supplies, with a diagnostic of its own in the output file.
 *
 * A uniform single-phase film (psi = 1: all phase d; rho_d = rho_c, no
 * viscosity) of length L = 20 cm and depth h0 = 1 cm, at rest, with the
 * gravest standing wave of height on it,
 *     h(x, 0) = h0 + a cos(k (x + L/2)),  k = pi / L,  a = 1e-3 cm,
 * set from an array (bf_sim_set "film/h") before the first step; the
 * scene itself offers only a kink, a uniform film or an earlier run.
 *
 * Linear theory.  With psi uniform the chemical potential mu = -a psi +
 * b psi^3 - gamma psi'' is constant and drops out of (3.9); with equal
 * densities P/rho_k = g h, so both phases obey the shallow-water equations
 *     h_t + (h u)_x = 0,   u_t + u u_x = -g h_x,
 * whose small waves travel at c = sqrt(g h0) (the film model's linear wave
 * speed is the shallow-water one).  The walls (u = 0, h_x = 0 at x = +-L/2)
 * make the standing mode cos(k (x + L/2)) with k = pi/L, of period
 *     T = 2 pi / (k c) = 2 L / sqrt(g h0) = 1.2777 s.
 * Amplitude a/h0 = 1e-3 shifts it by O((a/h0)^2) = 1e-6, below the
 * scheme's error here.
 *
 * The diagnostic: an observer (sim.h) records the height at the left wall
 * at every step into /wave/h_wall and, when the output closes, the times
 * at which h - h0 crosses zero downwards (linear interpolation between
 * steps) into /wave/crossings and their mean spacing into /wave/period.
 *
 * Trust numbers: the period against 2 L / sqrt(g h0) for dx = 0.4, 0.2,
 * 0.1 cm at a fixed Courant number c dt / dx = 0.25 (dt shrinks with dx);
 * the relative error must fall at the scheme's order, 2 (Lax-Wendroff type;
 * the crossing times are second order in dt too).
 *
 * Build and run: make -C examples standing_wave && examples/standing_wave
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <ballfilm/run.h>
#include <ballfilm/sim.h>

#define PI 3.14159265358979323846

static const double L = 20.0, h0 = 1.0, g = 980.0, amp = 1e-3;

/* ---- the diagnostic: an observer of the time loop ---- */

typedef struct wave {
    bf_sim *sim;
    bf_series *h_wall;
    double last_h, last_t;
    double *cross;
    size_t n, cap;
} wave;

static bf_status wave_open(void *self, bf_out *out, bf_err *err)
{
    wave *w = self;
    w->h_wall = bf_out_series(out, "/wave/h_wall", 0, 0, "cm",
                              "film height at the left wall, every step",
                              err);
    return w->h_wall ? BF_OK : err->status;
}

/* at every output row (every step here): record, look for a crossing */
static bf_status wave_row(void *self, long n, double t, bf_err *err)
{
    wave *w = self;
    const double h = bf_sim_get(w->sim, "film/h", NULL)[0];
    if (bf_series_append(w->h_wall, &h))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (n > 0 && w->last_h > h0 && h <= h0) {
        if (w->n == w->cap) {
            w->cap = w->cap ? 2 * w->cap : 16;
            double *c = realloc(w->cross, w->cap * sizeof *c);
            if (!c)
                return bf_fail(err, BF_EINTERNAL, "out of memory");
            w->cross = c;
        }
        const double s = (w->last_h - h0) / (w->last_h - h);
        w->cross[w->n++] = w->last_t + s * (t - w->last_t);
    }
    w->last_h = h;
    w->last_t = t;
    return BF_OK;
}

static double period(const wave *w)
{
    return w->n > 1 ? (w->cross[w->n - 1] - w->cross[0]) / (double)(w->n - 1)
                    : NAN;
}

static bf_status wave_close(void *self, bf_out *out, bf_err *err)
{
    wave *w = self;
    const double T = period(w);
    bf_status st = bf_out_array(out, "/wave/crossings", w->cross, w->n, 0,
                                "s", "times at which h - h0 at the left "
                                "wall crosses zero downwards", err);
    if (!st)
        st = bf_out_array(out, "/wave/period", &T, 1, 0, "s",
                          "mean spacing of the crossings", err);
    return st;
}

static const bf_observer_type wave_observer = {
    .name = "wave",
    .output_open = wave_open,
    .output_row = wave_row,
    .output_close = wave_close,
};

static const char *const scene =
    "[scene]\n"
    "title        = standing gravity wave on a uniform film\n"
    "model        = film\n"
    "t_end        = 6.5          ; s: five periods\n"
    "output_every = 1            ; every step: the wall's height\n"
    "[film]\n"
    "length       = 20           ; cm\n"
    "h0           = 1            ; cm\n"
    "g            = 980          ; cm/s^2\n"
    "nu           = 0            ; no viscosity\n"
    "initial      = uniform\n"
    "psi0         = 1            ; one phase\n"
    "profile_every = 0.05 s\n";

/* One film at node spacing dx: its period from the diagnostic. */
static int run(double dx, double *T)
{
    const double c = sqrt(g * h0), dt = 0.25 * dx / c;
    char set_dx[64], set_dt[64], out[64];
    snprintf(set_dx, sizeof set_dx, "film.dx=%.17g", dx);
    snprintf(set_dt, sizeof set_dt, "scene.dt=%.17g", dt);
    snprintf(out, sizeof out, "standing_wave_dx%g.h5", dx);
    const char *sets[] = {set_dx, set_dt};
    bf_err err = {0}, cerr = {0};
    bf_run *r;
    if (bf_run_from_text(&r, bf_catalog_builtin(), "standing_wave", scene,
                         sets, 2, NULL, &err)) {
        fprintf(stderr, "standing_wave: %s\n", err.msg);
        return 1;
    }
    bf_sim *sim = bf_run_sim(r);
    /* the initial height from an array on the film's nodes */
    size_t n;
    const double *x = bf_sim_get(sim, "film/x", &n);
    double *h = malloc(n * sizeof *h);
    for (size_t i = 0; h && i < n; i++)
        h[i] = h0 + amp * cos(PI / L * (x[i] + 0.5 * L));
    wave w = {.sim = sim};
    bf_status st = h ? bf_sim_set(sim, "film/h", h, n, &err)
                     : bf_fail(&err, BF_EINTERNAL, "out of memory");
    free(h);
    /* wave_observer has no destroy: w stays ours (it outlives the sim) */
    if (!st)
        st = bf_sim_observe(sim, &wave_observer, &w, &err);
    if (!st)
        st = bf_run_open_output(r, out, &err);
    if (!st)
        st = bf_sim_run(sim, &err);
    bf_status cst = bf_sim_close_output(sim, st, &err, &cerr);
    if (st || cst) {
        fprintf(stderr, "standing_wave: %s\n", st ? err.msg : cerr.msg);
        return 1;
    }
    *T = period(&w);
    printf("%8g %10.3g %6zu %12.8f", dx, dt, n, *T);
    free(w.cross);
    bf_run_free(r);
    return 0;
}

int main(void)
{
    const double theory = 2.0 * L / sqrt(g * h0);
    const double dxs[3] = {0.4, 0.2, 0.1};
    double err[3];
    printf("linear theory: T = 2 L / sqrt(g h0) = %.8f s\n", theory);
    printf("%8s %10s %6s %12s %12s %7s\n", "dx (cm)", "dt (s)", "nodes",
           "T (s)", "|T/T_th - 1|", "order");
    for (int k = 0; k < 3; k++) {
        double T;
        if (run(dxs[k], &T))
            return 1;
        err[k] = fabs(T / theory - 1.0);
        if (k)
            printf(" %12.3e %7.2f\n", err[k],
                   log(err[k - 1] / err[k]) / log(2.0));
        else
            printf(" %12.3e\n", err[k]);
    }
    const double order = log(err[1] / err[2]) / log(2.0);
    printf("period error %.2e at dx = 0.1 cm, observed order %.2f in dx "
           "(the scheme's: 2)\n", err[2], order);
    return fabs(order - 2.0) < 0.3 && err[2] < 1e-3 ? 0 : 1;
}
