/* sweep.c: cases, their runs and the summary of a parameter sweep (see
 * sweep.h).  Nothing here knows about processes or MPI: the front end
 * decides who runs which case. */
#include "base/clock.h"
#include "base/hash.h"
#include "base/xalloc.h"
#include "ballfilm/sweep.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "ballfilm/sim.h"
#include "ballfilm/run.h"
#include "io/outpath.h"

bf_status bf_sweep_parse_axis(bf_sweep_axis *ax, const char *spec, bf_err *err)
{
    memset(ax, 0, sizeof *ax);
    const char *eq = strchr(spec, '=');
    if (!eq || eq == spec || (size_t)(eq - spec) >= sizeof ax->key)
        return bf_fail(err, BF_EINPUT, "--vary '%s': expected "
                       "section.key=START:STOP:COUNT or section.key=v1,v2,...",
                       spec);
    memcpy(ax->key, spec, (size_t)(eq - spec));
    ax->key[eq - spec] = '\0';
    if (!strchr(ax->key, '.'))
        return bf_fail(err, BF_EINPUT, "--vary '%s': the key must be "
                       "section.key", spec);
    const char *v = eq + 1;
    double a, b;
    long count;
    char tail;
    if (strchr(v, ':')) {
        char *buf = strdup(v), *c1 = strchr(buf, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        int ok = c1 && c2;
        if (ok) {
            *c1 = *c2 = '\0';
            ok = bf_parse_real(buf, &a) && bf_parse_real(c1 + 1, &b) &&
                 bf_parse_long(c2 + 1, &count) && count >= 1 && count <= 1000000;
        }
        free(buf);
        (void)tail;
        if (!ok)
            return bf_fail(err, BF_EINPUT, "--vary '%s': expected "
                           "START:STOP:COUNT with COUNT >= 1", spec);
        ax->n = (size_t)count;
        ax->values = malloc(ax->n * sizeof *ax->values);
        if (!ax->values)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        for (size_t k = 0; k < ax->n; k++)
            ax->values[k] = ax->n == 1 ? a
                                       : a + (b - a) * (double)k /
                                                 (double)(ax->n - 1);
        if (ax->n > 1)
            ax->values[ax->n - 1] = b; /* the end exactly as given */
        return BF_OK;
    }
    /* list */
    size_t cap = 8;
    ax->values = malloc(cap * sizeof *ax->values);
    char *buf = strdup(v);
    if (!ax->values || !buf) {
        free(buf);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        if (ax->n == cap) {
            cap *= 2;
            double *nv = realloc(ax->values, cap * sizeof *nv);
            if (!nv) {
                free(buf);
                return bf_fail(err, BF_EINTERNAL, "out of memory");
            }
            ax->values = nv;
        }
        if (!bf_parse_real(tok, &ax->values[ax->n])) {
            /* the message before the free: tok points into buf */
            bf_status st = bf_fail(err, BF_EINPUT,
                                   "--vary '%s': '%s' is not a number", spec,
                                   tok);
            free(buf);
            return st;
        }
        ax->n++;
    }
    free(buf);
    if (!ax->n)
        return bf_fail(err, BF_EINPUT, "--vary '%s': no values", spec);
    return BF_OK;
}

void bf_sweep_free(bf_sweep *sw)
{
    for (size_t k = 0; k < sw->naxis; k++)
        free(sw->axis[k].values);
    bf_scene_free(sw->base);
    memset(sw, 0, sizeof *sw);
}

static void case_path(const bf_sweep *sw, long k, const char *ext, char *buf,
                      size_t cap)
{
    snprintf(buf, cap, "%s/case_%05ld.%s", sw->dir, k, ext);
}

/* The manifest ties a directory to one sweep definition: the scene, its
 * hash, the overrides and every value of every axis (as many as given:
 * a sweep of 10^4 cases along one axis is 10^4 values). */
static bf_status check_manifest(const bf_sweep *sw, const char *const *sets,
                                size_t nsets, bf_err *err)
{
    char path[1200];
    const char *text = bf_scene_text(sw->base);
    unsigned long long h = bf_hash64(BF_HASH_INIT, text, strlen(text));
    /* written into memory first: it is compared with, or becomes, the
     * file */
    char *want = NULL;
    size_t want_len = 0;
    FILE *m = open_memstream(&want, &want_len);
    if (!m)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    fprintf(m, "scene %s\nscene_hash %016llx\n", sw->scene_path, h);
    for (size_t k = 0; k < nsets; k++)
        fprintf(m, "set %s\n", sets[k]);
    for (size_t a = 0; a < sw->naxis; a++) {
        fprintf(m, "vary %s", sw->axis[a].key);
        for (size_t k = 0; k < sw->axis[a].n; k++)
            fprintf(m, " %.17g", sw->axis[a].values[k]);
        fprintf(m, "\n");
    }
    const int failed = ferror(m);
    if (fclose(m) || failed) {
        free(want);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    snprintf(path, sizeof path, "%s/sweep.txt", sw->dir);
    FILE *f = fopen(path, "r");
    if (f) {
        size_t n;
        int too_long;
        char *have = bf_xread_all(f, (size_t)1 << 30, &n, &too_long);
        fclose(f);
        const int same = have && n == want_len && !memcmp(have, want, n);
        free(want);
        if (!have)
            return bf_fail(err, BF_EIO, "%s: cannot read it (%s)", path,
                           too_long ? "larger than 1 GiB" : "a read error");
        free(have);
        if (!same)
            return bf_fail(err, BF_EINPUT, "%s holds a different sweep (see "
                           "%s: another scene, scene contents, overrides or "
                           "values); use another -o directory",
                           sw->dir, path);
        return BF_OK;
    }
    f = bf_path_fopen_own(path, err);
    if (!f) {
        free(want);
        return BF_EIO;
    }
    const int bad = fwrite(want, 1, want_len, f) != want_len;
    free(want);
    if (bad) {
        fclose(f);
        return bf_fail(err, BF_EIO, "%s: cannot write (%s)", path,
                       strerror(errno));
    }
    if (fclose(f))
        return bf_fail(err, BF_EIO, "%s: cannot write", path);
    return BF_OK;
}

bf_status bf_sweep_init(bf_sweep *sw, const char *scene_path,
                        const char *const *sets, size_t nsets,
                        const char *const *vary, size_t nvary, const char *dir,
                        bf_err *err)
{
    memset(sw, 0, sizeof *sw);
    snprintf(sw->scene_path, sizeof sw->scene_path, "%s", scene_path);
    snprintf(sw->dir, sizeof sw->dir, "%s", dir);
    if (nvary == 0)
        return bf_fail(err, BF_EINPUT, "a sweep needs at least one --vary");
    if (nvary > BF_SWEEP_MAX_VARY)
        return bf_fail(err, BF_EINPUT, "at most %d --vary options",
                       BF_SWEEP_MAX_VARY);
    bf_status st;
    sw->ncases = 1;
    for (size_t k = 0; k < nvary; k++) {
        if ((st = bf_sweep_parse_axis(&sw->axis[k], vary[k], err))) {
            sw->naxis = k + 1;
            bf_sweep_free(sw);
            return st;
        }
        sw->naxis = k + 1;
        sw->ncases *= sw->axis[k].n;
        if (sw->ncases > 10000000) {
            bf_sweep_free(sw);
            return bf_fail(err, BF_EINPUT, "more than 10^7 cases");
        }
    }
    if ((st = bf_scene_load(&sw->base, scene_path, err))) {
        bf_sweep_free(sw);
        return st;
    }
    for (size_t k = 0; k < nsets; k++)
        if ((st = bf_scene_set(sw->base, sets[k], "--set", err))) {
            bf_sweep_free(sw);
            return st;
        }
    /* The scene must be valid as given, and every varied key must exist in
     * it: a typo fails the sweep at once instead of every case.  Values are
     * checked per case (a case with a meaningless value fails alone). */
    bf_scene *probe = bf_scene_clone(sw->base);
    st = bf_catalog_resolve(bf_catalog_builtin(), probe, err);
    for (size_t a = 0; !st && a < sw->naxis; a++) {
        char sec[256];
        snprintf(sec, sizeof sec, "%s", sw->axis[a].key);
        char *dot = strrchr(sec, '.');
        *dot = '\0';
        if (!bf_scene_has_key(probe, sec, dot + 1))
            st = bf_fail(err, BF_EINPUT, "--vary %s: the scene has no key %s "
                         "in section [%s]", sw->axis[a].key, dot + 1, sec);
    }
    bf_scene_free(probe);
    if (st) {
        bf_sweep_free(sw);
        return st;
    }
    if (mkdir(dir, 0777) && errno != EEXIST) {
        bf_sweep_free(sw);
        return bf_fail(err, BF_EIO, "%s: cannot create directory (%s)", dir,
                       strerror(errno));
    }
    /* an existing DIR holds the sweep's records and results, which the
     * sweep writes over: it must be a directory of this user, not a link
     * someone planted at its name in a shared directory (outpath.h) */
    struct stat sb = {0};
    if (lstat(dir, &sb) || !S_ISDIR(sb.st_mode) || sb.st_uid != geteuid()) {
        bf_sweep_free(sw);
        return bf_fail(err, BF_EIO, "%s: not a directory of this user (%s); "
                       "a sweep writes only into its own directory", dir,
                       S_ISLNK(sb.st_mode) ? "a symbolic link"
                                           : "another user's, or not a "
                                             "directory");
    }
    if ((st = check_manifest(sw, sets, nsets, err))) {
        bf_sweep_free(sw);
        return st;
    }
    return BF_OK;
}

void bf_sweep_case_values(const bf_sweep *sw, long k, double *values)
{
    size_t rest = (size_t)k;
    for (size_t a = sw->naxis; a-- > 0;) {
        values[a] = sw->axis[a].values[rest % sw->axis[a].n];
        rest /= sw->axis[a].n;
    }
}

double bf_sweep_map_fill(const double *z, const double *v, size_t n)
{
    if (n < 2)
        return NAN;
    double z0 = z[0], z1 = z[0], v0 = v[0], v1 = v[0];
    for (size_t k = 1; k < n; k++) {
        z0 = fmin(z0, z[k]);
        z1 = fmax(z1, z[k]);
        v0 = fmin(v0, v[k]);
        v1 = fmax(v1, v[k]);
    }
    long B = (long)floor(sqrt((double)n / 4.0));
    B = B < 5 ? 5 : B > BF_SWEEP_FILL_BINS ? BF_SWEEP_FILL_BINS : B;
    unsigned char seen[BF_SWEEP_FILL_BINS * BF_SWEEP_FILL_BINS];
    memset(seen, 0, sizeof seen);
    double dz = z1 > z0 ? (z1 - z0) / B : 1.0, dv = v1 > v0 ? (v1 - v0) / B : 1.0;
    size_t count = 0;
    for (size_t k = 0; k < n; k++) {
        long i = (long)((z[k] - z0) / dz), j = (long)((v[k] - v0) / dv);
        i = i < 0 ? 0 : i >= B ? B - 1 : i;
        j = j < 0 ? 0 : j >= B ? B - 1 : j;
        if (!seen[i * B + j]) {
            seen[i * B + j] = 1;
            count++;
        }
    }
    return (double)count / (double)(B * B);
}

/* ------------------------------------------------------------------ rows */

void bf_sweep_row_format(const bf_sweep *sw, const bf_sweep_row *r, char *buf,
                         size_t cap)
{
    size_t used = (size_t)snprintf(buf, cap, "%ld", r->index);
    for (size_t a = 0; a < sw->naxis && used < cap; a++)
        used += (size_t)snprintf(buf + used, cap - used, ",%.17g", r->values[a]);
    if (used < cap)
        used += (size_t)snprintf(buf + used, cap - used,
                                 ",%d,%.6g,%.17g,%.17g,%.17g,%.17g,%ld,\"",
                                 r->status, r->wall, r->lyapunov,
                                 r->map_points, r->map_fill, r->energy_error,
                                 r->steps);
    /* the message without quotes or newlines */
    for (const char *p = r->message; *p && used + 2 < cap; p++)
        buf[used++] = (*p == '"' || *p == '\n' || *p == '\r') ? '\'' : *p;
    if (used + 2 <= cap) {
        buf[used++] = '"';
        buf[used] = '\0';
    } else if (cap) {
        buf[cap - 1] = '\0';
    }
}

int bf_sweep_row_parse(const bf_sweep *sw, const char *line, bf_sweep_row *r)
{
    memset(r, 0, sizeof *r);
    char *end;
    r->index = strtol(line, &end, 10);
    if (end == line || *end != ',')
        return 0;
    const char *p = end + 1;
    for (size_t a = 0; a < sw->naxis; a++) {
        r->values[a] = strtod(p, &end);
        if (end == p || *end != ',')
            return 0;
        p = end + 1;
    }
    r->status = (int)strtol(p, &end, 10);
    if (*end != ',')
        return 0;
    p = end + 1;
    double *d[] = {&r->wall, &r->lyapunov, &r->map_points, &r->map_fill,
                   &r->energy_error};
    for (int q = 0; q < 5; q++) {
        *d[q] = strtod(p, &end);
        if (end == p || *end != ',')
            return 0;
        p = end + 1;
    }
    r->steps = strtol(p, &end, 10);
    if (*end != ',' || end[1] != '"')
        return 0;
    p = end + 2;
    const char *q = strrchr(p, '"');
    if (!q)
        return 0;
    size_t len = (size_t)(q - p);
    if (len >= sizeof r->message)
        len = sizeof r->message - 1;
    memcpy(r->message, p, len);
    r->message[len] = '\0';
    return 1;
}

int bf_sweep_case_done(const bf_sweep *sw, long k, bf_sweep_row *row)
{
    char path[1200], line[4096];
    case_path(sw, k, "done", path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    int ok = fgets(line, sizeof line, f) != NULL;
    fclose(f);
    if (!ok)
        return 0;
    line[strcspn(line, "\n")] = '\0';
    return bf_sweep_row_parse(sw, line, row) && row->index == k;
}

int bf_sweep_case_pending(const bf_sweep *sw, long k, bf_sweep_retry retry,
                          bf_sweep_row *row)
{
    if (!bf_sweep_case_done(sw, k, row)) {
        row->index = -1;
        return 1;
    }
    if (row->status == BF_OK)
        return 0;
    return retry == BF_SWEEP_RETRY_FAILED || row->status == BF_EIO;
}

static bf_status write_done(const bf_sweep *sw, const bf_sweep_row *row,
                            bf_err *err)
{
    char path[1200], tmp[1300], line[4096];
    case_path(sw, row->index, "done", path, sizeof path);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    bf_sweep_row_format(sw, row, line, sizeof line);
    FILE *f = bf_path_fopen_own(tmp, err);
    if (!f)
        return BF_EIO;
    int bad = fprintf(f, "%s\n", line) < 0;
    bad |= fflush(f) != 0;
    bad |= fsync(fileno(f)) != 0;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path))
        return bf_fail(err, BF_EIO, "%s: cannot write the case summary", path);
    return BF_OK;
}

/* The result columns of a case from its run's analyses (bf_results):
 * the Lyapunov exponent, the number of return-map points and the
 * fraction of the map's box they visit (NaN: not measured). */
static void take_results(const bf_sim *sim, bf_sweep_row *row)
{
    bf_results r;
    bf_sim_results(sim, &r);
    if (r.has_lyapunov)
        row->lyapunov = r.lyapunov_exponent;
    if (r.has_return_map) {
        row->map_points = (double)r.map_points;
        if (r.map_z && r.map_v)
            row->map_fill = bf_sweep_map_fill(r.map_z, r.map_v, r.map_points);
    }
}

bf_status bf_sweep_run_case(const bf_sweep *sw, long k, bf_sweep_row *row,
                            bf_err *err)
{
    memset(row, 0, sizeof *row);
    row->index = k;
    row->lyapunov = row->map_points = row->energy_error = row->map_fill = NAN;
    bf_sweep_case_values(sw, k, row->values);
    double t0 = bf_wall_time();
    char out[1200];
    case_path(sw, k, "h5", out, sizeof out);
    bf_err cerr = {0};
    bf_scene *sc = bf_scene_clone(sw->base);
    bf_sim *sim = NULL;
    bf_status st = sc ? BF_OK : bf_fail(&cerr, BF_EINTERNAL, "out of memory");
    for (size_t a = 0; !st && a < sw->naxis; a++) {
        char set[512];
        snprintf(set, sizeof set, "%s=%.17g", sw->axis[a].key, row->values[a]);
        st = bf_scene_set(sc, set, "--vary", &cerr);
    }
    if (!st)
        st = bf_catalog_resolve(bf_catalog_builtin(), sc, &cerr);
    /* the map's points in the results (take_results) */
    bf_sim_opts opts = {.stop_flag = sw->stop_flag, .keep_map_points = 1};
    if (!st)
        st = bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, &opts, &cerr);
    if (!st)
        st = bf_sim_open_output(sim, out, &cerr);
    bf_status run_st = st;
    if (!st) {
        run_st = bf_sim_run(sim, &cerr);
        bf_err e2 = {0};
        bf_status cst = bf_sim_close_output(sim, run_st, &cerr, &e2);
        if (!run_st && cst) {
            run_st = cst;
            cerr = e2;
        }
        row->energy_error = bf_sim_max_energy_error(sim);
        row->steps = bf_sim_steps_done(sim);
        /* what the analyses measured, as the case's file records them
         * (a file that did not close holds none) */
        if (!cst)
            take_results(sim, row);
    }
    row->status = (int)run_st;
    /* a long message is cut to the row's size on purpose */
    if (snprintf(row->message, sizeof row->message, "%s",
                 run_st ? cerr.msg : "") < 0)
        row->message[0] = '\0';
    row->wall = bf_wall_time() - t0;
    bf_sim_free(sim);
    bf_scene_free(sc);
    if (run_st == BF_INTERRUPTED)
        return bf_fail(err, BF_INTERRUPTED, "case %ld interrupted (no summary "
                       "row: a rerun of the sweep runs it again)", k);
    return write_done(sw, row, err);
}

/* --------------------------------------------------------------- summary */

/* The units of the swept keys, as the resolved scene records them. */
typedef struct axis_units {
    const bf_sweep *sw;
    char unit[BF_SWEEP_MAX_VARY][32];
} axis_units;

static int note_axis_unit(void *ctx, const char *name, const char *value,
                          const char *unit, int is_default)
{
    (void)value;
    (void)is_default;
    axis_units *u = ctx;
    for (size_t a = 0; a < u->sw->naxis; a++)
        if (!strcmp(name, u->sw->axis[a].key))
            snprintf(u->unit[a], sizeof u->unit[a], "%s", unit ? unit : "");
    return 0;
}

/* The unit of /params and its column_units ("cm; g"): the one unit of a
 * one-key sweep, or "1" with a unit per column when the keys differ, as
 * every dataset whose columns differ in unit (series.h). */
static void params_units(const bf_sweep *sw, char *unit, size_t ucap,
                         char *cols, size_t ccap)
{
    axis_units u = {.sw = sw};
    bf_scene *probe = bf_scene_clone(sw->base);
    bf_err ignore = {0};
    if (probe && !bf_catalog_resolve(bf_catalog_builtin(), probe, &ignore))
        bf_scene_visit(probe, note_axis_unit, &u);
    bf_scene_free(probe);
    int same = 1;
    cols[0] = '\0';
    for (size_t a = 0; a < sw->naxis; a++) {
        if (!u.unit[a][0])
            snprintf(u.unit[a], sizeof u.unit[a], "1");
        same &= !strcmp(u.unit[a], u.unit[0]);
        size_t used = strlen(cols);
        snprintf(cols + used, ccap - used, "%s%s", a ? "; " : "", u.unit[a]);
    }
    snprintf(unit, ucap, "%s", same && sw->naxis ? u.unit[0] : "1");
}

bf_status bf_sweep_write_summary(const bf_sweep *sw, const bf_sweep_row *rows,
                                 bf_err *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/summary.csv", sw->dir);
    FILE *f = bf_path_fopen_own(path, err);
    if (!f)
        return BF_EIO;
    fprintf(f, "case");
    for (size_t a = 0; a < sw->naxis; a++)
        fprintf(f, ",%s", sw->axis[a].key);
    fprintf(f, ",status,wall_s,lyapunov_per_s,return_map_points,"
               "return_map_fill,max_rel_energy_error,steps,message\n");
    char line[4096];
    for (size_t k = 0; k < sw->ncases; k++) {
        bf_sweep_row_format(sw, &rows[k], line, sizeof line);
        fprintf(f, "%s\n", line);
    }
    if (fclose(f))
        return bf_fail(err, BF_EIO, "%s: cannot write", path);

    snprintf(path, sizeof path, "%s/summary.h5", sw->dir);
    bf_out *o;
    bf_status st = bf_out_create(&o, path, err);
    if (st)
        return st;
    size_t n = sw->ncases, na = sw->naxis;
    double *params = malloc(n * na * sizeof *params);
    double *col = malloc(n * sizeof *col);
    int64_t *icol = malloc(n * sizeof *icol);
    if (!params || !col || !icol) {
        free(params);
        free(col);
        free(icol);
        bf_out_close(o, NULL);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t k = 0; k < n; k++)
        for (size_t a = 0; a < na; a++)
            params[k * na + a] = rows[k].values[a];
    char unit[32], col_units[BF_SWEEP_MAX_VARY * 34];
    params_units(sw, unit, sizeof unit, col_units, sizeof col_units);
    st = bf_out_array(o, "/params", params, n, na, unit,
                      "varied parameter values, one column per --vary "
                      "(attribute keys; units in column_units)", err);
    if (!st)
        st = bf_out_attr_str(o, "/params", "column_units", col_units, err);
    char keys[4096] = "";
    for (size_t a = 0; a < na; a++) {
        strncat(keys, sw->axis[a].key, sizeof keys - strlen(keys) - 2);
        if (a + 1 < na)
            strncat(keys, ",", sizeof keys - strlen(keys) - 1);
    }
    if (!st)
        st = bf_out_attr_str(o, "/params", "keys", keys, err);
    if (!st)
        st = bf_out_attr_str(o, "/", "scene_file", sw->scene_path, err);
#define COLUMN(field, name, unit, doc)                                         \
    if (!st) {                                                                 \
        for (size_t k = 0; k < n; k++)                                         \
            col[k] = (double)rows[k].field;                                    \
        st = bf_out_array(o, name, col, n, 0, unit, doc, err);                 \
    }
    COLUMN(wall, "/wall", "s", "wall time of the case")
    COLUMN(lyapunov, "/lyapunov", "s-1", "largest Lyapunov exponent (NaN: "
                                         "not measured)")
    COLUMN(map_points, "/return_map_points", "1", "number of return-map points")
    COLUMN(map_fill, "/return_map_fill", "1",
           "fraction of the return map's bounding box visited (about 4 "
           "points per bin)")
    COLUMN(energy_error, "/energy_error", "1", "max relative energy error")
#undef COLUMN
    if (!st) {
        for (size_t k = 0; k < n; k++)
            icol[k] = rows[k].status;
        st = bf_out_array_i64(o, "/status", icol, n, 0, "1",
                              "exit status of the case (0 ok, 2 input, 3 "
                              "unstable, ...)",
                              err);
    }
    if (!st) {
        for (size_t k = 0; k < n; k++)
            icol[k] = rows[k].steps;
        st = bf_out_array_i64(o, "/steps", icol, n, 0, "1", "steps done", err);
    }
    for (size_t k = 0; !st && k < n; k++) {
        if (rows[k].message[0]) {
            char name[64];
            snprintf(name, sizeof name, "case_%05zu", k);
            st = bf_out_attr_str(o, "/messages", name, rows[k].message, err);
        }
    }
    free(params);
    free(col);
    free(icol);
    bf_status cst = bf_out_close(o, st ? NULL : err);
    return st ? st : cst;
}
