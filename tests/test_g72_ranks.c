/* test_g72_ranks.c: model greenspan72 split over ranks
 * (src/models/g72_ranks.c) keeps the serial bits at any rank count.
 *
 * same_bits_on_threaded_ranks: R = 2..4 ranks as threads of this process
 * (exchanging through shared memory, as MPI's collectives do between
 * processes; also under the sanitizers), the particles migrating between
 * them and the cuts placed again every 7 steps, end 150 steps with every
 * particle on one rank and the positions and velocities of one process,
 * bit for bit, with the support-set
 * gravity's cell method and its fast method (whose sweep starts up to 8 dx
 * left of a strip: the widest halo).  `mpirun -n R ballfilm-mpi run`
 * writes every dataset of the serial program's file: R = 1 and 4 on the
 * fast method's scene and R = 3 on the cell method's
 * (same_bits_on_1_to_4_ranks), R = 2 then 3 on the fast method's, stopped
 * and continued (stop_on_2_ranks_continue_on_3: the continued file is the
 * whole serial file, so each of its parts is that rank count's).  Every
 * mpirun costs about a second of CPU in start-up alone, so each rank
 * count runs once.  The scenes are chaotic (Example 2's
 * velocities of 500 cm/s), and any missing or reordered term shows in the
 * bits.  With the halo one column narrower than the fast method needs
 * (halo_columns: left halo - 2, its margin and one more), the threaded
 * test fails on 2 ranks, the processes' on 4, and the runs stopped on 2
 * ranks and continued (both tests of it); with no right halo, the
 * threaded one.
 *
 * Refusals: another model, and the options the split does not support,
 * named by their key (in the library and through the MPI program). */
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ballfilm/run.h"
#include "models/greenspan.h"
#include "testutil.h"

/* Example 2's physics, 256 particles, the cell method (16 bands). */
static const char *cell_scene =
    "[scene]\nmodel = greenspan72\ndt = 1e-2\nt_end = 3\noutput_every = 10\n"
    "[greenspan72]\nwidth = 100\nheight = 100\ninterface = 75\nd = 5\n"
    "m_heavy = 1\nm_light = 0.25\ngrid_nx = 16\ngrid_ny = 16\n"
    "v_random = 500\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\n"
    "[walls]\nomega = 0.9\n";

/* The same physics in a box 300 cm wide (6 chunks of the fast method's
 * sweep, 30 columns of cells), 384 particles, the fast method. */
static const char *fast_scene =
    "[scene]\nmodel = greenspan72\ndt = 1e-2\nt_end = 2\noutput_every = 10\n"
    "[greenspan72]\nwidth = 300\nheight = 100\ninterface = 75\nd = 5\n"
    "m_heavy = 1\nm_light = 0.25\ngrid_nx = 48\ngrid_ny = 16\n"
    "v_random = 500\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\nmethod = fast\n"
    "[walls]\nomega = 0.9\n";

/* ---------------------------------------------- ranks as threads
 *
 * The split without MPI: R models in one process, each a rank driven by
 * a thread of its own, exchanging through shared memory with barriers
 * (what MPI_Allgatherv, MPI_Alltoallv and MPI_Allreduce do between
 * processes).  It runs under the
 * sanitizers too. */

enum { MAXR = 4 };

typedef struct team {
    pthread_barrier_t bar;
    const double *send[MAXR];
    const size_t *scounts[MAXR];
    double *sum[MAXR];
    size_t n[MAXR];
    int mismatch;
} team;

typedef struct member {
    team *t;
    bf_ranks rk;
    int rank, size;
    void *model;
    long steps;
    double dt;
    bf_status st;
    bf_err err;
} member;

static int thread_allgather(void *ctx, const double *send, size_t n,
                            double *recv, const size_t *counts)
{
    member *me = ctx;
    team *t = me->t;
    t->send[me->rank] = send;
    t->n[me->rank] = n;
    pthread_barrier_wait(&t->bar);
    size_t off = 0;
    for (int q = 0; q < me->size; q++) {
        if (t->n[q] != counts[q])
            t->mismatch = 1;
        else
            memcpy(recv + off, t->send[q], counts[q] * sizeof *recv);
        off += counts[q];
    }
    /* every rank has copied before any sends again */
    pthread_barrier_wait(&t->bar);
    return t->mismatch;
}

/* what MPI_Alltoall of the counts and MPI_Alltoallv do */
static int thread_alltoallv(void *ctx, const double *send,
                            const size_t *scounts, double **recv,
                            size_t *rcap, size_t *rcounts)
{
    member *me = ctx;
    team *t = me->t;
    t->send[me->rank] = send;
    t->scounts[me->rank] = scounts;
    pthread_barrier_wait(&t->bar);
    size_t total = 0;
    for (int q = 0; q < me->size; q++)
        total += rcounts[q] = t->scounts[q][me->rank];
    int fail = 0;
    if (total > *rcap) {
        double *b = realloc(*recv, total * sizeof *b);
        if (b) {
            *recv = b;
            *rcap = total;
        } else {
            fail = 1;
        }
    }
    for (int q = 0, off = 0; q < me->size && !fail; q++) {
        size_t at = 0;
        for (int k = 0; k < me->rank; k++)
            at += t->scounts[q][k];
        if (rcounts[q])
            memcpy(*recv + off, t->send[q] + at, rcounts[q] * sizeof **recv);
        off += (int)rcounts[q];
    }
    pthread_barrier_wait(&t->bar);
    return fail;
}

/* what MPI_Allreduce with MPI_SUM does (in rank order) */
static int thread_allsum(void *ctx, double *v, size_t n)
{
    member *me = ctx;
    team *t = me->t;
    double *acc = calloc(n ? n : 1, sizeof *acc);
    t->sum[me->rank] = v;
    pthread_barrier_wait(&t->bar);
    for (int q = 0; q < me->size && acc; q++)
        for (size_t k = 0; k < n; k++)
            acc[k] += t->sum[q][k];
    pthread_barrier_wait(&t->bar);
    if (acc)
        memcpy(v, acc, n * sizeof *v);
    free(acc);
    return acc == NULL;
}

static void *member_run(void *arg)
{
    member *me = arg;
    const bf_model_type *mt =
        bf_catalog_model(bf_catalog_builtin(), "greenspan72");
    /* the split computes a(x) over the ranks: collective */
    me->st = bf_greenspan72_over_ranks(me->model, &me->rk, &me->err);
    for (long k = 0; k < me->steps && !me->st; k++)
        me->st = mt->step(me->model, k, (double)k * me->dt, me->dt, &me->err);
    return NULL;
}

/* The model of a scene, with an override "section.key=value" (or NULL),
 * without the time loop. */
static void *model_of(const char *text, const char *set, bf_setup **setup)
{
    bf_scene *sc = tu_scene(text);
    bf_err err = {0};
    void *m;
    if (set) {
        ck_assert(bf_scene_set(sc, set, "test", &err) == BF_OK);
        ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) ==
                  BF_OK);
    }
    ck_assert_msg(bf_model_from_scene(bf_catalog_builtin(), sc, setup, &m,
                                      &err) == BF_OK,
                  "%s", err.msg);
    bf_scene_free(sc);
    return m;
}

static void free_model(void *m, bf_setup *setup)
{
    bf_catalog_model(bf_catalog_builtin(), "greenspan72")->destroy(m);
    bf_setup_free(setup);
}

/* `steps` steps of the scene on one process and on R threaded ranks:
 * the same positions and velocities, bit for bit, on every rank. */
static void same_on_threads(const char *text, int R, long steps)
{
    const bf_model_type *mt =
        bf_catalog_model(bf_catalog_builtin(), "greenspan72");
    bf_setup *s0;
    void *serial = model_of(text, NULL, &s0);
    bf_err err = {0};
    for (long k = 0; k < steps; k++)
        ck_assert_msg(mt->step(serial, k, (double)k * 1e-2, 1e-2, &err) ==
                          BF_OK,
                      "%s", err.msg);
    const bf_particles *ps = bf_greenspan72_particles(serial);
    team t = {.mismatch = 0};
    ck_assert(pthread_barrier_init(&t.bar, NULL, (unsigned)R) == 0);
    member mem[MAXR];
    bf_setup *setups[MAXR];
    pthread_t th[MAXR];
    for (int r = 0; r < R; r++) {
        mem[r] = (member){.t = &t, .rank = r, .size = R, .steps = steps,
                          .dt = 1e-2};
        mem[r].model = model_of(text, NULL, &setups[r]);
        /* the cuts placed again every 7 steps (256 in the program) */
        mem[r].rk = (bf_ranks){r, R, &mem[r], thread_allgather,
                               thread_alltoallv, thread_allsum, 7};
    }
    for (int r = 0; r < R; r++)
        ck_assert(pthread_create(&th[r], NULL, member_run, &mem[r]) == 0);
    for (int r = 0; r < R; r++)
        pthread_join(th[r], NULL);
    ck_assert(!t.mismatch);
    /* each particle on one rank, with the serial bits */
    unsigned char *seen = calloc(ps->n, 1);
    ck_assert(seen);
    size_t held = 0;
    for (int r = 0; r < R; r++) {
        ck_assert_msg(mem[r].st == BF_OK, "%s", mem[r].err.msg);
        const bf_particles *p = bf_greenspan72_particles(mem[r].model);
        const uint32_t *id = bf_greenspan72_ids(mem[r].model);
        ck_assert(id);
        for (size_t i = 0; i < p->n; i++) {
            const uint32_t g = id[i];
            ck_assert_msg(g < ps->n && !seen[g] && (!i || id[i - 1] < g),
                          "rank %d: particle number %u", r, (unsigned)g);
            seen[g] = 1;
            ck_assert_msg(!memcmp(&p->x[i], &ps->x[g], sizeof *p->x) &&
                              !memcmp(&p->y[i], &ps->y[g], sizeof *p->y) &&
                              !memcmp(&p->vx[i], &ps->vx[g], sizeof *p->vx) &&
                              !memcmp(&p->vy[i], &ps->vy[g], sizeof *p->vy),
                          "rank %d of %d: particle %u not the serial bits "
                          "after %ld steps", r, R, (unsigned)g, steps);
        }
        held += p->n;
        free_model(mem[r].model, setups[r]);
    }
    free(seen);
    ck_assert_uint_eq(held, ps->n);
    pthread_barrier_destroy(&t.bar);
    free_model(serial, s0);
}

START_TEST(same_bits_on_threaded_ranks)
{
    for (int R = 2; R <= MAXR; R++) {
        same_on_threads(fast_scene, R, 150);
        same_on_threads(cell_scene, R, 150);
    }
}
END_TEST

/* What the split does not support is refused before any exchange. */
static void refused_key(const char *set, const char *section,
                        const char *key)
{
    bf_setup *setup;
    void *m = model_of(cell_scene, set, &setup);
    bf_err err = {0};
    bf_ranks rk = {0, 2, NULL, thread_allgather, thread_alltoallv,
                   thread_allsum, 0};
    ck_assert_int_eq(bf_greenspan72_over_ranks(m, &rk, &err), BF_EINPUT);
    ck_assert_msg(!strcmp(err.section, section) && !strcmp(err.key, key),
                  "[%s] %s: %s", err.section, err.key, err.msg);
    free_model(m, setup);
}

START_TEST(library_refuses_naming_the_key)
{
    refused_key("hertz.enabled=yes", "hertz", "enabled");
    refused_key("greenspan72.integrator=arkode", "greenspan72", "integrator");
    refused_key("support.method=naive", "support", "method");
    refused_key("repulsion.method=pairs", "repulsion", "method");
}
END_TEST

/* The MPI program, or NULL (the test is skipped: no MPI build, or the
 * sanitizers, which MPI's own allocations upset). */
static const char *mpi_bin(void)
{
    const char *mpi = getenv("BALLFILM_MPI_BIN");
    if (getenv("BALLFILM_SANITIZED") || !mpi || access(mpi, X_OK) ||
        system("command -v mpirun >/dev/null 2>&1")) {
        fprintf(stderr, "note: greenspan72 over ranks skipped (no "
                        "BALLFILM_MPI_BIN or mpirun)\n");
        return NULL;
    }
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    return mpi;
}

/* `mpirun -n R ballfilm-mpi run ARGS`, stderr into errfile; the exit
 * status (124: still running after 5 minutes, a rank waiting for another
 * that is gone). */
static int mpi_run(const char *mpi, int R, const char *args,
                   const char *errfile)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "timeout 300 mpirun -n %d --oversubscribe '%s' run %s -q "
             ">/dev/null 2>'%s'",
             R, mpi, args, errfile);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Whether the file at path holds `want`. */
static int file_has(const char *path, const char *want)
{
    FILE *f = fopen(path, "r");
    ck_assert(f);
    char buf[16384];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strstr(buf, want) != NULL;
}

/* The scene on one process and on each rank count of Rs: the same
 * datasets. */
static void same_on_ranks(const char *mpi, const char *name,
                          const char *text, const int *Rs, int nR)
{
    char ini[64], ser[64];
    snprintf(ini, sizeof ini, "%s.ini", name);
    snprintf(ser, sizeof ser, "%s_serial.h5", name);
    char scene[600], serial[600]; /* (tu_tmp's buffers rotate) */
    snprintf(scene, sizeof scene, "%s", tu_write(ini, text));
    snprintf(serial, sizeof serial, "%s", tu_tmp(ser));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", serial, "-q",
                            NULL),
                     0);
    for (int k = 0; k < nR; k++) {
        char out[600], err[600], args[1400], leaf[64];
        snprintf(leaf, sizeof leaf, "%s_R%d.h5", name, Rs[k]);
        snprintf(out, sizeof out, "%s", tu_tmp(leaf));
        snprintf(leaf, sizeof leaf, "%s_R%d.err", name, Rs[k]);
        snprintf(err, sizeof err, "%s", tu_tmp(leaf));
        snprintf(args, sizeof args, "'%s' -o '%s'", scene, out);
        int st = mpi_run(mpi, Rs[k], args, err);
        if (st) {
            char cmd[700];
            snprintf(cmd, sizeof cmd, "cat '%s' >&2", err);
            ck_assert(system(cmd) == 0);
        }
        ck_assert_msg(st == 0, "%s on %d ranks: status %d", name, Rs[k], st);
        tu_same_datasets(serial, out);
    }
}

START_TEST(same_bits_on_1_to_4_ranks)
{
    const char *mpi = mpi_bin();
    if (!mpi)
        return;
    /* R = 2 and 3 on the fast scene: stop_on_2_ranks_continue_on_3 */
    static const int fast[] = {1, 4}, cell[] = {3};
    same_on_ranks(mpi, "g72r_fast", fast_scene, fast, 2);
    same_on_ranks(mpi, "g72r_cell", cell_scene, cell, 1);
}
END_TEST

/* The scene stopped on 2 ranks after `stop` steps and continued on 3
 * from the checkpoint rank 0 wrote: the datasets and counters of an
 * uninterrupted run of one process. */
static void stop_2_continue_3(const char *mpi, const char *name,
                              const char *text, int stop)
{
    char leaf[64], scene[600], full[600], part[600], err[600], args[1400];
    snprintf(leaf, sizeof leaf, "%s.ini", name);
    snprintf(scene, sizeof scene, "%s", tu_write(leaf, text));
    snprintf(leaf, sizeof leaf, "%s_full.h5", name);
    snprintf(full, sizeof full, "%s", tu_tmp(leaf));
    snprintf(leaf, sizeof leaf, "%s_part.h5", name);
    snprintf(part, sizeof part, "%s", tu_tmp(leaf));
    snprintf(leaf, sizeof leaf, "%s.err", name);
    snprintf(err, sizeof err, "%s", tu_tmp(leaf));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q",
                            NULL),
                     0);
    snprintf(args, sizeof args, "'%s' -o '%s' --stop-after %d", scene, part,
             stop);
    ck_assert_int_eq(mpi_run(mpi, 2, args, err), 6);
    snprintf(args, sizeof args, "--restart '%s'", part);
    ck_assert_int_eq(mpi_run(mpi, 3, args, err), 0);
    tu_same_datasets(full, part);
    tu_same_counters(full, part);
}

START_TEST(stop_on_2_ranks_continue_on_3)
{
    const char *mpi = mpi_bin();
    if (mpi)
        stop_2_continue_3(mpi, "g72r_rs", fast_scene, 73);
}
END_TEST

/* 102400 particles (rank 0 gathers them in two blocks of 65536 at most
 * for every row and checkpoint), rows of positions and velocities every
 * step: stopped on 2 ranks after 3 steps, continued on 3, the datasets of
 * one process. */
static const char *blocks_scene =
    "[scene]\nmodel = greenspan72\ndt = 1e-2\nt_end = 0.06\n"
    "output_every = 1\n"
    "[greenspan72]\nwidth = 2000\nheight = 2000\ninterface = 1500\nd = 5\n"
    "m_heavy = 1\nm_light = 0.25\ngrid_nx = 320\ngrid_ny = 320\n"
    "v_random = 500\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\nmethod = fast\n"
    "[walls]\nomega = 0.9\n";

START_TEST(rows_and_checkpoints_gathered_in_blocks)
{
    const char *mpi = mpi_bin();
    if (mpi)
        stop_2_continue_3(mpi, "g72r_b", blocks_scene, 3);
}
END_TEST

/* Four particles in a list, two of them (1 at the right, 3 at the left:
 * on different ranks) too fast for the wall rule. */
static const char *failing_scene =
    "[scene]\nmodel = greenspan72\ndt = 1e-2\nt_end = %s\n"
    "output_every = 10\n"
    "[greenspan72]\nwidth = 100\nheight = 100\ninterface = 75\nd = 5\n"
    "m_heavy = 1\nm_light = 0.25\nlayout = list\n"
    "positions = 90 50 80 50 10 50 20 50\nvelocities = %s\n"
    "[repulsion]\nxi = 0.1\np = 2\nbeta = 2\ncutoff = 10\n"
    "[support]\ndx = 6.25\n"
    "[walls]\nomega = %s\nrule = %s\n";


/* A step that fails on two ranks at once fails as in one process: the
 * particle of the lowest number named, no wall hits of the failed step,
 * the same datasets.  A velocity that overflows while the position stays
 * in the box (the fortran rule with a tiny omega) fails only the final
 * state's check, on one rank: the run stops with status 3 instead of
 * leaving rank 0 waiting for the final row. */
START_TEST(failures_are_those_of_one_process)
{
    const char *mpi = mpi_bin();
    if (!mpi)
        return;
    char text[2048], scene[600], serial[600], out[600], errf[600];
    snprintf(text, sizeof text, failing_scene, "3", "1e9 0 10 0 1e9 0 0 10",
             "1", "clean");
    snprintf(scene, sizeof scene, "%s", tu_write("g72r_w.ini", text));
    snprintf(serial, sizeof serial, "%s", tu_tmp("g72r_w_s.h5"));
    snprintf(out, sizeof out, "%s", tu_tmp("g72r_w_2.h5"));
    snprintf(errf, sizeof errf, "%s", tu_tmp("g72r_w.err"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", serial, "-q",
                            NULL),
                     3);
    char args[1400];
    snprintf(args, sizeof args, "'%s' -o '%s'", scene, out);
    ck_assert_int_eq(mpi_run(mpi, 2, args, errf), 3);
    ck_assert_msg(file_has(errf, "particle 1 cannot be brought back"),
                  "not the particle one process names");
    tu_same_datasets(serial, out);
    tu_same_counters(serial, out);
    snprintf(text, sizeof text, failing_scene, "0.01",
             "1e160 0 10 0 0 0 -30 0", "1e-170", "fortran");
    snprintf(scene, sizeof scene, "%s", tu_write("g72r_n.ini", text));
    snprintf(out, sizeof out, "%s", tu_tmp("g72r_n_2.h5"));
    snprintf(args, sizeof args, "'%s' -o '%s'", scene, out);
    ck_assert_int_eq(mpi_run(mpi, 2, args, errf), 3);
    ck_assert(file_has(errf, "is not finite"));
}
END_TEST

/* SIGUSR1 to mpirun, which forwards it to every rank at its own moment:
 * the ranks agree on it at an exchange, all stop after the same step with
 * status 6, rank 0 writes the checkpoint, and one rank continues it to
 * the serial bits. */
START_TEST(usr1_stops_every_rank_at_one_step)
{
    const char *mpi = mpi_bin();
    if (!mpi)
        return;
    char scene[600], full[600], part[600], err[600];
    snprintf(scene, sizeof scene, "%s", tu_write("g72r_u.ini", fast_scene));
    snprintf(full, sizeof full, "%s", tu_tmp("g72r_u_full.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("g72r_u_part.h5"));
    snprintf(err, sizeof err, "%s", tu_tmp("g72r_u.err"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q",
                            "--set", "scene.t_end=40", NULL),
                     0);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        int fe = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0644),
            fo = open("/dev/null", O_WRONLY);
        dup2(fo, 1);
        dup2(fe, 2);
        execlp("mpirun", "mpirun", "-n", "2", "--oversubscribe", mpi, "run",
               scene, "-o", part, "-q", "--set", "scene.t_end=40",
               (char *)NULL);
        _exit(127);
    }
    char pp[700];
    snprintf(pp, sizeof pp, "%s.part", part);
    tu_wait_for_file(pp, 0);
    struct timespec pause = {0, 300000000};
    nanosleep(&pause, NULL);
    ck_assert(kill(pid, SIGUSR1) == 0);
    int ws;
    ck_assert(waitpid(pid, &ws, 0) == pid);
    ck_assert_msg(WIFEXITED(ws) && WEXITSTATUS(ws) == 6,
                  "mpirun status %d (the run ended before the signal?)", ws);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", part, "-q", NULL),
                     0);
    tu_same_datasets(full, part);
    tu_same_counters(full, part);
}
END_TEST


/* Run ARGS on 2 ranks: status 2 and a message holding `want`. */
static void refused(const char *mpi, const char *args, const char *want)
{
    const char *errf = tu_tmp("g72r_refused.err");
    ck_assert_int_eq(mpi_run(mpi, 2, args, errf), 2);
    ck_assert_msg(file_has(errf, want), "'%s' not in %s", want, errf);
}

START_TEST(refusals_name_the_model_or_key)
{
    const char *mpi = mpi_bin();
    if (!mpi)
        return;
    char args[1400];
    snprintf(args, sizeof args, "'%s' -o '%s'", tu_repo("runs/two_balls_B.ini"),
             tu_tmp("g72r_balls.h5"));
    refused(mpi, args, "the models that do: greenspan72");
    char scene[600];
    snprintf(scene, sizeof scene, "%s", tu_write("g72r_ref.ini", cell_scene));
    snprintf(args, sizeof args,
             "'%s' -o '%s' --set greenspan72.integrator=arkode", scene,
             tu_tmp("g72r_ark.h5"));
    refused(mpi, args, "[greenspan72] integrator");
}
END_TEST

Suite *suite_g72_ranks(void)
{
    Suite *s = suite_create("g72_ranks");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, same_bits_on_threaded_ranks);
    tcase_add_test(tc, library_refuses_naming_the_key);
    tcase_add_test(tc, same_bits_on_1_to_4_ranks);
    tcase_add_test(tc, refusals_name_the_model_or_key);
    tcase_add_test(tc, stop_on_2_ranks_continue_on_3);
    tcase_add_test(tc, rows_and_checkpoints_gathered_in_blocks);
    tcase_add_test(tc, failures_are_those_of_one_process);
    tcase_add_test(tc, usr1_stops_every_rank_at_one_step);
    suite_add_tcase(s, tc);
    return s;
}
