/* lyapunov.c: the largest Lyapunov exponent of a ball system by a
 * renormalised shadow trajectory (see lyapunov.h and src/diag/lyapsum.h). */
#include "lyapunov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct bf_lyap {
    bf_lyap_sum sum;
    double *x, *v; /* shadow state */
    size_t n2;     /* 2 bf_ode.n: the length of x followed by v */
    bf_integrator *it;
    bf_ball_twin twin; /* x, v and it, as the model steps them */
    bf_ball_view view;
};

static void lyap_free(void *self)
{
    bf_lyap *ly = self;
    if (!ly)
        return;
    bf_integrator_free(ly->it);
    free(ly->x);
    free(ly);
}

static bf_status lyap_create(void **out, const void *keys,
                             const bf_analysis_env *env, bf_err *err)
{
    *out = NULL;
    const bf_lyap_keys *k = keys;
    if (!k->enabled)
        return BF_OK;
    const bf_ball_view *view = env->view;
    bf_lyap_sum sum;
    const bf_integrator_type *t = view->it->type;
    bf_status st = bf_lyap_sum_init(&sum, k, env->run->dt, view->n,
                                    t->flags & BF_INT_ADAPTIVE ? t->name : NULL,
                                    err);
    if (st)
        return st;
    bf_lyap *ly = calloc(1, sizeof *ly);
    if (!ly)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    /* the shadow steps every component of the ODE: the balls and, with
     * non-conservative effects, the work after them (bf_ode.n); the
     * distance is measured on the balls only */
    const size_t n = view->ode->n;
    ly->sum = sum;
    ly->view = *view;
    ly->n2 = 2 * n;
    ly->x = calloc(2 * n, sizeof *ly->x);
    if (!ly->x) {
        free(ly);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    ly->v = ly->x + n;
    st = bf_integrator_create(&ly->it, t, n, view->it_params, err);
    if (st) {
        lyap_free(ly);
        return st;
    }
    ly->twin = (bf_ball_twin){ly->it, ly->x, ly->v, NAN};
    bf_lyap_displace(&ly->sum, view->x, view->v, ly->x, ly->v);
    *out = ly;
    return BF_OK;
}

/* The shadow's step over the step t -> t + dt that the balls have just
 * taken (n_done steps done), and the renormalisation when due.  The model
 * steps it as it steps the balls (with event splitting, at the shadow's
 * own contact onsets and releases). */
static bf_status lyap_after_step(void *self, long n_done, double t, double dt,
                                 bf_err *err)
{
    bf_lyap *ly = self;
    const bf_ball_view *b = &ly->view;
    bf_status st =
        b->step_twin
            ? b->step_twin(b->step_ctx, &ly->twin, t, dt, err)
            : bf_integrator_step(ly->it, b->ode, t, dt, ly->x, ly->v, err);
    if (st) {
        bf_err_prefix(err, "Lyapunov shadow trajectory");
        return st;
    }
    if (!bf_lyap_due(&ly->sum, n_done))
        return BF_OK;
    double factor;
    st = bf_lyap_measure(&ly->sum, b->x, b->v, ly->x, ly->v, t + dt, &factor,
                         err);
    if (st || factor == 1.0)
        return st;
    if (factor == 0.0) {
        bf_lyap_displace(&ly->sum, b->x, b->v, ly->x, ly->v);
        return BF_OK;
    }
    bf_lyap_pull(ly->sum.n, factor, b->x, ly->x);
    bf_lyap_pull(ly->sum.n, factor, b->v, ly->v);
    return BF_OK;
}

static void lyap_report(const void *self, FILE *f)
{
    const bf_lyap *ly = self;
    bf_lyap_sum_report(&ly->sum, ly->it->count.evals, f);
}

static void lyap_results(const void *self, bf_results *r)
{
    const bf_lyap *ly = self;
    r->has_lyapunov = 1;
    r->lyapunov_exponent = bf_lyap_sum_estimate(&ly->sum, &r->lyapunov_time);
}

const bf_counters *bf_lyap_counters(const bf_lyap *ly)
{
    return &ly->it->count;
}

static bf_status lyap_output_open(void *self, bf_out *out, bf_err *err)
{
    return bf_lyap_sum_output_open(&((bf_lyap *)self)->sum, out, err);
}

static bf_status lyap_output_close(void *self, bf_out *out, bf_err *err)
{
    return bf_lyap_sum_output_close(&((const bf_lyap *)self)->sum, out, err);
}

/* The shadow state (x then v) in a checkpoint. */
static const bf_field shadow_state[] = {
    BF_FIELD_PTR(bf_lyap, x, BF_F_DOUBLE, n2, "cm, cm/s"),
};

static bf_status lyap_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const bf_lyap *ly = self;
    bf_status st = bf_ckpt_put_fields(ck, "lyapunov", shadow_state,
                                      BF_NFIELDS(shadow_state), ly, err);
    if (!st)
        st = bf_lyap_sum_save(&ly->sum, ck, err);
    if (!st)
        st = bf_integrator_save(ly->it, ck, "lyapunov.integrator", err);
    return st;
}

static bf_status lyap_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    bf_lyap *ly = self;
    bf_status st = bf_ckpt_get_fields(ck, "lyapunov", shadow_state,
                                      BF_NFIELDS(shadow_state), ly, err);
    if (!st)
        st = bf_lyap_sum_load(&ly->sum, ck, err);
    if (!st)
        st = bf_integrator_load(ly->it, ck, "lyapunov.integrator", err);
    return st;
}

/* The balls got a new initial state (bf_sim_set): the shadow starts
 * from it, displaced as at creation. */
static bf_status lyap_state_set(void *self, bf_err *err)
{
    (void)err;
    bf_lyap *ly = self;
    bf_lyap_displace(&ly->sum, ly->view.x, ly->view.v, ly->x, ly->v);
    bf_integrator_reset(ly->it);
    ly->twin.t_cached = NAN;
    return BF_OK;
}

const bf_observer_type bf_lyap_observer = {
    .name = "lyapunov",
    .flags = BF_OBS_STEPS,
    .after_step = lyap_after_step,
    .output_open = lyap_output_open,
    .output_close = lyap_output_close,
    .report = lyap_report,
    .save = lyap_save,
    .load = lyap_load,
    .results = lyap_results,
    .destroy = lyap_free,
    .state_set = lyap_state_set,
};

const bf_analysis_type bf_lyap_analysis = {
    .name = "lyapunov",
    .spec = &bf_lyap_spec,
    .observer = &bf_lyap_observer,
    .series = &bf_lyap_series,
    .create = lyap_create,
};
