/* ballsys.c: balls + effects + integrator (see ballsys.h). */
#include "ballfilm/ballsys.h"

#include "ballfilm/effect_kernels.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const bf_param ball_params[] = {
    {"position", BF_REAL, "cm", NULL,
     "centre position at t = 0 (height above the floor, or x in the film)", 0,
     0, 0, NULL},
    {"velocity", BF_REAL, "cm/s", "0", "velocity at t = 0", 0, 0, 0, NULL},
    {"mass", BF_REAL, "g", "1", "mass", BF_POS, 0, 0, NULL},
    {"radius", BF_REAL, "cm", "0.1", "radius", BF_POS, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_ballsys_ball_spec = {
    "ball.N", "one section per ball, N = 1, 2, ... in increasing position",
    ball_params};

/* The acceleration callback handed to the integrator: the effects' dispatch
 * point, inlined here (see effect_kernels.h for why). */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-tree-loop-distribute-patterns")))
#endif
static int ballsys_accel(void *ctx, double t, const double *x, const double *v,
                         double *acc)
{
    (void)v;
    const bf_ballsys *s = ctx;
    return bf_effects_accel_inline(s->eff, s->neff, &s->b, t, x, acc);
}

void bf_ballsys_free(bf_ballsys *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->neff; k++)
        if (s->eff[k].type->destroy && s->eff[k].self)
            s->eff[k].type->destroy(s->eff[k].self);
    free(s->eff);
    bf_integrator_free(s->it);
    free(s->b.x);
    free(s->b.v);
    free(s->b.m);
    free(s->b.inv_m);
    free(s->b.R);
    free(s);
}

bf_status bf_ballsys_create(bf_ballsys **out, const bf_scene *sc,
                            const bf_effect_env *env, bf_err *err)
{
    *out = NULL;
    int n = bf_scene_count(sc, "ball");
    if (n < 1)
        return bf_scene_fail(sc, err, "scene", NULL,
                             "no balls: add a [ball.1] section with a "
                             "position");
    bf_ballsys *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    size_t nb = (size_t)n;
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
    char sec[32];
    for (size_t i = 0; i < nb; i++) {
        snprintf(sec, sizeof sec, "ball.%zu", i + 1);
        s->b.x[i] = bf_scene_real(sc, sec, "position");
        s->b.v[i] = bf_scene_real(sc, sec, "velocity");
        s->b.m[i] = bf_scene_real(sc, sec, "mass");
        s->b.inv_m[i] = 1.0 / s->b.m[i];
        s->b.R[i] = bf_scene_real(sc, sec, "radius");
    }
    for (size_t i = 0; i + 1 < nb; i++) {
        double d = s->b.x[i + 1] - s->b.x[i];
        if (d < s->b.R[i] + s->b.R[i + 1]) {
            snprintf(sec, sizeof sec, "ball.%zu", i + 2);
            bf_status st;
            if (d < 0)
                st = bf_scene_fail(sc, err, sec, "position",
                                   "balls must be numbered in increasing "
                                   "position: ball %zu at %g cm lies below "
                                   "ball %zu at %g cm",
                                   i + 2, s->b.x[i + 1], i + 1, s->b.x[i]);
            else
                st = bf_scene_fail(sc, err, sec, "position",
                                   "balls %zu and %zu overlap at t = 0 "
                                   "(centres %g cm apart, radii sum %g cm)",
                                   i + 1, i + 2, d, s->b.R[i] + s->b.R[i + 1]);
            bf_ballsys_free(s);
            return st;
        }
    }
    /* effects, in the order the scene lists them */
    size_t ne;
    const char *const *names = bf_scene_names(sc, "scene", "effects", &ne);
    s->eff = calloc(ne ? ne : 1, sizeof *s->eff);
    if (!s->eff) {
        bf_ballsys_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t k = 0; k < ne; k++) {
        const bf_effect_type *t = bf_effect_find(names[k]);
        if (!t) { /* the registry has already checked the names */
            bf_ballsys_free(s);
            return bf_fail(err, BF_EINTERNAL, "unknown effect %s", names[k]);
        }
        s->eff[k].type = t;
        s->neff = k + 1;
        bf_status st = t->create(&s->eff[k].self, sc, &s->b, env, err);
        if (st) {
            bf_ballsys_free(s);
            return st;
        }
    }
    bf_status st = bf_integrator_create(&s->it, bf_scene_str(sc, "scene",
                                                              "integrator"),
                                        nb, sc, err);
    if (st) {
        bf_ballsys_free(s);
        return st;
    }
    s->ode.n = nb;
    s->ode.accel = ballsys_accel;
    s->ode.ctx = s;
    s->ode.velocity_dependent = 0;
    s->ode.epoch = 0;
    *out = s;
    return BF_OK;
}

bf_status bf_ballsys_step(bf_ballsys *s, double t, double dt, bf_err *err)
{
    bf_status st = bf_integrator_step(s->it, &s->ode, t, dt, s->b.x, s->b.v, err);
    if (st)
        return st;
    for (size_t i = 0; i < s->b.n; i++)
        if (!isfinite(s->b.x[i]) || !isfinite(s->b.v[i]))
            return bf_fail(err, BF_EUNSTABLE,
                           "ball %zu: non-finite state (position %g cm, "
                           "velocity %g cm/s); the step is too large for "
                           "this integrator",
                           i + 1, s->b.x[i], s->b.v[i]);
    return BF_OK;
}

void bf_ballsys_energy(const bf_ballsys *s, double t, double *kin, double *pot)
{
    double k = 0.0;
    for (size_t i = 0; i < s->b.n; i++)
        k += 0.5 * s->b.m[i] * s->b.v[i] * s->b.v[i];
    *kin = k;
    *pot = bf_effects_potential(s->eff, s->neff, &s->b, t, s->b.x);
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
