/* cmd_sweep.c: `ballfilm sweep SCENE.ini --vary s.k=A:B:N ... [-o DIR]`.
 *
 * Who runs which case:
 *  - plain build: one case after another, or a pool of --jobs N processes
 *    (fork) that take case numbers from a pipe, so a slow case does not hold
 *    up the others (dynamic load balancing);
 *  - MPI build (bin/ballfilm-mpi, `make mpi`): rank 0 hands out case numbers
 *    on request (dynamic load balancing, cases differ in cost) and runs cases
 *    itself in a second thread, so that every rank computes; each reply to a
 *    request carries the previous case's summary row, which rank 0 gathers
 *    into one table.  Only rank 0's main thread calls MPI.
 * In every mode a case is computed by the same library call
 * (bf_sweep_run_case), so per-case results are bit-identical.
 */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifdef BF_MPI
#include <mpi.h>
#include <pthread.h>
#endif

#include "ballfilm/sweep.h"
#include "cli.h"

static void sweep_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm sweep SCENE.ini --vary section.key=START:STOP:COUNT"
            " [--vary ...]\n"
            "                      [-o DIR] [--set section.key=value]... "
            "[--jobs N] [-q]\n"
            "                      [--retry-failed]\n"
            "\n"
            "  --vary s.k=A:B:N varied key: N values from A to B inclusive, "
            "or s.k=v1,v2,...\n"
            "                   (repeatable, at most %d)\n"
            "  -o, --output DIR directory of the cases and the summary\n"
            "  --set s.k=v      override a scene key for every case "
            "(repeatable)\n"
            "  -j, --jobs N     run N cases at a time (processes)\n"
            "  --retry-failed   run the failed cases of an earlier run "
            "again\n"
            "  -q, --quiet      no line per case\n"
            "\n"
            "Runs SCENE for every combination of the varied keys (COUNT values "
            "from START to\n"
            "STOP inclusive, or a list: section.key=v1,v2,...).  Each case "
            "writes DIR/case_NNNNN.h5;\n"
            "DIR/summary.h5 and DIR/summary.csv gather parameters, status, wall "
            "time, Lyapunov\n"
            "exponent, return-map points and energy error.  Rerunning the same "
            "sweep skips\n"
            "finished cases and runs again those that failed to write (status 5, "
            "I/O: a full\n"
            "disk); --retry-failed runs every failed case again.  --jobs N runs "
            "N cases at a\n"
            "time (processes); with MPI use\n"
            "  mpirun -n N bin/ballfilm-mpi sweep ...\n"
            "(as root: mpirun --allow-run-as-root ...).\n"
            "Default DIR: out/<scene name>_sweep.\n",
            BF_SWEEP_MAX_VARY);
}

typedef struct sweep_args {
    const char *scene, *dir;
    const char *sets[256], *vary[BF_SWEEP_MAX_VARY + 1];
    size_t nsets, nvary;
    long jobs;
    int quiet;
    bf_sweep_retry retry;
    char defdir[1100];
} sweep_args;

static int parse_args(int argc, char **argv, sweep_args *a)
{
    memset(a, 0, sizeof *a);
    a->jobs = 1;
    enum { VARY = BF_CLI_LONG, SET, RETRY };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"output", required_argument, NULL, 'o'},
        {"quiet", no_argument, NULL, 'q'},
        {"jobs", required_argument, NULL, 'j'},
        {"vary", required_argument, NULL, VARY},
        {"set", required_argument, NULL, SET},
        {"retry-failed", no_argument, NULL, RETRY},
        {NULL, 0, NULL, 0},
    };
    const bf_cli_cmd cmd = {"sweep", ":ho:qj:", longopts, sweep_usage};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        char *end;
        switch (c) {
        case BF_CLI_HELP:
            return -1;
        case BF_CLI_BAD:
            return 2;
        case VARY:
            if (a->nvary == BF_SWEEP_MAX_VARY) {
                fprintf(stderr, "ballfilm: error: at most %d --vary\n",
                        BF_SWEEP_MAX_VARY);
                return 2;
            }
            a->vary[a->nvary++] = optarg;
            break;
        case SET:
            if (a->nsets == 256) {
                fprintf(stderr, "ballfilm: error: at most 256 --set\n");
                return 2;
            }
            a->sets[a->nsets++] = optarg;
            break;
        case 'o':
            a->dir = optarg;
            break;
        case 'j':
            a->jobs = strtol(optarg, &end, 10);
            if (!*optarg || *end || a->jobs < 1 || a->jobs > 1024) {
                bf_cli_error(&cmd, "--jobs needs 1..1024");
                return 2;
            }
            break;
        case 'q':
            a->quiet = 1;
            break;
        case RETRY:
            a->retry = BF_SWEEP_RETRY_FAILED;
            break;
        }
    }
    for (int k = optind; k < argc; k++) {
        if (a->scene) {
            fprintf(stderr, "ballfilm: error: more than one scene\n");
            return 2;
        }
        a->scene = argv[k];
    }
    if (!a->scene || !a->nvary) {
        sweep_usage(stderr);
        return 2;
    }
    if (!a->dir) {
        const char *base = strrchr(a->scene, '/');
        base = base ? base + 1 : a->scene;
        size_t len = strlen(base);
        if (len > 4 && !strcmp(base + len - 4, ".ini"))
            len -= 4;
        snprintf(a->defdir, sizeof a->defdir, "out/%.*s_sweep", (int)len, base);
        a->dir = a->defdir;
        if (bf_cli_mkdir_out())
            return 5;
    }
    return 0;
}

/* Report one finished case on stderr (a line per case; cheap and useful
 * on long sweeps). */
static void report_case(const bf_sweep *sw, const bf_sweep_row *r, int quiet,
                        int rank)
{
    if (quiet)
        return;
    fprintf(stderr, "case %5ld", r->index);
    for (size_t a = 0; a < sw->naxis; a++)
        fprintf(stderr, "  %s=%.6g", sw->axis[a].key, r->values[a]);
    fprintf(stderr, "  status %d  %.2f s", r->status, r->wall);
    if (!isnan(r->lyapunov))
        fprintf(stderr, "  lyapunov %.4g/s", r->lyapunov);
    if (!isnan(r->map_fill))
        fprintf(stderr, "  map fill %.3f", r->map_fill);
    if (rank >= 0)
        fprintf(stderr, "  (rank %d)", rank);
    fprintf(stderr, "\n");
}

/* How to run the failed cases again: those that failed to write by
 * rerunning the same command (once there is room), the others with
 * --retry-failed (a rerun alone keeps their rows, since they would fail
 * the same way unless something outside the sweep changed). */
static void report_retry_hints(const bf_sweep *sw, const bf_sweep_row *rows)
{
    size_t io = 0, other = 0;
    for (size_t k = 0; k < sw->ncases; k++) {
        if (rows[k].status == BF_EIO)
            io++;
        else if (rows[k].status != BF_OK)
            other++;
    }
    if (io)
        fprintf(stderr, "ballfilm: %zu case%s failed to write (status 5, "
                        "I/O: a full disk?); run the same command again once "
                        "there is room: it retries %s\n",
                io, io > 1 ? "s" : "", io > 1 ? "them" : "it");
    if (other)
        fprintf(stderr, "ballfilm: %zu case%s failed (status and message in "
                        "%s/summary.csv); a rerun keeps %s row%s, "
                        "--retry-failed runs %s again\n",
                other, other > 1 ? "s" : "", sw->dir,
                other > 1 ? "their" : "its", other > 1 ? "s" : "",
                other > 1 ? "them" : "it");
}

/* The cases a run of the sweep computes, in order, into todo: those
 * without a summary row and those whose row records a failure that
 * `retry` runs again.  Returns how many; *nretried: how many of them
 * failed before. */
static size_t pending_cases(const bf_sweep *sw, bf_sweep_retry retry,
                            long *todo, size_t *nretried)
{
    size_t n = 0;
    *nretried = 0;
    bf_sweep_row row;
    for (size_t k = 0; k < sw->ncases; k++)
        if (bf_sweep_case_pending(sw, (long)k, retry, &row)) {
            todo[n++] = (long)k;
            *nretried += row.index == (long)k;
        }
    return n;
}

/* The first line of a sweep: how many cases, how many left, on what. */
static void report_start(const bf_sweep *sw, size_t ntodo, size_t nretried,
                         bf_sweep_retry retry, long workers,
                         const char *what)
{
    fprintf(stderr, "sweep: %zu cases, %zu already done, %zu to run on %ld "
                    "%s%s",
            sw->ncases, sw->ncases - ntodo, ntodo, workers, what,
            workers > 1 ? (strcmp(what, "process") ? "s" : "es") : "");
    if (nretried)
        fprintf(stderr, " (%zu of them again after a %s)", nretried,
                retry == BF_SWEEP_RETRY_FAILED ? "failure"
                                               : "failure to write");
    fprintf(stderr, "\n");
}

/* Summary rows for every case: read from the .done files; a case without
 * one (a worker died) is recorded as such. */
static int gather_and_write(const bf_sweep *sw, bf_sweep_row *rows)
{
    size_t ok = 0, failed = 0, missing = 0;
    for (size_t k = 0; k < sw->ncases; k++) {
        if (rows[k].index == (long)k && rows[k].message[0] != '\x01')
            ; /* filled by the caller */
        else if (!bf_sweep_case_done(sw, (long)k, &rows[k])) {
            memset(&rows[k], 0, sizeof rows[k]);
            rows[k].index = (long)k;
            bf_sweep_case_values(sw, (long)k, rows[k].values);
            rows[k].status = 1;
            rows[k].lyapunov = rows[k].map_points = rows[k].energy_error =
                rows[k].map_fill = NAN;
            snprintf(rows[k].message, sizeof rows[k].message,
                     "case did not finish (its worker died); rerun the sweep");
            missing++;
            continue;
        }
        if (rows[k].status == 0)
            ok++;
        else
            failed++;
    }
    bf_err err = {0};
    if (bf_sweep_write_summary(sw, rows, &err)) {
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
        report_retry_hints(sw, rows);
        return 5;
    }
    printf("%zu cases: %zu ok, %zu failed, %zu missing; summary in %s/summary.h5 "
           "and %s/summary.csv\n",
           sw->ncases, ok, failed, missing, sw->dir, sw->dir);
    report_retry_hints(sw, rows);
    /* the sweep's status: interrupted, a case that failed (the first), a
     * case that did not finish, or ok */
    if (bf_cli_stop)
        return 6;
    for (size_t k = 0; k < sw->ncases; k++)
        if (rows[k].status)
            return rows[k].status;
    return missing ? 1 : 0;
}

static void mark_unfilled(bf_sweep_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        rows[k].index = -1;
        rows[k].message[0] = '\x01';
    }
}

#ifndef BF_MPI

static int run_pool(const bf_sweep *sw, const sweep_args *a, const long *todo,
                    size_t ntodo);

int bf_cmd_sweep(int argc, char **argv)
{
    sweep_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc < 0 ? 0 : rc;
    bf_sweep sw;
    bf_err err = {0};
    if (bf_sweep_init(&sw, a.scene, a.sets, a.nsets, a.vary, a.nvary, a.dir,
                      &err)) {
        fprintf(stderr, "%s%s\n", strstr(err.msg, "error:") ? "" :
                "ballfilm: error: ", err.msg);
        return err.status;
    }
    sw.stop_flag = &bf_cli_stop;
    bf_sweep_row *rows = calloc(sw.ncases, sizeof *rows);
    long *todo = malloc(sw.ncases * sizeof *todo);
    if (!rows || !todo) {
        free(rows);
        free(todo);
        bf_sweep_free(&sw);
        return 1;
    }
    mark_unfilled(rows, sw.ncases);
    size_t nretried;
    const size_t ntodo = pending_cases(&sw, a.retry, todo, &nretried);
    if (!a.quiet)
        report_start(&sw, ntodo, nretried, a.retry, a.jobs, "process");
    int status = 0;
    if (a.jobs == 1 || ntodo <= 1) {
        for (size_t q = 0; q < ntodo && !bf_cli_stop; q++) {
            bf_sweep_row r;
            if (bf_sweep_run_case(&sw, todo[q], &r, &err)) {
                fprintf(stderr, "ballfilm: %s\n", err.msg);
                status = err.status;
                break;
            }
            report_case(&sw, &r, a.quiet, -1);
        }
    } else {
        status = run_pool(&sw, &a, todo, ntodo);
    }
    if (bf_cli_stop) {
        fprintf(stderr, "ballfilm: sweep interrupted; finished cases are kept, "
                        "a rerun runs the others\n");
        status = 6;
    }
    if (!status || status == 6) {
        int gs = gather_and_write(&sw, rows);
        if (gs && status != 6)
            status = gs;
    }
    free(rows);
    free(todo);
    bf_sweep_free(&sw);
    return status;
}

/* The process pool: workers take case numbers from a pipe.  A worker dies
 * with its parent (PR_SET_PDEATHSIG), and an interrupted sweep forwards
 * the interrupt to its workers (as SIGTERM), whose running cases stop as interrupted
 * runs do, and waits for them. */
static int run_pool(const bf_sweep *sw, const sweep_args *a, const long *todo,
                    size_t ntodo)
{
    int status = 0;
    {
        int fd[2];
        if (pipe(fd)) {
            fprintf(stderr, "ballfilm: error: pipe: %s\n", strerror(errno));
            status = 1;
        } else {
            long nproc = a->jobs < (long)ntodo ? a->jobs : (long)ntodo;
            pid_t pids[1024];
            long started = 0;
            const pid_t parent = getpid();
            fflush(NULL);
            for (long w = 0; w < nproc; w++) {
                pid_t pid = fork();
                if (pid == 0) {
                    close(fd[1]);
                    /* die with the parent, as an interrupted run */
                    prctl(PR_SET_PDEATHSIG, SIGTERM);
                    if (getppid() != parent)
                        _exit(6);
                    int32_t k;
                    /* reads of 4 bytes from a pipe are atomic: every case
                     * number goes to exactly one worker */
                    while (!bf_cli_stop &&
                           read(fd[0], &k, sizeof k) == (ssize_t)sizeof k) {
                        bf_sweep_row r;
                        bf_err e = {0};
                        if (bf_sweep_run_case(sw, k, &r, &e))
                            fprintf(stderr, "ballfilm: %s\n", e.msg);
                        else
                            report_case(sw, &r, a->quiet, -1);
                    }
                    fflush(NULL);
                    _exit(bf_cli_stop ? 6 : 0);
                }
                if (pid < 0) {
                    fprintf(stderr, "ballfilm: error: fork: %s\n",
                            strerror(errno));
                    status = 1;
                    break;
                }
                pids[started++] = pid;
            }
            close(fd[0]);
            for (size_t q = 0; q < ntodo && !status && !bf_cli_stop; q++) {
                int32_t k = (int32_t)todo[q];
                if (write(fd[1], &k, sizeof k) != (ssize_t)sizeof k) {
                    status = bf_cli_stop ? 0 : 1;
                    break;
                }
            }
            close(fd[1]);
            int forwarded = 0;
            for (;;) {
                if (bf_cli_stop && !forwarded) {
                    /* SIGTERM: workers of a sweep that ignores SIGINT
                     * (main.c) ignore it too */
                    for (long w = 0; w < started; w++)
                        kill(pids[w], SIGTERM);
                    forwarded = 1;
                }
                pid_t p = wait(NULL);
                if (p < 0 && errno == EINTR)
                    continue;
                if (p < 0)
                    break;
            }
        }
    }
    return status;
}

#else /* BF_MPI */

enum { TAG_REQ = 1, TAG_WORK = 2 };
#define ROWLEN 4096

typedef struct shared {
    const bf_sweep *sw;
    long *todo;
    size_t ntodo, next;
    bf_sweep_row *rows;
    int quiet, failed;
    pthread_mutex_t lock;
} shared;

/* The next case to run, -1 when none is left or the sweep was
 * interrupted (no case is started after an interrupt). */
static long take(shared *s)
{
    pthread_mutex_lock(&s->lock);
    long k = !bf_cli_stop && s->next < s->ntodo ? s->todo[s->next++] : -1;
    pthread_mutex_unlock(&s->lock);
    return k;
}

/* rank 0's own worker thread: never calls MPI */
static void *local_worker(void *arg)
{
    shared *s = arg;
    for (long k; (k = take(s)) >= 0;) {
        bf_sweep_row r;
        bf_err e = {0};
        if (bf_sweep_run_case(s->sw, k, &r, &e)) {
            fprintf(stderr, "ballfilm: %s%s\n",
                    e.status == BF_INTERRUPTED ? "" : "error: ", e.msg);
            s->failed |= e.status != BF_INTERRUPTED;
            continue;
        }
        report_case(s->sw, &r, s->quiet, 0);
        pthread_mutex_lock(&s->lock);
        s->rows[k] = r;
        pthread_mutex_unlock(&s->lock);
    }
    return NULL;
}

int bf_cmd_sweep(int argc, char **argv)
{
    int provided, rank, size;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    sweep_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc) {
        MPI_Finalize();
        return rc < 0 ? 0 : rc;
    }
    bf_sweep sw;
    bf_err err = {0};
    int ok = 1;
    /* rank 0 creates the directory and manifest first */
    if (rank == 0)
        ok = bf_sweep_init(&sw, a.scene, a.sets, a.nsets, a.vary, a.nvary,
                           a.dir, &err) == BF_OK;
    MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (ok && rank != 0)
        ok = bf_sweep_init(&sw, a.scene, a.sets, a.nsets, a.vary, a.nvary,
                           a.dir, &err) == BF_OK;
    int all_ok;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all_ok) {
        if (!ok)
            fprintf(stderr, "ballfilm: error (rank %d): %s\n", rank, err.msg);
        if (ok)
            bf_sweep_free(&sw);
        MPI_Finalize();
        return 2;
    }
    /* SIGINT/SIGTERM (mpirun forwards them as SIGTERM to every rank):
     * running cases stop as interrupted runs, no new case starts, the
     * finished ones are gathered, and every rank ends with status 6 */
    sw.stop_flag = &bf_cli_stop;
    char buf[ROWLEN];
    int status = 0;
    if (rank == 0) {
        shared s = {.sw = &sw, .quiet = a.quiet};
        s.rows = calloc(sw.ncases, sizeof *s.rows);
        s.todo = malloc(sw.ncases * sizeof *s.todo);
        pthread_mutex_init(&s.lock, NULL);
        mark_unfilled(s.rows, sw.ncases);
        size_t nretried;
        s.ntodo = pending_cases(&sw, a.retry, s.todo, &nretried);
        if (!a.quiet)
            report_start(&sw, s.ntodo, nretried, a.retry, size, "rank");
        pthread_t th;
        pthread_create(&th, NULL, local_worker, &s);
        int active = size - 1;
        while (active > 0) {
            int flag;
            MPI_Status mst;
            MPI_Iprobe(MPI_ANY_SOURCE, TAG_REQ, MPI_COMM_WORLD, &flag, &mst);
            if (!flag) {
                /* poll gently: the local worker needs the core */
                struct timespec ts = {0, 1000000};
                nanosleep(&ts, NULL);
                continue;
            }
            MPI_Recv(buf, ROWLEN, MPI_CHAR, mst.MPI_SOURCE, TAG_REQ,
                     MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            bf_sweep_row r;
            if (buf[0] && bf_sweep_row_parse(&sw, buf, &r) && r.index >= 0 &&
                (size_t)r.index < sw.ncases) {
                report_case(&sw, &r, a.quiet, mst.MPI_SOURCE);
                pthread_mutex_lock(&s.lock);
                s.rows[r.index] = r;
                pthread_mutex_unlock(&s.lock);
            }
            long k = take(&s);
            MPI_Send(&k, 1, MPI_LONG, mst.MPI_SOURCE, TAG_WORK, MPI_COMM_WORLD);
            if (k < 0)
                active--;
        }
        pthread_join(th, NULL);
        status = gather_and_write(&sw, s.rows);
        if (s.failed && !status)
            status = 5;
        if (bf_cli_stop) {
            fprintf(stderr, "ballfilm: sweep interrupted; finished cases are "
                            "kept, a rerun runs the others\n");
            status = 6;
        }
        pthread_mutex_destroy(&s.lock);
        free(s.rows);
        free(s.todo);
    } else {
        buf[0] = '\0';
        for (;;) {
            long k;
            MPI_Send(buf, (int)strlen(buf) + 1, MPI_CHAR, 0, TAG_REQ,
                     MPI_COMM_WORLD);
            MPI_Recv(&k, 1, MPI_LONG, 0, TAG_WORK, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
            if (k < 0)
                break;
            bf_sweep_row r;
            if (bf_sweep_run_case(&sw, k, &r, &err)) {
                int intr = err.status == BF_INTERRUPTED;
                fprintf(stderr, "ballfilm: %s(rank %d): %s\n",
                        intr ? "" : "error ", rank, err.msg);
                buf[0] = '\0';
                if (!intr)
                    status = 5;
                continue;
            }
            bf_sweep_row_format(&sw, &r, buf, sizeof buf);
        }
        if (bf_cli_stop)
            status = 6;
    }
    bf_sweep_free(&sw);
    MPI_Finalize();
    return status;
}

#endif
