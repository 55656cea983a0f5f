/* ballsys.c: balls + effects + integrator (see ballsys.h).
 *
 * Speed: a step goes through the integrator's specialised ball step
 * (bf_integrator_type.balls, made by src/integrators/ball_steps.h for
 * Verlet and MV2M) with the effects' kernels inlined, not through the
 * bf_ode callback; the same operations in the same order, so the same bits
 * as the generic path (bench/bench_balls.c compares them), same counters.
 * Every other integrator takes the generic path, and so does every step
 * when a caller has replaced s->ode.accel by its own force function.
 */
#include "models/ballsys.h"

#include "effects/effect_kernels.h"

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
    (void)v;
    const bf_ballsys *s = ctx;
    return bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, acc);
}

bf_status bf_ballsys_step_generic(bf_ballsys *s, double t, double dt,
                                  bf_err *err)
{
    bf_status st = bf_integrator_step(s->it, &s->ode, t, dt, s->b.x, s->b.v,
                                      err);
    if (st)
        return st;
    for (size_t i = 0; i < s->b.n; i++)
        if (!isfinite(s->b.x[i]) || !isfinite(s->b.v[i]))
            return bf_balls_not_finite(&s->b, err);
    return BF_OK;
}

bf_status bf_ballsys_advance_generic(bf_ballsys *s, long n0, long k,
                                     double dt, long *done, bf_err *err)
{
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
        if (s->eff[k].type->destroy && s->eff[k].self)
            s->eff[k].type->destroy(s->eff[k].self);
    free(s->eff);
    free(s->effect_types);
    free(s->it_params);
    bf_integrator_free(s->it);
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

bf_status bf_ballsys_create(bf_ballsys **out, const bf_model_setup *setup,
                            const bf_effect_env *env, bf_err *err)
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
    if (!s->b.x || !s->b.v || !s->b.m || !s->b.inv_m || !s->b.R) {
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
    if (!st && !s->eff)
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    for (size_t k = 0; !st && k < ne; k++) {
        s->eff[k].type = setup->effects[k];
        s->neff = k + 1;
        st = s->eff[k].type->create(&s->eff[k].self, setup->effect_params[k],
                                    &s->b, env, err);
    }
    if (!st)
        st = bf_integrator_create(&s->it, setup->integrator, nb,
                                  setup->integrator_params, err);
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
    if (s->it_params)
        memcpy(s->it_params, setup->integrator_params, isp->size);
    s->ode.n = nb;
    s->ode.accel = bf_ballsys_accel;
    s->ode.ctx = s;
    s->ode.velocity_dependent = 0;
    s->ode.epoch = 0;
    s->forces = (bf_ball_forces){&s->b, s->eff, s->neff};
    if (s->it->type->balls)
        s->it->type->balls->pick(&s->forces, &s->fast_step, &s->fast_advance);
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
    snprintf(name, sizeof name, "%s.integrator", prefix);
    return bf_integrator_load(s->it, ck, name, err);
}
