/* converge.c: the convergence and work-precision study (converge.h), the
 * driver common to every model.  What a model's study compares, which of
 * its methods adapt and what its reference is come from the study its
 * descriptor points to (model.h, study.h), asked with the model's filled
 * structs (its setup) or the model built from them; printing and writing
 * the table are in converge_out.c. */
#include "ballfilm/converge.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "compose/compose.h"
#include "compose/converge_impl.h"
#include "diag/energy.h"
#include "core/model_energy.h"
#include "integrators/stop.h"

/* A resolved clone of the scene with the method string
 * "name:key=value:sec.key=value..." applied (name to the study's method
 * key, key=value to its parameter section, sec.key=value as written) and
 * then the overrides `extra` (NULL-terminated). */
static bf_status method_scene(const bf_converge_priv *P, const char *method,
                              const char *const *extra, bf_scene **out,
                              bf_err *err)
{
    *out = NULL;
    bf_scene *sc = bf_scene_clone(P->base);
    if (!sc)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    char buf[512];
    const char *colon = strchr(method, ':');
    size_t len = colon ? (size_t)(colon - method) : strlen(method);
    if (len >= 64 || len == 0) {
        bf_scene_free(sc);
        return bf_fail(err, BF_EINPUT, "bad method '%s'", method);
    }
    /* the method's name sets method_key, or what the study's method_sets
     * makes of it */
    char sets[2][96] = {{0}, {0}};
    size_t nsets = 1;
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)len, method);
    if (P->S->method_sets)
        nsets = P->S->method_sets(name, sets);
    else
        snprintf(sets[0], sizeof sets[0], "%s=%s", P->S->method_key, name);
    bf_status st = BF_OK;
    for (size_t k = 0; k < nsets && !st; k++)
        st = bf_scene_set(sc, sets[k], "--methods", err);
    for (const char *p = colon; !st && p && *p;) {
        p++;
        const char *q = strchr(p, ':');
        int l = (int)(q ? (size_t)(q - p) : strlen(p));
        const char *eq = memchr(p, '=', (size_t)l);
        const char *dot = memchr(p, '.', (size_t)l);
        if (dot && eq && dot < eq)
            snprintf(buf, sizeof buf, "%.*s", l, p);
        else
            snprintf(buf, sizeof buf, "%s.%.*s", P->S->param_section, l, p);
        st = bf_scene_set(sc, buf, "--methods", err);
        p = q;
    }
    for (const char *const *e = extra; !st && e && *e; e++)
        st = bf_scene_set(sc, *e, "converge", err);
    if (!st)
        st = bf_catalog_resolve(bf_catalog_builtin(), sc, err);
    if (st) {
        bf_err_prefix(err, "method '%s'", method);
        bf_scene_free(sc);
        return st;
    }
    *out = sc;
    return BF_OK;
}

/* Copy the state of view v into row (group after group). */
static size_t copy_state(const bf_study_view *v, double *row)
{
    size_t k = 0;
    for (size_t g = 0; g < v->ngroups; g++) {
        if (row)
            memcpy(row + k, v->g[g].a, v->g[g].n * sizeof *row);
        k += v->g[g].n;
        if (v->g[g].b) {
            if (row)
                memcpy(row + k, v->g[g].b, v->g[g].n * sizeof *row);
            k += v->g[g].n;
        }
    }
    return k;
}

/* The relative changes of the conserved totals (or the energy) since the
 * start: start (d == NULL on entry: set up), check after a step. */
typedef struct invariants {
    size_t n; /* 0: none */
    int energy; /* the model's energy (else the view's totals) */
    int work;   /* the model tracks the work of non-conservative forces:
                 * the balance E + W_diss - W_inj is what is conserved */
    bf_energy_diag d[4];
} invariants;

static double invariant_now(const bf_model_type *mt, void *model,
                            const bf_study_type *S, invariants *iv, double t)
{
    if (!iv->n)
        return NAN;
    double k, p;
    if (iv->energy)
        return bf_energy_check(&iv->d[0],
                               bf_model_balance(mt, model, t, iv->work, &k, &p));
    bf_study_view v;
    S->view(model, &v);
    double e = 0.0;
    for (size_t j = 0; j < iv->n; j++)
        e = fmax(e, bf_energy_check(&iv->d[j], v.inv[j]));
    return e;
}

static double invariant_max(const invariants *iv)
{
    if (!iv->n)
        return NAN;
    double e = 0.0;
    for (size_t j = 0; j < iv->n; j++)
        e = fmax(e, iv->d[j].max_rel);
    return e;
}

/* A model built from a method's scene, with its setup and type. */
typedef struct built {
    bf_setup *setup;
    void *model;
    const bf_model_type *mt;
} built;

static bf_status build(const bf_scene *sc, built *b, bf_err *err)
{
    bf_status st = bf_model_from_scene(bf_catalog_builtin(), sc, &b->setup,
                                       &b->model, err);
    b->mt = st ? NULL : bf_setup_model_type(b->setup);
    return st;
}

static void unbuild(built *b)
{
    b->mt->destroy(b->model);
    bf_setup_free(b->setup);
}

/* The study's stop flag is set: its failure. */
static int study_stopped(const bf_converge_priv *P, bf_err *err)
{
    if (!P->stop_flag || !*P->stop_flag)
        return 0;
    bf_fail(err, BF_INTERRUPTED, "the convergence study was interrupted; "
            "nothing was written");
    return 1;
}

/* The steps of one run (bf_converge_run_once); a stop flag set between
 * two steps or inside ARKODE's ends it with rst BF_INTERRUPTED. */
static bf_status run_steps(const bf_converge_priv *P, const bf_scene *sc,
                           long nper, double h, unsigned flags,
                           bf_converge_runout *o, bf_err *err);

bf_status bf_converge_run_once(const bf_converge_priv *P, const bf_scene *sc,
                               long nper, double h, unsigned flags,
                               bf_converge_runout *o, bf_err *err)
{
    if (study_stopped(P, err))
        return BF_INTERRUPTED;
    bf_stop_flag before = bf_stop_watch(P->stop_flag);
    bf_status st = run_steps(P, sc, nper, h, flags, o, err);
    bf_stop_watch(before);
    if (!st && o->status == BF_INTERRUPTED)
        st = bf_fail(err, BF_INTERRUPTED, "%s", o->msg);
    if (!st && study_stopped(P, err))
        st = BF_INTERRUPTED;
    return st;
}

/* the study's watch (study.h): the energy after an internal step */
static void check_energy(void *ctx, double energy)
{
    bf_energy_check(ctx, energy);
}

static bf_status run_steps(const bf_converge_priv *P, const bf_scene *sc,
                           long nper, double h, unsigned flags,
                           bf_converge_runout *o, bf_err *err)
{
    const int measure = (flags & BF_RUN_MEASURE) != 0;
    built b;
    bf_status st = build(sc, &b, err);
    if (st)
        return st;
    const bf_model_type *mt = b.mt;
    void *model = b.model;
    const bf_study_type *S = P->S;
    S->describe(model, o->label, sizeof o->label, &o->order);
    o->status = BF_OK;
    o->msg[0] = '\0';
    o->wall = 0.0;
    memset(&o->count, 0, sizeof o->count);
    invariants iv = {0};
    bf_study_view v;
    S->view(model, &v);
    o->nstate = copy_state(&v, NULL);
    if (v.ninv) {
        iv.n = v.ninv;
        for (size_t j = 0; j < v.ninv; j++)
            bf_energy_start(&iv.d[j], v.inv[j]);
    } else if (mt->energy) {
        iv.n = 1;
        iv.energy = 1;
        iv.work = bf_model_tracks_work(mt, model);
        double k, p;
        bf_energy_start(&iv.d[0],
                        bf_model_balance(mt, model, 0.0, iv.work, &k, &p));
    }
    const long R = P->R;
    const int sync = nper > 0 || (flags & BF_RUN_SYNC);
    const long ncalls = sync ? R : 1;
    const double hh = nper > 0 ? h : P->T / (double)ncalls;
    bf_dt_limit lim = {0};
    if (nper > 0 && mt->stable_dt)
        mt->stable_dt(model, &lim);
    if (o->nstate != P->nstate && P->nstate) {
        st = bf_fail(err, BF_EINPUT, "the state of '%s' has %zu values, "
                     "the reference's %zu", o->label, o->nstate, P->nstate);
        goto done;
    }
    if (lim.dt_max > 0 && hh > lim.dt_max) {
        /* beyond the model's stable step: a failed row, not garbage */
        o->status = BF_EUNSTABLE;
        snprintf(o->msg, sizeof o->msg, "dt = %g s exceeds %s", hh, lim.why);
        goto done;
    }
    /* (the watch checks E - E0 after ARKODE's internal steps: not the
     * balance, so not used when the model tracks work) */
    void *watch = measure && iv.energy && !iv.work && S->watch
                      ? S->watch(model, check_energy, &iv.d[0])
                      : NULL;
    /* the scene's energy bound stops a run beyond the method's stable
     * step, as in `ballfilm run`, instead of reporting garbage */
    const double bound = bf_scene_real(sc, "scene", "max_energy_error");
    bf_err rerr = {0};
    bf_status rst = BF_OK;
    const long per = nper > 0 ? nper : 1;
    long n = 0;
    const double t0 = bf_wall_time();
    for (long j = 0; j < ncalls && !rst; j++) {
        if (!measure && mt->advance && per > 1) {
            /* in runs of at most 1024 steps (the same bits as one run,
             * model.h), the stop flag looked at between them */
            for (long left = per; left > 0 && !rst;) {
                long done = 0, k = left < 1024 ? left : 1024;
                if (P->stop_flag && *P->stop_flag) {
                    rst = bf_fail(&rerr, BF_INTERRUPTED, "interrupted at "
                                  "t = %.9g s", (double)n * hh);
                    break;
                }
                rst = mt->advance(model, n, k, hh, NULL, &done, &rerr);
                if (rst)
                    bf_err_prefix(&rerr, "step %ld (t = %.9g s)",
                                  n + done + 1, (double)(n + done) * hh);
                n += done;
                left -= done;
            }
        } else {
            for (long s = 0; s < per && !rst; s++) {
                if (P->stop_flag && *P->stop_flag) {
                    rst = bf_fail(&rerr, BF_INTERRUPTED, "interrupted at "
                                  "t = %.9g s", (double)n * hh);
                    break;
                }
                rst = mt->step(model, n, (double)n * hh, hh, &rerr);
                if (rst) {
                    bf_err_prefix(&rerr, "step %ld (t = %.9g s)", n + 1,
                                  (double)n * hh);
                    break;
                }
                n++;
                if (!measure || !iv.n)
                    continue;
                double e = invariant_now(mt, model, S, &iv, (double)n * hh);
                if (iv.energy && bound > 0 && !(iv.d[0].max_rel <= bound))
                    rst = bf_fail(&rerr, BF_EUNSTABLE,
                                  "relative energy %serror %.3g exceeds "
                                  "[scene] max_energy_error = %g by t = "
                                  "%.9g s", iv.work ? "balance " : "", e,
                                  bound, (double)n * hh);
            }
        }
        if (!rst && o->rows) {
            S->view(model, &v);
            copy_state(&v, o->rows + (size_t)(sync ? j : R - 1) * o->nstate);
        }
    }
    o->wall = bf_wall_time() - t0;
    o->status = rst;
    snprintf(o->msg, sizeof o->msg, "%s", rst ? rerr.msg : "");
    free(watch);
done:
    o->invariant_err = measure ? invariant_max(&iv) : NAN;
    if (mt->counters)
        mt->counters(model, &o->count);
    unbuild(&b);
    return st;
}

/* Per group: max over the group's values of |row - ref| (offsets from the
 * reference's view). */
static void group_errors(const bf_converge_priv *P, const double *row,
                         const double *ref, double *e)
{
    for (size_t g = 0; g < P->ngroups; g++) {
        double m = 0.0;
        for (size_t i = P->off[g]; i < P->off[g] + P->len[g]; i++)
            m = fmax(m, fabs(row[i] - ref[i]));
        e[g] = isnan(m) ? INFINITY : m;
    }
}

/* errors of the rows of a run (R x nstate) against the reference rows:
 * at T, and the max and RMS over the rows */
void bf_converge_errors(const bf_converge_priv *P, const double *rows,
                        const double *ref, double *at_T, double *mx,
                        double *rms)
{
    double e[BF_CONVERGE_MAX_GROUPS], s2[BF_CONVERGE_MAX_GROUPS] = {0};
    for (size_t g = 0; g < P->ngroups; g++)
        mx[g] = 0.0;
    for (long j = 0; j < P->R; j++) {
        group_errors(P, rows + (size_t)j * P->nstate,
                     ref + (size_t)j * P->nstate, e);
        for (size_t g = 0; g < P->ngroups; g++) {
            mx[g] = fmax(mx[g], e[g]);
            s2[g] += e[g] * e[g];
            if (j == P->R - 1)
                at_T[g] = e[g];
        }
    }
    if (rms)
        for (size_t g = 0; g < P->ngroups; g++)
            rms[g] = sqrt(s2[g] / (double)P->R);
}

/* The overrides of one run: final time, step (fixed: h; adaptive: the row
 * interval) and, for adaptive runs, the tolerances and the largest step
 * (unless the method string sets them). */
typedef struct run_sets {
    char t_end[64], dt[64], rtol[96], atol[96], hmax[96];
    const char *list[6];
} run_sets;

static void make_sets(const bf_converge_priv *P, const char *method,
                      int adaptive, double h, double tol, run_sets *s)
{
    const char *sec = P->S->param_section;
    size_t k = 0;
    snprintf(s->t_end, sizeof s->t_end, "scene.t_end=%.17g", P->T);
    snprintf(s->dt, sizeof s->dt, "scene.dt=%.17g",
             adaptive ? P->T / (double)P->R : h);
    s->list[k++] = s->t_end;
    s->list[k++] = s->dt;
    if (adaptive) {
        snprintf(s->rtol, sizeof s->rtol, "%s.rtol=%.17g", sec, tol);
        snprintf(s->atol, sizeof s->atol, "%s.atol=%.17g", sec, tol / 100);
        snprintf(s->hmax, sizeof s->hmax, "%s.max_step=%.17g", sec, P->hmax);
        s->list[k++] = s->rtol;
        if (!strstr(method, "atol="))
            s->list[k++] = s->atol;
        if (P->hmax > 0 && !strstr(method, "max_step="))
            s->list[k++] = s->hmax;
    }
    s->list[k] = NULL;
}

/* The layout of the compared state (groups, offsets, sizes) from a model
 * built from scene sc, and the buffers that depend on it. */
static bf_status layout(bf_converge_result *r, const bf_scene *sc,
                        bf_err *err)
{
    bf_converge_priv *P = r->priv;
    built b;
    bf_status st = build(sc, &b, err);
    if (st)
        return st;
    bf_study_view v;
    P->S->view(b.model, &v);
    size_t off = 0;
    r->ngroups = P->ngroups = v.ngroups;
    for (size_t g = 0; g < v.ngroups; g++) {
        P->off[g] = off;
        P->len[g] = v.g[g].n * (v.g[g].b ? 2 : 1);
        off += P->len[g];
        snprintf(r->groups[g].name, sizeof r->groups[g].name, "%s",
                 v.g[g].name);
        snprintf(r->groups[g].unit, sizeof r->groups[g].unit, "%s",
                 v.g[g].unit);
        r->groups[g].n = P->len[g];
    }
    if (!v.ninv && b.mt->energy && bf_model_tracks_work(b.mt, b.model))
        snprintf(r->invariant, sizeof r->invariant,
                 "energy balance (E + W_diss - W_inj)");
    unbuild(&b);
    const size_t R = (size_t)P->R, m = off ? off : 1;
    P->nstate = r->nstate = off;
    P->ref_rows = calloc(R * m, sizeof *P->ref_rows);
    P->rows = calloc(2 * R * m, sizeof *P->rows);
    P->ref_final = calloc(m, sizeof *P->ref_final);
    r->ref_state = calloc(m, sizeof *r->ref_state);
    if (!P->ref_rows || !P->rows || !P->ref_final || !r->ref_state)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    return BF_OK;
}

/* A fixed-step run of step about h: a whole number of steps per output
 * row (*nper), all runs ending at T, and its step. */
static void fixed_steps(const bf_converge_priv *P, double h, long *nper,
                        double *step)
{
    long per = (long)ceil(P->T / ((double)P->R * h) * (1 - 1e-12));
    *nper = per < 1 ? 1 : per;
    *step = P->T / (double)(*nper * P->R);
}

/* The reference: the study's reference method at the given tolerance (its
 * rows in the scratch) and at a tenth of it (the reference rows, r->
 * ref_rtol); their difference is its estimated error.  A self-convergence
 * study (study.h, self_reference = K): the method at the fixed steps
 * [scene] dt / K and dt / 2K instead (r->ref_rtol NaN). */
static bf_status reference(bf_converge_result *r, const bf_converge_opts *o,
                           bf_err *err)
{
    bf_converge_priv *P = r->priv;
    char method[256];
    const bf_study_methods ms = {o->methods, o->nmethods, o->ref_table,
                                 o->ref_may_be_compared};
    bf_status st = P->S->reference(bf_setup_model(P->setup), &ms, method,
                                   sizeof method, err);
    const double rtols[2] = {r->ref_rtol, r->ref_rtol / 10};
    const int K = P->S->self_reference;
    const double dt0 = bf_scene_real(P->base, "scene", "dt");
    for (int k = 0; k < 2 && !st; k++) {
        long per = 0;
        double step = 0.0;
        if (K > 0)
            fixed_steps(P, dt0 / (double)(K * (k + 1)), &per, &step);
        run_sets s;
        make_sets(P, method, K == 0, step, rtols[k], &s);
        bf_scene *sc;
        if ((st = method_scene(P, method, s.list, &sc, err)))
            break;
        if (!P->nstate)
            st = layout(r, sc, err);
        /* synchronised at the rows (their errors), and in one call to T
         * (the state at T, the cost) */
        const size_t RS = (size_t)P->R * P->nstate;
        bf_converge_runout ro = {.rows = k ? P->ref_rows : P->rows};
        bf_converge_runout rt = {.rows = P->rows + RS};
        if (!st)
            st = bf_converge_run_once(P, sc, per, step,
                                      BF_RUN_MEASURE | BF_RUN_SYNC, &ro, err);
        if (!st && !ro.status && P->R > 1 && !per)
            st = bf_converge_run_once(P, sc, 0, 0.0, 0, &rt, err);
        else
            rt = ro;
        bf_scene_free(sc);
        if (!st && (ro.status || rt.status))
            st = bf_fail(err, ro.status ? ro.status : rt.status,
                         "reference run (%s) failed: %s", ro.label,
                         ro.status ? ro.msg : rt.msg);
        if (st)
            break;
        memcpy(k ? P->ref_final : P->rows + RS, rt.rows + RS - P->nstate,
               P->nstate * sizeof *P->ref_final);
        if (k == 1) {
            snprintf(r->ref_label, sizeof r->ref_label, "%s", ro.label);
            r->ref_count = rt.count;
            r->ref_wall = rt.wall;
            r->ref_invariant_err = ro.invariant_err;
        }
    }
    if (st)
        return st;
    r->ref_rtol = K > 0 ? NAN : rtols[1];
    double at_T[BF_CONVERGE_MAX_GROUPS];
    bf_converge_errors(P, P->rows, P->ref_rows, at_T, r->ref_err_max, NULL);
    group_errors(P, P->rows + (size_t)P->R * P->nstate, P->ref_final,
                 r->ref_err);
    memcpy(r->ref_state, P->ref_final, P->nstate * sizeof *r->ref_state);
    return BF_OK;
}

void bf_converge_free(bf_converge_result *r)
{
    if (!r)
        return;
    for (size_t k = 0; k < r->nmethods; k++)
        free(r->methods[k]);
    free(r->methods);
    free(r->rows);
    free(r->ref_state);
    bf_converge_priv *P = r->priv;
    if (P) {
        bf_setup_free(P->setup);
        bf_scene_free(P->base);
        free(P->ref_rows);
        free(P->ref_final);
        free(P->rows);
        free(P->adaptive);
        free(P->last);
        free(P);
    }
    free(r);
}

int bf_converge_adaptive(const bf_converge_result *r, size_t m)
{
    return m < r->nmethods && r->priv->adaptive[m];
}

/* Whether the method of scene sc (made by method_scene) is adaptive:
 * its study's answer on the filled structs of its setup. */
static bf_status method_adaptive(const bf_converge_priv *P,
                                 const char *method, const bf_scene *sc,
                                 int *adaptive, bf_err *err)
{
    bf_setup *s;
    bf_status st = bf_compose_setup(&s, bf_catalog_builtin(), sc, err);
    if (st) {
        bf_err_prefix(err, "method '%s'", method);
        return st;
    }
    *adaptive = P->S->adaptive(bf_setup_model(s));
    bf_setup_free(s);
    return BF_OK;
}

bf_status bf_converge_begin(const bf_scene *base_in,
                            const bf_converge_opts *opts,
                            bf_converge_result **out, bf_err *err)
{
    *out = NULL;
    bf_converge_opts o = *opts;
    if (!o.nmethods)
        return bf_fail(err, BF_EINPUT, "no methods given");
    /* the scene as given, resolved, for dt, t_end and the model */
    bf_scene *base = bf_scene_clone(base_in);
    if (!base)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_status st = bf_catalog_resolve(bf_catalog_builtin(), base, err);
    if (st) {
        bf_scene_free(base);
        return st;
    }
    const char *model = bf_scene_str(base, "scene", "model");
    bf_setup *setup = NULL;
    const bf_study_type *S = NULL;
    if (!(st = bf_compose_setup(&setup, bf_catalog_builtin(), base, err)) &&
        !(S = bf_setup_model_type(setup)->study))
        st = bf_fail(err, BF_EINPUT, "converge has no study of model '%s'",
                     model);
    if (!st && o.ref_rtol == 0)
        o.ref_rtol = S->default_ref_rtol;
    if (!st && !(o.ref_rtol > 0 && o.ref_rtol <= S->max_ref_rtol))
        st = bf_fail(err, BF_EINPUT, "the reference of model %s needs "
                     "0 < rtol <= %g", model, S->max_ref_rtol);
    bf_converge_result *r = st ? NULL : calloc(1, sizeof *r);
    bf_converge_priv *P = st ? NULL : calloc(1, sizeof *P);
    if (!st && (!r || !P))
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    if (st) {
        free(r);
        free(P);
        bf_setup_free(setup);
        bf_scene_free(base);
        return st;
    }
    r->priv = P;
    P->base = base;
    P->setup = setup;
    P->S = S;
    P->R = o.rows > 0 ? o.rows : 10;
    P->T = o.t_end > 0 ? o.t_end : bf_scene_real(base, "scene", "t_end");
    P->repeats = o.repeats;
    P->skip_checks = o.skip_checks;
    P->progress = o.progress;
    P->stop_flag = o.stop_flag;
    const bf_model_setup *ms = bf_setup_model(setup);
    const double hdef = S->max_step ? S->max_step(ms) : 0.0;
    P->hmax = o.max_step < 0 ? 0 : o.max_step > 0 ? o.max_step : hdef;
    snprintf(r->scene, sizeof r->scene, "%s", bf_scene_path(base));
    snprintf(r->model, sizeof r->model, "%s", model);
    snprintf(r->invariant, sizeof r->invariant, "%s", S->invariant);
    r->max_step = P->hmax;
    r->t_end = P->T;
    r->out_rows = P->R;
    r->ref_rtol = o.ref_rtol;
    if (S->notes)
        S->notes(ms, r->notes, sizeof r->notes);
    r->methods = calloc(o.nmethods, sizeof *r->methods);
    P->adaptive = calloc(o.nmethods, sizeof *P->adaptive);
    P->last = calloc(o.nmethods, sizeof *P->last);
    if (!r->methods || !P->adaptive || !P->last) {
        bf_converge_free(r);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    r->nmethods = o.nmethods;
    for (size_t m = 0; m < o.nmethods; m++) {
        r->methods[m] = strdup(o.methods[m]);
        P->last[m] = -1;
    }
    /* validate every method before the (long) reference */
    for (size_t m = 0; m < o.nmethods && !st; m++) {
        bf_scene *sc;
        if (!(st = method_scene(P, o.methods[m], NULL, &sc, err))) {
            st = method_adaptive(P, o.methods[m], sc, &P->adaptive[m], err);
            bf_scene_free(sc);
        }
    }
    if (!st)
        st = reference(r, &o, err);
    if (!st && o.progress)
        fprintf(o.progress, "reference: %s, %llu steps, %.3g s\n",
                r->ref_label, r->ref_count.steps, r->ref_wall);
    if (st) {
        bf_converge_free(r);
        return st;
    }
    *out = r;
    return BF_OK;
}

/* One more row (zeroed) at the end of r->rows. */
static bf_status add_row(bf_converge_result *r, bf_err *err)
{
    bf_converge_priv *P = r->priv;
    const size_t want = P->cap > r->nrows ? P->cap : 2 * P->cap + 32;
    bf_converge_row *p = want == P->cap
                             ? r->rows
                             : realloc(r->rows, want * sizeof *p);
    if (!p)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    r->rows = p;
    P->cap = want;
    memset(&r->rows[r->nrows++], 0, sizeof *p);
    return BF_OK;
}

/* The scene of row w's setting and its steps per output row (0:
 * adaptive, one call per row) and step. */
static bf_status row_scene(const bf_converge_result *r, size_t m, double h,
                           bf_scene **sc, long *nper, double *step,
                           bf_err *err)
{
    const bf_converge_priv *P = r->priv;
    const int adaptive = P->adaptive[m];
    *nper = 0;
    *step = 0.0;
    if (!adaptive)
        fixed_steps(P, h, nper, step);
    run_sets s;
    make_sets(P, r->methods[m], adaptive, *step, h, &s);
    return method_scene(P, r->methods[m], s.list, sc, err);
}

/* The runs that are timed: no checks, adaptive methods in one call from
 * 0 to T (ARKODE chooses every step); the smallest wall time; the first
 * keeps the state at T (ro->rows, last row) and its status; the counters
 * are the cost reported (a step monitor costs ARKODE's FSAL tables one
 * evaluation per step). */
static bf_status timed(const bf_converge_priv *P, const bf_scene *sc,
                       long nper, double step, int repeats,
                       bf_converge_runout *ro, bf_err *err)
{
    bf_status st = BF_OK;
    for (int rep = 0; !st && rep < (repeats < 1 ? 1 : repeats); rep++) {
        bf_converge_runout rt = {.rows = rep ? NULL : ro->rows};
        st = bf_converge_run_once(P, sc, nper, step, 0, &rt, err);
        if (st)
            break;
        if (rep == 0) {
            ro->status = rt.status;
            snprintf(ro->msg, sizeof ro->msg, "%s", rt.msg);
            snprintf(ro->label, sizeof ro->label, "%s", rt.label);
            ro->order = rt.order;
        }
        if (rt.wall < ro->wall)
            ro->wall = rt.wall;
        ro->count = rt.count;
        if (rt.status)
            break;
    }
    return st;
}

bf_status bf_converge_add(bf_converge_result *r, size_t m, double h,
                          int repeats, bf_err *err)
{
    bf_converge_priv *P = r->priv;
    if (m >= r->nmethods)
        return bf_fail(err, BF_EINTERNAL, "no method %zu", m);
    const int adaptive = P->adaptive[m];
    long nper;
    double step;
    bf_scene *sc;
    bf_status st = row_scene(r, m, h, &sc, &nper, &step, err);
    if (!st)
        st = add_row(r, err);
    if (st) {
        bf_scene_free(sc);
        return st;
    }
    bf_converge_row *row = &r->rows[r->nrows - 1];
    row->method = (int)m;
    row->adaptive = adaptive;
    row->tol = adaptive ? h : 0.0;
    /* the measured run: checks, the state at every output row (adaptive
     * methods synchronised there); then the timed runs (adaptive ones in
     * one call to T), whose state at T gives the error at T */
    const size_t RS = (size_t)P->R * P->nstate;
    bf_converge_runout ro = {.rows = P->rows};
    st = bf_converge_run_once(P, sc, nper, step,
                              BF_RUN_SYNC |
                                  (P->skip_checks ? 0 : BF_RUN_MEASURE),
                              &ro, err);
    bf_converge_runout rt = {.rows = P->rows + RS, .wall = INFINITY};
    if (!st && !ro.status)
        st = timed(P, sc, nper, step, repeats, &rt, err);
    bf_scene_free(sc);
    if (st) {
        r->nrows--;
        return st;
    }
    snprintf(row->label, sizeof row->label, "%s", ro.label);
    row->order = ro.order;
    row->status = ro.status ? ro.status : rt.status;
    snprintf(row->msg, sizeof row->msg, "%s", ro.status ? ro.msg : rt.msg);
    row->count = ro.status ? ro.count : rt.count;
    row->wall = ro.status || repeats < 1 ? ro.wall : rt.wall;
    row->invariant_err = ro.invariant_err;
    row->dt = adaptive ? (row->count.steps ? P->T / (double)row->count.steps
                                           : NAN)
                       : step;
    for (size_t g = 0; g < BF_CONVERGE_MAX_GROUPS; g++)
        row->err[g] = row->err_max[g] = row->err_rms[g] = row->order_obs[g] =
            NAN;
    if (!row->status) {
        double at_T[BF_CONVERGE_MAX_GROUPS];
        bf_converge_errors(P, P->rows, P->ref_rows, at_T, row->err_max,
                           row->err_rms);
        group_errors(P, P->rows + RS + RS - P->nstate, P->ref_final, row->err);
    }
    if (P->last[m] >= 0) {
        const bf_converge_row *prev = &r->rows[P->last[m]];
        if (!prev->status && !row->status) {
            double lh = log(prev->dt / row->dt);
            for (size_t g = 0; g < P->ngroups; g++)
                row->order_obs[g] = log(prev->err[g] / row->err[g]) / lh;
        }
    }
    P->last[m] = (long)r->nrows - 1;
    if (P->progress)
        fprintf(P->progress, "  %-28s %s %-9.3g err %.3e  %s\n", row->label,
                adaptive ? "tol" : "dt ", adaptive ? row->tol : row->dt,
                row->err[0], row->status ? bf_status_name(row->status) : "");
    return BF_OK;
}

bf_status bf_converge_retime(bf_converge_result *r, size_t k, int repeats,
                             bf_err *err)
{
    if (k >= r->nrows)
        return bf_fail(err, BF_EINTERNAL, "no row %zu", k);
    bf_converge_row *row = &r->rows[k];
    if (row->status)
        return BF_OK;
    const size_t m = (size_t)row->method;
    long nper;
    double step;
    bf_scene *sc;
    bf_status st = row_scene(r, m, r->priv->adaptive[m] ? row->tol : row->dt,
                             &sc, &nper, &step, err);
    if (st)
        return st;
    bf_converge_runout ro = {.wall = row->wall};
    if (repeats > 0)
        st = timed(r->priv, sc, nper, step, repeats, &ro, err);
    bf_scene_free(sc);
    if (!st)
        row->wall = ro.wall;
    return st;
}

bf_status bf_converge_run(const bf_scene *sc, const bf_converge_opts *opts,
                          bf_converge_result **out, bf_err *err)
{
    bf_converge_result *r;
    bf_status st = bf_converge_begin(sc, opts, &r, err);
    if (st)
        return st;
    const double dt0 = bf_scene_real(r->priv->base, "scene", "dt");
    const double def_dts[4] = {4 * dt0, 2 * dt0, dt0, dt0 / 2};
    const double def_tols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
    const double *dts = opts->dts ? opts->dts : def_dts;
    const double *tols = opts->tols ? opts->tols : def_tols;
    const size_t ndts = opts->dts ? opts->ndts : 4;
    const size_t ntols = opts->tols ? opts->ntols : 4;
    const int repeats = opts->repeats ? opts->repeats : 3;
    for (size_t m = 0; m < r->nmethods && !st; m++) {
        const int adaptive = r->priv->adaptive[m];
        const size_t nruns = adaptive ? ntols : ndts;
        for (size_t k = 0; k < nruns && !st; k++)
            st = bf_converge_add(r, m, adaptive ? tols[k] : dts[k], repeats,
                                 err);
    }
    if (st) {
        bf_converge_free(r);
        return st;
    }
    *out = r;
    return BF_OK;
}

bf_status bf_converge_file(const char *scene_path, const char *const *sets,
                           size_t nsets, const bf_converge_opts *opts,
                           bf_converge_result **out, bf_err *err)
{
    *out = NULL;
    bf_scene *sc = NULL;
    bf_status st = bf_scene_load(&sc, scene_path, err);
    for (size_t k = 0; !st && k < nsets; k++)
        st = bf_scene_set(sc, sets[k], "--set", err);
    if (!st)
        st = bf_converge_run(sc, opts, out, err);
    bf_scene_free(sc);
    return st;
}
