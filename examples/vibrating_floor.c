/* vibrating_floor.c: the classic chaotic bouncer, a ball under gravity on
 * a floor that moves up and down as s(t) = A sin(2 pi f t).
 *
 * The floor is an effect written here (a time-dependent potential): the
 * Hertz contact of Yasuda eq. 2.5 with the moving floor,
 *     force  k d^{3/2},  potential (2/5) k d^{5/2},  d = R - (x - s(t)) > 0,
 * with its own section [vibrating_floor] (amplitude A in cm, frequency f in
 * Hz, Hertz constant k), added to the program's catalog next to the
 * built-in gravity.  Because the potential depends on t the energy is not
 * conserved: the floor does work on the ball, dE/dt = dV/dt = F s'(t), the
 * contact force times the floor's velocity.  A heartbeat after every step
 * integrates that power (trapezoid rule) into W(t) and records the first-
 * return map at the floor contacts: at each release (the end of a contact)
 * the floor's phase 2 pi f t mod 2 pi and the ball's velocity.  The map
 * goes into the run's output file (/floor_map/phase, /floor_map/velocity,
 * written by an observer); plots/vibrating_floor_map.py draws it.
 *
 * Trust numbers: the energy balance |E(T) - E(0) - W(T)| / E(0), small
 * and falling at least like dt^2 (the trapezoid rule; MV2M is of order 3)
 * between dt and dt/2, so that force, potential and its time derivative
 * agree; and the number of map points.  With A (2 pi f)^2 / g = 0.5 and
 * elastic contacts the map is a chaotic sea with the bands of the
 * resonances v = n g / (2 f) (flights of n floor periods); a few hundred
 * seconds fill it.
 *
 * Build and run: make -C examples vibrating_floor && examples/vibrating_floor
 *   [T]  (simulated seconds, default 10; the map in vibrating_floor.h5)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <ballfilm/run.h>
#include <ballfilm/sim.h>

#define PI 3.14159265358979323846

/* ---- the effect ---- */

typedef struct vfloor {
    double A; /* cm */
    double f; /* Hz */
    double k; /* g cm^-1/2 s^-2 */
} vfloor;

static const bf_param vfloor_params[] = {
    {"amplitude", BF_AT(vfloor, A, BF_REAL), "cm", "0.01",
     "amplitude A of the floor's motion s(t) = A sin(2 pi f t)", BF_NONNEG, 0,
     0, NULL},
    {"frequency", BF_AT(vfloor, f, BF_REAL), "Hz", "50",
     "frequency f of the floor's motion", BF_POS, 0, 0, NULL},
    {"k", BF_AT(vfloor, k, BF_REAL), "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the ball-floor contact", BF_POS, 0, 0, NULL},
    {0},
};

static const bf_section_spec vfloor_spec = BF_SECTION(
    "vibrating_floor", "a floor moving as A sin(2 pi f t), Hertz contact",
    vfloor_params, vfloor);

static double floor_at(const vfloor *w, double t)
{
    return w->A * sin(2.0 * PI * w->f * t);
}

static bf_status vfloor_create(void **self, const void *params,
                               const bf_balls *b, bf_err *err)
{
    const vfloor *p = params;
    if (b->x[0] - b->R[0] < p->A) /* above the floor's highest point */
        return bf_fail_key(err, BF_EINPUT, "ball.1", "position",
                           "the ball must start above the floor's highest "
                           "point (position - radius >= amplitude)");
    vfloor *w = malloc(sizeof *w);
    if (!w)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    *w = *p;
    *self = w;
    return BF_OK;
}

/* the overlap d of ball i with the floor at time t (<= 0: no contact) */
static double overlap(const vfloor *w, const bf_balls *b, size_t i, double t,
                      const double *x)
{
    return b->R[i] - (x[i] - floor_at(w, t));
}

static int vfloor_accel(const void *self, const bf_balls *b, double t,
                        const double *x, const double *v, double *acc)
{
    (void)v;
    const vfloor *w = self;
    for (size_t i = 0; i < b->n; i++) {
        const double d = overlap(w, b, i, t, x);
        if (d > 0)
            acc[i] += w->k * d * sqrt(d) * b->inv_m[i];
    }
    return 0;
}

static double vfloor_potential(const void *self, const bf_balls *b, double t,
                               const double *x)
{
    const vfloor *w = self;
    double V = 0.0;
    for (size_t i = 0; i < b->n; i++) {
        const double d = overlap(w, b, i, t, x);
        if (d > 0)
            V += 0.4 * w->k * d * d * sqrt(d);
    }
    return V;
}

static const bf_effect_type vibrating_floor = {
    .name = "vibrating_floor",
    .doc = "a floor moving as A sin(2 pi f t) with Hertz contact",
    .spec = &vfloor_spec,
    .flags = BF_EFFECT_TIME, /* s(t): the force depends on t */
    .create = vfloor_create,
    .accel = vfloor_accel,
    .potential = vfloor_potential,
    .destroy = free,
};

/* ---- the heartbeat: the floor's work and the return map ---- */

typedef struct watch {
    vfloor w;      /* the floor's keys, as the scene resolved them */
    double R;      /* the ball's radius (cm) */
    double work;   /* W(t), erg */
    double power;  /* F s' at the last step, erg/s */
    int in_contact;
    double *phase, *vel;
    size_t n, cap;
} watch;

static bf_status beat(void *ctx, bf_sim *sim, bf_err *err)
{
    watch *h = ctx;
    const double t = bf_sim_time(sim);
    const double x = bf_sim_get(sim, "balls/position", NULL)[0];
    const double v = bf_sim_get(sim, "balls/velocity", NULL)[0];
    const double d = h->R - (x - floor_at(&h->w, t));
    const double force = d > 0 ? h->w.k * d * sqrt(d) : 0.0;
    const double speed = 2.0 * PI * h->w.f * h->w.A *
                         cos(2.0 * PI * h->w.f * t); /* s'(t) */
    const double power = force * speed;
    if (bf_sim_steps_done(sim) > 0)
        h->work += 0.5 * bf_sim_dt(sim) * (h->power + power);
    h->power = power;
    if (h->in_contact && d <= 0) { /* a release: one point of the map */
        if (h->n == h->cap) {
            h->cap = h->cap ? 2 * h->cap : 256;
            h->phase = realloc(h->phase, h->cap * sizeof *h->phase);
            h->vel = realloc(h->vel, h->cap * sizeof *h->vel);
            if (!h->phase || !h->vel)
                return bf_fail(err, BF_EINTERNAL, "out of memory");
        }
        h->phase[h->n] = fmod(2.0 * PI * h->w.f * t, 2.0 * PI);
        h->vel[h->n++] = v;
    }
    h->in_contact = d > 0;
    return BF_OK;
}

/* An observer writes the map into the output when it closes. */
static bf_status map_close(void *self, bf_out *out, bf_err *err)
{
    const watch *h = self;
    bf_status st = bf_out_array(out, "/floor_map/phase", h->phase, h->n, 0,
                                "rad", "floor phase 2 pi f t mod 2 pi at "
                                "each release from the floor", err);
    if (!st)
        st = bf_out_array(out, "/floor_map/velocity", h->vel, h->n, 0, "cm/s",
                          "ball velocity at each release", err);
    return st;
}

static const bf_observer_type map_writer = {
    .name = "floor_map",
    .output_close = map_close,
};

static const char *const scene =
    "[scene]\n"
    "title      = ball on a vibrating floor\n"
    "integrator = mv2m\n"
    "effects    = gravity vibrating_floor\n"
    "output_every = 0.01 s\n"
    "energy_every = 0\n"
    "[vibrating_floor]\n"
    "amplitude  = 0.005    ; cm: A (2 pi f)^2 / g = 0.50\n"
    "frequency  = 50       ; Hz\n"
    "[ball.1]\n"
    "position   = 0.3\n"
    "radius     = 0.1\n";

/* One run of T s at step dt; *balance = |E(T) - E(0) - W(T)| / E(0). */
static int run(const bf_catalog *cat, double T, double dt, const char *out,
               double *balance, size_t *points)
{
    char set_t[64], set_dt[64];
    snprintf(set_t, sizeof set_t, "scene.t_end=%.17g", T);
    snprintf(set_dt, sizeof set_dt, "scene.dt=%.17g", dt);
    const char *sets[] = {set_t, set_dt};
    bf_err err = {0};
    bf_run *r;
    watch *h = calloc(1, sizeof *h);
    if (!h || bf_run_from_text(&r, cat, "vibrating_floor", scene, sets, 2,
                               NULL, &err)) {
        fprintf(stderr, "vibrating_floor: %s\n", h ? err.msg : "no memory");
        return 1;
    }
    bf_sim *sim = bf_run_sim(r);
    /* the keys as the scene resolved them: the values the effect has */
    const bf_scene *sc = bf_run_scene_of(r);
    h->w.A = bf_scene_real(sc, "vibrating_floor", "amplitude");
    h->w.f = bf_scene_real(sc, "vibrating_floor", "frequency");
    h->w.k = bf_scene_real(sc, "vibrating_floor", "k");
    h->R = bf_scene_real(sc, "ball.1", "radius");
    bf_status st = bf_sim_heartbeat(sim, 1, beat, h, &err);
    /* the observer type has no destroy: h stays ours */
    if (!st)
        st = bf_sim_observe(sim, &map_writer, h, &err);
    if (!st && out)
        st = bf_run_open_output(r, out, &err);
    if (!st)
        st = bf_sim_run(sim, &err);
    bf_err cerr = {0};
    bf_status cst = bf_sim_close_output(sim, st, &err, &cerr);
    if (st || cst) {
        fprintf(stderr, "vibrating_floor: %s\n", st ? err.msg : cerr.msg);
        return 1;
    }
    double kin, pot;
    bf_sim_energy(sim, &kin, &pot);
    const double e0 = bf_sim_initial_energy(sim);
    *balance = fabs(kin + pot - e0 - h->work) / fabs(e0);
    *points = h->n;
    bf_run_free(r);
    free(h->phase);
    free(h->vel);
    free(h);
    return 0;
}

int main(int argc, char **argv)
{
    const double T = argc > 1 ? atof(argv[1]) : 10.0;
    bf_err err = {0};
    bf_catalog *cat = bf_catalog_new(bf_catalog_builtin());
    if (!cat || bf_catalog_add_effect(cat, &vibrating_floor, &err)) {
        fprintf(stderr, "vibrating_floor: %s\n", err.msg);
        return 1;
    }
    double b1, b2;
    size_t n1, n2;
    /* the map from the run at dt; the balance from a short run at dt and
     * dt/2 (chaos separates the two runs' trajectories in the long run,
     * but each one's balance is its own) */
    if (run(cat, T, 2e-5, "vibrating_floor.h5", &b1, &n1) ||
        run(cat, 1.0, 2e-5, NULL, &b1, &n2) ||
        run(cat, 1.0, 1e-5, NULL, &b2, &n2))
        return 1;
    bf_catalog_free(cat);
    printf("return map: %zu releases in %g s, written to vibrating_floor.h5 "
           "(draw it with plots/vibrating_floor_map.py)\n", n1, T);
    printf("energy balance |E - E0 - W| / E0 over 1 s: %.3e at dt = 2e-5 s, "
           "%.3e at 1e-5 s: observed order %.2f (at least 2: the trapezoid "
           "rule)\n",
           b1, b2, log(b1 / b2) / log(2.0));
    return log(b1 / b2) / log(2.0) > 1.8 && b2 < 1e-4 ? 0 : 1;
}
