/* converge_out.c: the table of a convergence study (converge.h), printed
 * and written as HDF5 (docs/output.md, "converge"). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "compose/converge_impl.h"

static void fmt_order(char *buf, size_t cap, double p)
{
    if (isnan(p))
        snprintf(buf, cap, "%7s", "-");
    else
        snprintf(buf, cap, "%7.2f", p);
}

void bf_converge_print(const bf_converge_result *r, FILE *f)
{
    const size_t G = r->ngroups;
    fprintf(f, "convergence study of %s (model %s) to T = %g s, compared at "
               "%ld output rows\n",
            r->scene, r->model, r->t_end, r->out_rows);
    const int K = r->priv->S->self_reference;
    char how[160];
    if (K > 0) {
        const double dt0 = bf_scene_real(r->priv->base, "scene", "dt");
        snprintf(how, sizeof how, "SELF-CONVERGENCE: the method itself at "
                 "dt %g and %g", dt0 / K, dt0 / (2 * K));
    } else {
        snprintf(how, sizeof how, "run at rtol %g and %g", r->ref_rtol * 10,
                 r->ref_rtol);
    }
    fprintf(f, "reference: %s (%s), %llu steps, %llu evaluations, %.3g s;\n"
               "  its estimated error at T (difference of the two):",
            r->ref_label, how, r->ref_count.steps, r->ref_count.evals,
            r->ref_wall);
    for (size_t g = 0; g < G; g++)
        fprintf(f, "%s %s %.2e %s", g ? "," : "", r->groups[g].name,
                r->ref_err[g], r->groups[g].unit);
    fprintf(f, ";\n  over the rows at most:");
    for (size_t g = 0; g < G; g++)
        fprintf(f, "%s %s %.2e %s", g ? "," : "", r->groups[g].name,
                r->ref_err_max[g], r->groups[g].unit);
    fprintf(f, "\n");
    if (!isnan(r->ref_invariant_err))
        fprintf(f, "  its max relative %s error: %.2e\n", r->invariant,
                r->ref_invariant_err);
    if (r->max_step > 0)
        fprintf(f, "adaptive runs and the reference: largest internal step "
                   "%g s\n",
                r->max_step);
    int lw = 6;
    for (size_t k = 0; k < r->nrows; k++)
        if ((int)strlen(r->rows[k].label) > lw)
            lw = (int)strlen(r->rows[k].label);
    fprintf(f, "\n%-*s %3s %10s %9s %11s", lw, "method", "ord", "dt [s]",
            "tol", "evals");
    for (size_t g = 0; g < G; g++) {
        char h[48];
        snprintf(h, sizeof h, "err %s", r->groups[g].name);
        fprintf(f, " %10s", h);
    }
    for (size_t g = 0; g < G; g++) {
        char h[48];
        snprintf(h, sizeof h, "p_%s", r->groups[g].name);
        fprintf(f, " %7.7s", h);
    }
    fprintf(f, " %10s %10s %10s %10s\n", "max rows", "rms rows", "max dI/I",
            "wall [s]");
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        char tol[16];
        if (w->adaptive)
            snprintf(tol, sizeof tol, "%9.1e", w->tol);
        else
            snprintf(tol, sizeof tol, "%9s", "-");
        fprintf(f, "%-*s %3d %10.4g %s %11llu", lw, w->label, w->order, w->dt,
                tol, w->count.evals);
        if (w->status) {
            fprintf(f, "  %s: %s\n", bf_status_name(w->status), w->msg);
            continue;
        }
        for (size_t g = 0; g < G; g++)
            fprintf(f, " %10.3e", w->err[g]);
        for (size_t g = 0; g < G; g++) {
            char p[16];
            fmt_order(p, sizeof p, w->order_obs[g]);
            fprintf(f, " %s", p);
        }
        fprintf(f, " %10.3e %10.3e %10.3e %10.4f\n", w->err_max[0],
                w->err_rms[0], w->invariant_err, w->wall);
    }
    /* errors at the reference's own level make orders meaningless */
    int near_ref = 0;
    for (size_t k = 0; k < r->nrows; k++)
        if (!r->rows[k].status && r->rows[k].err[0] < 10 * r->ref_err[0])
            near_ref = 1;
    if (near_ref)
        fprintf(f, "\nnote: some errors are within 10x of the reference's "
                   "estimated error; their orders are not meaningful.\n");
    if (r->notes[0])
        fprintf(f, "\n%s", r->notes);
    fprintf(f, "\ndt: step of fixed-step methods, mean internal step T/steps "
               "of adaptive ones; err: max |y - y_ref| over the group's "
               "values at T; p: observed orders between successive runs; "
               "max rows, rms rows: the error of %s over the output rows; "
               "dI/I: %s%s; wall: stepping loop, minimum over the "
               "repeats.\n",
            G ? r->groups[0].name : "-",
            strcmp(r->invariant, "none") ? "relative change of the "
                                         : "none, the model has no invariant",
            strcmp(r->invariant, "none") ? r->invariant : "");
}

/* names joined with a separator (malloc'd) */
static char *joined(char *const *names, size_t n, size_t stride,
                    const char *sep)
{
    size_t len = 1;
    for (size_t k = 0; k < n; k++)
        len += strlen(*(char *const *)((const char *)names + k * stride)) +
               strlen(sep);
    char *s = calloc(len, 1);
    for (size_t k = 0; s && k < n; k++) {
        strcat(s, *(char *const *)((const char *)names + k * stride));
        if (k + 1 < n)
            strcat(s, sep);
    }
    return s;
}

bf_status bf_converge_write(const bf_converge_result *r, const char *path,
                            bf_err *err)
{
    bf_out *o;
    bf_status st = bf_out_create(&o, path, err);
    if (st)
        return st;
    const size_t n = r->nrows, G = r->ngroups ? r->ngroups : 1;
    double *col = calloc(n * G + G, sizeof *col);
    int64_t *icol = calloc(n ? n : 1, sizeof *icol);
    char **labels = calloc(n ? n : 1, sizeof *labels);
    char *gnames[BF_CONVERGE_MAX_GROUPS], *gunits[BF_CONVERGE_MAX_GROUPS];
    for (size_t g = 0; g < r->ngroups; g++) {
        gnames[g] = (char *)r->groups[g].name;
        gunits[g] = (char *)r->groups[g].unit;
    }
    for (size_t k = 0; labels && k < n; k++)
        labels[k] = (char *)r->rows[k].label;
    char *ms = joined(r->methods, r->nmethods, sizeof(char *), ",");
    char *ls = labels ? joined(labels, n, sizeof(char *), "\n") : NULL;
    char *gs = joined(gnames, r->ngroups, sizeof(char *), ",");
    char *us = joined(gunits, r->ngroups, sizeof(char *), ",");
    if (!col || !icol || !ms || !ls || !gs || !us) {
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
        goto done;
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
#define GCOL(path_, member_, doc_)                                            \
    do {                                                                      \
        for (size_t k_ = 0; k_ < n; k_++)                                     \
            for (size_t g_ = 0; g_ < r->ngroups; g_++)                        \
                col[k_ * r->ngroups + g_] = r->rows[k_].member_[g_];          \
        if (!st)                                                              \
            st = bf_out_array(o, path_, col, n, r->ngroups,                   \
                              "the groups' units", doc_, err);                \
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
    ICOL("/converge/order", w->order, "nominal order (0: unknown)");
    ICOL("/converge/adaptive", w->adaptive, "1 for adaptive methods");
    ICOL("/converge/status", w->status, "0 ok, else the bf_status that "
                                        "stopped the run");
    ICOL("/converge/steps", w->count.steps, "accepted steps");
    ICOL("/converge/evals", w->count.evals, "right-hand-side evaluations");
    ICOL("/converge/rejected", w->count.rejected, "rejected steps");
    ICOL("/converge/iterations", w->count.iterations, "inner iterations");
    COL("/converge/dt", w->dt, "s",
        "step (fixed-step methods) or mean internal step T/steps");
    COL("/converge/tol", w->tol, "1", "rtol of adaptive methods, else 0");
    GCOL("/converge/error", err,
         "[run x group] max |y - y_ref| over the group's values at T (NaN: "
         "the run failed); groups and units in the attributes of /converge");
    GCOL("/converge/error_max", err_max,
         "[run x group] the same, largest over the output rows");
    GCOL("/converge/error_rms", err_rms,
         "[run x group] the same, root mean square over the output rows");
    GCOL("/converge/observed_order", order_obs,
         "[run x group] log(e1/e2)/log(h1/h2) of the error at T against the "
         "previous run of the method (NaN for its first)");
    COL("/converge/invariant_error", w->invariant_err, "1",
        "largest relative change of the energy or the conserved totals "
        "(attribute 'invariant'; NaN: none)");
    COL("/converge/wall", w->wall, "s",
        "wall time of the stepping loop, minimum over the repeats");
#undef COL
#undef GCOL
#undef ICOL
    if (!st)
        st = bf_out_array(o, "/reference/state", r->ref_state, r->nstate, 0,
                          "the groups' units",
                          "the reference's state at T, group after group",
                          err);
    for (size_t g = 0; !st && g < r->ngroups; g++)
        col[g] = r->ref_err[g];
    if (!st)
        st = bf_out_array(o, "/reference/estimated_error", col, r->ngroups, 0,
                          "the groups' units",
                          "difference of the two reference runs at T, per "
                          "group", err);
    for (size_t g = 0; !st && g < r->ngroups; g++)
        col[g] = r->ref_err_max[g];
    if (!st)
        st = bf_out_array(o, "/reference/estimated_error_max", col,
                          r->ngroups, 0, "the groups' units",
                          "the same, largest over the output rows", err);
    /* the attributes: texts, then numbers */
    const struct {
        const char *obj, *name, *value;
    } texts[] = {
        {"/", "scene_file", r->scene},
        {"/", "model", r->model},
        {"/", "methods", ms},
        {"/", "notes", r->notes},
        {"/converge", "labels", ls},
        {"/converge", "groups", gs},
        {"/converge", "units", us},
        {"/converge", "invariant", r->invariant},
        {"/reference", "method", r->ref_label},
    };
    const struct {
        const char *obj, *name;
        double value;
    } reals[] = {
        {"/", "t_end", r->t_end},
        {"/", "max_step", r->max_step},
        {"/reference", "rtol", r->ref_rtol},
        {"/reference", "invariant_error", r->ref_invariant_err},
    };
    for (size_t k = 0; !st && k < sizeof texts / sizeof texts[0]; k++)
        st = bf_out_attr_str(o, texts[k].obj, texts[k].name, texts[k].value,
                             err);
    for (size_t k = 0; !st && k < sizeof reals / sizeof reals[0]; k++)
        st = bf_out_attr_real(o, reals[k].obj, reals[k].name, reals[k].value,
                              err);
    if (!st)
        st = bf_out_attr_int(o, "/", "output_rows", r->out_rows, err);
    if (!st)
        st = bf_out_attr_int(o, "/reference", "evals",
                             (int64_t)r->ref_count.evals, err);
done:
    free(col);
    free(icol);
    free(labels);
    free(ms);
    free(ls);
    free(gs);
    free(us);
    bf_status cst = bf_out_close(o, st ? NULL : err);
    return st ? st : cst;
}
