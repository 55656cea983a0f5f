/* returnmap.c: first-return maps of falling balls (see returnmap.h for the
 * definition, the interpolation and how several minima in one contact are
 * counted).
 * The interpolant inside a step is diag/hermite.h's.
 */
#include "returnmap.h"
#include "diag/hermite.h"
#include "io/dataset_paths.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const bf_param retmap_params[] = {
    {"enabled", BF_AT(bf_retmap_keys, enabled, BF_BOOL), "", "no",
     "record the first-return map (docs/models/balls.md): the recorded "
     "ball's (z, v) "
     "at each lowest point of the trigger ball on the floor",
     0, 0, 0, NULL},
    {"trigger", BF_AT(bf_retmap_keys, trigger, BF_INT), "1", "1",
     "ball whose lowest points on the floor define the map (1 = lowest)",
     BF_MIN, 1, 0, NULL},
    {"record", BF_AT(bf_retmap_keys, record, BF_INT), "1", "2",
     "ball whose (z, v) is recorded", BF_MIN, 1, 0, NULL},
    {0},
};

static const bf_section_spec retmap_spec = BF_SECTION(
    "return_map", "first-return map of falling balls (Yasuda Figs 2-3)",
    retmap_params, bf_retmap_keys);

/* columns of a point */
enum { P_T, P_Z, P_V, P_ZT, P_MIN, NCOL };

struct bf_retmap {
    size_t trig, rec; /* 0-based */
    size_t n;         /* balls */
    double R;         /* trigger radius */
    double *x0, *v0, *a0, *a1; /* state at the start of the step, forces */
    /* the deepest minimum of the current contact */
    int pending;
    double cand[NCOL];
    /* recorded points, one array per column */
    double *col[NCOL];
    size_t npts, cap;
    size_t nmem; /* points held in col[]: every column without an output
                    file, else z and v alone if keep_map, else none
                    (kept_col) */
    int keep_map; /* bf_run_ctx keep_map */
    size_t multi;
    bf_events ev;
    int dir;
    bf_ball_view view; /* the balls, their forces and integrator */
    bf_series *s_t, *s_z, *s_v, *s_zt, *s_min;
};

/* A minimum of the trigger ball at time t with the recorded ball at
 * (z, v): keep it if it is the deepest of this contact. */
static void candidate(bf_retmap *rm, double t, double zt, double z, double v)
{
    double mins = rm->pending ? rm->cand[P_MIN] + 1 : 1;
    if (!rm->pending || zt < rm->cand[P_ZT]) {
        rm->cand[P_T] = t;
        rm->cand[P_Z] = z;
        rm->cand[P_V] = v;
        rm->cand[P_ZT] = zt;
    }
    rm->cand[P_MIN] = mins;
    rm->pending = 1;
}

/* Column c is held in memory: every column without an output (the
 * caller's bf_retmap_points), z and v also with one when the run keeps
 * the map (bf_run_ctx keep_map: bf_results, a sweep's statistics of the
 * map without reading the file back). */
static int kept_col(const bf_retmap *rm, int c)
{
    return !rm->s_t || (rm->keep_map && (c == P_Z || c == P_V));
}

static bf_status reserve(bf_retmap *rm, size_t need, bf_err *err)
{
    if (need <= rm->cap)
        return BF_OK;
    size_t cap = rm->cap ? 2 * rm->cap : 256;
    while (cap < need)
        cap *= 2;
    if (cap > SIZE_MAX / sizeof(double))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    for (int c = 0; c < NCOL; c++) {
        if (!kept_col(rm, c))
            continue;
        double *p = realloc(rm->col[c], cap * sizeof *p);
        if (!p)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        rm->col[c] = p;
    }
    rm->cap = cap;
    return BF_OK;
}

/* A point goes to the output's series when there is an output (streamed:
 * only its z and v stay in memory, and only with keep_map), else into
 * col[] for the caller (bf_retmap_points). */
static bf_status emit(bf_retmap *rm, bf_err *err)
{
    /* a blown-up state's contact is no point of the map */
    for (int c = 0; c < NCOL; c++)
        if (!isfinite(rm->cand[c]))
            return bf_fail(err, BF_EUNSTABLE,
                           "return map: the contact at t = %g s has z = %g "
                           "cm, v = %g cm/s: the state is not finite",
                           rm->cand[P_T], rm->cand[P_Z], rm->cand[P_V]);
    if (kept_col(rm, P_Z)) {
        bf_status st = reserve(rm, rm->nmem + 1, err);
        if (st)
            return st;
        for (int c = 0; c < NCOL; c++)
            if (kept_col(rm, c))
                rm->col[c][rm->nmem] = rm->cand[c];
        rm->nmem++;
    }
    rm->npts++;
    if (rm->cand[P_MIN] > 1)
        rm->multi++;
    rm->pending = 0;
    if (rm->s_t) {
        int64_t m = (int64_t)rm->cand[P_MIN];
        if (bf_series_append(rm->s_t, &rm->cand[P_T]) ||
            bf_series_append(rm->s_z, &rm->cand[P_Z]) ||
            bf_series_append(rm->s_v, &rm->cand[P_V]) ||
            bf_series_append(rm->s_zt, &rm->cand[P_ZT]) ||
            bf_series_append_i64(rm->s_min, &m))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    return BF_OK;
}

/* rootfinding integrators: g = v_trigger, located by the integrator */
static int rm_g(void *ctx, double t, const double *x, const double *v,
                double *g)
{
    (void)t;
    (void)x;
    g[0] = v[((bf_retmap *)ctx)->trig];
    return 0;
}

static void rm_hit(void *ctx, int k, double t, const double *x,
                   const double *v)
{
    (void)k;
    bf_retmap *rm = ctx;
    candidate(rm, t, x[rm->trig], x[rm->rec], v[rm->rec]);
}

static void retmap_free(void *self)
{
    bf_retmap *rm = self;
    if (!rm)
        return;
    if (rm->view.it && rm->view.it->events == &rm->ev)
        bf_integrator_set_events(rm->view.it, NULL);
    free(rm->x0);
    for (int c = 0; c < NCOL; c++)
        free(rm->col[c]);
    free(rm);
}

static bf_status retmap_create(void **out, const void *keys,
                               const bf_analysis_env *env, bf_err *err)
{
    *out = NULL;
    const bf_retmap_keys *k = keys;
    if (!k->enabled)
        return BF_OK;
    const bf_ball_view *view = env->view;
    const size_t n = view->n;
    if ((size_t)k->trigger > n)
        return bf_fail_key(err, BF_EINPUT, "return_map", "trigger",
                           "ball %ld does not exist (%zu balls)", k->trigger,
                           n);
    if ((size_t)k->record > n)
        return bf_fail_key(err, BF_EINPUT, "return_map", "record",
                           "ball %ld does not exist (%zu balls)", k->record,
                           n);
    int floor = 0;
    for (size_t e = 0; e < view->neffects; e++)
        floor |= (view->effects[e]->flags & BF_EFFECT_FLOOR) != 0;
    if (!floor)
        return bf_fail_key(err, BF_EINPUT, "return_map", "enabled",
                           "the return map is defined by floor contacts, "
                           "but [scene] effects has no 'floor'");
    bf_retmap *rm = calloc(1, sizeof *rm);
    if (!rm)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    rm->trig = (size_t)k->trigger - 1;
    rm->rec = (size_t)k->record - 1;
    rm->n = n;
    rm->keep_map = env->run && env->run->keep_map;
    rm->R = view->R[rm->trig];
    /* the force callback fills every component of the ODE: the balls and,
     * with non-conservative effects, the work after them (bf_ode.n) */
    const size_t no = view->ode->n;
    rm->x0 = calloc(4 * no, sizeof *rm->x0);
    if (!rm->x0) {
        free(rm);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    rm->v0 = rm->x0 + no;
    rm->a0 = rm->x0 + 2 * no;
    rm->a1 = rm->x0 + 3 * no;
    rm->view = *view;
    if (view->it->type->flags & BF_INT_ROOTS) {
        rm->dir = 1;
        rm->ev = (bf_events){1, rm_g, &rm->dir, rm_hit, rm};
        bf_integrator_set_events(view->it, &rm->ev);
    }
    *out = rm;
    return BF_OK;
}

static bf_status retmap_before_step(void *self, long n, double t, double dt,
                                   bf_err *err)
{
    (void)n;
    (void)t;
    (void)dt;
    (void)err;
    bf_retmap *rm = self;
    memcpy(rm->x0, rm->view.x, rm->n * sizeof *rm->x0);
    memcpy(rm->v0, rm->view.v, rm->n * sizeof *rm->v0);
    return BF_OK;
}

static bf_status retmap_after_step(void *self, long n_done, double t,
                                   double dt, bf_err *err)
{
    (void)n_done;
    bf_retmap *rm = self;
    const size_t i = rm->trig, r = rm->rec;
    const double *x1 = rm->view.x, *v1 = rm->view.v;
    const bf_ode *ode = rm->view.ode;
    if (!(rm->view.it->type->flags & BF_INT_ROOTS) && rm->v0[i] < 0 &&
        v1[i] >= 0) {
        const double z0 = rm->x0[i], u0 = rm->v0[i], z1 = x1[i], u1 = v1[i];
        /* the upward zero of the quadratic slope in [0, 1] */
        const double th = bf_hermite_slope_root((z1 - z0) / dt, u0, u1);
        /* forces at both ends for the velocity interpolant */
        if (ode->accel(ode->ctx, t, rm->x0, rm->v0, rm->a0) ||
            ode->accel(ode->ctx, t + dt, x1, v1, rm->a1))
            return bf_fail(err, BF_EUNSTABLE, "return map: force undefined");
        double zt, z, v;
        zt = bf_hermite(th, dt, z0, u0, z1, u1);
        z = bf_hermite(th, dt, rm->x0[r], rm->v0[r], x1[r], v1[r]);
        v = bf_hermite(th, dt, rm->v0[r], rm->a0[r], v1[r], rm->a1[r]);
        candidate(rm, t + th * dt, zt, z, v);
    }
    /* the contact is over once the trigger ball is off the floor */
    if (rm->pending && x1[i] >= rm->R)
        return emit(rm, err);
    return BF_OK;
}

/* Runs of steps may find the map's events themselves (sim.h, watch): a
 * lowest point of the trigger ball (its velocity from < 0 to >= 0), which
 * ends the run, and, while a candidate is pending, the end of its floor
 * contact, which the run notes and goes on.  Not with an
 * integrator that locates the lowest points inside its steps (BF_INT_ROOTS):
 * its candidates arrive during a step. */
static int retmap_watch(void *self, bf_ball_watch *w)
{
    const bf_retmap *rm = self;
    if (rm->view.it->type->flags & BF_INT_ROOTS)
        return 0;
    w->low = (long)rm->trig;
    if (rm->pending) {
        w->above = (long)rm->trig;
        w->above_x = rm->R;
    }
    return 1;
}

/* After a run that found an event.  The end of the contact (`above`) does
 * not end a run: the point pending then is the one to emit, whichever
 * step of the run it was (the run watches for it once; a step that is
 * also a lowest point ends the run and after_step sees both, in its
 * order).  A lowest point ends the run at its step: the step's start from
 * the run, then what after_step does. */
static bf_status retmap_watched(void *self, const bf_ball_watch *w,
                                long n_done, double t, double dt, bf_err *err)
{
    bf_retmap *rm = self;
    if ((w->fired & BF_WATCH_ABOVE) && rm->pending) {
        bf_status st = emit(rm, err);
        if (st)
            return st;
    }
    if (!(w->fired & BF_WATCH_LOW))
        return BF_OK;
    memcpy(rm->x0, w->x_start, rm->n * sizeof *rm->x0);
    memcpy(rm->v0, w->v_start, rm->n * sizeof *rm->v0);
    return retmap_after_step(self, n_done, t, dt, err);
}

static const bf_series_spec retmap_series[] = {
    {.path = "/return_map/time", .unit = "s", .kind = BF_SK_EVENTS,
     .role = BF_SR_TIME,
     .doc = "time of each lowest point of the trigger ball on the floor (one "
            "per contact, the deepest)",
     .slot = BF_SLOT(bf_retmap, s_t)},
    {.path = BF_DS_RETURN_MAP_Z, .unit = "cm", .kind = BF_SK_EVENTS,
     .doc = "position of the recorded ball at that time",
     .slot = BF_SLOT(bf_retmap, s_z)},
    {.path = BF_DS_RETURN_MAP_V, .unit = "cm/s", .kind = BF_SK_EVENTS,
     .doc = "velocity of the recorded ball at that time",
     .slot = BF_SLOT(bf_retmap, s_v)},
    {.path = "/return_map/z_trigger", .unit = "cm", .kind = BF_SK_EVENTS,
     .doc = "lowest position of the trigger ball",
     .slot = BF_SLOT(bf_retmap, s_zt)},
    {.path = "/return_map/minima", .unit = "1", .kind = BF_SK_EVENTS,
     .is_int = 1,
     .doc = "number of minima of the trigger ball in this floor contact (the "
            "deepest is recorded)",
     .slot = BF_SLOT(bf_retmap, s_min)},
};

const bf_series_table bf_retmap_series = {"return_map", retmap_series,
                                          BF_NSERIES(retmap_series)};

static bf_status retmap_output_open(void *self, bf_out *out, bf_err *err)
{
    return bf_out_open_table(out, retmap_series, BF_NSERIES(retmap_series),
                             self, NULL, 0, 0, err);
}

static bf_status retmap_output_close(void *self, bf_out *out, bf_err *err)
{
    const bf_retmap *rm = self;
    bf_status st = bf_out_attr_int(out, "/", "return_map_points",
                                   (int64_t)rm->npts, err);
    if (!st)
        st = bf_out_attr_int(out, "/", "return_map_multi_minima",
                             (int64_t)rm->multi, err);
    return st;
}

/* The checkpoint holds the counts and the pending candidate; the points
 * themselves are rows of the output (a checkpoint needs one), which a
 * restart truncates to the counts stored by the loop. */
static bf_status retmap_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    const bf_retmap *rm = self;
    int64_t meta[3] = {(int64_t)rm->npts, (int64_t)rm->multi, rm->pending};
    bf_status st = bf_ckpt_put_i64(ck, "return_map.meta", meta, 3, err);
    if (!st)
        st = bf_ckpt_put(ck, "return_map.candidate", rm->cand, NCOL, err);
    return st;
}

static bf_status retmap_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    bf_retmap *rm = self;
    int64_t meta[3];
    bf_status st = bf_ckpt_get_i64(ck, "return_map.meta", meta, 3, err);
    if (!st)
        st = bf_ckpt_get(ck, "return_map.candidate", rm->cand, NCOL, err);
    if (st)
        return st;
    if (meta[0] < 0 || meta[1] < 0 || meta[1] > meta[0] || meta[2] < 0 ||
        meta[2] > 1)
        return bf_fail(err, BF_EINPUT, "checkpoint: the return map's counts "
                       "(%lld points, %lld with several minima, pending %lld) "
                       "are inconsistent",
                       (long long)meta[0], (long long)meta[1],
                       (long long)meta[2]);
    rm->npts = (size_t)meta[0];
    rm->multi = (size_t)meta[1];
    rm->pending = (int)meta[2];
    rm->nmem = 0;
    return BF_OK;
}

size_t bf_retmap_points(const bf_retmap *rm, const double **t,
                        const double **z, const double **v,
                        const double **z_trigger)
{
    if (t)
        *t = rm->col[P_T];
    if (z)
        *z = rm->col[P_Z];
    if (v)
        *v = rm->col[P_V];
    if (z_trigger)
        *z_trigger = rm->col[P_ZT];
    return rm->s_t ? 0 : rm->nmem;
}

size_t bf_retmap_multi_minima(const bf_retmap *rm) { return rm->multi; }

static void retmap_report(const void *self, FILE *f)
{
    const bf_retmap *rm = self;
    fprintf(f, "return map:        %zu points (%zu contacts with more than "
               "one minimum)\n",
            rm->npts, rm->multi);
}

static void retmap_results(const void *self, bf_results *r)
{
    const bf_retmap *rm = self;
    r->has_return_map = 1;
    r->map_points = rm->npts;
    r->map_multi_minima = rm->multi;
    /* every point of the run, or none (a run continued from a checkpoint
     * holds only the points found since) */
    const int all = rm->nmem && rm->nmem == rm->npts;
    r->map_z = all ? rm->col[P_Z] : NULL;
    r->map_v = all ? rm->col[P_V] : NULL;
}

const bf_observer_type bf_retmap_observer = {
    .name = "return_map",
    .flags = BF_OBS_STEPS,
    .before_step = retmap_before_step,
    .after_step = retmap_after_step,
    .watch = retmap_watch,
    .watched = retmap_watched,
    .output_open = retmap_output_open,
    .output_close = retmap_output_close,
    .report = retmap_report,
    .save = retmap_save,
    .load = retmap_load,
    .results = retmap_results,
    .destroy = retmap_free,
};

const bf_analysis_type bf_retmap_analysis = {
    .name = "return_map",
    .spec = &retmap_spec,
    .observer = &bf_retmap_observer,
    .series = &bf_retmap_series,
    .create = retmap_create,
};
