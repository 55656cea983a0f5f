/* cmd_run.c: `ballfilm run SCENE.ini [-o OUT.h5] [--set s.k=v]... [-q]`.
 *
 * Order matters for "nothing already written is lost": the scene is read,
 * overridden, resolved and the model is built (all validation) before the
 * output file is created, so a bad scene never truncates an earlier result.
 */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "cli.h"

#ifdef BF_MPI
#include <mpi.h>

#include "models/greenspan.h"

/* The stop flag of a run over ranks: the OR of every rank's bf_cli_stop,
 * agreed at each exchange of particles (every step has two), so that every
 * rank stops after the same step (a signal reaches the ranks at different
 * moments). */
static volatile sig_atomic_t ranks_stop;

typedef struct ranks_ctx {
    /* MPI's counts and displacements, sent and received */
    int *cnt, *dsp, *rcnt, *rdsp;
    int *pair, *rpair; /* [2 size]: a count and the stop flag, each rank */
} ranks_ctx;

/* An exchange that cannot go on (its sizes beyond MPI's ints, or no
 * memory to receive): the other ranks are waiting in it, so the whole run
 * stops, with status 1. */
static void ranks_abort(const char *why)
{
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    fprintf(stderr, "ballfilm: rank %d: %s\n", rank, why);
    MPI_Abort(MPI_COMM_WORLD, BF_EINTERNAL);
}

/* Counts and their displacements as MPI's ints. */
static void ranks_ints(const size_t *counts, int size, int *cnt, int *dsp)
{
    size_t off = 0;
    for (int q = 0; q < size; q++) {
        if (counts[q] > INT_MAX || off > INT_MAX)
            ranks_abort("an exchange beyond MPI's int counts");
        cnt[q] = (int)counts[q];
        dsp[q] = (int)off;
        off += counts[q];
    }
}

/* bf_ranks.allgather over MPI_COMM_WORLD (models/greenspan.h) */
static int ranks_allgather(void *ctx, const double *send, size_t n,
                           double *recv, const size_t *counts)
{
    ranks_ctx *c = ctx;
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    ranks_ints(counts, size, c->cnt, c->dsp);
    return MPI_Allgatherv(send, (int)n, MPI_DOUBLE, recv, c->cnt, c->dsp,
                          MPI_DOUBLE, MPI_COMM_WORLD) != MPI_SUCCESS;
}

/* bf_ranks.alltoallv: the counts first, each with the stop flag
 * (MPI_Alltoall: no collective of its own for the flag), then the data */
static int ranks_alltoallv(void *ctx, const double *send,
                           const size_t *scounts, double **recv,
                           size_t *rcap, size_t *rcounts)
{
    ranks_ctx *c = ctx;
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    ranks_ints(scounts, size, c->cnt, c->dsp);
    for (int q = 0; q < size; q++) {
        c->pair[2 * q] = c->cnt[q];
        c->pair[2 * q + 1] = bf_cli_stop != 0;
    }
    if (MPI_Alltoall(c->pair, 2, MPI_INT, c->rpair, 2, MPI_INT,
                     MPI_COMM_WORLD))
        return 1;
    size_t total = 0;
    for (int q = 0; q < size; q++) {
        rcounts[q] = (size_t)c->rpair[2 * q];
        total += rcounts[q];
        if (c->rpair[2 * q + 1])
            ranks_stop = 1;
    }
    ranks_ints(rcounts, size, c->rcnt, c->rdsp);
    if (total > *rcap) {
        double *b = realloc(*recv, total * sizeof *b);
        if (!b)
            ranks_abort("out of memory for an exchange between ranks");
        *recv = b;
        *rcap = total;
    }
    return MPI_Alltoallv(send, c->cnt, c->dsp, MPI_DOUBLE, *recv, c->rcnt,
                         c->rdsp, MPI_DOUBLE, MPI_COMM_WORLD) != MPI_SUCCESS;
}

/* bf_ranks.allsum */
static int ranks_allsum(void *ctx, double *v, size_t n)
{
    (void)ctx;
    if (n > INT_MAX)
        ranks_abort("a sum beyond MPI's int counts");
    return MPI_Allreduce(MPI_IN_PLACE, v, (int)n, MPI_DOUBLE, MPI_SUM,
                         MPI_COMM_WORLD) != MPI_SUCCESS;
}

/* Whether the run can be split over the ranks: only greenspan72 runs so
 * (the other models' state is not split), and not with every option;
 * refusals are BF_EINPUT naming the key. */
static bf_status ranks_can_split(bf_sim *sim, int size, bf_err *err)
{
    const char *name = bf_sim_model_type(sim)->name;
    if (strcmp(name, "greenspan72"))
        return bf_fail_key(err, BF_EINPUT, "scene", "model",
                           "model %s does not run over ranks (%d ranks "
                           "given); the models that do: greenspan72.  Run "
                           "it with one rank",
                           name, size);
    return bf_greenspan72_ranks_refuse(bf_sim_model(sim), err);
}

static bf_status ranks_attach(bf_sim *sim, int rank, int size, ranks_ctx *c,
                              bf_err *err)
{
    c->cnt = calloc((size_t)size, sizeof *c->cnt);
    c->dsp = calloc((size_t)size, sizeof *c->dsp);
    c->rcnt = calloc((size_t)size, sizeof *c->rcnt);
    c->rdsp = calloc((size_t)size, sizeof *c->rdsp);
    c->pair = calloc(2 * (size_t)size, sizeof *c->pair);
    c->rpair = calloc(2 * (size_t)size, sizeof *c->rpair);
    if (!c->cnt || !c->dsp || !c->rcnt || !c->rdsp || !c->pair || !c->rpair)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    bf_ranks r = {rank, size, c, ranks_allgather, ranks_alltoallv,
                  ranks_allsum, 0};
    return bf_greenspan72_over_ranks(bf_sim_model(sim), &r, err);
}

static void print_setup_error(bf_status st, const char *msg);

/* The worst status of all ranks (a rank that failed alone must not leave
 * the others waiting in the run's exchanges). */
static bf_status ranks_worst(bf_status st)
{
    int mine = (int)st, worst = 0;
    MPI_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return (bf_status)worst;
}

/* After the set-up (status st) of a run over ranks: whether it can be
 * split, agreed.  Every rank reads the scene (or checkpoint) and builds
 * the whole model: the same failures everywhere, said once by rank 0 (an
 * allocation may fail alone, and says so). */
static bf_status ranks_check(bf_status st, bf_run *run, const char *what,
                             int rank, int nranks, bf_err *err)
{
    if (st && (!rank || st == BF_EINTERNAL))
        print_setup_error(st, err->msg);
    else if (!st && (st = ranks_can_split(bf_run_sim(run), nranks, err)) &&
             !rank)
        fprintf(stderr, "ballfilm: error: %s: [%s] %s: %s\n", what,
                err->section, err->key, err->msg);
    return ranks_worst(st);
}

/* After rank 0 opened the output (status st there): the split, each rank
 * keeping its particles, agreed.  The whole model was there until now, so
 * that rank 0 could write the particles' static datasets. */
static bf_status ranks_split(bf_status st, bf_run *run, int rank, int nranks,
                             ranks_ctx *c, bf_err *err)
{
    if ((st = ranks_worst(st)))
        return st;
    if ((st = ranks_attach(bf_run_sim(run), rank, nranks, c, err)) &&
        (!rank || st == BF_EINTERNAL))
        print_setup_error(st, err->msg);
    return ranks_worst(st);
}
#endif

void bf_cli_print_keys(FILE *f)
{
    bf_catalog_print_help(bf_catalog_builtin(), f);
}

static void run_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm run SCENE.ini [-o OUT.h5] [--set section.key=value]"
            "... [-q]\n"
            "       ballfilm run --restart OUT.h5 [--set section.key=value]... "
            "[-q]\n"
            "\n"
            "  -o, --output OUT.h5\n"
            "                   output file (default: out/<scene name>.h5)\n"
            "  --restart OUT.h5 continue the run of OUT.h5 from its checkpoint "
            "OUT.h5.ckpt\n"
            "                   (written every [scene] checkpoint_every and on "
            "SIGINT/SIGTERM)\n"
            "  --stop-after N   stop after N steps as if interrupted "
            "(checkpoint written)\n"
            "  --keep-checkpoint keep OUT.h5.ckpt when the run ends normally "
            "(to continue it\n"
            "                   later with --restart OUT.h5 --set "
            "scene.t_end=...; the\n"
            "                   finished OUT.h5 stays as it is until the "
            "continued run ends);\n"
            "                   it is the last checkpoint of [scene] "
            "checkpoint_every, refused\n"
            "                   (status 2) when that is 0\n"
            "  --set s.k=v      override key k of section [s] (repeatable);\n"
            "                   e.g. --set scene.integrator=verlet --set "
            "ball.2.mass=0.8\n"
            "  -q, --quiet      no progress line, only the final summary\n"
            "  --progress       progress line even when stderr is not a "
            "terminal\n"
            "\n");
}

/* --restart OUT.h5 of a run that left nothing there: neither OUT.h5 nor
 * its .part nor its checkpoint (one that left some of them is the
 * restart's to judge and explain). */
static int no_run_at(const char *out)
{
    char part[4096], ckpt[4096];
    struct stat st;
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(ckpt, sizeof ckpt, "%s.ckpt", out);
    const char *const all[] = {out, part, ckpt};
    for (size_t k = 0; k < 3; k++)
        if (!stat(all[k], &st) || (errno != ENOENT && errno != ENOTDIR))
            return 0;
    fprintf(stderr, "ballfilm: error: %s: no such file (nor %s, nor its "
                    "checkpoint %s)\n", out, part, ckpt);
    return 1;
}

/* --help: the options and every scene key */
static void run_usage_keys(FILE *f)
{
    run_usage(f);
    bf_cli_print_keys(f);
}

int bf_cli_mkdir_out(void)
{
    if (mkdir("out", 0777) && errno != EEXIST) {
        fprintf(stderr, "ballfilm: error: cannot create directory 'out': %s\n",
                strerror(errno));
        return 1;
    }
    return 0;
}

/* out/<basename of scene without .ini>.h5 */
static char *default_output(const char *scene)
{
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    size_t len = strlen(base);
    if (len > 4 && !strcmp(base + len - 4, ".ini"))
        len -= 4;
    char *p = malloc(len + 16);
    if (!p)
        return NULL;
    snprintf(p, len + 16, "out/%.*s.h5", (int)len, base);
    if (bf_cli_mkdir_out()) {
        free(p);
        return NULL;
    }
    return p;
}

/* Detect at the start what can be detected: an output that will not fit
 * on its file system. */
/* The process's peak resident memory (VmHWM of /proc/self/status: this
 * program's own, not the memory of whatever exec'ed it; getrusage's
 * ru_maxrss would count the parent's image before the exec). */
static void print_peak_memory(FILE *f)
{
    FILE *st = fopen("/proc/self/status", "r");
    if (!st)
        return;
    char line[256];
    long kib = -1;
    while (fgets(line, sizeof line, st))
        if (sscanf(line, "VmHWM: %ld kB", &kib) == 1)
            break;
    fclose(st);
    if (kib >= 0)
        fprintf(f, "peak memory:       %.1f MiB (resident)\n", kib / 1024.0);
}

static void warn_disk_space(const bf_sim *sim, const char *out_path)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", out_path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *(slash == dir ? slash + 1 : slash) = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    struct statvfs vfs;
    if (statvfs(dir, &vfs))
        return;
    double avail = (double)vfs.f_bavail * (double)vfs.f_frsize;
    double need = bf_sim_output_estimate(sim);
    if (need > avail)
        fprintf(stderr,
                "ballfilm: warning: the output may need about %.0f MiB but only "
                "%.0f MiB are free for %s; thin it with [scene] output_every\n",
                need / 1048576.0, avail / 1048576.0, out_path);
}

/* A failure before the run started: scene errors come located
 * ("FILE:LINE: error: ..."); the others get the program's prefix, and an
 * allocation that failed says so (status 1 is documented as that or a
 * bug, docs/output.md). */
static void print_setup_error(bf_status st, const char *msg)
{
    if (strstr(msg, ": error: ") && strncmp(msg, "ballfilm:", 9))
        fprintf(stderr, "%s\n", msg);
    else if (st == BF_EINTERNAL && strstr(msg, "out of memory"))
        fprintf(stderr, "ballfilm: error: %s: the run needs more memory than "
                        "this process may allocate (free memory, ulimit -v); "
                        "make it smaller\n", msg);
    else
        fprintf(stderr, "ballfilm: error: %s\n", msg);
}

int bf_cmd_run(int argc, char **argv)
{
    const char *scene_path = NULL, *out_path = NULL, *restart = NULL;
    int quiet = 0, force_progress = 0, keep_ckpt = 0;
    long stop_after = 0;
    int nset = 0;
    const char **sets = calloc((size_t)argc, sizeof *sets);
    if (!sets)
        return BF_EINTERNAL;
    enum { RESTART = BF_CLI_LONG, STOP_AFTER, SET, KEEP, PROGRESS };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"output", required_argument, NULL, 'o'},
        {"quiet", no_argument, NULL, 'q'},
        {"restart", required_argument, NULL, RESTART},
        {"stop-after", required_argument, NULL, STOP_AFTER},
        {"set", required_argument, NULL, SET},
        {"keep-checkpoint", no_argument, NULL, KEEP},
        {"progress", no_argument, NULL, PROGRESS},
        {NULL, 0, NULL, 0},
    };
    const bf_cli_cmd cmd = {"run", ":ho:q", longopts, run_usage_keys};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        switch (c) {
        case BF_CLI_HELP:
        case BF_CLI_BAD:
            free(sets);
            return c == BF_CLI_HELP ? 0 : BF_EINPUT;
        case 'o':
            out_path = optarg;
            break;
        case RESTART:
            restart = optarg;
            break;
        case STOP_AFTER:
            if (!bf_parse_long(optarg, &stop_after) || stop_after < 1) {
                bf_cli_error(&cmd, "--stop-after needs a number of steps "
                                   ">= 1");
                free(sets);
                return BF_EINPUT;
            }
            break;
        case SET:
            sets[nset++] = optarg;
            break;
        case KEEP:
            keep_ckpt = 1;
            break;
        case 'q':
            quiet = 1;
            break;
        case PROGRESS:
            force_progress = 1;
            break;
        }
    }
    for (int k = optind; k < argc; k++) {
        if (scene_path) {
            fprintf(stderr, "ballfilm: error: more than one scene file "
                            "('%s')\n", argv[k]);
            free(sets);
            return BF_EINPUT;
        }
        scene_path = argv[k];
    }
    if (!scene_path == !restart || (restart && out_path)) {
        if (scene_path && restart)
            fprintf(stderr, "ballfilm: error: give a scene or --restart, not "
                            "both\n");
        if (restart && out_path)
            fprintf(stderr, "ballfilm: error: --restart continues OUT.h5 in "
                            "place; -o is not used with it\n");
        run_usage(stderr);
        free(sets);
        return BF_EINPUT;
    }
    if (restart && no_run_at(restart)) {
        free(sets);
        return BF_EINPUT;
    }

    /* rank 0 writes (the output, the messages); over several ranks the
     * others compute only */
    int rank = 0, nranks = 1;
    const volatile sig_atomic_t *stop_flag = &bf_cli_stop;
#ifdef BF_MPI
    ranks_ctx rctx = {0};
    MPI_Init(NULL, NULL);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    if (nranks > 1)
        stop_flag = &ranks_stop;
#endif
    const int writer = rank == 0;
    (void)nranks; /* (one process without MPI) */
    if (!writer)
        quiet = 1;
    bf_err err = {0};
    bf_run *run = NULL;
    bf_sim *sim = NULL;
    char *defout = NULL;
    bf_sim_opts opts = {
        .progress = !quiet && (force_progress || isatty(STDERR_FILENO)),
        .stop_flag = stop_flag,
        .stop_after = stop_after,
        .keep_checkpoint = keep_ckpt,
        .rank = rank,
        .nranks = nranks,
    };
    bf_status st;
    if (restart) {
        /* the checkpoint holds the whole state (rank 0 wrote it): any
         * number of ranks continues it, only rank 0 reopens the output */
        st = writer ? bf_run_restart(&run, bf_catalog_builtin(), restart,
                                     sets, (size_t)nset, &opts, &err)
                    : bf_run_restart_state(&run, bf_catalog_builtin(),
                                           restart, sets, (size_t)nset,
                                           &opts, &err);
#ifdef BF_MPI
        if (nranks > 1 &&
            ((st = ranks_check(st, run, restart, rank, nranks, &err)) ||
             (st = ranks_split(BF_OK, run, rank, nranks, &rctx, &err))))
            goto done;
#endif
        if (st) {
            print_setup_error(st, err.msg);
            goto done;
        }
        sim = bf_run_sim(run);
        out_path = restart;
        goto run;
    }
    st = bf_run_load(&run, bf_catalog_builtin(), scene_path, sets,
                     (size_t)nset, &opts, &err);
#ifdef BF_MPI
    if (nranks > 1 &&
        (st = ranks_check(st, run, scene_path, rank, nranks, &err)))
        goto done;
#endif
    if (st) {
        print_setup_error(st, err.msg);
        goto done;
    }
    sim = bf_run_sim(run);
    /* interrupted while the scene was read and the model built: nothing
     * has been written yet, and nothing will be (over ranks the ranks
     * agree on a stop at the first step) */
    if (nranks == 1 && (*stop_flag || bf_cli_stop)) {
        fprintf(stderr, "ballfilm: interrupted during set-up; nothing was "
                        "written\n");
        st = BF_INTERRUPTED;
        goto done;
    }
    /* rank 0 creates the output while it holds every particle (their
     * static datasets), then the ranks split them */
    if (writer && !out_path) {
        out_path = defout = default_output(scene_path);
        if (!defout) {
            fprintf(stderr, "ballfilm: error: cannot create directory 'out': %s\n",
                    strerror(errno));
            st = BF_EIO;
        }
    }
    if (writer && !st && (st = bf_run_open_output(run, out_path, &err)))
        print_setup_error(st, err.msg);
#ifdef BF_MPI
    if (nranks > 1)
        st = ranks_split(st, run, rank, nranks, &rctx, &err);
#endif
    if (st)
        goto done;
run:;
    if (writer)
        warn_disk_space(sim, out_path);

    bf_status run_st = bf_sim_run(sim, &err);
    bf_err cerr = {0};
    bf_status close_st = bf_sim_close_output(sim, run_st, &err, &cerr);
#ifdef BF_MPI
    /* the model's failures over ranks that its exchanges found (a step
     * that is unstable) and a stop are every rank's, and rank 0 says
     * them; any other (memory, the output's I/O, the final state's check
     * of one rank's particles) may be one rank's, and the others may be
     * waiting for it in the next exchange: the run is aborted with its
     * status after rank 0 has closed its output and said what it knows */
    const int alone = nranks > 1 && run_st && run_st != BF_INTERRUPTED &&
                      !bf_greenspan72_failed_together(bf_sim_model(sim));
    if (alone && !writer) {
        fprintf(stderr, "ballfilm: rank %d: %s: %s\n", rank,
                bf_status_name(run_st), err.msg);
        MPI_Abort(MPI_COMM_WORLD, (int)run_st);
    }
#endif
    if (!writer) {
        st = run_st;
        goto done;
    }
    bf_sim_summary(sim, stdout);
    print_peak_memory(stdout);
    if (run_st == BF_INTERRUPTED) {
        fprintf(stderr, "ballfilm: %s\n", err.msg);
        st = run_st;
    } else if (run_st == BF_EIO) {
        fprintf(stderr, "ballfilm: I/O error: %s\n", err.msg);
        fprintf(stderr, "ballfilm: %s may be incomplete; free space (or thin "
                        "the output) and run again\n", out_path);
        st = run_st;
    } else if (run_st == BF_EINTERNAL && strstr(err.msg, "out of memory")) {
        fprintf(stderr, "ballfilm: out of memory: %s; the run needed more "
                        "memory than this process may allocate (free memory, "
                        "ulimit -v)\n", err.msg);
        fprintf(stderr, "ballfilm: output up to the last good output row is in "
                        "%s\n", out_path);
        st = run_st;
    } else if (run_st) {
        fprintf(stderr, "ballfilm: %s: %s\n", bf_status_name(run_st), err.msg);
        fprintf(stderr, "ballfilm: output up to the last good output row is in "
                        "%s\n", out_path);
        st = run_st;
    } else {
        st = close_st;
    }
#ifdef BF_MPI
    if (alone)
        MPI_Abort(MPI_COMM_WORLD, (int)run_st);
#endif
    if (close_st && run_st != BF_EIO)
        fprintf(stderr, "ballfilm: error: %s\n", cerr.msg);
    else if (!run_st)
        printf("wrote %s\n", out_path);
    if (!close_st && run_st != BF_EIO && run_st != BF_INTERRUPTED &&
        bf_cli_write_xdmf(out_path) == BF_INTERRUPTED && !st)
        st = BF_INTERRUPTED;
done:
    bf_run_free(run);
    free(defout);
    free(sets);
#ifdef BF_MPI
    free(rctx.cnt);
    free(rctx.dsp);
    free(rctx.rcnt);
    free(rctx.rdsp);
    free(rctx.pair);
    free(rctx.rpair);
    MPI_Finalize();
#endif
    return (int)st;
}
