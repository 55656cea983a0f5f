/* ballsys.c: balls + effects + integrator (see ballsys.h).
 *
 * Speed: a step goes through the integrator's specialised ball step
 * (bf_integrator_type.balls, made by src/integrators/ball_steps.h for
 * Verlet and MV2M) with the effects' kernels inlined, not through the
 * bf_ode callback; the same operations in the same order, so the same bits
 * as the generic path (bench/bench_balls.c compares them), same counters.
 * Every other integrator takes the generic path, and so does every step
 * when a caller has replaced s->ode.accel by its own force function, and
 * every step of a scene with an effect whose force depends on velocity or
 * explicitly on time (BF_EFFECT_VELOCITY, BF_EFFECT_TIME).
 *
 * Velocity-dependent forces: the callback passes the stage velocities the
 * integrator evaluates at to the effects; an integrator made for a = a(x)
 * (BF_INT_POSITION_ONLY) is refused at creation, naming [scene] integrator
 * and the effect (docs/forces.md).
 */
#include "models/balls_out.h"
#include "models/ballsys.h"

#include "integrators/ball_steps.h"
#include "effects/effect_kernels.h"

#include <float.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param ball_params[] = {
    {"position", BF_AT(bf_ball_keys, position, BF_REAL), "cm", NULL,
     "centre position at t = 0 (height above the floor, or x in the film)", 0,
     0, 0, NULL},
    {"velocity", BF_AT(bf_ball_keys, velocity, BF_REAL), "cm/s", "0",
     "velocity at t = 0", 0, 0, 0, NULL},
    {"mass", BF_AT(bf_ball_keys, mass, BF_REAL), "g", "1", "mass", BF_POS, 0,
     0, NULL},
    {"radius", BF_AT(bf_ball_keys, radius, BF_REAL), "cm", "0.1", "radius",
     BF_POS, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_ballsys_ball_spec = BF_SECTION(
    "ball.N", "one section per ball, N = 1, 2, ... in increasing position",
    ball_params, bf_ball_keys);

/* The acceleration callback handed to the integrator: the effects'
 * dispatch point, inlined.  The attribute keeps GCC from turning the
 * zeroing loop into a memset call (effects.c says why). */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-tree-loop-distribute-patterns")))
#endif
int bf_ballsys_accel(void *ctx, double t, const double *x, const double *v,
                     double *acc)
{
    const bf_ballsys *s = ctx;
    if (s->nw)
        return bf_ballsys_accel_work(ctx, t, x, v, acc);
    return bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, v, acc, NULL);
}

/* Work of the non-conservative forces (erg) as two more ODE components:
 * W_diss' = D(t, x, v), W_inj' = J(t, x, v) (the powers of damped.c and
 * drag; an effect without a potential and not built in dissipates
 * D = -sum_i m_i a_i v_i), the "velocities" of components n and n + 1,
 * so every integrator integrates the work with its own stages, at its
 * own order, and E(t) - E(0) + W_diss - W_inj closes to that order
 * (docs/forces.md).  Each force is evaluated once, for the acceleration
 * and its power.  The ball components keep their bits. */
int bf_ballsys_accel_work(void *ctx, double t, const double *x,
                          const double *v, double *acc)
{
    bf_ballsys *s = ctx;
    bf_power pw = {0.0, 0.0, s->w_acc};
    if (bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, v, acc, &pw))
        return 1;
    acc[s->b.n] = pw.diss;
    acc[s->b.n + 1] = pw.inj;
    return 0;
}

void bf_ballsys_work(const bf_ballsys *s, double *diss, double *inj)
{
    *diss = s->nw ? s->b.v[s->b.n] : 0.0;
    *inj = s->nw ? s->b.v[s->b.n + 1] : 0.0;
}

int bf_ballsys_daccel(void *ctx, double t, const double *x, const double *xn,
                      double *abar)
{
    const bf_ballsys *s = ctx;
    return bf_effects_daccel_inline(s->eff, s->neff, &s->b, t, x, xn, abar);
}

bf_status bf_ballsys_step_generic(bf_ballsys *s, double t, double dt,
                                  bf_err *err)
{
    /* A force of t: the first-same-as-last cache (keyed by x and the
     * epoch) holds the force of the last step's end, t' + dt', and is
     * valid for this step exactly when it starts at that time (to the
     * bit: (n + 1) dt and n dt + dt differ now and then). */
    if (s->time_dependent && !(t == s->t_cached))
        s->ode.epoch++;
    s->t_cached = NAN;
    bf_status st = bf_integrator_step(s->it, &s->ode, t, dt, s->b.x, s->b.v,
                                      err);
    if (st)
        return st;
    s->t_cached = t + dt; /* as the integrators form the end's time */
    for (size_t i = 0; i < s->b.n; i++)
        if (!isfinite(s->b.x[i]) || !isfinite(s->b.v[i]))
            return bf_balls_not_finite(&s->b, err);
    return BF_OK;
}

/* one step of the ball system whose forces are f, as a bf_ball_step_fn */
static bf_status step_of_forces(bf_integrator *it, const bf_ode *ode,
                                const bf_ball_forces *f, double t, double dt,
                                bf_err *err)
{
    (void)it;
    (void)ode;
    bf_ballsys *s = (bf_ballsys *)((char *)f - offsetof(bf_ballsys, forces));
    return bf_ballsys_step(s, t, dt, err);
}

bf_status bf_ballsys_advance_generic(bf_ballsys *s, long n0, long k,
                                     double dt, bf_ball_watch *w, long *done,
                                     bf_err *err)
{
    if (w)
        return bf_ball_steps_watched(step_of_forces, s->it, &s->ode,
                                     &s->forces, n0, k, dt, w, done, err);
    for (long j = 0; j < k; j++) {
        bf_status st = bf_ballsys_step(s, (double)(n0 + j) * dt, dt, err);
        if (st) {
            *done = j;
            return st;
        }
    }
    *done = k;
    return BF_OK;
}

void bf_ballsys_free(bf_ballsys *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->neff; k++)
        if (s->eff[k].type->destroy && s->eff[k].self &&
            !(s->lent && s->lent[k]))
            s->eff[k].type->destroy(s->eff[k].self);
    free(s->lent);
    for (size_t k = 0; s->effect_params && k < s->neff; k++)
        free(s->effect_params[k]);
    free(s->effect_params);
    free(s->eff);
    free(s->ev_work);
    free(s->ev_side);
    free(s->branch);
    free(s->effect_types);
    free(s->it_params);
    bf_integrator_free(s->it);
    free(s->x_start);
    free(s->w_acc);
    free(s->b.x);
    free(s->b.v);
    free(s->b.m);
    free(s->b.inv_m);
    free(s->b.R);
    free(s);
}

/* Balls in increasing position that do not overlap, or the key to blame. */
static bf_status check_order(const bf_balls *b, bf_err *err)
{
    for (size_t i = 0; i + 1 < b->n; i++) {
        double d = b->x[i + 1] - b->x[i];
        if (d >= b->R[i] + b->R[i + 1])
            continue;
        char sec[32];
        snprintf(sec, sizeof sec, "ball.%zu", i + 2);
        if (d < 0)
            return bf_fail_key(err, BF_EINPUT, sec, "position",
                               "balls must be numbered in increasing "
                               "position: ball %zu at %g cm lies below "
                               "ball %zu at %g cm",
                               i + 2, b->x[i + 1], i + 1, b->x[i]);
        return bf_fail_key(err, BF_EINPUT, sec, "position",
                           "balls %zu and %zu overlap at t = 0 (centres %g "
                           "cm apart, radii sum %g cm)",
                           i + 1, i + 2, d, b->R[i] + b->R[i + 1]);
    }
    return BF_OK;
}

/* An initial state whose energy is finite (the loop measures the energy
 * error against it): a kinetic energy m v^2/2 that overflows names that
 * ball's velocity; a potential that does not names the position farthest
 * from the origin (every built-in potential grows with |x|). */
static bf_status check_initial_energy(const bf_ballsys *s, bf_err *err)
{
    const bf_balls *b = &s->b;
    char sec[32];
    for (size_t i = 0; i < b->n; i++) {
        double k = 0.5 * b->m[i] * b->v[i] * b->v[i];
        if (isfinite(k))
            continue;
        snprintf(sec, sizeof sec, "ball.%zu", i + 1);
        return bf_fail_key(err, BF_EINPUT, sec, "velocity",
                           "the kinetic energy of ball %zu at t = 0 "
                           "(m v^2/2 with v = %g cm/s) is not finite",
                           i + 1, b->v[i]);
    }
    double pot = bf_effects_potential(s->eff, s->neff, b, 0.0, b->x);
    if (isfinite(pot))
        return BF_OK;
    size_t far = 0;
    for (size_t i = 1; i < b->n; i++)
        if (fabs(b->x[i]) > fabs(b->x[far]))
            far = i;
    snprintf(sec, sizeof sec, "ball.%zu", far + 1);
    return bf_fail_key(err, BF_EINPUT, sec, "position",
                       "the potential energy at t = 0 is not finite (%g erg; "
                       "ball %zu at %g cm is the farthest out)",
                       pot, far + 1, b->x[far]);
}

/* the name of the first effect with one of the flags */
static const char *effect_with(const bf_ballsys *s, unsigned flags)
{
    for (size_t k = 0; k < s->neff; k++)
        if (bf_effect_flags(&s->eff[k]) & flags)
            return s->eff[k].type->name;
    return "";
}

/* An integrator for a = a(x) (BF_INT_POSITION_ONLY) with an effect whose
 * force depends on velocity: refused, naming [scene] integrator and the
 * effect.  Such a method evaluates the force at predicted positions with
 * the velocities of the step's start, which is first order in v.  A
 * discrete-gradient method (BF_INT_POTENTIAL) with a force of t is
 * refused too: it steps with the discrete gradient of the potential at
 * one time and has no stage at which to integrate the work of the
 * driving (greenspan73 closed the energy balance of a driven floor at
 * first order only). */
static bf_status check_velocity_forces(const bf_ballsys *s, bf_err *err)
{
    const bf_integrator_type *it = s->it->type;
    if (s->time_dependent && (it->flags & BF_INT_POTENTIAL))
        return bf_fail_key(err, BF_EINPUT, "scene", "integrator",
                           "integrator '%s' conserves the energy of a "
                           "potential of the positions, and effect '%s' "
                           "depends explicitly on time (its energy balance "
                           "would lose its order): use rk4, rk3, verlet, "
                           "impmid, rkn6 or arkode (docs/forces.md)",
                           it->name, effect_with(s, BF_EFFECT_TIME));
    if (!s->ode.velocity_dependent || !(it->flags & BF_INT_POSITION_ONLY))
        return BF_OK;
    return bf_fail_key(err, BF_EINPUT, "scene", "integrator",
                       "integrator '%s' is made for forces of the positions "
                       "only, and effect '%s' depends on velocity (it would "
                       "lose its order): use rk4, rk3, verlet, impmid or "
                       "arkode (docs/forces.md)",
                       it->name, effect_with(s, BF_EFFECT_VELOCITY));
}

bf_status bf_ballsys_create(bf_ballsys **out, const bf_model_setup *setup,
                            const bf_effect *given, size_t ngiven,
                            bf_err *err)
{
    *out = NULL;
    size_t nb;
    const bf_ball_keys *keys = bf_setup_get(setup, &bf_ballsys_ball_spec, &nb);
    if (!keys || nb < 1)
        return bf_fail_key(err, BF_EINPUT, "scene", "",
                           "no balls: add a [ball.1] section with a "
                           "position");
    bf_ballsys *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->b.n = nb;
    s->b.x = calloc(nb, sizeof(double));
    s->b.v = calloc(nb, sizeof(double));
    s->b.m = calloc(nb, sizeof(double));
    s->b.inv_m = calloc(nb, sizeof(double));
    s->b.R = calloc(nb, sizeof(double));
    s->x_start = calloc(2 * nb, sizeof(double));
    s->v_start = s->x_start ? s->x_start + nb : NULL;
    if (!s->b.x || !s->b.v || !s->b.m || !s->b.inv_m || !s->b.R ||
        !s->x_start) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t i = 0; i < nb; i++) {
        s->b.x[i] = keys[i].position;
        s->b.v[i] = keys[i].velocity;
        s->b.m[i] = keys[i].mass;
        s->b.inv_m[i] = 1.0 / s->b.m[i];
        s->b.R[i] = keys[i].radius;
    }
    bf_status st = check_order(&s->b, err);
    /* effects, in the order the scene lists them */
    const size_t ne = setup->neffects;
    s->eff = calloc(ne ? ne : 1, sizeof *s->eff);
    s->lent = calloc(ne ? ne : 1, sizeof *s->lent);
    if (!st && (!s->eff || !s->lent))
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    for (size_t k = 0; !st && k < ne; k++) {
        s->eff[k].type = setup->effects[k];
        s->neff = k + 1;
        for (size_t j = 0; j < ngiven && !s->lent[k]; j++)
            if (given[j].type == s->eff[k].type) {
                s->eff[k].self = given[j].self;
                s->lent[k] = 1;
            }
        if (!s->lent[k])
            st = s->eff[k].type->create(&s->eff[k].self,
                                        setup->effect_params[k], &s->b, err);
        const unsigned fl = st ? 0 : bf_effect_flags(&s->eff[k]);
        if (fl & BF_EFFECT_VELOCITY)
            s->ode.velocity_dependent = 1;
        if (fl & BF_EFFECT_TIME)
            s->time_dependent = 1;
        if (fl & (BF_EFFECT_VELOCITY | BF_EFFECT_TIME))
            s->no_fast = 1;
    }
    if (!st)
        st = check_initial_energy(s, err);
    /* the work of non-conservative forces, tracked for the balls' own
     * scenes (not for a caller's lent effects: the coupled model) */
    if (!st && !ngiven && (s->ode.velocity_dependent || s->time_dependent)) {
        double *x = realloc(s->b.x, (nb + 2) * sizeof *x);
        if (x)
            s->b.x = x;
        double *v = x ? realloc(s->b.v, (nb + 2) * sizeof *v) : NULL;
        if (v)
            s->b.v = v;
        s->w_acc = calloc(nb, sizeof *s->w_acc);
        if (!x || !v || !s->w_acc)
            st = bf_fail(err, BF_EINTERNAL, "out of memory");
        else {
            s->nw = 2;
            s->b.x[nb] = s->b.x[nb + 1] = s->b.v[nb] = s->b.v[nb + 1] = 0.0;
        }
    }
    if (!st)
        st = bf_integrator_create(&s->it, setup->integrator, nb + s->nw,
                                  setup->integrator_params, err);
    if (!st)
        st = check_velocity_forces(s, err);
    if (st) {
        bf_ballsys_free(s);
        return st;
    }
    s->effect_types = calloc(ne ? ne : 1, sizeof *s->effect_types);
    const bf_section_spec *isp = setup->integrator->spec;
    if (isp && setup->integrator_params)
        s->it_params = malloc(isp->size);
    if (!s->effect_types || (isp && setup->integrator_params && !s->it_params)) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    memcpy(s->effect_types, setup->effects, ne * sizeof *s->effect_types);
    s->effect_params = calloc(ne ? ne : 1, sizeof *s->effect_params);
    for (size_t k = 0; s->effect_params && k < ne; k++) {
        const bf_section_spec *sp = setup->effects[k]->spec;
        if (!sp || !sp->size || !setup->effect_params[k])
            continue;
        if (!(s->effect_params[k] = malloc(sp->size))) {
            bf_ballsys_free(s);
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        }
        memcpy(s->effect_params[k], setup->effect_params[k], sp->size);
    }
    if (!s->effect_params) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (s->it_params)
        memcpy(s->it_params, setup->integrator_params, isp->size);
    s->ode.n = nb + s->nw;
    s->ode.n_check = nb; /* the work follows from the balls' state */
    s->ode.accel = bf_ballsys_accel;
    s->ode.ctx = s;
    s->ode.epoch = 0;
    s->t_cached = NAN;
    s->ode.daccel = bf_ballsys_daccel;
    s->forces = (bf_ball_forces){&s->b, s->eff, s->neff};
    if (s->it->type->balls && !s->no_fast)
        s->it->type->balls->pick(&s->forces, &s->fast_step, &s->fast_advance);
    bf_ballsys_gaps_setup(s);
    if (s->it->split_events && (st = bf_ballsys_events_setup(s, err))) {
        bf_ballsys_free(s);
        return st;
    }
    *out = s;
    return BF_OK;
}

void bf_ballsys_energy(const bf_ballsys *s, double t, double *kin, double *pot)
{
    double k = 0.0;
    for (size_t i = 0; i < s->b.n; i++)
        k += 0.5 * s->b.m[i] * s->b.v[i] * s->b.v[i];
    *kin = k;
    *pot = bf_effects_potential_inline(s->eff, s->neff, &s->b, t, s->b.x);
}

size_t bf_ballsys_state(bf_ballsys *s, bf_state_var *vars, size_t cap)
{
    const bf_state_var v[2] = {
        {BF_DS_BALLS_POSITION + 1, "cm", s->b.n, s->b.x, 1},
        {BF_DS_BALLS_VELOCITY + 1, "cm/s", s->b.n, s->b.v, 1},
    };
    for (size_t k = 0; k < 2 && k < cap; k++)
        vars[k] = v[k];
    return 2;
}

/* The positions now in s->b.x as a scene's would be checked: order,
 * overlap, each effect's own check (a trial instance of it; not of an
 * effect the caller handed over, which it checks itself). */
static bf_status check_positions(bf_ballsys *s, bf_err *err)
{
    bf_status st = check_order(&s->b, err);
    for (size_t k = 0; !st && k < s->neff; k++) {
        const bf_effect_type *t = s->eff[k].type;
        void *trial = NULL;
        if (s->lent[k])
            continue;
        st = t->create(&trial, s->effect_params[k], &s->b, err);
        if (trial && t->destroy)
            t->destroy(trial);
    }
    return st;
}

bf_status bf_ballsys_set(bf_ballsys *s, const char *name, const double *v,
                         size_t n, bf_err *err)
{
    const int pos = !strcmp(name, "balls/position");
    if ((!pos && strcmp(name, "balls/velocity")) || n != s->b.n)
        return bf_fail(err, BF_EINPUT, "%s: not an array of %zu balls", name,
                       s->b.n);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return bf_fail(err, BF_EINPUT, "%s: ball %zu: %g is not finite",
                           name, i + 1, v[i]);
    double *dst = pos ? s->b.x : s->b.v, *old = malloc(n * sizeof *old);
    if (!old)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    memcpy(old, dst, n * sizeof *old);
    memcpy(dst, v, n * sizeof *dst);
    bf_status st = pos ? check_positions(s, err) : BF_OK;
    if (st) {
        memcpy(dst, old, n * sizeof *dst);
        bf_err_prefix(err, "%s", name);
    }
    free(old);
    bf_integrator_reset(s->it);
    return st;
}

/* 0.5: balls whose computed energy changed by half are no result of a
 * conservative system (shot up, or come to rest: docs/integrators.md),
 * while the methods of Yasuda's Fig. 3, inaccurate on contacts, stay
 * below it on the scenes of runs/ (their own max_energy_error is 0.5).
 * With a non-conservative effect: 0 (the balance E - E0 + W_diss - W_inj
 * is checked and reported, and bounded by [scene] max_energy_error; its
 * relative error is absolute, in erg, when E0 = 0). */
double bf_ballsys_energy_bound(const bf_ballsys *s)
{
    for (size_t k = 0; k < s->neff; k++)
        if (!(bf_effect_flags(&s->eff[k]) & BF_EFFECT_CONSERVATIVE))
            return 0.0;
    return 0.5;
}

void bf_ballsys_view(bf_ballsys *s, bf_ball_view *v)
{
    v->n = s->b.n;
    v->x = s->b.x;
    v->v = s->b.v;
    v->m = s->b.m;
    v->R = s->b.R;
    v->ode = &s->ode;
    v->it = s->it;
    v->it_params = s->it_params;
    v->effects = s->effect_types;
    v->neffects = s->neff;
    v->step_twin = bf_ballsys_step_twin;
    v->step_ctx = s;
}

bf_status bf_ballsys_save(const bf_ballsys *s, bf_ckpt *ck, const char *prefix,
                          bf_err *err)
{
    char name[256];
    bf_status st;
    snprintf(name, sizeof name, "%s.x", prefix);
    if ((st = bf_ckpt_put(ck, name, s->b.x, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.v", prefix);
    if ((st = bf_ckpt_put(ck, name, s->b.v, s->b.n, err)))
        return st;
    if (s->nw) {
        const double w[4] = {s->b.x[s->b.n], s->b.x[s->b.n + 1],
                             s->b.v[s->b.n], s->b.v[s->b.n + 1]};
        snprintf(name, sizeof name, "%s.work", prefix);
        if ((st = bf_ckpt_put(ck, name, w, 4, err)))
            return st;
    }
    /* the time of the cached force, to continue with the same reuses */
    snprintf(name, sizeof name, "%s.t_cached", prefix);
    if (s->time_dependent && isfinite(s->t_cached) &&
        (st = bf_ckpt_put(ck, name, &s->t_cached, 1, err)))
        return st;
    snprintf(name, sizeof name, "%s.integrator", prefix);
    return bf_integrator_save(s->it, ck, name, err);
}

bf_status bf_ballsys_load(bf_ballsys *s, const bf_ckpt *ck, const char *prefix,
                          bf_err *err)
{
    char name[256];
    bf_status st;
    snprintf(name, sizeof name, "%s.x", prefix);
    if ((st = bf_ckpt_get(ck, name, s->b.x, s->b.n, err)))
        return st;
    snprintf(name, sizeof name, "%s.v", prefix);
    if ((st = bf_ckpt_get(ck, name, s->b.v, s->b.n, err)))
        return st;
    if (s->nw) {
        double w[4];
        snprintf(name, sizeof name, "%s.work", prefix);
        if ((st = bf_ckpt_get(ck, name, w, 4, err)))
            return st;
        s->b.x[s->b.n] = w[0];
        s->b.x[s->b.n + 1] = w[1];
        s->b.v[s->b.n] = w[2];
        s->b.v[s->b.n + 1] = w[3];
    }
    /* as the initial state (non-finite refused before any row): a state
     * that is not finite is nothing to continue from (an edited file, or
     * one written between a blow-up and the energy check that stops it) */
    for (size_t k = 0; k < s->b.n; k++)
        if (!isfinite(s->b.x[k]) || !isfinite(s->b.v[k]))
            return bf_fail(err, BF_EINPUT, "checkpoint: %s: ball %zu at x = "
                           "%g cm with v = %g cm/s: not finite", prefix,
                           k + 1, s->b.x[k], s->b.v[k]);
    snprintf(name, sizeof name, "%s.t_cached", prefix);
    s->t_cached = NAN;
    if (s->time_dependent && bf_ckpt_has(ck, name) &&
        (st = bf_ckpt_get(ck, name, &s->t_cached, 1, err)))
        return st;
    snprintf(name, sizeof name, "%s.integrator", prefix);
    if ((st = bf_integrator_load(s->it, ck, name, err)))
        return st;
    /* with a force of t the loaded cache is valid where the time of its
     * force is known (and the step starts then), else never */
    if (s->time_dependent)
        s->ode.epoch = s->it->cache_epoch + !isfinite(s->t_cached);
    return BF_OK;
}
