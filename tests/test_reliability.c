/* test_reliability.c: what a user can rely on when things go wrong
 * (docs/reliability.md): two runs on one output path, a result that
 * survives a failing or killed new run, an output equal to an input, a full
 * disk, damaged and edited checkpoints, restarts that would change the
 * physics, an interrupt during set-up, an interrupted sweep.
 *
 * No test waits a fixed time: a background run is waited for by a marker
 * (its output file appearing with data, a line on its stderr), and
 * signals that must arrive "early" are sent while blocked, so that they
 * are pending when the program starts. */
#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "testutil.h"

static const char *bin(void)
{
    const char *b = getenv("BALLFILM_BIN");
    return b ? b : "bin/ballfilm";
}

/* Start `prog` (argv[0] is given) in the background with stdout/stderr to
 * files; with `blocked`, SIGINT is blocked (and so pending if sent) when
 * it starts. */
static pid_t start_prog(const char *prog, const char *const *argv,
                        const char *errfile, int blocked)
{
    /* blocked before the fork, so that the child has it blocked from its
     * first instruction on, whenever the signal is sent */
    sigset_t set, old;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    if (blocked)
        sigprocmask(SIG_BLOCK, &set, &old);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid > 0 && blocked)
        sigprocmask(SIG_SETMASK, &old, NULL);
    if (pid == 0) {
        /* the tests send SIGINT: caught, even when this runner was
         * started with it ignored (nohup, a script's background job),
         * which the program would honour */
        signal(SIGINT, SIG_DFL);
        int fo = open("/dev/null", O_WRONLY);
        int fe = open(errfile ? errfile : "/dev/null",
                      O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fo, 1);
        dup2(fe, 2);
        size_t n = 0;
        while (argv[n])
            n++;
        char **a = calloc(n + 2, sizeof *a);
        a[0] = (char *)prog;
        for (size_t k = 0; k < n; k++)
            a[k + 1] = (char *)argv[k];
        execvp(prog, a);
        _exit(127);
    }
    return pid;
}

/* The program (bin/ballfilm) with arguments argv. */
static pid_t start(const char *const *argv, const char *errfile, int blocked)
{
    return start_prog(bin(), argv, errfile, blocked);
}

static int finish(pid_t pid)
{
    int status;
    ck_assert(waitpid(pid, &status, 0) == pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

static void pause_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void wait_for_line(const char *path, const char *text)
{
    for (int k = 0; k < 60000; k++) {
        FILE *f = fopen(path, "r");
        char line[1024];
        int found = 0;
        while (f && fgets(line, sizeof line, f))
            found |= strstr(line, text) != NULL;
        if (f)
            fclose(f);
        if (found)
            return;
        pause_ms(1);
    }
    ck_abort_msg("'%s' never appeared in %s", text, path);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "%s", path);
    char *buf = calloc(1, 1 << 20);
    size_t n = fread(buf, 1, (1 << 20) - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* A byte-for-byte copy (checkpoints are binary). */
static void copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
    ck_assert_msg(in && out, "%s -> %s", from, to);
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        ck_assert(fwrite(buf, 1, n, out) == n);
    fclose(in);
    ck_assert(fclose(out) == 0);
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* Every case file of a sweep of `n` cases in dir is free: no writer (a
 * worker, a rank) is left. */
static void no_writer_left(const char *dir, int n)
{
    char part[800];
    for (int k = 0; k < n; k++) {
        snprintf(part, sizeof part, "%s/case_%05d.h5.part", dir, k);
        int fd = open(part, O_RDWR);
        if (fd < 0)
            continue;
        ck_assert_msg(tu_part_unlocked(fd), "%s is still locked", part);
        close(fd);
    }
}

/* A second run on the output path of a running one is refused before it
 * touches anything; the earlier result survives the running run and its
 * killing; a new run that fails leaves it alone. */
START_TEST(one_output_path_one_run)
{
    char out[600], copy[600], part[700], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("owned.h5"));
    snprintf(copy, sizeof copy, "%s", tu_tmp("owned_copy.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(errf, sizeof errf, "%s", tu_tmp("owned.err"));
    /* an earlier result */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", copy, "-q", NULL),
                     0);
    /* a long run on the same path, under way */
    const char *argv[] = {"run", tu_repo("runs/two_balls_B.ini"), "-o", out,
                          "-q", "--set", "scene.t_end=1e6", "--set",
                          "scene.flush_seconds=0.01", NULL};
    pid_t a = start(argv, errf, 0);
    tu_wait_for_file(part, 4096);
    tu_wait_for_rows(part, "/time", 1);
    /* the second run is refused, exit 5, and names the reason */
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o", out,
                    "-q", NULL);
    ck_assert_int_eq(rc, 5);
    ck_assert_msg(strstr(err, "in use"), "%s", err);
    free(err);
    tu_same_datasets(out, copy);
    /* killing the long run leaves its part and the earlier result */
    kill(a, SIGKILL);
    ck_assert_int_eq(finish(a), -SIGKILL);
    tu_same_datasets(out, copy);
    double *t;
    size_t n, n1;
    bf_err e = {0};
    ck_assert_msg(bf_h5_read(part, "/time", &t, &n, &n1, &e) == BF_OK, "%s",
                  e.msg);
    ck_assert(n > 1);
    free(t);
    /* a new run that fails (bad input) does not touch the result */
    rc = tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"), "-o", out,
                "-q", "--set", "spring.stiffness=-1", NULL);
    ck_assert_int_eq(rc, 2);
    tu_same_datasets(out, copy);
    /* the next run on the path (the lock went with the killed run) ends
     * by replacing the result */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", "--set", "scene.t_end=5", NULL),
                     0);
    ck_assert(!exists(part));
}
END_TEST

START_TEST(output_equal_to_an_input_refused)
{
    char scene[600];
    snprintf(scene, sizeof scene, "%s", tu_tmp("input.ini"));
    copy_file(tu_repo("runs/harmonic.ini"), scene);
    char *before = slurp(scene), *err = NULL;
    int rc = tu_run(NULL, &err, "run", scene, "-o", scene, "-q", NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "input"), "%s", err);
    char *after = slurp(scene);
    ck_assert_str_eq(before, after);
    free(before);
    free(after);
    free(err);
}
END_TEST

/* A full disk (the file-size limit at 2 MiB): the run stops with exit 5
 * naming the cause; what it wrote before is a readable file; after room is
 * made, --restart continues from the last checkpoint and ends with the
 * datasets of an uninterrupted run. */
START_TEST(full_disk_readable_and_restartable)
{
    char out[600], full[600], part[700], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("disk.h5"));
    snprintf(full, sizeof full, "%s", tu_tmp("disk_full_run.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(errf, sizeof errf, "%s", tu_tmp("disk.err"));
    const char *common[] = {"--set", "scene.t_end=60", "--set",
                            "scene.output_every=20", "--set",
                            "scene.checkpoint_every=2 s", "--set",
                            "scene.flush_seconds=0.001"};
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {2u << 20, 2u << 20};
        setrlimit(RLIMIT_FSIZE, &rl);
        if (!freopen("/dev/null", "w", stdout) || !freopen(errf, "w", stderr))
            _exit(126);
        execl(bin(), "ballfilm", "run", tu_repo("runs/two_balls_B.ini"), "-o",
              out, "-q", common[0], common[1], common[2], common[3], common[4],
              common[5], common[6], common[7], (char *)NULL);
        _exit(127);
    }
    ck_assert_int_eq(finish(pid), 5);
    char *msg = slurp(errf);
    ck_assert_msg(strstr(msg, "disk full") && strstr(msg, "step"), "%s", msg);
    free(msg);
    /* the file opens and holds whole rows */
    double *t, *x;
    size_t n, n1, nx, nx1;
    bf_err e = {0};
    ck_assert_msg(bf_h5_read(part, "/time", &t, &n, &n1, &e) == BF_OK, "%s",
                  e.msg);
    ck_assert(bf_h5_read(part, "/balls/position", &x, &nx, &nx1, &e) ==
              BF_OK);
    ck_assert(n > 100 && nx == n && nx1 == 2);
    free(t);
    free(x);
    /* room again: continue */
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", out, "-q", NULL);
    ck_assert_msg(rc == 0, "restart: exit %d\n%s", rc, err);
    free(err);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"),
                            "-o", full, "-q", common[0], common[1], common[2],
                            common[3], common[4], common[5], common[6],
                            common[7], NULL),
                     0);
    tu_same_datasets(out, full);
}
END_TEST

/* A run killed outright while it steps (its file in SWMR mode, HDF5's
 * open-for-writing mark on it) continues from its last checkpoint: the
 * restart clears the mark, drops the rows after the checkpoint, and ends
 * with the datasets of an uninterrupted run. */
START_TEST(sigkill_then_restart_identical)
{
    char out[600], full[600], part[700], ckpt[700];
    snprintf(out, sizeof out, "%s", tu_tmp("killed.h5"));
    snprintf(full, sizeof full, "%s", tu_tmp("killed_full.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(ckpt, sizeof ckpt, "%s.ckpt", out);
/* 3e7 steps, about a second; a checkpoint every 5e5 steps */
#define KILLED_RUN_SETS                                                     \
    "--set", "scene.t_end=3000", "--set", "scene.checkpoint_every=50 s",    \
        "--set", "scene.flush_seconds=0.01"
    const char *argv[] = {"run", tu_repo("runs/two_balls_B.ini"), "-o", out,
                          "-q", KILLED_RUN_SETS, NULL};
    pid_t pid = start(argv, NULL, 0);
    tu_wait_for_file(ckpt, 0);
    /* readable rows: the file is in SWMR mode (h5out.h) */
    tu_wait_for_rows(part, "/time", 1000);
    kill(pid, SIGKILL);
    ck_assert_int_eq(finish(pid), -SIGKILL);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", out, "-q", NULL);
    ck_assert_msg(rc == 0, "restart: exit %d\n%s", rc, err);
    free(err);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"),
                            "-o", full, "-q", KILLED_RUN_SETS, NULL),
                     0);
#undef KILLED_RUN_SETS
    tu_same_datasets(out, full);
}
END_TEST

/* Replace the first value of an integer dataset of an HDF5 file. */
static void poke_i64(const char *file, const char *dset, long long v)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDWR, H5P_DEFAULT);
    ck_assert(f >= 0);
    hid_t d = H5Dopen2(f, dset, H5P_DEFAULT);
    ck_assert(d >= 0);
    hid_t sp = H5Dget_space(d);
    hsize_t start = 0, count = 1;
    H5Sselect_hyperslab(sp, H5S_SELECT_SET, &start, NULL, &count, NULL);
    hid_t ms = H5Screate_simple(1, &count, NULL);
    int64_t val = v;
    ck_assert(H5Dwrite(d, H5T_NATIVE_INT64, ms, sp, H5P_DEFAULT, &val) >= 0);
    H5Sclose(ms);
    H5Sclose(sp);
    H5Dclose(d);
    H5Fclose(f);
}

/* A checkpoint that was edited or cut short is refused with a message
 * (exit 2), never trusted: no loop, no crash, no spliced rows. */
START_TEST(damaged_checkpoints_refused)
{
    char out[600], ck[700];
    snprintf(out, sizeof out, "%s", tu_tmp("ck.h5"));
    snprintf(ck, sizeof ck, "%s.ckpt", out);
    int rc = tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"), "-o",
                    out, "-q", "--set", "scene.t_end=5", "--stop-after",
                    "10000", NULL);
    ck_assert_int_eq(rc, 6);
    /* an edited count (the file's seal no longer matches its bytes;
     * edits that are sealed again: test_fuzz.c,
     * checkpoint_damage_and_edits) */
    poke_i64(ck, "sim.n", 999999999);
    char *err = NULL;
    rc = tu_run(NULL, &err, "run", "--restart", out, "-q", NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "damaged") && strstr(err, "changed"), "%s", err);
    free(err);
    /* a file cut short */
    struct stat sb;
    ck_assert(stat(ck, &sb) == 0);
    ck_assert(truncate(ck, sb.st_size / 2) == 0);
    rc = tu_run(NULL, &err, "run", "--restart", out, "-q", NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "checkpoint"), "%s", err);
    free(err);
}
END_TEST

/* The output and its checkpoint carry the run's identifier and the
 * scene's hash; a checkpoint of another run (even of the same scene) is
 * refused with exit 2 before the output is touched, and the right one
 * still continues it. */
START_TEST(checkpoint_of_another_run_refused)
{
    char a[600], b[600], cka[700], ckb[700], keep[800], parta[700];
    snprintf(a, sizeof a, "%s", tu_tmp("runa.h5"));
    snprintf(b, sizeof b, "%s", tu_tmp("runb.h5"));
    snprintf(cka, sizeof cka, "%s.ckpt", a);
    snprintf(ckb, sizeof ckb, "%s.ckpt", b);
    snprintf(keep, sizeof keep, "%s.mine", cka);
    snprintf(parta, sizeof parta, "%s.part", a);
    const char *outs[2] = {a, b};
    for (int k = 0; k < 2; k++)
        ck_assert_int_eq(tu_run(NULL, NULL, "run",
                                tu_repo("runs/two_balls_B.ini"), "-o", outs[k],
                                "-q", "--set", "scene.t_end=2",
                                "--stop-after", "3000", NULL),
                         6);
    char *ida = NULL, *idb = NULL, *ha = NULL, *hb = NULL;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_str(parta, "/", "run_id", &ida, &e) == BF_OK);
    ck_assert(bf_h5_read_attr_str(tu_result(b), "/", "run_id", &idb, &e) ==
              BF_OK);
    ck_assert(bf_h5_read_attr_str(parta, "/", "scene_hash", &ha, &e) ==
              BF_OK);
    ck_assert(bf_h5_read_attr_str(tu_result(b), "/", "scene_hash", &hb,
                                  &e) == BF_OK);
    ck_assert_msg(strlen(ida) == 16 && strcmp(ida, idb), "%s %s", ida, idb);
    ck_assert_str_eq(ha, hb); /* the same scene and overrides */
    /* B's checkpoint next to A's output */
    rename(cka, keep);
    copy_file(ckb, cka);
    struct stat before, after;
    ck_assert(stat(parta, &before) == 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", a, "-q", NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "another run") && strstr(err, ida) &&
                      strstr(err, idb),
                  "%s", err);
    free(err);
    ck_assert(stat(parta, &after) == 0);
    ck_assert(before.st_size == after.st_size &&
              before.st_mtime == after.st_mtime);
    /* its own checkpoint continues it */
    rename(keep, cka);
    rc = tu_run(NULL, &err, "run", "--restart", a, "-q", NULL);
    ck_assert_msg(rc == 0, "%s", err);
    free(err);
    /* another override is another scene */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"),
                            "-o", b, "-q", "--set", "scene.t_end=2.5", NULL),
                     0);
    free(hb);
    ck_assert(bf_h5_read_attr_str(b, "/", "scene_hash", &hb, &e) == BF_OK);
    ck_assert_str_ne(ha, hb);
    free(ida);
    free(idb);
    free(ha);
    free(hb);
}
END_TEST

/* --restart --set may change when a run ends and how often it writes,
 * not what it computes. */
START_TEST(restart_cannot_change_the_physics)
{
    char out[600];
    snprintf(out, sizeof out, "%s", tu_tmp("phys.h5"));
    int rc = tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"), "-o",
                    out, "-q", "--set", "scene.t_end=2", "--stop-after", "5000",
                    NULL);
    ck_assert_int_eq(rc, 6);
    const char *refused[] = {"scene.dt=1e-5", "ball.1.mass=0.9",
                             "floor.k=2e7", "scene.integrator=verlet"};
    for (int k = 0; k < 4; k++) {
        char *err = NULL;
        rc = tu_run(NULL, &err, "run", "--restart", out, "-q", "--set",
                    refused[k], NULL);
        ck_assert_int_eq(rc, 2);
        char key[64];
        snprintf(key, sizeof key, "%.*s", (int)strcspn(refused[k], "="),
                 refused[k]);
        ck_assert_msg(strstr(err, key), "%s: %s", refused[k], err);
        free(err);
    }
    rc = tu_run(NULL, NULL, "run", "--restart", out, "-q", "--set",
                "scene.t_end=3", NULL);
    ck_assert_int_eq(rc, 0);
}
END_TEST

START_TEST(checkpoint_removed_when_the_run_ends)
{
    char out[600], ck[700];
    snprintf(out, sizeof out, "%s", tu_tmp("ckend.h5"));
    snprintf(ck, sizeof ck, "%s.ckpt", out);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", "--set",
                            "scene.checkpoint_every=100", NULL),
                     0);
    ck_assert(!exists(ck));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", "--set",
                            "scene.checkpoint_every=100", "--keep-checkpoint",
                            NULL),
                     0);
    ck_assert(exists(ck));
}
END_TEST

/* An interrupt that arrives before the handlers could run (here: pending
 * when the program starts) ends the run in set-up with status 6 and
 * writes nothing. */
START_TEST(interrupt_during_setup)
{
    char out[600], part[700], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("early.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(errf, sizeof errf, "%s", tu_tmp("early.err"));
    const char *argv[] = {"run", tu_repo("runs/two_balls_B.ini"), "-o", out,
                          "-q", NULL};
    pid_t pid = start(argv, errf, 1);
    kill(pid, SIGINT);
    ck_assert_int_eq(finish(pid), 6);
    ck_assert(!exists(out) && !exists(part));
    char *msg = slurp(errf);
    ck_assert_msg(strstr(msg, "interrupted"), "%s", msg);
    free(msg);
}
END_TEST

/* A sweep of 4 long cases on a pool of 2 workers, started as `name` in
 * dir, once its first case is being written. */
static pid_t start_pool_sweep(const char *name, char *dir, size_t cap)
{
    char errf[700], part[800];
    snprintf(dir, cap, "%s", tu_tmp(name));
    snprintf(errf, sizeof errf, "%s.err", dir);
    const char *argv[] = {"sweep", tu_repo("runs/two_balls_A.ini"), "--vary",
                          "ball.1.mass=0.5:2:4", "--set", "scene.t_end=1e5",
                          "--jobs", "2", "-o", dir, NULL};
    pid_t pid = start(argv, errf, 0);
    wait_for_line(errf, "to run on");
    snprintf(part, sizeof part, "%s/case_00000.h5.part", dir);
    tu_wait_for_file(part, 0);
    return pid;
}

/* An interrupted sweep forwards the interrupt to its workers and ends
 * with status 6; no worker is left writing a case. */
START_TEST(interrupted_sweep_stops_its_workers)
{
    char dir[600];
    pid_t pid = start_pool_sweep("sweep_int", dir, sizeof dir);
    kill(pid, SIGINT);
    ck_assert_int_eq(finish(pid), 6);
    /* every case file it was writing is free again: its writer is gone */
    no_writer_left(dir, 4);
}
END_TEST

/* A sweep killed outright (SIGKILL, nothing forwarded) takes its workers
 * with it: they die with their parent (each gets SIGTERM, stops its case
 * as interrupted and exits), so no case file stays locked by a worker
 * racing a later resume.  Polled (each case file's lock) for at most a
 * minute; the workers' cases would run for hours otherwise. */
START_TEST(killed_sweep_takes_its_workers)
{
    char dir[600], part[800];
    pid_t pid = start_pool_sweep("sweep_kill", dir, sizeof dir);
    kill(pid, SIGKILL);
    ck_assert_int_eq(finish(pid), -SIGKILL);
    int locked = 1;
    for (int k = 0; k < 60000 && locked; k++) {
        locked = 0;
        for (int c = 0; c < 4; c++) {
            snprintf(part, sizeof part, "%s/case_%05d.h5.part", dir, c);
            int fd = open(part, O_RDWR);
            if (fd < 0)
                continue;
            locked |= !tu_part_unlocked(fd);
            close(fd);
        }
        if (locked)
            pause_ms(1);
    }
    ck_assert_msg(!locked, "a worker still writes a case a minute after its "
                           "sweep was killed");
}
END_TEST

/* An MPI sweep under mpirun (Open MPI 4.1).  SIGUSR1 to mpirun, which
 * Open MPI forwards to every rank at once: the running cases stop as
 * interrupted runs, no case starts, the summary is written and the sweep
 * ends with status 6 (every rank reaches MPI_Finalize, so no rank is
 * killed early).  SIGINT to mpirun (Ctrl-C) is not forwarded: mpirun
 * aborts the job, sending each rank SIGCONT at once, SIGTERM after
 * odls_base_sigkill_timeout (1 s) and SIGKILL one more timeout later, and
 * exits with its own status 1.  A rank that gets the SIGTERM stops its
 * case as interrupted if it has the time, one killed leaves its case's
 * .part unlocked: which one happens depends on the load, so for SIGINT
 * only what always holds is checked: status 1, no rank left, and a rerun
 * of the sweep runs what did not finish and ends with status 0. */
START_TEST(interrupted_mpi_sweep)
{
    const char *mpi = getenv("BALLFILM_MPI_BIN");
    if (getenv("BALLFILM_SANITIZED") || !mpi || access(mpi, X_OK) ||
        system("command -v mpirun >/dev/null 2>&1")) {
        fprintf(stderr, "note: interrupted_mpi_sweep skipped (no MPI)\n");
        return;
    }
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    static const struct {
        int sig, status;
        const char *name;
    } how[] = {{SIGUSR1, 6, "usr1"}, {SIGINT, 1, "int"}};
    for (int h = 0; h < 2; h++) {
        char dir[600], errf[700], name[64], part[800];
        snprintf(name, sizeof name, "mpi_sweep_%s", how[h].name);
        snprintf(dir, sizeof dir, "%s", tu_tmp(name));
        snprintf(errf, sizeof errf, "%s.err", dir);
        const char *argv[] = {"-n", "2", "--oversubscribe", mpi, "sweep",
                              tu_repo("runs/two_balls_A.ini"), "--vary",
                              "ball.1.mass=0.5:2:4", "--set",
                              "scene.t_end=1000", "-o", dir, NULL};
        pid_t pid = start_prog("mpirun", argv, errf, 0);
        /* both ranks are computing: rank 0's thread takes case 0 first,
         * rank 1 the next */
        snprintf(part, sizeof part, "%s/case_00001.h5.part", dir);
        tu_wait_for_file(part, 0);
        snprintf(part, sizeof part, "%s/case_00000.h5.part", dir);
        tu_wait_for_file(part, 0);
        kill(pid, how[h].sig);
        int rc = finish(pid);
        char *msg = slurp(errf);
        ck_assert_msg(rc == how[h].status, "%s: exit %d\n%s", how[h].name, rc,
                      msg);
        if (how[h].sig == SIGUSR1)
            ck_assert_msg(strstr(msg, "interrupted"), "%s: %s", how[h].name,
                          msg);
        free(msg);
        no_writer_left(dir, 4);
        char *err = NULL;
        rc = tu_run(NULL, &err, "sweep", tu_repo("runs/two_balls_A.ini"),
                    "--vary", "ball.1.mass=0.5:2:4", "--set",
                    "scene.t_end=1000", "-o", dir, "-q", NULL);
        ck_assert_msg(rc == 0, "%s: the rerun: exit %d\n%s", how[h].name, rc,
                      err);
        free(err);
        for (int k = 0; k < 4; k++) {
            char out[800];
            snprintf(out, sizeof out, "%s/case_%05d.h5", dir, k);
            ck_assert_msg(exists(out), "%s: %s missing", how[h].name, out);
        }
    }
}
END_TEST

/* A sweep rerun after its scene was edited is refused instead of reusing
 * the old scene's results. */
START_TEST(sweep_of_an_edited_scene_refused)
{
    char dir[600], scene[600];
    snprintf(dir, sizeof dir, "%s", tu_tmp("sweep_edit"));
    snprintf(scene, sizeof scene, "%s", tu_tmp("sweep_edit.ini"));
    copy_file(tu_repo("runs/two_balls_A.ini"), scene);
    ck_assert_int_eq(tu_run(NULL, NULL, "sweep", scene, "--vary",
                            "ball.1.mass=0.9,1.1", "--set", "scene.t_end=1",
                            "-o", dir, "-q", NULL),
                     0);
    /* any edit, even of a comment, is another scene */
    FILE *f = fopen(scene, "a");
    ck_assert(f && fputs("; edited\n", f) >= 0 && fclose(f) == 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "sweep", scene, "--vary", "ball.1.mass=0.9,1.1",
                    "--set", "scene.t_end=1", "-o", dir, "-q", NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "different sweep"), "%s", err);
    free(err);
}
END_TEST

Suite *suite_reliability(void)
{
    Suite *s = suite_create("reliability");
    TCase *tc = tu_tcase("reliability");
    tcase_add_test(tc, one_output_path_one_run);
    tcase_add_test(tc, output_equal_to_an_input_refused);
    tcase_add_test(tc, full_disk_readable_and_restartable);
    tcase_add_test(tc, sigkill_then_restart_identical);
    tcase_add_test(tc, damaged_checkpoints_refused);
    tcase_add_test(tc, checkpoint_of_another_run_refused);
    tcase_add_test(tc, restart_cannot_change_the_physics);
    tcase_add_test(tc, checkpoint_removed_when_the_run_ends);
    tcase_add_test(tc, interrupt_during_setup);
    tcase_add_test(tc, interrupted_sweep_stops_its_workers);
    tcase_add_test(tc, killed_sweep_takes_its_workers);
    tcase_add_test(tc, interrupted_mpi_sweep);
    tcase_add_test(tc, sweep_of_an_edited_scene_refused);
    suite_add_tcase(s, tc);
    return s;
}
