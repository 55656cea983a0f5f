/* balls.c: the "balls" model: balls on a vertical line in space (Yasuda
 * sec. 2), or any set of balls under the ball effects.
 *
 * Output: /balls/position and /balls/velocity [rows x balls] at every output
 * row, /balls/mass and /balls/radius once.  Optional analyses, each off
 * unless its section enables it: the first-return map ([return_map],
 * returnmap.h), the largest Lyapunov exponent ([lyapunov], lyapunov.h) and
 * the one-step comparison of two integrators at output rows ([compare],
 * compare.h).
 * With both off a step is exactly bf_ballsys_step, and a run of steps
 * between the core loop's events exactly bf_ballsys_advance.
 */
#include <math.h>
#include <stdlib.h>

#include "ballfilm/balls.h"
#include "ballfilm/compare.h"
#include "ballfilm/coupled.h"
#include "analysis/lyapunov.h"
#include "ballfilm/model.h"

typedef struct balls_model {
    bf_ballsys *sys;
    bf_retmap *rm;
    bf_lyap *ly;
    bf_compare *cmp;
    double dt;
    bf_series *pos, *vel;
} balls_model;

extern const bf_model_type bf_model_balls;

bf_ballsys *bf_balls_model_system(void *self)
{
    return ((balls_model *)self)->sys;
}

const bf_retmap *bf_balls_model_retmap(const void *self)
{
    return ((const balls_model *)self)->rm;
}

void bf_balls_model_analysis(const void *self, bf_balls_analysis *a)
{
    const balls_model *m = self;
    a->has_return_map = m->rm != NULL;
    a->return_map_points = m->rm ? bf_retmap_points(m->rm, 0, 0, 0, 0) : 0;
    a->return_map_multi_minima = m->rm ? bf_retmap_multi_minima(m->rm) : 0;
    a->has_lyapunov = m->ly != NULL;
    a->lyapunov_time = 0;
    a->lyapunov_exponent = m->ly ? bf_lyap_estimate(m->ly, &a->lyapunov_time)
                                 : NAN;
}

bf_status bf_balls_sim_analysis(bf_sim *sim, bf_balls_analysis *a)
{
    if (bf_sim_model_type(sim) != &bf_model_balls)
        return bf_coupled_sim_analysis(sim, a); /* or BF_EINPUT */
    bf_balls_model_analysis(bf_sim_model(sim), a);
    return BF_OK;
}

static void balls_destroy(void *self)
{
    balls_model *m = self;
    if (!m)
        return;
    bf_compare_free(m->cmp);
    bf_lyap_free(m->ly);
    bf_retmap_free(m->rm);
    bf_ballsys_free(m->sys);
    free(m);
}

static bf_status balls_create(void **self, const bf_scene *sc,
                              const bf_model_setup *setup, bf_err *err)
{
    balls_model *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_effect_env env = {0};
    bf_status st = bf_ballsys_create(&m->sys, setup, &env, err);
    if (!st)
        st = bf_retmap_create(&m->rm, sc, m->sys, err);
    if (!st)
        st = bf_lyap_create(&m->ly, bf_setup_get(setup, &bf_lyap_spec, NULL),
                            setup->run.dt, m->sys, err);
    if (!st)
        st = bf_compare_create(&m->cmp, sc, m->sys, err);
    m->dt = setup->run.dt;
    if (st) {
        balls_destroy(m);
        return st;
    }
    *self = m;
    return BF_OK;
}

static bf_status balls_step(void *self, long n, double t, double dt, bf_err *err)
{
    balls_model *m = self;
    if (!m->rm && !m->ly)
        return bf_ballsys_step(m->sys, t, dt, err);
    if (m->rm)
        bf_retmap_before_step(m->rm, m->sys);
    bf_status st = bf_ballsys_step(m->sys, t, dt, err);
    if (!st && m->rm)
        st = bf_retmap_after_step(m->rm, m->sys, t, dt, err);
    if (!st && m->ly)
        st = bf_lyap_after_step(m->ly, m->sys, n + 1, t, dt, err);
    return st;
}

/* Without per-step analyses the ball system takes the whole run (for
 * Verlet and MV2M in one call that keeps the state in registers);
 * otherwise one step at a time. */
static bf_status balls_advance(void *self, long n, long k, double dt,
                               long *done, bf_err *err)
{
    balls_model *m = self;
    if (!m->rm && !m->ly)
        return bf_ballsys_advance(m->sys, n, k, dt, done, err);
    for (long j = 0; j < k; j++) {
        bf_status st = balls_step(self, n + j, (double)(n + j) * dt, dt, err);
        if (st) {
            *done = j;
            return st;
        }
    }
    *done = k;
    return BF_OK;
}

static void balls_energy(const void *self, double t, double *kin, double *pot)
{
    const balls_model *m = self;
    bf_ballsys_energy(m->sys, t, kin, pot);
}

static bf_status balls_output_open(void *self, bf_out *out, bf_err *err)
{
    balls_model *m = self;
    const bf_balls *b = &m->sys->b;
    m->pos = bf_out_series(out, "/balls/position", b->n, 0, "cm",
                           "ball centre positions, one column per ball", err);
    if (!m->pos)
        return err->status;
    m->vel = bf_out_series(out, "/balls/velocity", b->n, 0, "cm/s",
                           "ball velocities, one column per ball", err);
    if (!m->vel)
        return err->status;
    bf_status st = bf_out_array(out, "/balls/mass", b->m, b->n, 0, "g",
                                "ball masses", err);
    if (!st)
        st = bf_out_array(out, "/balls/radius", b->R, b->n, 0, "cm",
                          "ball radii", err);
    if (!st && m->rm)
        st = bf_retmap_output_open(m->rm, out, err);
    if (!st && m->ly)
        st = bf_lyap_output_open(m->ly, out, err);
    if (!st && m->cmp)
        st = bf_compare_output_open(m->cmp, out, err);
    return st;
}

static bf_status balls_output_row(void *self, long n, double t, bf_err *err)
{
    (void)n;
    balls_model *m = self;
    if (bf_series_append(m->pos, m->sys->b.x) ||
        bf_series_append(m->vel, m->sys->b.v))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (m->cmp)
        return bf_compare_output_row(m->cmp, m->sys, t, m->dt, err);
    return BF_OK;
}

static bf_status balls_output_close(void *self, bf_out *out, bf_err *err)
{
    balls_model *m = self;
    bf_status st = BF_OK;
    if (m->rm)
        st = bf_retmap_output_close(m->rm, out, err);
    if (!st && m->ly)
        st = bf_lyap_output_close(m->ly, out, err);
    return st;
}

static void balls_counters(const void *self, bf_counters *c)
{
    const balls_model *m = self;
    *c = m->sys->it->count;
}

static void balls_report(const void *self, FILE *f)
{
    const balls_model *m = self;
    bf_balls_analysis a;
    bf_balls_model_analysis(m, &a);
    if (a.has_return_map)
        fprintf(f, "return map:        %zu points (%zu contacts with more "
                   "than one minimum)\n",
                a.return_map_points, a.return_map_multi_minima);
    if (a.has_lyapunov)
        bf_lyap_report(m->ly, f);
}

static bf_status balls_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const balls_model *m = self;
    bf_status st = bf_ballsys_save(m->sys, ck, "balls", err);
    if (!st && m->rm)
        st = bf_retmap_save(m->rm, ck, err);
    if (!st && m->ly)
        st = bf_lyap_save(m->ly, ck, err);
    return st;
}

static bf_status balls_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    balls_model *m = self;
    bf_status st = bf_ballsys_load(m->sys, ck, "balls", err);
    if (!st && m->rm)
        st = bf_retmap_load(m->rm, ck, err);
    if (!st && m->ly)
        st = bf_lyap_load(m->ly, ck, err);
    return st;
}

static const bf_section_spec *const balls_specs[] = {
    &bf_ballsys_ball_spec, &bf_retmap_spec, &bf_lyap_spec, &bf_compare_spec,
    NULL};

const bf_model_type bf_model_balls = {
    .name = "balls",
    .doc = "balls on a line under the listed effects (Yasuda sec. 2)",
    .flags = BF_MODEL_INTEGRATOR | BF_MODEL_EFFECTS,
    .specs = balls_specs,
    .create_scene = balls_create,
    .destroy = balls_destroy,
    .step = balls_step,
    .energy = balls_energy,
    .output_open = balls_output_open,
    .output_row = balls_output_row,
    .output_close = balls_output_close,
    .counters = balls_counters,
    .report = balls_report,
    .checkpoint_save = balls_save,
    .checkpoint_load = balls_load,
    .advance = balls_advance,
};
