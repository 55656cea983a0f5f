/* testutil.c: see testutil.h. */
#include "testutil.h"

#include <ctype.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <hdf5.h>

#include "ballfilm/h5out.h"
#include "ballfilm/run.h"

static char tmpdir[256];

static void rm_tmpdir(void)
{
    if (tmpdir[0]) {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
        if (system(cmd)) {
        }
    }
}

const char *tu_tmpdir(void)
{
    if (!tmpdir[0]) {
        snprintf(tmpdir, sizeof tmpdir, "/tmp/ballfilm-test-XXXXXX");
        if (!mkdtemp(tmpdir))
            ck_abort_msg("mkdtemp failed");
        atexit(rm_tmpdir);
    }
    return tmpdir;
}

const char *tu_tmp(const char *name)
{
    static char buf[8][512];
    static int k;
    char *b = buf[k++ % 8];
    snprintf(b, 512, "%s/%s", tu_tmpdir(), name);
    return b;
}

const char *tu_write(const char *name, const char *text)
{
    const char *p = tu_tmp(name);
    FILE *f = fopen(p, "w");
    ck_assert_msg(f != NULL, "cannot write %s", p);
    fputs(text, f);
    fclose(f);
    return p;
}

const char *tu_repo(const char *rel)
{
    static char buf[8][512];
    static int k;
    char *b = buf[k++ % 8];
    const char *root = getenv("BALLFILM_ROOT");
    snprintf(b, 512, "%s/%s", root ? root : ".", rel);
    return b;
}

static char *slurp_fd(int fd)
{
    size_t cap = 4096, n = 0;
    char *s = malloc(cap);
    ssize_t r;
    while ((r = read(fd, s + n, cap - n - 1)) > 0) {
        n += (size_t)r;
        if (n + 1 == cap) {
            cap *= 2;
            s = realloc(s, cap);
        }
    }
    s[n] = '\0';
    return s;
}

static long long run_limit_as; /* RLIMIT_AS of the runs (0: none) */

void tu_run_limit_as(long long bytes) { run_limit_as = bytes; }

int tu_runv(char **out, char **errout, const char *const *argv)
{
    const char *bin = getenv("BALLFILM_BIN");
    if (!bin)
        bin = "bin/ballfilm";
    char ofile[600], efile[600];
    static int seq;
    snprintf(ofile, sizeof ofile, "%s/run%d.out", tu_tmpdir(), seq);
    snprintf(efile, sizeof efile, "%s/run%d.err", tu_tmpdir(), seq++);
    pid_t pid = fork();
    ck_assert_msg(pid >= 0, "fork failed");
    if (pid == 0) {
        int fo = open(ofile, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int fe = open(efile, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fo, 1);
        dup2(fe, 2);
        if (run_limit_as > 0) {
            struct rlimit rl = {(rlim_t)run_limit_as, (rlim_t)run_limit_as};
            setrlimit(RLIMIT_AS, &rl);
        }
        size_t n = 0;
        while (argv[n])
            n++;
        char **a = calloc(n + 2, sizeof *a);
        a[0] = (char *)bin;
        for (size_t k = 0; k < n; k++)
            a[k + 1] = (char *)argv[k];
        execv(bin, a);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    int fo = open(ofile, O_RDONLY), fe = open(efile, O_RDONLY);
    char *o = slurp_fd(fo), *e = slurp_fd(fe);
    close(fo);
    close(fe);
    if (out)
        *out = o;
    else
        free(o);
    if (errout)
        *errout = e;
    else
        free(e);
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return -WTERMSIG(status);
}

int tu_run(char **out, char **errout, const char *arg0, ...)
{
    const char *argv[64];
    size_t n = 0;
    va_list ap;
    va_start(ap, arg0);
    for (const char *a = arg0; a && n < 63; a = va_arg(ap, const char *))
        argv[n++] = a;
    va_end(ap);
    argv[n] = NULL;
    return tu_runv(out, errout, argv);
}

bf_scene *tu_scene(const char *text)
{
    bf_scene *sc;
    bf_err err = {0};
    bf_status st = bf_scene_load_string(&sc, "test.ini", text, &err);
    ck_assert_msg(st == BF_OK, "scene: %s", err.msg);
    st = bf_catalog_resolve(bf_catalog_builtin(), sc, &err);
    ck_assert_msg(st == BF_OK, "scene: %s", err.msg);
    return sc;
}

bf_status tu_scene_error(const char *text, char *msg, size_t cap)
{
    bf_scene *sc;
    bf_err err = {0};
    bf_status st = bf_scene_load_string(&sc, "test.ini", text, &err);
    if (!st) {
        st = bf_catalog_resolve(bf_catalog_builtin(), sc, &err);
        if (!st) {
            bf_sim *sim;
            st = bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err);
            if (!st)
                bf_sim_free(sim);
        }
        bf_scene_free(sc);
    }
    snprintf(msg, cap, "%s", st ? err.msg : "");
    return st;
}

/* The sim keeps a pointer to its scene; keep scenes alive with the sims. */
typedef struct keep {
    bf_sim *sim;
    bf_scene *sc;
    struct keep *next;
} keep;
static keep *kept;

static void free_kept(void)
{
    while (kept) {
        keep *k = kept;
        kept = k->next;
        bf_sim_free(k->sim);
        bf_scene_free(k->sc);
        free(k);
    }
}

bf_sim *tu_run_scene(const char *text, ...)
{
    bf_scene *sc;
    bf_err err = {0};
    bf_status st = bf_scene_load_string(&sc, "test.ini", text, &err);
    ck_assert_msg(st == BF_OK, "scene: %s", err.msg);
    va_list ap;
    va_start(ap, text);
    for (const char *a = va_arg(ap, const char *); a;
         a = va_arg(ap, const char *)) {
        st = bf_scene_set(sc, a, "--set", &err);
        ck_assert_msg(st == BF_OK, "%s", err.msg);
    }
    va_end(ap);
    st = bf_catalog_resolve(bf_catalog_builtin(), sc, &err);
    ck_assert_msg(st == BF_OK, "scene: %s", err.msg);
    bf_sim *sim;
    st = bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err);
    ck_assert_msg(st == BF_OK, "create: %s", err.msg);
    st = bf_sim_run(sim, &err);
    ck_assert_msg(st == BF_OK, "run: %s", err.msg);
    keep *k = malloc(sizeof *k);
    k->sim = NULL; /* the caller frees the sim; we keep the scene */
    k->sc = sc;
    k->next = kept;
    if (!kept)
        atexit(free_kept);
    kept = k;
    return sim;
}

double tu_max(const double *v, size_t n)
{
    double m = -INFINITY;
    for (size_t k = 0; k < n; k++)
        if (v[k] > m)
            m = v[k];
    return m;
}

double tu_absmax(const double *v, size_t n)
{
    double m = 0;
    for (size_t k = 0; k < n; k++)
        if (fabs(v[k]) > m)
            m = fabs(v[k]);
    return m;
}

TCase *tu_tcase(const char *name)
{
    TCase *tc = tcase_create(name);
    tcase_set_timeout(tc, 600);
    return tc;
}

typedef struct dlist {
    char **v;
    size_t n, cap;
} dlist;

static herr_t visit_ds(hid_t obj, const char *name, const H5O_info_t *info,
                       void *op)
{
    (void)obj;
    dlist *l = op;
    if (info->type != H5O_TYPE_DATASET)
        return 0;
    if (l->n + 2 > l->cap) {
        l->cap = l->cap ? 2 * l->cap : 16;
        l->v = realloc(l->v, l->cap * sizeof *l->v);
    }
    size_t len = strlen(name) + 2;
    l->v[l->n] = malloc(len);
    snprintf(l->v[l->n], len, "/%s", name);
    l->n++;
    l->v[l->n] = NULL;
    return 0;
}

char **tu_h5_datasets(const char *file)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert_msg(f >= 0, "cannot open %s", file);
    dlist l = {0};
    l.cap = 16;
    l.v = calloc(l.cap, sizeof *l.v);
    H5Ovisit(f, H5_INDEX_NAME, H5_ITER_INC, visit_ds, &l);
    H5Fclose(f);
    return l.v;
}

void tu_free_list(char **list)
{
    for (char **p = list; p && *p; p++)
        free(*p);
    free(list);
}

void tu_wait_for_file(const char *path, long bytes)
{
    struct stat sb;
    const struct timespec ms = {0, 1000000};
    for (int k = 0; k < 60000; k++) {
        if (!stat(path, &sb) && sb.st_size > bytes)
            return;
        nanosleep(&ms, NULL);
    }
    ck_abort_msg("%s never appeared", path);
}

const char *tu_result(const char *path)
{
    static char buf[8][1100];
    static int next;
    char *r = buf[next++ % 8];
    struct stat sb;
    snprintf(r, sizeof buf[0], "%s", path);
    if (stat(path, &sb)) {
        snprintf(r, sizeof buf[0], "%s.part", path);
        if (stat(r, &sb))
            snprintf(r, sizeof buf[0], "%s", path);
    }
    return r;
}

void tu_same_datasets(const char *a_in, const char *b_in)
{
    const char *a = tu_result(a_in), *b = tu_result(b_in);
    char **la = tu_h5_datasets(a), **lb = tu_h5_datasets(b);
    size_t na = 0, nb = 0;
    while (la[na])
        na++;
    while (lb[nb])
        nb++;
    ck_assert_msg(na == nb && na > 0, "%s has %zu datasets, %s has %zu", a, na,
                  b, nb);
    bf_err err = {0};
    for (size_t k = 0; k < na; k++) {
        ck_assert_str_eq(la[k], lb[k]);
        double *da, *db;
        size_t a0, a1, b0, b1;
        ck_assert_msg(bf_h5_read(a, la[k], &da, &a0, &a1, &err) == BF_OK, "%s",
                      err.msg);
        ck_assert_msg(bf_h5_read(b, lb[k], &db, &b0, &b1, &err) == BF_OK, "%s",
                      err.msg);
        ck_assert_msg(a0 == b0 && a1 == b1, "%s: shape %zux%zu vs %zux%zu",
                      la[k], a0, a1, b0, b1);
        size_t n = a0 * (a1 ? a1 : 1);
        ck_assert_msg(!memcmp(da, db, n * sizeof *da), "%s differs: %s vs %s",
                      la[k], a, b);
        free(da);
        free(db);
    }
    tu_free_list(la);
    tu_free_list(lb);
}

int tu_accel_harmonic(void *ctx, double t, const double *x, const double *v,
                      double *a)
{
    (void)ctx;
    (void)t;
    (void)v;
    a[0] = -x[0];
    return 0;
}

bf_ballsys *tu_ballsys(const char *text)
{
    bf_scene *sc = tu_scene(text);
    bf_ballsys *sys;
    bf_err err = {0};
    ck_assert_msg(bf_ballsys_from_scene(&sys, bf_catalog_builtin(), sc, &err) ==
                      BF_OK,
                  "%s", err.msg);
    bf_scene_free(sc); /* the system copies what it needs */
    return sys;
}

bf_integrator *tu_integrator(const char *name, const char *keys, size_t n)
{
    char text[1024];
    int len = snprintf(text, sizeof text,
                       "[scene]\nintegrator = %s\ndt = 1\nt_end = 1\n", name);
    if (keys) {
        len += snprintf(text + len, sizeof text - (size_t)len, "[integrator]\n");
        for (const char *p = keys; *p;) {
            const char *e = strchr(p, ';');
            size_t l = e ? (size_t)(e - p) : strlen(p);
            len += snprintf(text + len, sizeof text - (size_t)len, "%.*s\n",
                            (int)l, p);
            p += l + (e ? 1 : 0);
        }
    }
    snprintf(text + len, sizeof text - (size_t)len, "[ball.1]\nposition = 1\n");
    bf_scene *sc = tu_scene(text);
    bf_integrator *it;
    bf_err err = {0};
    bf_setup *setup;
    bf_run_ctx run = {1, 1, 1, 1, 0};
    ck_assert(bf_setup_create(&setup, bf_catalog_builtin(), sc, &run, &err) ==
              BF_OK);
    const bf_model_setup *ms = bf_setup_model(setup);
    ck_assert_msg(bf_integrator_create(&it, ms->integrator, n,
                                       ms->integrator_params, &err) == BF_OK,
                  "%s", err.msg);
    bf_setup_free(setup);
    bf_scene_free(sc);
    return it;
}

void tu_same_counters(const char *a, const char *b)
{
    static const char *const counters[] = {
        "steps_done", "force_evaluations", "rejected_steps", "iterations",
        "max_relative_energy_error"};
    for (size_t k = 0; k < sizeof counters / sizeof *counters; k++) {
        double va = 0, vb = 0;
        bf_err e = {0};
        int has_a = bf_h5_read_attr_real(tu_result(a), "/", counters[k], &va,
                                         &e) == BF_OK;
        int has_b = bf_h5_read_attr_real(tu_result(b), "/", counters[k], &vb,
                                         &e) == BF_OK;
        ck_assert_msg(has_a == has_b &&
                          (!has_a || va == vb || (va != va && vb != vb)),
                      "%s %s %.17g, %s %.17g", counters[k], a, va, b, vb);
    }
}

void tu_stop_restart_same(const char *scene, const char *full,
                          const char *part, const char *stop,
                          const char *const *args)
{
    const char *argv[32] = {"run", scene, "-o", part, "-q"};
    size_t n = 5;
    for (; *args && n < 5 + 16; args++)
        argv[n++] = *args;
    argv[n++] = "--stop-after";
    argv[n++] = stop;
    argv[n] = NULL;
    char *err = NULL;
    int rc = tu_runv(NULL, &err, argv);
    ck_assert_msg(rc == 6, "%s stopped at %s: exit %d\n%s", scene, stop, rc,
                  err ? err : "");
    free(err);
    const char *again[] = {"run", "--restart", part, "-q", NULL};
    rc = tu_runv(NULL, &err, again);
    ck_assert_msg(rc == 0, "restart of %s: exit %d\n%s", part, rc,
                  err ? err : "");
    free(err);
    tu_same_datasets(full, part);
    tu_same_counters(full, part);
}

int tu_part_unlocked(int fd)
{
    struct flock lk = {.l_type = F_WRLCK, .l_whence = SEEK_SET};
#ifdef F_OFD_GETLK
    if (fcntl(fd, F_OFD_GETLK, &lk))
        return 0;
#else
    if (fcntl(fd, F_GETLK, &lk))
        return 0;
#endif
    return lk.l_type == F_UNLCK;
}

/* ---- golden lines ---- */

/* Does a number start at p (not inside a word such as "x2")? */
static int number_at(const char *line, const char *p)
{
    if (p > line && (isalnum((unsigned char)p[-1]) || p[-1] == '_' ||
                     p[-1] == '.'))
        return 0;
    const char *q = p;
    if (*q == '-' || *q == '+')
        q++;
    if (*q == '.')
        q++;
    return isdigit((unsigned char)*q);
}

/* The line with every number replaced by '#' (into key), and the numbers
 * (at most max). */
static size_t ref_split(const char *line, char *key, size_t cap,
                        double *num, size_t max)
{
    size_t nk = 0, nn = 0;
    for (const char *p = line; *p && nk + 1 < cap;) {
        if (number_at(line, p)) {
            char *end;
            double v = strtod(p, &end);
            if (end > p) {
                if (nn < max)
                    num[nn] = v;
                nn++;
                key[nk++] = '#';
                p = end;
                continue;
            }
        }
        key[nk++] = *p++;
    }
    key[nk] = '\0';
    return nn;
}

void tu_ref(const char *name, const char *fmt, ...)
{
    char line[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    line[strcspn(line, "\n")] = '\0';
    fprintf(stderr, "%s\n", line);

    char path[256];
    snprintf(path, sizeof path, "tests/ref/%.200s.ref", name);
    const char *file = tu_repo(path);
    FILE *f = fopen(file, "r");
    ck_assert_msg(f, "%s: cannot open the reference file", file);
    enum { MAXN = 64 };
    char key[1024], rkey[1024], buf[1024];
    double num[MAXN], rnum[MAXN];
    const size_t n = ref_split(line, key, sizeof key, num, MAXN);
    ck_assert_msg(n <= MAXN, "too many numbers in '%s'", line);
    double rtol = -1, atol = -1;
    int found = 0;
    while (!found && fgets(buf, sizeof buf, f)) {
        buf[strcspn(buf, "\n")] = '\0';
        if (buf[0] == '#') {
            const char *t = strstr(buf, "tolerance:");
            if (t && sscanf(t, "tolerance: rtol=%lf atol=%lf", &rtol, &atol) !=
                         2)
                ck_abort_msg("%s: bad tolerance line '%s'", file, buf);
            continue;
        }
        if (ref_split(buf, rkey, sizeof rkey, rnum, MAXN) != n ||
            strcmp(key, rkey))
            continue;
        found = 1;
        ck_assert_msg(rtol >= 0 && atol >= 0,
                      "%s: no '# tolerance: rtol=R atol=A' line before the "
                      "lines", file);
        for (size_t k = 0; k < n; k++) {
            const double d = fabs(num[k] - rnum[k]);
            ck_assert_msg(d <= rtol * fmax(fabs(num[k]), fabs(rnum[k])) + atol,
                          "%s: number %zu differs beyond rtol=%g atol=%g:\n"
                          "  got      %s\n  expected %s",
                          file, k + 1, rtol, atol, line, buf);
        }
    }
    fclose(f);
    if (found)
        return;
    const char *update = getenv("BALLFILM_REF_UPDATE");
    if (update && !strcmp(update, "1")) {
        char newpath[600];
        snprintf(newpath, sizeof newpath, "%s.new", file);
        FILE *o = fopen(newpath, "a");
        ck_assert_msg(o, "%s: cannot write", newpath);
        fprintf(o, "%s\n", line);
        fclose(o);
        return;
    }
    ck_abort_msg("%s has no line like\n  %s\n(run with BALLFILM_REF_UPDATE=1 "
                 "to collect the new lines in %s.new)", file, line, file);
}

size_t tu_wait_for_rows(const char *path, const char *dset, size_t rows)
{
    /* The reads are made in a child process: a read in the middle of a
     * flush fails inside HDF5, whose error path can leak a little (112 B
     * in two blocks were seen under LeakSanitizer), and the child ends
     * with _exit, so that only this process's own allocations are checked
     * for leaks. */
    int fd[2];
    ck_assert(pipe(fd) == 0);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        close(fd[0]);
        const struct timespec ms = {0, 1000000};
        size_t seen = 0;
        int ok = 0;
        for (int k = 0; k < 60000 && !ok; k++) {
            double *d;
            size_t n = 0, n1;
            bf_err e = {0};
            if (bf_h5_read(path, dset, &d, &n, &n1, &e) == BF_OK) {
                free(d);
                seen = n;
                ok = seen > rows;
            }
            if (!ok)
                nanosleep(&ms, NULL);
        }
        ssize_t w = write(fd[1], &seen, sizeof seen);
        _exit(ok && w == (ssize_t)sizeof seen ? 0 : 1);
    }
    close(fd[1]);
    size_t seen = 0;
    ssize_t got = read(fd[0], &seen, sizeof seen);
    close(fd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (got != (ssize_t)sizeof seen || !WIFEXITED(status) ||
        WEXITSTATUS(status) != 0)
        ck_abort_msg("%s: %s never had more than %zu rows (%zu seen)", path,
                     dset, rows, seen);
    return seen;
}

bf_film *tu_film(double L, double dx, double (*h_of)(double),
                 double (*psi_of)(double))
{
    bf_film_params p = {.length = L, .dx = dx, .rho_d = 1, .rho_c = 1,
                        .nu = 0.01, .g = 980, .a = 1, .b = 1, .gamma = 1,
                        .mu_taylor = BF_FILM_MU_MIDPOINT,
                        .limit_positive = 1, .vanish = 1e-8};
    bf_film *f;
    bf_err err = {0};
    ck_assert_msg(bf_film_create(&f, &p, &err) == BF_OK, "%s", err.msg);
    size_t n = bf_film_nodes(f);
    double *h = malloc(n * sizeof *h), *psi = malloc(n * sizeof *psi),
           *z = calloc(n, sizeof *z);
    ck_assert(h && psi && z);
    for (size_t i = 0; i < n; i++) {
        h[i] = h_of(bf_film_x(f)[i]);
        psi[i] = psi_of(bf_film_x(f)[i]);
    }
    ck_assert_msg(bf_film_set_state(f, h, psi, z, z, &err) == BF_OK, "%s",
                  err.msg);
    free(h);
    free(psi);
    free(z);
    return f;
}
