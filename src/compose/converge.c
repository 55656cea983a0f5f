/* converge.c: convergence and work-precision study (see converge.h). */
#include "ballfilm/converge.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/arkode.h"
#include "models/ballsys.h"
#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "base/clock.h"
#include "diag/energy.h"


/* A resolved clone of the scene with `integrator` and the overrides of a
 * method string "name:key=value:..." plus `extra` (NULL-terminated). */
static bf_status method_scene(const bf_scene *base, const char *method,
                              const char *const *extra, bf_scene **out,
                              char *name, size_t cap, bf_err *err)
{
    *out = NULL;
    bf_scene *sc = bf_scene_clone(base);
    if (!sc)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    char buf[512];
    const char *colon = strchr(method, ':');
    size_t len = colon ? (size_t)(colon - method) : strlen(method);
    if (len >= cap || len == 0) {
        bf_scene_free(sc);
        return bf_fail(err, BF_EINPUT, "bad method '%s'", method);
    }
    memcpy(name, method, len);
    name[len] = '\0';
    snprintf(buf, sizeof buf, "scene.integrator=%s", name);
    bf_status st = bf_scene_set(sc, buf, "--methods", err);
    for (const char *p = colon; !st && p && *p;) {
        p++;
        const char *q = strchr(p, ':');
        size_t l = q ? (size_t)(q - p) : strlen(p);
        snprintf(buf, sizeof buf, "integrator.%.*s", (int)l, p);
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

/* One run: nsteps calls of step size h from t = 0.  With `measure` the
 * energy is checked after every call and, for adaptive integrators, after
 * every internal step (step monitor); the final state goes to x, v. */
typedef struct run_out {
    double *x, *v;
    double energy_err;
    bf_counters count;
    double wall;
    bf_status status;
    char msg[BF_ERR_MSG];
    char label[160];
    int order;
} run_out;

typedef struct energy_watch {
    const bf_ballsys *sys;
    bf_energy_diag d;
} energy_watch;

static void monitor_energy(void *ctx, double t, const double *x,
                           const double *v)
{
    energy_watch *w = ctx;
    const bf_ballsys *s = w->sys;
    double k = 0.0;
    for (size_t i = 0; i < s->b.n; i++)
        k += 0.5 * s->b.m[i] * v[i] * v[i];
    bf_energy_check(&w->d,
                    k + bf_effects_potential(s->eff, s->neff, &s->b, t, x));
}

static bf_status run_once(const bf_scene *sc, long nsteps, double h,
                          int measure, run_out *o, bf_err *err)
{
    bf_ballsys *sys;
    bf_status st = bf_ballsys_from_scene(&sys, bf_catalog_builtin(), sc, err);
    if (st)
        return st;
    bf_integrator_describe(sys->it, o->label, sizeof o->label);
    o->order = bf_integrator_order(sys->it);
    double k, p;
    bf_ballsys_energy(sys, 0.0, &k, &p);
    energy_watch w = {.sys = sys};
    bf_energy_start(&w.d, k + p);
    /* the scene's energy bound stops a run beyond the method's stable
     * step, as in `ballfilm run`, instead of reporting garbage */
    const double bound = bf_scene_real(sc, "scene", "max_energy_error");
    if (measure)
        bf_integrator_set_monitor(sys->it, monitor_energy, &w);
    bf_err rerr = {0};
    bf_status rst = BF_OK;
    double t0 = bf_wall_time();
    for (long s = 0; s < nsteps; s++) {
        rst = bf_ballsys_step(sys, (double)s * h, h, &rerr);
        if (rst) {
            bf_err_prefix(&rerr, "step %ld (t = %.9g s)", s + 1,
                          (double)s * h);
            break;
        }
        if (measure) {
            bf_ballsys_energy(sys, (double)(s + 1) * h, &k, &p);
            bf_energy_check(&w.d, k + p);
            if (bound > 0 && !(w.d.max_rel <= bound)) {
                rst = bf_fail(&rerr, BF_EUNSTABLE,
                              "relative energy error %.3g exceeds [scene] "
                              "max_energy_error = %g by t = %.9g s",
                              w.d.max_rel, bound, (double)(s + 1) * h);
                break;
            }
        }
    }
    o->wall = bf_wall_time() - t0;
    o->status = rst;
    snprintf(o->msg, sizeof o->msg, "%s", rst ? rerr.msg : "");
    o->energy_err = w.d.max_rel;
    o->count = sys->it->count;
    memcpy(o->x, sys->b.x, sys->b.n * sizeof *o->x);
    memcpy(o->v, sys->b.v, sys->b.n * sizeof *o->v);
    bf_ballsys_free(sys);
    return BF_OK;
}

/* Reference tables in order of preference.  Not FEHLBERG_13_7_8: its
 * error estimate (b - d) k involves only stages 1, 11, 12 and 13, which
 * all agree in free flight, so a step whose middle stages reach into a
 * contact is accepted with a zero estimate; on runs/bouncing_ball.ini it
 * gave relative energy errors of 4e2 at rtol 1e-12 and 2e7 at 1e-8. */
static const char *const default_refs[] = {"ARKODE_VERNER_8_5_6",
                                           "ARKODE_DORMAND_PRINCE_7_4_5",
                                           "ARKODE_CASH_KARP_6_4_5"};

/* Does a method string use this ARKODE table? (an arkode method without a
 * table key uses its default) */
static int method_uses_table(const char *m, const char *table)
{
    if (strncmp(m, "arkode", 6) || (m[6] && m[6] != ':' && m[6] != '-'))
        return 0;
    const char *t = strstr(m, "table=");
    if (t)
        return !strncmp(t + 6, table, strlen(table));
    const char *def = !strncmp(m, "arkode-fixed", 12)
                          ? "ARKODE_ZONNEVELD_5_3_4"
                          : "ARKODE_DORMAND_PRINCE_7_4_5";
    return !strcmp(def, table);
}

static bf_status reference(const bf_scene *base, const bf_converge_opts *o,
                           double T, bf_converge_result *r, bf_err *err)
{
    const char *table = o->ref_table;
    for (size_t k = 0; !table && k < 3; k++) {
        int used = 0;
        for (size_t m = 0; m < o->nmethods; m++)
            used |= method_uses_table(o->methods[m], default_refs[k]);
        if (!used)
            table = default_refs[k];
    }
    if (!table)
        return bf_fail(err, BF_EINPUT, "every candidate reference table is "
                       "compared; give --ref-table");
    if (bf_arkode_table_index(table) < 0)
        return bf_fail(err, BF_EINPUT, "unknown ARKODE table '%s'", table);
    for (size_t m = 0; m < o->nmethods; m++)
        if (method_uses_table(o->methods[m], table))
            return bf_fail(err, BF_EINPUT, "the reference table %s is also "
                           "compared (method '%s'); the reference must use "
                           "another method", table, o->methods[m]);
    const double rtols[2] = {o->ref_rtol, o->ref_rtol / 10};
    char set_h[64];
    snprintf(set_h, sizeof set_h, "integrator.max_step=%.17g", r->max_step);
    double *xs[2] = {r->x_ref, NULL}, *vs[2] = {r->v_ref, NULL};
    double *tmp = calloc(2 * r->n, sizeof *tmp);
    if (!tmp)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    xs[1] = tmp;
    vs[1] = tmp + r->n;
    bf_status st = BF_OK;
    for (int k = 0; k < 2 && !st; k++) {
        char set_t[128], set_r[64], set_a[64];
        snprintf(set_t, sizeof set_t, "integrator.table=%s", table);
        snprintf(set_r, sizeof set_r, "integrator.rtol=%.17g", rtols[k]);
        snprintf(set_a, sizeof set_a, "integrator.atol=%.17g", rtols[k] / 100);
        /* events: rootfinding at every contact onset and release, the
         * integration restarted there (arkode.c), so that no step of the
         * reference straddles a kink of the Hertz force */
        const char *extra[] = {set_t, set_r, set_a, set_h,
                               "integrator.max_steps=2000000000",
                               "integrator.events=yes", NULL};
        bf_scene *sc;
        char name[64];
        if ((st = method_scene(base, "arkode", extra, &sc, name, sizeof name,
                               err)))
            break;
        /* the tighter run (k = 1) is the reference */
        run_out ro = {.x = k ? xs[0] : xs[1], .v = k ? vs[0] : vs[1]};
        st = run_once(sc, 1, T, 1, &ro, err);
        bf_scene_free(sc);
        if (!st && ro.status)
            st = bf_fail(err, ro.status, "reference run (%s) failed: %s",
                         ro.label, ro.msg);
        if (!st && k == 1) {
            snprintf(r->ref_label, sizeof r->ref_label, "%s", ro.label);
            r->ref_count = ro.count;
            r->ref_wall = ro.wall;
            r->ref_energy_err = ro.energy_err;
        }
    }
    if (!st) {
        r->ref_err_x = r->ref_err_v = 0;
        for (size_t i = 0; i < r->n; i++) {
            r->ref_err_x = fmax(r->ref_err_x, fabs(xs[0][i] - xs[1][i]));
            r->ref_err_v = fmax(r->ref_err_v, fabs(vs[0][i] - vs[1][i]));
        }
        r->ref_rtol = rtols[1];
    }
    free(tmp);
    return st;
}

static bf_status add_row(bf_converge_result *r, size_t *cap, bf_err *err)
{
    if (r->nrows == *cap) {
        size_t c = *cap ? 2 * *cap : 32;
        bf_converge_row *p = realloc(r->rows, c * sizeof *p);
        if (!p)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        r->rows = p;
        *cap = c;
    }
    memset(&r->rows[r->nrows], 0, sizeof r->rows[0]);
    r->nrows++;
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
    free(r->x_ref); /* v_ref points into the same block */
    free(r);
}

bf_status bf_converge_run(const bf_scene *base_in, const bf_converge_opts *opts,
                          bf_converge_result **out, bf_err *err)
{
    *out = NULL;
    bf_converge_opts o = *opts;
    if (!o.nmethods)
        return bf_fail(err, BF_EINPUT, "no methods given");
    if (!o.repeats)
        o.repeats = 3;
    if (o.ref_rtol == 0)
        o.ref_rtol = 1e-12;
    if (!(o.ref_rtol <= 1e-12))
        return bf_fail(err, BF_EINPUT, "the reference needs rtol <= 1e-12");
    /* the scene as given, resolved, for dt, t_end and the model */
    bf_scene *base = bf_scene_clone(base_in);
    if (!base)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_status st = bf_catalog_resolve(bf_catalog_builtin(), base, err);
    if (st) {
        bf_scene_free(base);
        return st;
    }
    if (strcmp(bf_scene_str(base, "scene", "model"), "balls")) {
        bf_scene_free(base);
        return bf_fail(err, BF_EINPUT, "converge works on ball scenes "
                       "([scene] model = balls)");
    }
    const double dt0 = bf_scene_real(base, "scene", "dt");
    const int hertz = bf_scene_has_name(base, "scene", "effects", "floor") ||
                      bf_scene_has_name(base, "scene", "effects", "contact");
    const double hmax = o.max_step < 0 ? 0
                        : o.max_step > 0 ? o.max_step
                        : hertz         ? 10 * dt0
                                        : 0;
    const double T = o.t_end > 0 ? o.t_end : bf_scene_real(base, "scene",
                                                           "t_end");
    double def_dts[4] = {4 * dt0, 2 * dt0, dt0, dt0 / 2};
    double def_tols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
    if (!o.dts) {
        o.dts = def_dts;
        o.ndts = 4;
    }
    if (!o.tols) {
        o.tols = def_tols;
        o.ntols = 4;
    }
    bf_converge_result *r = calloc(1, sizeof *r);
    if (!r) {
        bf_scene_free(base);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    snprintf(r->scene, sizeof r->scene, "%s", bf_scene_path(base));
    r->max_step = hmax;
    r->t_end = T;
    r->n = (size_t)bf_scene_count(base, "ball");
    r->hertz = hertz;
    r->x_ref = calloc(2 * r->n, sizeof *r->x_ref);
    r->methods = calloc(o.nmethods, sizeof *r->methods);
    double *x = calloc(4 * r->n, sizeof *x);
    if (!r->x_ref || !r->methods || !x) {
        free(x);
        bf_scene_free(base);
        bf_converge_free(r);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    r->v_ref = r->x_ref + r->n;
    r->nmethods = o.nmethods;
    for (size_t m = 0; m < o.nmethods; m++)
        r->methods[m] = strdup(o.methods[m]);
    /* validate every method before the (long) reference */
    for (size_t m = 0; m < o.nmethods && !st; m++) {
        bf_scene *sc;
        char name[64];
        st = method_scene(base, o.methods[m], NULL, &sc, name, sizeof name,
                          err);
        bf_scene_free(sc);
    }
    if (!st)
        st = reference(base, &o, T, r, err);
    if (!st && o.progress)
        fprintf(o.progress, "reference: %s, %llu steps, %.3g s\n",
                r->ref_label, r->ref_count.steps, r->ref_wall);
    size_t cap = 0;
    for (size_t m = 0; m < o.nmethods && !st; m++) {
        char name[64];
        bf_scene *probe;
        if ((st = method_scene(base, o.methods[m], NULL, &probe, name,
                               sizeof name, err)))
            break;
        bf_scene_free(probe);
        const bf_integrator_type *type =
            bf_catalog_integrator(bf_catalog_builtin(), name);
        const int adaptive = (type->flags & BF_INT_ADAPTIVE) != 0;
        const int has_atol = strstr(o.methods[m], "atol=") != NULL;
        const size_t nruns = adaptive ? o.ntols : o.ndts;
        size_t first = r->nrows;
        for (size_t k = 0; k < nruns && !st; k++) {
            char set_r[64], set_a[64], set_h[64];
            const char *extra[4] = {NULL, NULL, NULL, NULL};
            long nsteps;
            double h;
            if (adaptive) {
                snprintf(set_r, sizeof set_r, "integrator.rtol=%.17g",
                         o.tols[k]);
                snprintf(set_a, sizeof set_a, "integrator.atol=%.17g",
                         o.tols[k] / 100);
                snprintf(set_h, sizeof set_h, "integrator.max_step=%.17g",
                         hmax);
                extra[0] = set_r;
                extra[1] = strstr(o.methods[m], "max_step=") ? NULL : set_h;
                extra[2] = has_atol ? NULL : set_a;
                if (!extra[1]) {
                    extra[1] = extra[2];
                    extra[2] = NULL;
                }
                nsteps = 1; /* one call: ARKODE chooses every step */
            } else {
                nsteps = (long)ceil(T / o.dts[k] * (1 - 1e-12));
                if (nsteps < 1)
                    nsteps = 1;
            }
            h = T / (double)nsteps;
            bf_scene *sc;
            if ((st = method_scene(base, o.methods[m], extra, &sc, name,
                                   sizeof name, err)))
                break;
            if ((st = add_row(r, &cap, err))) {
                bf_scene_free(sc);
                break;
            }
            bf_converge_row *row = &r->rows[r->nrows - 1];
            row->method = (int)m;
            row->adaptive = adaptive;
            row->tol = adaptive ? o.tols[k] : 0.0;
            row->order_x = row->order_v = NAN;
            /* measured run (energy, error), then timed runs without any
             * monitoring; their counters are the cost reported (a step
             * monitor costs ARKODE's FSAL tables one evaluation per step) */
            run_out ro = {.x = x, .v = x + r->n};
            st = run_once(sc, nsteps, h, 1, &ro, err);
            double best = INFINITY;
            for (int rep = 0; !st && !ro.status && rep < o.repeats; rep++) {
                run_out rt = {.x = x + 2 * r->n, .v = x + 3 * r->n};
                st = run_once(sc, nsteps, h, 0, &rt, err);
                if (!st && rt.wall < best)
                    best = rt.wall;
                if (!st)
                    ro.count = rt.count;
            }
            if (!(best < INFINITY))
                best = ro.wall;
            bf_scene_free(sc);
            if (st)
                break;
            snprintf(row->label, sizeof row->label, "%s", ro.label);
            row->order = ro.order;
            row->count = ro.count;
            row->wall = best;
            row->status = ro.status;
            snprintf(row->msg, sizeof row->msg, "%s", ro.msg);
            row->energy_err = ro.energy_err;
            row->dt = adaptive ? (ro.count.steps ? T / (double)ro.count.steps
                                                 : NAN)
                               : h;
            row->err_x = row->err_v = NAN;
            if (!ro.status) {
                row->err_x = row->err_v = 0;
                for (size_t i = 0; i < r->n; i++) {
                    row->err_x = fmax(row->err_x, fabs(x[i] - r->x_ref[i]));
                    row->err_v = fmax(row->err_v,
                                      fabs(x[r->n + i] - r->v_ref[i]));
                }
            }
            if (r->nrows - 1 > first) {
                const bf_converge_row *prev = row - 1;
                if (!prev->status && !row->status) {
                    double lh = log(prev->dt / row->dt);
                    row->order_x = log(prev->err_x / row->err_x) / lh;
                    row->order_v = log(prev->err_v / row->err_v) / lh;
                }
            }
            if (o.progress)
                fprintf(o.progress, "  %-28s %s %-9.3g err %.3e  %s\n",
                        row->label, adaptive ? "tol" : "dt ",
                        adaptive ? row->tol : row->dt, row->err_x,
                        row->status ? bf_status_name(row->status) : "");
        }
    }
    free(x);
    bf_scene_free(base);
    if (st) {
        bf_converge_free(r);
        return st;
    }
    *out = r;
    return BF_OK;
}

static void fmt_order(char *buf, size_t cap, double p)
{
    if (isnan(p))
        snprintf(buf, cap, "%6s", "-");
    else
        snprintf(buf, cap, "%6.2f", p);
}

void bf_converge_print(const bf_converge_result *r, FILE *f)
{
    fprintf(f, "convergence study of %s to T = %g s\n", r->scene, r->t_end);
    fprintf(f, "reference: %s (run at rtol %g and %g), %llu steps, %llu "
               "force evaluations, %.3g s;\n"
               "  its estimated error (difference of the two): position "
               "%.2e cm, velocity %.2e cm/s;\n"
               "  its max relative energy error: %.2e\n",
            r->ref_label, r->ref_rtol * 10, r->ref_rtol, r->ref_count.steps,
            r->ref_count.evals, r->ref_wall, r->ref_err_x, r->ref_err_v,
            r->ref_energy_err);
    if (r->max_step > 0)
        fprintf(f, "adaptive runs and the reference: largest internal step "
                   "%g s\n",
                r->max_step);
    int lw = 6;
    for (size_t k = 0; k < r->nrows; k++)
        if ((int)strlen(r->rows[k].label) > lw)
            lw = (int)strlen(r->rows[k].label);
    fprintf(f, "\n%-*s %3s %10s %9s %11s %10s %10s %6s %6s %10s %10s\n",
            lw, "method", "ord", "dt [s]", "tol", "evals", "err x [cm]",
            "err v", "p_x", "p_v", "max dE/E", "wall [s]");
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        char px[16], pv[16], tol[16];
        fmt_order(px, sizeof px, w->order_x);
        fmt_order(pv, sizeof pv, w->order_v);
        if (w->adaptive)
            snprintf(tol, sizeof tol, "%9.1e", w->tol);
        else
            snprintf(tol, sizeof tol, "%9s", "-");
        if (w->status) {
            fprintf(f, "%-*s %3d %10.4g %s %11llu  %s: %s\n", lw, w->label,
                    w->order, w->dt, tol, w->count.evals,
                    bf_status_name(w->status), w->msg);
            continue;
        }
        fprintf(f, "%-*s %3d %10.4g %s %11llu %10.3e %10.3e %s %s %10.3e "
                   "%10.4f\n",
                lw, w->label, w->order, w->dt, tol, w->count.evals, w->err_x,
                w->err_v, px, pv, w->energy_err, w->wall);
    }
    /* errors at the reference's own level make orders meaningless */
    int near_ref = 0;
    for (size_t k = 0; k < r->nrows; k++)
        if (!r->rows[k].status && r->rows[k].err_x < 10 * r->ref_err_x)
            near_ref = 1;
    if (near_ref)
        fprintf(f, "\nnote: some errors are within 10x of the reference's "
                   "estimated error; their orders are not meaningful.\n");
    if (r->hertz)
        fprintf(f, "\nnote: the scene has Hertz contacts.  The contact "
                   "force k x^{3/2} is continuous with a continuous first "
                   "derivative at contact onset (x = 0) but its second "
                   "derivative is infinite there, so the error expansions "
                   "behind the nominal orders do not hold across contact "
                   "onsets: observed orders below nominal are what is "
                   "measured, not a defect.\n");
    fprintf(f, "\ndt: step of fixed-step methods, mean internal step T/steps "
               "of adaptive ones; p_x, p_v: observed orders between "
               "successive runs; wall: stepping loop, minimum over the "
               "repeats.\n");
}

bf_status bf_converge_write(const bf_converge_result *r, const char *path,
                            bf_err *err)
{
    bf_out *o;
    bf_status st = bf_out_create(&o, path, err);
    if (st)
        return st;
    size_t n = r->nrows;
    double *col = calloc(n ? n : 1, sizeof *col);
    int64_t *icol = calloc(n ? n : 1, sizeof *icol);
    size_t mlen = 1, llen = 1;
    for (size_t m = 0; m < r->nmethods; m++)
        mlen += strlen(r->methods[m]) + 1;
    for (size_t k = 0; k < n; k++)
        llen += strlen(r->rows[k].label) + 1;
    char *ms = calloc(mlen, 1), *ls = calloc(llen, 1);
    if (!col || !icol || !ms || !ls) {
        free(col);
        free(icol);
        free(ms);
        free(ls);
        bf_out_close(o, NULL);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t m = 0; m < r->nmethods; m++) {
        strcat(ms, r->methods[m]);
        if (m + 1 < r->nmethods)
            strcat(ms, ",");
    }
    for (size_t k = 0; k < n; k++) {
        strcat(ls, r->rows[k].label);
        if (k + 1 < n)
            strcat(ls, "\n");
    }
#define COL(path_, expr_, unit_, doc_)                                        \
    do {                                                                      \
        for (size_t k_ = 0; k_ < n; k_++) {                                   \
            const bf_converge_row *w = &r->rows[k_];                          \
            (void)w;                                                          \
            col[k_] = (expr_);                                                \
        }                                                                     \
        if (!st)                                                              \
            st = bf_out_array(o, path_, col, n, 0, unit_, doc_, err);         \
    } while (0)
#define ICOL(path_, expr_, doc_)                                              \
    do {                                                                      \
        for (size_t k_ = 0; k_ < n; k_++) {                                   \
            const bf_converge_row *w = &r->rows[k_];                          \
            icol[k_] = (int64_t)(expr_);                                      \
        }                                                                     \
        if (!st)                                                              \
            st = bf_out_array_i64(o, path_, icol, n, 0, "1", doc_, err);      \
    } while (0)
    ICOL("/converge/method", w->method,
         "index of the method in the root attribute 'methods'");
    ICOL("/converge/order", w->order, "nominal order");
    ICOL("/converge/adaptive", w->adaptive, "1 for adaptive methods");
    ICOL("/converge/status", w->status, "0 ok, else the bf_status that "
                                        "stopped the run");
    ICOL("/converge/steps", w->count.steps, "accepted steps");
    ICOL("/converge/evals", w->count.evals, "force evaluations");
    ICOL("/converge/rejected", w->count.rejected, "rejected steps");
    ICOL("/converge/iterations", w->count.iterations, "inner iterations");
    COL("/converge/dt", w->dt, "s",
        "step (fixed-step methods) or mean internal step T/steps");
    COL("/converge/tol", w->tol, "1", "rtol of adaptive methods, else 0");
    COL("/converge/err_x", w->err_x, "cm",
        "max over balls of |x - x_ref| at T (NaN: run failed)");
    COL("/converge/err_v", w->err_v, "cm/s",
        "max over balls of |v - v_ref| at T");
    COL("/converge/energy_error", w->energy_err, "1",
        "max relative energy error over the run");
    COL("/converge/order_x", w->order_x, "1",
        "observed order of err_x against the previous run of the method");
    COL("/converge/order_v", w->order_v, "1", "the same for err_v");
    COL("/converge/wall", w->wall, "s",
        "wall time of the stepping loop, minimum over the repeats");
#undef COL
#undef ICOL
    if (!st)
        st = bf_out_array(o, "/reference/x", r->x_ref, r->n, 0, "cm",
                          "reference positions at T", err);
    if (!st)
        st = bf_out_array(o, "/reference/v", r->v_ref, r->n, 0, "cm/s",
                          "reference velocities at T", err);
    if (!st)
        st = bf_out_attr_str(o, "/", "scene_file", r->scene, err);
    if (!st)
        st = bf_out_attr_real(o, "/", "t_end", r->t_end, err);
    if (!st)
        st = bf_out_attr_str(o, "/", "methods", ms, err);
    if (!st)
        st = bf_out_attr_str(o, "/converge", "labels", ls, err);
    if (!st)
        st = bf_out_attr_str(o, "/reference", "method", r->ref_label, err);
    if (!st)
        st = bf_out_attr_real(o, "/reference", "rtol", r->ref_rtol, err);
    if (!st)
        st = bf_out_attr_real(o, "/reference", "estimated_error_x",
                              r->ref_err_x, err);
    if (!st)
        st = bf_out_attr_real(o, "/reference", "estimated_error_v",
                              r->ref_err_v, err);
    if (!st)
        st = bf_out_attr_int(o, "/reference", "evals",
                             (int64_t)r->ref_count.evals, err);
    if (!st)
        st = bf_out_attr_real(o, "/reference", "energy_error",
                              r->ref_energy_err, err);
    if (!st)
        st = bf_out_attr_real(o, "/", "max_step", r->max_step, err);
    free(col);
    free(icol);
    free(ms);
    free(ls);
    bf_status cst = bf_out_close(o, st ? NULL : err);
    return st ? st : cst;
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
