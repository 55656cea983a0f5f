/* fuzz_h5.c: hostile HDF5 files for the readers (see fuzz_h5.h). */
#define _DEFAULT_SOURCE /* setrlimit's RLIMIT_* with -std=c11 */
#include "fuzz_h5.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *s = NULL;
    size_t n = 0, cap = 0;
    int c;
    while ((c = fgetc(f)) != EOF) {
        if (n + 2 > cap) {
            char *t = realloc(s, cap = cap ? 2 * cap : 4096);
            if (!t)
                break;
            s = t;
        }
        s[n++] = (char)c;
    }
    fclose(f);
    if (s)
        s[n] = '\0';
    return s ? s : calloc(1, 1);
}

/* A child blocked without using CPU (a lock, a pipe, a sleep) escapes
 * RLIMIT_CPU: the wall-clock limit is a few times the CPU limit, since
 * the machine may be shared. */
static double wall_limit(int cpu) { return 4.0 * cpu + 10.0; }

/* waitpid with a wall-clock limit of `seconds`: 0 with *status, or -1
 * after the child was killed (SIGKILL) for exceeding it. */
static int wait_bounded(pid_t pid, double seconds, int *status)
{
    struct timespec nap = {0, 1000000}; /* 1 ms, doubling up to 16 ms */
    double waited = 0;
    for (;;) {
        pid_t r = waitpid(pid, status, WNOHANG);
        if (r == pid)
            return 0;
        if (r < 0 && errno != EINTR)
            return -1;
        if (waited > seconds) {
            kill(pid, SIGKILL);
            while (waitpid(pid, status, 0) < 0 && errno == EINTR)
                ;
            return -1;
        }
        nanosleep(&nap, NULL);
        waited += nap.tv_nsec * 1e-9;
        if (nap.tv_nsec < 16000000)
            nap.tv_nsec *= 2;
    }
}

int fh5_exec(const char *const *argv, int cpu, long long fsize,
             int pending_term, char **errout)
{
    const char *bin = getenv("BALLFILM_BIN");
    char errpath[] = "/tmp/fuzz_h5_err_XXXXXX";
    int efd = mkstemp(errpath);
    if (!bin || efd < 0)
        return -1000;
    pid_t pid = fork();
    if (pid == 0) {
        struct rlimit c = {(rlim_t)cpu, (rlim_t)cpu},
                      f = {(rlim_t)fsize, (rlim_t)fsize};
        setrlimit(RLIMIT_CPU, &c);
        setrlimit(RLIMIT_FSIZE, &f);
        int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        dup2(efd, 2);
        size_t n = 0;
        while (argv[n])
            n++;
        const char **av = calloc(n + 2, sizeof *av);
        av[0] = bin;
        memcpy(av + 1, argv, n * sizeof *av);
        if (pending_term) {
            sigset_t set;
            sigemptyset(&set);
            sigaddset(&set, SIGTERM);
            sigprocmask(SIG_BLOCK, &set, NULL);
            raise(SIGTERM);
        }
        execv(bin, (char *const *)av);
        _exit(127);
    }
    int status = 0;
    const int late = pid > 0 && wait_bounded(pid, wall_limit(cpu), &status);
    close(efd);
    if (errout)
        *errout = slurp(errpath);
    unlink(errpath);
    if (pid < 0)
        return -1000;
    if (late)
        return -SIGKILL;
    return WIFSIGNALED(status) ? -WTERMSIG(status) : WEXITSTATUS(status);
}

/* ------------------------------------------------------------ corpus */

static int run_ok(const char *const *argv, int want)
{
    char *err = NULL;
    int rc = fh5_exec(argv, 120, 1LL << 30, 0, &err);
    if (rc != want)
        fprintf(stderr, "fuzz_h5: corpus: %s %s exited %d: %s\n", argv[0],
                argv[1], rc, err ? err : "");
    free(err);
    return rc == want ? 0 : -1;
}

int fh5_make_corpus(const char *dir, const char *name)
{
    const char *root = getenv("BALLFILM_ROOT");
    static const char *const runs[][3] = {
        /* name, scene, a shortened t_end */
        {"balls", "runs/harmonic.ini", "scene.t_end=1"},
        {"film", "runs/kink_steady.ini", "scene.t_end=2"},
        {"mac", "runs/mac_rest.ini", "scene.t_end=0.05"},
        {"coupled", "runs/coupled_fig8.ini", "scene.t_end=0.01"},
        {"g72", "runs/greenspan72_ex1.ini", "scene.t_end=0.01"},
        {"g73", "runs/greenspan73_hex_v50.ini", "scene.t_end=0.1"},
    };
    char scene[4096], out[4096];
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        if (strcmp(name, runs[k][0]))
            continue;
        snprintf(scene, sizeof scene, "%s/%s", root ? root : ".", runs[k][1]);
        snprintf(out, sizeof out, "%s/%s.h5", dir, runs[k][0]);
        if (!access(out, F_OK))
            return 0;
        const char *argv[] = {"run", scene, "-q", "-o", out, "--set",
                              runs[k][2], NULL};
        return run_ok(argv, 0);
    }
    if (strcmp(name, "part") && strcmp(name, "ckpt"))
        return -1;
    snprintf(scene, sizeof scene, "%s/runs/harmonic.ini", root ? root : ".");
    snprintf(out, sizeof out, "%s/part.h5.part", dir);
    if (!access(out, F_OK))
        return 0;
    snprintf(out, sizeof out, "%s/part.h5", dir);
    const char *argv[] = {"run", scene, "-q", "-o", out, "--stop-after",
                          "20", NULL};
    return run_ok(argv, 6);
}

/* --------------------------------------------------------- mutations */

static double number(const char *s)
{
    if (!strcmp(s, "nan"))
        return NAN;
    if (!strcmp(s, "inf"))
        return INFINITY;
    return strtod(s, NULL);
}

static hsize_t count(const char *s) { return strtoull(s, NULL, 10); }

/* Replace attribute `name` of object `obj` by one of type t and space sp,
 * with the data `buf` (NULL: not written). */
static int put_attr(hid_t f, const char *obj, const char *name, hid_t t,
                    hid_t sp, const void *buf)
{
    if (H5Aexists_by_name(f, obj, name, H5P_DEFAULT) > 0 &&
        H5Adelete_by_name(f, obj, name, H5P_DEFAULT) < 0)
        return -1;
    hid_t a = H5Acreate_by_name(f, obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT);
    int rc = a < 0 || (buf && H5Awrite(a, t, buf) < 0) ? -1 : 0;
    if (a >= 0)
        H5Aclose(a);
    return rc;
}

static int attr_array(hid_t f, const char *obj, const char *name, hsize_t n)
{
    double *v = malloc(n * sizeof *v);
    for (hsize_t k = 0; v && k < n; k++)
        v[k] = (double)k;
    hid_t sp = H5Screate_simple(1, &n, NULL);
    int rc = !v ? -1 : put_attr(f, obj, name, H5T_NATIVE_DOUBLE, sp, v);
    H5Sclose(sp);
    free(v);
    return rc;
}

static int attr_strarray(hid_t f, const char *obj, const char *name,
                         hsize_t n)
{
    const char **v = malloc(n * sizeof *v);
    for (hsize_t k = 0; v && k < n; k++)
        v[k] = "ok";
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    int rc = !v ? -1 : put_attr(f, obj, name, t, sp, v);
    H5Sclose(sp);
    H5Tclose(t);
    free(v);
    return rc;
}

static int attr_int(hid_t f, const char *obj, const char *name, int64_t v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = put_attr(f, obj, name, H5T_NATIVE_INT64, sp, &v);
    H5Sclose(sp);
    return rc;
}

static int attr_double(hid_t f, const char *obj, const char *name, double v)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = put_attr(f, obj, name, H5T_NATIVE_DOUBLE, sp, &v);
    H5Sclose(sp);
    return rc;
}

/* A variable-length string of `bytes` letters, written (not a claim). */
static int attr_longstr(hid_t f, const char *obj, const char *name,
                        size_t bytes)
{
    char *v = malloc(bytes + 1);
    if (!v)
        return -1;
    memset(v, 'x', bytes);
    v[bytes] = '\0';
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    hid_t sp = H5Screate(H5S_SCALAR);
    const char *p = v;
    int rc = put_attr(f, obj, name, t, sp, &p);
    H5Sclose(sp);
    H5Tclose(t);
    free(v);
    return rc;
}

static int attr_bigstr(hid_t f, const char *obj, const char *name,
                       size_t bytes)
{
    /* a fixed-length string whose data HDF5 keeps in dense attribute
     * storage: written unset, its size is the claim */
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, bytes);
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = put_attr(f, obj, name, t, sp, NULL);
    H5Sclose(sp);
    H5Tclose(t);
    return rc;
}

/* Replace dataset `path` by one of type t, rank r and dims, chunked and
 * never written (HDF5 reads it as its fill value). */
static int dset_claim(hid_t f, const char *path, hid_t t, int r,
                      const hsize_t *dims)
{
    if (H5Lexists(f, path, H5P_DEFAULT) > 0 &&
        H5Ldelete(f, path, H5P_DEFAULT) < 0)
        return -1;
    hsize_t maxd[3] = {H5S_UNLIMITED, H5S_UNLIMITED, H5S_UNLIMITED},
            chunk[3] = {1, 1, 1};
    for (int k = 0; k < r; k++)
        chunk[k] = dims[k] < 64 ? (dims[k] ? dims[k] : 1) : 64;
    hid_t sp = H5Screate_simple(r, dims, maxd);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, r, chunk);
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t d = H5Dcreate2(f, path, t, sp, lcpl, dcpl, H5P_DEFAULT);
    H5Pclose(lcpl);
    H5Pclose(dcpl);
    H5Sclose(sp);
    if (d < 0)
        return -1;
    H5Dclose(d);
    return 0;
}

static int dset_set(hid_t f, const char *path, hsize_t at, double v)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0)
        return -1;
    hid_t sp = H5Dget_space(d);
    hsize_t one = 1;
    hid_t msp = H5Screate_simple(1, &one, NULL);
    int rc = H5Sselect_elements(sp, H5S_SELECT_SET, 1, &at) < 0 ||
                     H5Dwrite(d, H5T_NATIVE_DOUBLE, msp, sp, H5P_DEFAULT,
                              &v) < 0
                 ? -1
                 : 0;
    H5Sclose(msp);
    H5Sclose(sp);
    H5Dclose(d);
    return rc;
}

/* Change the extent of an existing chunked dataset (a series longer or
 * shorter than its neighbours, or than its rows are): dims[k] of 0 keeps
 * that dimension, except the first. */
static int dset_resize(hid_t f, const char *path, hsize_t d0, hsize_t d1)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0)
        return -1;
    hid_t sp = H5Dget_space(d);
    hsize_t dims[H5S_MAX_RANK];
    int r = H5Sget_simple_extent_dims(sp, dims, NULL);
    H5Sclose(sp);
    int rc = -1;
    if (r >= 1) {
        dims[0] = d0;
        if (r >= 2 && d1)
            dims[1] = d1;
        rc = H5Dset_extent(d, dims) < 0 ? -1 : 0;
    }
    H5Dclose(d);
    return rc;
}

/* A flush log (h5part.h) of one row {1, rows}, for /time. */
static int log_rows(hid_t f, int64_t rows)
{
    hsize_t dims[2] = {1, 2};
    if (dset_claim(f, "/flushed_rows", H5T_STD_I64LE, 2, dims))
        return -1;
    hid_t d = H5Dopen2(f, "/flushed_rows", H5P_DEFAULT);
    int64_t row[2] = {1, rows};
    int rc = H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                      row) < 0;
    const char *series = "/time";
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(d, "series", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    rc |= a < 0 || H5Awrite(a, t, &series) < 0;
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return rc ? -1 : 0;
}

static int log_claim(hid_t f, hsize_t rows, hsize_t width)
{
    hsize_t dims[2] = {rows, width};
    if (dset_claim(f, "/flushed_rows", H5T_STD_I64LE, 2, dims))
        return -1;
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = put_attr(f, "/flushed_rows", "series", H5T_C_S1, sp, "/");
    H5Sclose(sp);
    return rc;
}

/* The number of arguments of the mutation op[0]: the words up to the
 * end or to the separator of the next mutation. */
static int nargs(const char *const *op)
{
    int n = 0;
    while (op[n] && strcmp(op[n], FH5_AND))
        n++;
    return n - 1;
}

/* Words that name a size for attr_array and the like are bounded, so that
 * a recipe cannot make the mutator itself allocate without limit. */
static hsize_t bounded(const char *s, hsize_t most)
{
    hsize_t n = count(s);
    return n < most ? n : most;
}

static int mutate_one(hid_t f, const char *const *op)
{
    const char *o = op[0];
    if (!o)
        return -1;
    const int n = nargs(op);
    int rc = -1;
    if (!strcmp(o, "attr_array") && n == 3)
        rc = attr_array(f, op[1], op[2], bounded(op[3], 1u << 24));
    else if (!strcmp(o, "attr_strarray") && n == 3)
        rc = attr_strarray(f, op[1], op[2], bounded(op[3], 1u << 24));
    else if (!strcmp(o, "attr_int") && (n == 2 || n == 3))
        rc = attr_int(f, op[1], op[2],
                      n == 3 ? strtoll(op[3], NULL, 10) : 42);
    else if (!strcmp(o, "attr_double") && n == 3)
        rc = attr_double(f, op[1], op[2], number(op[3]));
    else if (!strcmp(o, "attr_longstr") && n == 3)
        rc = attr_longstr(f, op[1], op[2], (size_t)bounded(op[3], 1u << 26));
    else if (!strcmp(o, "attr_delete") && n == 2)
        rc = H5Adelete_by_name(f, op[1], op[2], H5P_DEFAULT) < 0 ? -1 : 0;
    else if (!strcmp(o, "attr_bigstr") && n == 3)
        rc = attr_bigstr(f, op[1], op[2], (size_t)bounded(op[3], 1u << 30));
    else if (!strcmp(o, "dset_claim") && n == 3) {
        hsize_t dims[2] = {count(op[2]), count(op[3])};
        rc = dset_claim(f, op[1], H5T_IEEE_F64LE, dims[1] ? 2 : 1, dims);
    } else if (!strcmp(o, "dset_rank3") && n == 1) {
        hsize_t dims[3] = {2, 2, 2};
        rc = dset_claim(f, op[1], H5T_IEEE_F64LE, 3, dims);
    } else if (!strcmp(o, "dset_string") && n == 1) {
        hsize_t dims[1] = {4};
        hid_t t = H5Tcopy(H5T_C_S1);
        H5Tset_size(t, H5T_VARIABLE);
        rc = dset_claim(f, op[1], t, 1, dims);
        H5Tclose(t);
    } else if (!strcmp(o, "dset_set") && n == 3)
        rc = dset_set(f, op[1], count(op[2]), number(op[3]));
    else if (!strcmp(o, "log_claim") && n == 2)
        rc = log_claim(f, count(op[1]), count(op[2]));
    else if (!strcmp(o, "log_rows") && n == 1)
        rc = log_rows(f, strtoll(op[1], NULL, 10));
    else if (!strcmp(o, "dset_resize") && n == 3)
        rc = dset_resize(f, op[1], count(op[2]), count(op[3]));
    else if (!strcmp(o, "delete") && n == 1)
        rc = H5Ldelete(f, op[1], H5P_DEFAULT) < 0 ? -1 : 0;
    return rc;
}

int fh5_mutate(const char *file, const char *const *op)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t f = H5Fopen(file, H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0 || !op[0])
        return -1;
    int rc = 0;
    /* one mutation, or several joined by FH5_AND, applied in turn */
    for (const char *const *w = op; !rc; w++) {
        rc = mutate_one(f, w);
        while (*w && strcmp(*w, FH5_AND))
            w++;
        if (!*w)
            break;
    }
    if (H5Fclose(f) < 0)
        rc = -1;
    return rc;
}

/* ------------------------------------------------------------ a case */

static int copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    char buf[65536];
    size_t n;
    int rc = in && out ? 0 : -1;
    while (!rc && (n = fread(buf, 1, sizeof buf, in)) > 0)
        rc = fwrite(buf, 1, n, out) == n ? 0 : -1;
    if (in)
        fclose(in);
    if (out && fclose(out))
        rc = -1;
    return rc;
}

int fh5_run(const char *corpus_dir, const char *work, const char *corpus,
            const char *command, const char *const *op, char **errout,
            const char **target)
{
    static char file[4096];
    char from[4096], to[4096], other[4096];
    const int part = !strcmp(corpus, "part") || !strcmp(corpus, "ckpt");
    *errout = NULL;
    if (fh5_make_corpus(corpus_dir, corpus))
        return -1001;
    if (part) {
        /* the stopped run: its .part and its checkpoint, beside each other */
        snprintf(from, sizeof from, "%s/part.h5.part", corpus_dir);
        snprintf(to, sizeof to, "%s/part.h5.part", work);
        snprintf(other, sizeof other, "%s/part.h5.ckpt", work);
        char ck[4096];
        snprintf(ck, sizeof ck, "%s/part.h5.ckpt", corpus_dir);
        unlink(other);
        if (copy_file(from, to) || copy_file(ck, other))
            return -1001;
        snprintf(file, sizeof file, "%s", !strcmp(corpus, "ckpt") ? other
                                                                   : to);
    } else {
        snprintf(from, sizeof from, "%s/%s.h5", corpus_dir, corpus);
        snprintf(file, sizeof file, "%s/%s.h5", work, corpus);
        if (copy_file(from, file))
            return -1001;
    }
    *target = file;
    if (op && op[0] && fh5_mutate(file, op))
        return -1002;
    const int cpu = getenv("BALLFILM_SANITIZED") ? 20 : 5;
    const long long fsize = 64LL << 20;
    char xmf[4096], out[4096], scene[8192], fileset[4200];
    if (!strcmp(command, "info")) {
        const char *argv[] = {"info", part ? to : file, NULL};
        return fh5_exec(argv, cpu, fsize, 0, errout);
    }
    if (!strcmp(command, "xdmf")) {
        snprintf(xmf, sizeof xmf, "%s/out.xmf", work);
        const char *argv[] = {"xdmf", part ? to : file, "-o", xmf, "--all",
                              NULL};
        return fh5_exec(argv, cpu, fsize, 0, errout);
    }
    if (!strcmp(command, "restart")) {
        snprintf(out, sizeof out, "%s/part.h5", work);
        const char *argv[] = {"run", "--restart", out, "-q", NULL};
        return fh5_exec(argv, cpu, fsize, 0, errout);
    }
    if (!strcmp(command, "initial")) {
        const char *root = getenv("BALLFILM_ROOT");
        snprintf(scene, sizeof scene, "%s/runs/kink_steady.ini",
                 root ? root : ".");
        snprintf(out, sizeof out, "%s/initial.h5", work);
        snprintf(fileset, sizeof fileset, "film.file=%s", file);
        const char *argv[] = {"run", scene, "-q", "-o", out, "--set",
                              "scene.t_end=0.01", "--set",
                              "film.initial=file", "--set", fileset, NULL};
        return fh5_exec(argv, cpu, fsize, 0, errout);
    }
    return -1003;
}

/* ------------------------------------------------------------ verdict */

const char *fh5_verdict(int rc, const char *err, const char *target)
{
    static char why[128];
    if (rc <= -1000)
        return NULL;
    if (rc < 0) {
        snprintf(why, sizeof why, "killed by signal %d (%s)", -rc,
                 -rc == SIGXCPU   ? "CPU limit"
                 : -rc == SIGXFSZ ? "file-size limit"
                 : -rc == SIGKILL ? "wall-clock limit"
                                  : strsignal(-rc));
        return why;
    }
    if (rc > 6) {
        snprintf(why, sizeof why, "exit %d outside the documented set", rc);
        return why;
    }
    /* ASan and UBSan report, then exit 1 unless told otherwise */
    if (err && (strstr(err, "Sanitizer") || strstr(err, "runtime error:")))
        return "a sanitizer report";
    /* a refusal (bad input, I/O, or the program's own failure) names the
     * file; for the files of a stopped run (OUT.part, OUT.ckpt) any of
     * them: what is wrong may show only when they are compared */
    const char *base = strrchr(target, '/');
    char name[4096];
    snprintf(name, sizeof name, "%s", base ? base + 1 : target);
    const size_t n = strlen(name);
    if (n > 5 && (!strcmp(name + n - 5, ".part") ||
                  !strcmp(name + n - 5, ".ckpt")))
        name[n - 5] = '\0';
    if ((rc == 1 || rc == 2 || rc == 5) && !(err && strstr(err, name)))
        return "a refusal that does not name the file";
    return NULL;
}
