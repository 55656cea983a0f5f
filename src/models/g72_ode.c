/* g72_ode.c: the 1972 particles as an ODE under ARKODE (g72_ode.h). */
#include "models/g72_ode.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/greenspan.h"

struct bf_g72_ode {
    bf_particles *p;
    const double *ax, *ay, *g;
    bf_g72_accel_fn accel;
    void *model;
    double *y; /* 4n: the state at the start of a step */
    bf_ark1 *ark;
    bf_err rhs_err; /* why the right-hand side stopped ARKODE */
    int rhs_failed;
};

static int rhs(void *ctx, double t, const double *y, double *ydot)
{
    (void)t;
    bf_g72_ode *o = ctx;
    bf_particles *p = o->p;
    const size_t n = p->n;
    /* a stage's positions: non-finite ones are a step too large, which
     * ARKODE retries smaller */
    for (size_t i = 0; i < 2 * n; i++)
        if (!isfinite(y[i]))
            return 1;
    memcpy(p->x, y, n * sizeof *y);
    memcpy(p->y, y + n, n * sizeof *y);
    if (o->accel(o->model, &o->rhs_err)) {
        o->rhs_failed = 1;
        return -1;
    }
    memcpy(ydot, y + 2 * n, 2 * n * sizeof *y);
    for (size_t i = 0; i < n; i++) {
        ydot[2 * n + i] = o->ax[i];
        ydot[3 * n + i] = o->ay[i] + o->g[i];
    }
    return 0;
}

void bf_g72_ode_free(bf_g72_ode *o)
{
    if (!o)
        return;
    bf_ark1_free(o->ark);
    free(o->y);
    free(o);
}

bf_status bf_g72_ode_create(bf_g72_ode **out, bf_particles *p,
                            const double *ax, const double *ay,
                            const double *g, bf_g72_accel_fn accel,
                            void *model, const bf_g72_ode_opts *opts,
                            bf_err *err)
{
    *out = NULL;
    bf_g72_ode *o = calloc(1, sizeof *o);
    if (!o)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    *o = (bf_g72_ode){.p = p, .ax = ax, .ay = ay, .g = g, .accel = accel,
                      .model = model};
    o->y = malloc(4 * (p->n ? p->n : 1) * sizeof *o->y);
    bf_ark1_opts ao = {
        .kind = BF_ARK1_ERK,
        .table = opts->table,
        .rtol = opts->rtol,
        .atol = opts->atol,
        .max_step = opts->max_step,
        .max_steps = opts->max_steps,
        .work_around_311 = 1,
    };
    bf_status st = o->y ? bf_ark1_create(&o->ark, 4 * p->n, rhs, NULL, o,
                                         &ao, err)
                        : bf_fail(err, BF_EINTERNAL, "out of memory");
    if (st == BF_EINPUT)
        bf_err_prefix(err, "[greenspan72] table");
    if (st) {
        bf_g72_ode_free(o);
        return st;
    }
    *out = o;
    return BF_OK;
}

bf_status bf_g72_ode_step(bf_g72_ode *o, double t, double dt, bf_err *err)
{
    bf_particles_pack(o->p, o->y);
    o->rhs_failed = 0;
    bf_status st = bf_ark1_evolve(o->ark, t, t + dt, o->y, err);
    /* success: the state at t + dt; failure: the one at t (the right-hand
     * side left a stage's positions in the particles) */
    bf_particles_unpack(o->p, o->y);
    if (st && o->rhs_failed) {
        *err = o->rhs_err;
        st = err->status;
    }
    return st;
}


void bf_g72_ode_describe(const bf_g72_ode *o, char *buf, size_t cap,
                         int *order)
{
    if (!o) {
        snprintf(buf, cap, "leapfrog (the 1972 paper's, half step first)");
        *order = 2;
        return;
    }
    char a[160];
    bf_ark1_describe(o->ark, a, sizeof a);
    snprintf(buf, cap, "arkode %s", a);
    *order = bf_ark1_order(o->ark);
}

bf_ark1 *bf_g72_ode_arkode(const bf_g72_ode *o)
{
    return o->ark;
}
