/* compare.c: one-step comparison of two integrators along a run (see
 * compare.h). */
#include "compare.h"

#include <stdlib.h>
#include <string.h>

static const bf_param compare_params[] = {
    {"a", BF_AT(bf_compare_keys, a, BF_STR), "", "",
     "integrator a (empty: no comparison); /compare/dv = v after one step of "
     "a - v after one step of b, from the state of every output row",
     0, 0, 0, NULL},
    {"b", BF_AT(bf_compare_keys, b, BF_STR), "", "alpha",
     "integrator b (default parameters; alpha = 1/8 is the second-order "
     "mid-point rule)",
     0, 0, 0, NULL},
    {0},
};

static const bf_section_spec compare_spec = BF_SECTION(
    "compare", "one-step difference of two integrators along the run (Fig. 4)",
    compare_params, bf_compare_keys);

typedef struct bf_compare {
    size_t n;
    bf_integrator *a, *b;
    double *xa, *va, *xb, *vb, *dv;
    double dt;
    bf_ball_view view;
    bf_series *s;
} bf_compare;

static void compare_free(void *self);

static bf_status compare_create(void **out, const void *keys,
                               const bf_analysis_env *env, bf_err *err)
{
    *out = NULL;
    const bf_compare_keys *k = keys;
    const char *na = k->a, *nb = k->b;
    if (!*na)
        return BF_OK;
    const char *names[2] = {na, nb}, *keys_[2] = {"a", "b"};
    const bf_integrator_type *types[2];
    for (int q = 0; q < 2; q++) {
        const bf_integrator_type *t = env->integrator(env->ctx, names[q]);
        types[q] = t;
        if (!t)
            return bf_fail_key(err, BF_EINPUT, "compare", keys_[q],
                               "unknown integrator '%s'", names[q]);
        if (t->flags & BF_INT_ADAPTIVE)
            return bf_fail_key(err, BF_EINPUT, "compare", keys_[q],
                               "'%s' is adaptive; compare fixed-step "
                               "methods", names[q]);
    }
    bf_compare *c = calloc(1, sizeof *c);
    /* the steps advance every component of the ODE: the balls and, with
     * non-conservative effects, the work after them (bf_ode.n) */
    const size_t n = env->view->n, no = env->view->ode->n;
    if (!c || !(c->xa = calloc(4 * no + n, sizeof *c->xa))) {
        free(c);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    c->n = n;
    c->dt = env->run->dt;
    c->view = *env->view;
    c->va = c->xa + no;
    c->xb = c->xa + 2 * no;
    c->vb = c->xa + 3 * no;
    c->dv = c->xa + 4 * no;
    /* default parameters: their [integrator] keys belong to the run's
     * own integrator */
    bf_status st = bf_integrator_create(&c->a, types[0], no, NULL, err);
    if (!st)
        st = bf_integrator_create(&c->b, types[1], no, NULL, err);
    if (st) {
        compare_free(c);
        return st;
    }
    *out = c;
    return BF_OK;
}

static void compare_free(void *self)
{
    bf_compare *c = self;
    if (!c)
        return;
    bf_integrator_free(c->a);
    bf_integrator_free(c->b);
    free(c->xa);
    free(c);
}

static const bf_series_spec compare_series[] = {
    {.path = "/compare/dv", .unit = "cm/s", .per = "ball",
     .doc = "velocity after one step of [compare] a minus after one step of "
            "[compare] b, both from the state of the row",
     .slot = BF_SLOT(bf_compare, s)},
};

const bf_series_table bf_compare_series = {"compare", compare_series,
                                           BF_NSERIES(compare_series)};

static bf_status compare_output_open(void *self, bf_out *out, bf_err *err)
{
    bf_compare *c = self;
    const bf_series_extent ext[] = {{"ball", c->n}};
    return bf_out_open_table(out, compare_series, BF_NSERIES(compare_series),
                             c, ext, 1, 0, err);
}

/* At every output row: one step of a and one of b from the row's state. */
static bf_status compare_output_row(void *self, long n, double t, bf_err *err)
{
    (void)n;
    bf_compare *c = self;
    const bf_ball_view *b = &c->view;
    const double dt = c->dt;
    const size_t bytes = c->n * sizeof *c->xa;
    memcpy(c->xa, b->x, bytes);
    memcpy(c->va, b->v, bytes);
    memcpy(c->xb, b->x, bytes);
    memcpy(c->vb, b->v, bytes);
    bf_status st = bf_integrator_step(c->a, b->ode, t, dt, c->xa, c->va, err);
    if (!st)
        st = bf_integrator_step(c->b, b->ode, t, dt, c->xb, c->vb, err);
    if (st)
        return st;
    for (size_t i = 0; i < c->n; i++)
        c->dv[i] = c->va[i] - c->vb[i];
    if (c->s && bf_series_append(c->s, c->dv))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

const bf_observer_type bf_compare_observer = {
    .name = "compare",
    .output_open = compare_output_open,
    .output_row = compare_output_row,
    .destroy = compare_free,
};

const bf_analysis_type bf_compare_analysis = {
    .name = "compare",
    .spec = &compare_spec,
    .observer = &bf_compare_observer,
    .series = &bf_compare_series,
    .create = compare_create,
};
