/* g73_ode.c: the 1973 particles as an ODE under the leapfrog and ARKODE
 * (g73_ode.h). */
#include "models/g73_ode.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/ark1.h"
#include "models/greenspan.h"

struct bf_g73_ode {
    bf_g73_ode_opts o;
    const bf_dforce *f;
    const double *mu;
    bf_particles *p;
    size_t n;
    double *r;      /* n x n distances */
    double *fx, *fy; /* the force at the current positions (leapfrog) */
    double *y;       /* arkode: 4n */
    bf_ark1 *ark;
    int force_valid, replay;
    unsigned long long steps, evals;
};

/* F(x) into fx, fy (fixed particles 0). */
static void force(bf_g73_ode *o, const double *x, const double *y)
{
    bf_dforce_distances(o->f, x, y, o->r);
    bf_dforce_eval(o->f, x, y, o->r, x, y, o->r, o->fx, o->fy);
    if (o->replay)
        o->replay = 0;
    else
        o->evals++;
}

static int rhs(void *ctx, double t, const double *y, double *ydot)
{
    (void)t;
    bf_g73_ode *o = ctx;
    const size_t n = o->n;
    force(o, y, y + n);
    for (size_t i = 0; i < n; i++) {
        const int fixed = o->f->fixed[i];
        ydot[i] = fixed ? 0.0 : y[2 * n + i];
        ydot[n + i] = fixed ? 0.0 : y[3 * n + i];
        ydot[2 * n + i] = fixed ? 0.0 : o->fx[i] / o->mu[i];
        ydot[3 * n + i] = fixed ? 0.0 : o->fy[i] / o->mu[i];
    }
    return 0;
}

void bf_g73_ode_free(bf_g73_ode *o)
{
    if (!o)
        return;
    bf_ark1_free(o->ark);
    free(o->r);
    free(o->fx);
    free(o->fy);
    free(o->y);
    free(o);
}

bf_status bf_g73_ode_create(bf_g73_ode **out, const bf_dforce *f,
                            const double *mu, bf_particles *p,
                            const bf_g73_ode_opts *opts, bf_err *err)
{
    *out = NULL;
    bf_g73_ode *o = calloc(1, sizeof *o);
    if (!o)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    o->o = *opts;
    o->f = f;
    o->mu = mu;
    o->p = p;
    o->n = p->n;
    const size_t n = o->n ? o->n : 1;
    o->r = malloc(n * n * sizeof *o->r);
    o->fx = malloc(n * sizeof *o->fx);
    o->fy = malloc(n * sizeof *o->fy);
    o->y = malloc(4 * n * sizeof *o->y);
    bf_status st = o->r && o->fx && o->fy && o->y
                       ? BF_OK
                       : bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st && o->o.method == BF_G73_ARKODE) {
        bf_ark1_opts ao = {
            .kind = BF_ARK1_ERK,
            .table = o->o.table,
            .rtol = o->o.rtol,
            .atol = o->o.atol,
            .max_step = o->o.max_step,
            .max_steps = o->o.max_steps,
            .work_around_311 = 1,
        };
        st = bf_ark1_create(&o->ark, 4 * o->n, rhs, NULL, o, &ao, err);
        if (st == BF_EINPUT)
            bf_err_prefix(err, "[greenspan73] table");
    }
    if (st) {
        bf_g73_ode_free(o);
        return st;
    }
    *out = o;
    return BF_OK;
}

void bf_g73_ode_changed(bf_g73_ode *o) { o->force_valid = 0; }

/* v += h F/mu for the free particles */
static void kick(bf_g73_ode *o, double h)
{
    bf_particles *p = o->p;
    for (size_t i = 0; i < o->n; i++)
        if (!o->f->fixed[i]) {
            p->vx[i] += h * o->fx[i] / o->mu[i];
            p->vy[i] += h * o->fy[i] / o->mu[i];
        }
}

static bf_status leapfrog(bf_g73_ode *o, double dt)
{
    bf_particles *p = o->p;
    if (!o->force_valid)
        force(o, p->x, p->y);
    kick(o, 0.5 * dt);
    for (size_t i = 0; i < o->n; i++)
        if (!o->f->fixed[i]) {
            p->x[i] += dt * p->vx[i];
            p->y[i] += dt * p->vy[i];
        }
    force(o, p->x, p->y);
    kick(o, 0.5 * dt);
    o->force_valid = 1;
    return BF_OK;
}

static bf_status arkode(bf_g73_ode *o, double t, double dt, bf_err *err)
{
    bf_particles_pack(o->p, o->y);
    bf_status st = bf_ark1_evolve(o->ark, t, t + dt, o->y, err);
    if (!st)
        bf_particles_unpack(o->p, o->y);
    return st;
}

bf_status bf_g73_ode_step(bf_g73_ode *o, double t, double dt, bf_err *err)
{
    bf_status st = o->o.method == BF_G73_ARKODE ? arkode(o, t, dt, err)
                                                : leapfrog(o, dt);
    if (st)
        return st;
    size_t bad;
    if (!bf_particles_finite(o->p, &bad))
        return bf_fail(err, BF_EUNSTABLE,
                       "particle %zu: position (%g, %g) or velocity (%g, %g) "
                       "not finite (a step too large for the %s)",
                       bad + 1, o->p->x[bad], o->p->y[bad], o->p->vx[bad],
                       o->p->vy[bad],
                       o->o.method == BF_G73_ARKODE ? "tolerances"
                                                    : "leapfrog");
    o->steps++;
    return BF_OK;
}

void bf_g73_ode_counters(const bf_g73_ode *o, bf_counters *c)
{
    memset(c, 0, sizeof *c);
    if (o->ark) {
        bf_ark1_counters(o->ark, c);
        return;
    }
    c->steps = o->steps;
    c->evals = o->evals;
}

void bf_g73_ode_describe(const bf_g73_ode *o, char *buf, size_t cap,
                         int *order)
{
    if (!o->ark) {
        snprintf(buf, cap, "leapfrog (kick-drift-kick)");
        *order = 2;
        return;
    }
    char a[160];
    bf_ark1_describe(o->ark, a, sizeof a);
    snprintf(buf, cap, "arkode %s", a);
    *order = bf_ark1_order(o->ark);
}

static const bf_field lf_fields[] = {
    BF_FIELD(bf_g73_ode, steps, BF_F_ULL, "1"),
    BF_FIELD(bf_g73_ode, evals, BF_F_ULL, "1"),
    BF_FIELD(bf_g73_ode, force_valid, BF_F_INT, "1"),
};

bf_status bf_g73_ode_save(const bf_g73_ode *o, bf_ckpt *ck, bf_err *err)
{
    if (o->ark)
        return bf_ark1_save(o->ark, ck, "g73.ode", err);
    return bf_ckpt_put_fields(ck, "g73.ode", lf_fields, BF_NFIELDS(lf_fields),
                              o, err);
}

bf_status bf_g73_ode_load(bf_g73_ode *o, const bf_ckpt *ck, bf_err *err)
{
    if (o->ark)
        return bf_ark1_load(o->ark, ck, "g73.ode", err);
    bf_status st = bf_ckpt_get_fields(ck, "g73.ode", lf_fields,
                                      BF_NFIELDS(lf_fields), o, err);
    /* the kept force is recomputed from the restored positions: no new
     * evaluation if the interrupted run had it */
    o->replay = o->force_valid;
    o->force_valid = 0;
    return st;
}
