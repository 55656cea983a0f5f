/* compare.c: one-step comparison of two integrators along a run (see
 * compare.h). */
#include "ballfilm/compare.h"

#include <stdlib.h>

#include "ballfilm/run.h"
#include <string.h>

static const bf_param compare_params[] = {
    {"a", BF_STR, 0, "", "",
     "integrator a (empty: no comparison); /compare/dv = v after one step of "
     "a - v after one step of b, from the state of every output row",
     0, 0, 0, NULL},
    {"b", BF_STR, 0, "", "alpha",
     "integrator b (default parameters; alpha = 1/8 is the second-order "
     "mid-point rule)",
     0, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_compare_spec = {
    "compare", "one-step difference of two integrators along the run (Fig. 4)",
    compare_params, 0};

struct bf_compare {
    size_t n;
    bf_integrator *a, *b;
    double *xa, *va, *xb, *vb, *dv;
    bf_series *s;
};

bf_status bf_compare_create(bf_compare **out, const bf_scene *sc,
                            const bf_ballsys *sys, bf_err *err)
{
    *out = NULL;
    const char *na = bf_scene_str(sc, "compare", "a");
    const char *nb = bf_scene_str(sc, "compare", "b");
    if (!*na)
        return BF_OK;
    const char *names[2] = {na, nb}, *keys[2] = {"a", "b"};
    const bf_integrator_type *types[2];
    for (int k = 0; k < 2; k++) {
        const bf_integrator_type *t =
            bf_catalog_integrator(bf_catalog_builtin(), names[k]);
        types[k] = t;
        if (!t)
            return bf_scene_fail(sc, err, "compare", keys[k],
                                 "unknown integrator '%s'", names[k]);
        if (t->flags & BF_INT_ADAPTIVE)
            return bf_scene_fail(sc, err, "compare", keys[k],
                                 "'%s' is adaptive; compare fixed-step "
                                 "methods", names[k]);
    }
    bf_compare *c = calloc(1, sizeof *c);
    const size_t n = sys->b.n;
    if (!c || !(c->xa = calloc(5 * n, sizeof *c->xa))) {
        free(c);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    c->n = n;
    c->va = c->xa + n;
    c->xb = c->xa + 2 * n;
    c->vb = c->xa + 3 * n;
    c->dv = c->xa + 4 * n;
    /* default parameters: their [integrator] keys belong to the run's
     * own integrator */
    bf_status st = bf_integrator_create(&c->a, types[0], n, NULL, err);
    if (!st)
        st = bf_integrator_create(&c->b, types[1], n, NULL, err);
    if (st) {
        bf_compare_free(c);
        return st;
    }
    *out = c;
    return BF_OK;
}

void bf_compare_free(bf_compare *c)
{
    if (!c)
        return;
    bf_integrator_free(c->a);
    bf_integrator_free(c->b);
    free(c->xa);
    free(c);
}

bf_status bf_compare_output_open(bf_compare *c, bf_out *out, bf_err *err)
{
    c->s = bf_out_series(out, "/compare/dv", c->n, 0, "cm/s",
                         "velocity after one step of [compare] a minus after "
                         "one step of [compare] b, both from the state of "
                         "the row",
                         err);
    return c->s ? BF_OK : err->status;
}

bf_status bf_compare_output_row(bf_compare *c, const bf_ballsys *sys, double t,
                                double dt, bf_err *err)
{
    const size_t bytes = c->n * sizeof *c->xa;
    memcpy(c->xa, sys->b.x, bytes);
    memcpy(c->va, sys->b.v, bytes);
    memcpy(c->xb, sys->b.x, bytes);
    memcpy(c->vb, sys->b.v, bytes);
    bf_status st = bf_integrator_step(c->a, &sys->ode, t, dt, c->xa, c->va, err);
    if (!st)
        st = bf_integrator_step(c->b, &sys->ode, t, dt, c->xb, c->vb, err);
    if (st)
        return st;
    for (size_t i = 0; i < c->n; i++)
        c->dv[i] = c->va[i] - c->vb[i];
    if (c->s && bf_series_append(c->s, c->dv))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}
