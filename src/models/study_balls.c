/* study_balls.c: the convergence study of balls on a line (model balls):
 * methods are [scene] integrators with their [integrator] keys; compared
 * are the positions x (cm) and velocities v (cm/s) of the balls; the
 * invariant is the energy, checked after every internal step of ARKODE
 * too (its step monitor).
 *
 * The reference: ARKODE's adaptive ERK with rootfinding at every contact
 * onset and release, re-initialised there (src/integrators/arkode.c,
 * "events"), so that no internal step straddles a kink of the Hertz
 * force; VERNER_8_5_6 (with the issue-311 padding), else DORMAND_PRINCE_
 * 7_4_5, else CASH_KARP_6_4_5 when compared.  Not FEHLBERG_13_7_8: its
 * error estimate (b - d) k involves only stages 1, 11, 12 and 13, which
 * all agree in free flight, so a step whose middle stages reach into a
 * contact is accepted with a zero estimate; on runs/bouncing_ball.ini it
 * gave relative energy errors of 4e2 at rtol 1e-12 and 2e7 at 1e-8.
 *
 * Largest internal step on scenes with Hertz contacts: 10 x [scene] dt
 * (see converge.h: in free flight the error estimate is zero; without the
 * limit the reference on runs/bouncing_ball.ini took 28 steps to
 * T = 100 s and ended at 9e35 cm). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "effects/effect_kernels.h"
#include "models/ballsys.h"
#include "models/studies.h"

static int balls_adaptive(const bf_model_setup *s)
{
    return s->integrator && (s->integrator->flags & BF_INT_ADAPTIVE);
}

/* Whether the setup's effects have Hertz contacts: floor and contact
 * (recognised by their descriptors, like the ball system's kernels). */
static int study_hertz(const bf_model_setup *s)
{
    for (size_t k = 0; k < s->neffects; k++)
        if (s->effects[k] == &bf_effect_floor ||
            s->effects[k] == &bf_effect_contact)
            return 1;
    return 0;
}

static bf_status balls_reference(const bf_model_setup *s,
                                 const bf_study_methods *o, char *method,
                                 size_t cap, bf_err *err)
{
    (void)s;
    static const char *const names[] = {"arkode", "arkode-fixed", NULL};
    static const char *const defaults[] = {"ARKODE_DORMAND_PRINCE_7_4_5",
                                           "ARKODE_ZONNEVELD_5_3_4"};
    /* events: rootfinding at every contact onset and release, the
     * integration restarted there (arkode.c) */
    return bf_study_arkode_reference(o, names, defaults, ":events=yes",
                                     method, cap, err);
}

double bf_study_hertz_max_step(const bf_model_setup *s)
{
    return study_hertz(s) ? 10 * s->run.dt : 0.0;
}

void bf_study_balls_groups(const bf_balls *b, bf_study_view *v)
{
    static const char *const names[2] = {"x", "v"};
    static const char *const units[2] = {"cm", "cm/s"};
    const double *data[2] = {b->x, b->v};
    for (size_t k = 0; k < 2; k++) {
        size_t g = v->ngroups++;
        v->g[g].name = names[k];
        v->g[g].unit = units[k];
        v->g[g].a = data[k];
        v->g[g].n = b->n;
    }
}

static void balls_view(void *self, bf_study_view *v)
{
    memset(v, 0, sizeof *v);
    bf_study_balls_groups(&bf_balls_model_system(self)->b, v);
}

static void balls_describe(void *self, char *buf, size_t cap, int *order)
{
    const bf_ballsys *s = bf_balls_model_system(self);
    bf_integrator_describe(s->it, buf, cap);
    *order = bf_integrator_order(s->it);
}

/* the energy after every internal step of adaptive integrators */
typedef struct energy_watch {
    const bf_ballsys *sys;
    bf_study_energy_fn check;
    void *ctx;
} energy_watch;

static void monitor_energy(void *ctx, double t, const double *x,
                           const double *v)
{
    energy_watch *w = ctx;
    const bf_ballsys *s = w->sys;
    double k = 0.0;
    for (size_t i = 0; i < s->b.n; i++)
        k += 0.5 * s->b.m[i] * v[i] * v[i];
    w->check(w->ctx, k + bf_effects_potential(s->eff, s->neff, &s->b, t, x));
}

static void *balls_watch(void *self, bf_study_energy_fn check, void *ctx)
{
    bf_ballsys *s = bf_balls_model_system(self);
    energy_watch *w = malloc(sizeof *w);
    if (!w)
        return NULL;
    w->sys = s;
    w->check = check;
    w->ctx = ctx;
    bf_integrator_set_monitor(s->it, monitor_energy, w);
    return w;
}

static void balls_notes(const bf_model_setup *s, char *buf, size_t cap)
{
    if (!study_hertz(s))
        return;
    snprintf(buf + strlen(buf), cap - strlen(buf),
             "note: the scene has Hertz contacts.  The contact force "
             "k x^{3/2} is continuous with a continuous first derivative at "
             "contact onset (x = 0) but its second derivative is infinite "
             "there, so the error expansions behind the nominal orders do "
             "not hold across contact onsets: observed orders below nominal "
             "are what is measured, not a defect ([integrator] events = yes "
             "splits the steps there; docs/accuracy-balls.md).\n");
}

const bf_study_type bf_study_balls = {
    .method_key = "scene.integrator",
    .param_section = "integrator",
    .invariant = "energy",
    .default_ref_rtol = 1e-12,
    .max_ref_rtol = 1e-12,
    .adaptive = balls_adaptive,
    .reference = balls_reference,
    .max_step = bf_study_hertz_max_step,
    .view = balls_view,
    .describe = balls_describe,
    .watch = balls_watch,
    .notes = balls_notes,
};
