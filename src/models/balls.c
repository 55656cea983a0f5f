/* balls.c: the "balls" model: balls on a vertical line in space (Yasuda
 * sec. 2), or any set of balls under the ball effects.
 *
 * Output: /balls/position and /balls/velocity [rows x balls] at every output
 * row, /balls/mass and /balls/radius once.  The model shows its balls to
 * the analyses of the time loop (sim.h: the first-return map, the largest
 * Lyapunov exponent, the one-step comparison of two integrators), each off
 * unless its section enables it.  A step is exactly bf_ballsys_step, and a
 * run of steps between the loop's events exactly bf_ballsys_advance.
 */
#include <math.h>
#include <stdlib.h>

#include "models/balls_out.h"
#include "models/ballsys.h"
#include "models/studies.h"
#include "ballfilm/model.h"

typedef struct balls_model {
    bf_ballsys *sys;
    bf_balls_out o;
} balls_model;

bf_ballsys *bf_balls_model_system(void *self)
{
    return ((balls_model *)self)->sys;
}

static void balls_destroy(void *self)
{
    balls_model *m = self;
    if (!m)
        return;
    bf_ballsys_free(m->sys);
    free(m);
}

static bf_status balls_create(void **self, const bf_model_setup *setup,
                              bf_err *err)
{
    balls_model *m = calloc(1, sizeof *m);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_status st = bf_ballsys_create(&m->sys, setup, NULL, 0, err);
    if (st) {
        balls_destroy(m);
        return st;
    }
    *self = m;
    return BF_OK;
}

static bf_status balls_step(void *self, long n, double t, double dt, bf_err *err)
{
    (void)n;
    return bf_ballsys_step(((balls_model *)self)->sys, t, dt, err);
}

static bf_status balls_advance(void *self, long n, long k, double dt,
                               bf_ball_watch *w, long *done, bf_err *err)
{
    return bf_ballsys_advance(((balls_model *)self)->sys, n, k, dt, w, done,
                              err);
}

static void balls_energy(const void *self, double t, double *kin, double *pot)
{
    const balls_model *m = self;
    bf_ballsys_energy(m->sys, t, kin, pot);
}

static int balls_work(const void *self, double *diss, double *inj)
{
    const bf_ballsys *sys = ((const balls_model *)self)->sys;
    bf_ballsys_work(sys, diss, inj);
    return sys->nw > 0;
}

static double balls_energy_bound(const void *self)
{
    return bf_ballsys_energy_bound(((const balls_model *)self)->sys);
}

static bf_status balls_output_open(void *self, bf_out *out, bf_err *err)
{
    balls_model *m = self;
    return bf_balls_output_open(&m->o, out, &m->sys->b, err);
}

static bf_status balls_output_row(void *self, long n, double t, bf_err *err)
{
    (void)n;
    (void)t;
    balls_model *m = self;
    if (bf_balls_output_row(&m->o, &m->sys->b))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

static const bf_series_table *const balls_tables[] = {&bf_balls_series,
                                                      NULL};

static void balls_counters(const void *self, bf_counters *c)
{
    const balls_model *m = self;
    *c = m->sys->it->count;
}

static bf_status balls_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const balls_model *m = self;
    return bf_ballsys_save(m->sys, ck, "balls", err);
}

static bf_status balls_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    balls_model *m = self;
    return bf_ballsys_load(m->sys, ck, "balls", err);
}

static int balls_view(void *self, bf_ball_view *v)
{
    bf_ballsys_view(((balls_model *)self)->sys, v);
    return 1;
}

static size_t balls_state(void *self, bf_state_var *vars, size_t cap)
{
    return bf_ballsys_state(((balls_model *)self)->sys, vars, cap);
}

static bf_status balls_set_state(void *self, const char *name,
                                 const double *v, size_t n, bf_err *err)
{
    return bf_ballsys_set(((balls_model *)self)->sys, name, v, n, err);
}

static const bf_section_spec *const balls_specs[] = {&bf_ballsys_ball_spec,
                                                     NULL};

const bf_model_type bf_model_balls = {
    .name = "balls",
    .series = balls_tables,
    .doc = "balls on a line under the listed effects (Yasuda sec. 2)",
    .flags = BF_MODEL_INTEGRATOR | BF_MODEL_EFFECTS | BF_MODEL_BALL_ANALYSES |
             BF_MODEL_WATCH,
    .specs = balls_specs,
    .create = balls_create,
    .destroy = balls_destroy,
    .step = balls_step,
    .energy = balls_energy,
    .energy_bound = balls_energy_bound,
    .work = balls_work,
    .output_open = balls_output_open,
    .output_row = balls_output_row,
    .counters = balls_counters,
    .checkpoint_save = balls_save,
    .checkpoint_load = balls_load,
    .advance = balls_advance,
    .ball_view = balls_view,
    .state = balls_state,
    .set_state = balls_set_state,
    .study = &bf_study_balls,
};
