/* test_h5out.c: what is written reads back exactly, and a run killed with
 * SIGKILL while it steps, at a random moment or before any chosen write of
 * a flush, leaves a file that opens and holds, in every series, the rows
 * of the last complete flush. */
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "testutil.h"

START_TEST(roundtrip_exact)
{
    const char *path = tu_tmp("rt.h5");
    bf_out *o;
    bf_err err = {0};
    ck_assert(bf_out_create(&o, path, &err) == BF_OK);
    bf_series *s1 = bf_out_series(o, "/a/one", 0, 0, "s", "1-D", &err);
    bf_series *s3 = bf_out_series(o, "/b/three", 3, 0, "cm", "2-D", &err);
    ck_assert(s1 && s3);
    /* awkward values: subnormal, negative zero, huge, pi */
    const double special[] = {4.9e-324, -0.0, 1.7976931348623157e308, 3.141592653589793};
    const size_t nrows = 10000; /* several chunks and several flushes */
    for (size_t k = 0; k < nrows; k++) {
        double v = special[k % 4] * (k % 7 == 0 ? 1 : 1.0 / (double)(k + 1));
        double row[3] = {v, (double)k, -v};
        ck_assert(bf_series_append(s1, &v) == BF_OK);
        ck_assert(bf_series_append(s3, row) == BF_OK);
        if (k % 3333 == 0)
            ck_assert(bf_out_flush(o, &err) == BF_OK);
    }
    double arr[6] = {1, 2, 3, 4, 5, 6};
    ck_assert(bf_out_array(o, "/fixed", arr, 2, 3, "g", "fixed", &err) == BF_OK);
    ck_assert(bf_out_attr_str(o, "/", "note", "héllo", &err) == BF_OK);
    ck_assert(bf_out_close(o, &err) == BF_OK);

    double *d;
    size_t n0, n1;
    ck_assert(bf_h5_read(path, "/a/one", &d, &n0, &n1, &err) == BF_OK);
    ck_assert(n0 == nrows && n1 == 0);
    for (size_t k = 0; k < nrows; k++) {
        double v = special[k % 4] * (k % 7 == 0 ? 1 : 1.0 / (double)(k + 1));
        ck_assert(memcmp(&d[k], &v, sizeof v) == 0); /* bit for bit */
    }
    free(d);
    ck_assert(bf_h5_read(path, "/b/three", &d, &n0, &n1, &err) == BF_OK);
    ck_assert(n0 == nrows && n1 == 3);
    for (size_t k = 0; k < nrows; k++)
        ck_assert(d[3 * k + 1] == (double)k);
    free(d);
    ck_assert(bf_h5_read(path, "/fixed", &d, &n0, &n1, &err) == BF_OK);
    ck_assert(n0 == 2 && n1 == 3 && d[5] == 6);
    free(d);
    char *s;
    ck_assert(bf_h5_read_attr_str(path, "/", "note", &s, &err) == BF_OK);
    ck_assert_str_eq(s, "héllo");
    free(s);
    ck_assert(bf_h5_read_attr_str(path, "/a/one", "unit", &s, &err) == BF_OK);
    ck_assert_str_eq(s, "s");
    free(s);
}
END_TEST

/* The program's file: provenance attributes and datasets. */
START_TEST(run_file_layout)
{
    const char *out = tu_tmp("hb.h5");
    int rc = tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"), "-o", out,
                    "-q", NULL);
    ck_assert_int_eq(rc, 0);
    bf_err err = {0};
    char *s;
    ck_assert(bf_h5_read_attr_str(out, "/", "scene_text", &s, &err) == BF_OK);
    ck_assert(strstr(s, "[spring]") != NULL);
    free(s);
    ck_assert(bf_h5_read_attr_str(out, "/", "scene.dt.unit", &s, &err) == BF_OK);
    ck_assert_str_eq(s, "s");
    free(s);
    ck_assert(bf_h5_read_attr_str(out, "/", "version", &s, &err) == BF_OK);
    ck_assert(strstr(s, "ballfilm") != NULL);
    free(s);
    ck_assert(bf_h5_read_attr_str(out, "/", "status", &s, &err) == BF_OK);
    ck_assert_str_eq(s, "ok");
    free(s);
    double *t, *x, *e;
    size_t n, n1, nx, nx1, ne, ne1;
    ck_assert(bf_h5_read(out, "/time", &t, &n, &n1, &err) == BF_OK);
    ck_assert(bf_h5_read(out, "/balls/position", &x, &nx, &nx1, &err) == BF_OK);
    ck_assert(bf_h5_read(out, "/energy/total", &e, &ne, &ne1, &err) == BF_OK);
    /* 1000 steps, output every 10 steps: rows 0, 10, ..., 1000 */
    ck_assert_uint_eq(n, 101);
    ck_assert(nx == 101 && nx1 == 1 && ne == 101);
    for (size_t k = 0; k < n; k++) {
        ck_assert(t[k] == (double)(10 * k) * 0.01);
        /* x = cos t to MV2M accuracy at dt = 0.01 */
        ck_assert_msg(fabs(x[k] - cos(t[k])) < 1e-5, "x(%g) = %.9f", t[k], x[k]);
    }
    free(t);
    free(x);
    free(e);
}
END_TEST

/* The first row of a killed two-ball run (output every 10 steps of 1e-4
 * s) that is not a real one, or n: step 10 k at t = step dt, the balls
 * above the floor and in order.  (A loop of ck_asserts would send a
 * message to the runner for each of some 10^5 rows.) */
static size_t first_unreal_row(const double *t, const double *step,
                               const double *x, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (!(step[k] == 10.0 * (double)k && t[k] == step[k] * 1e-4 &&
              isfinite(x[2 * k]) && x[2 * k] > 0 && x[2 * k + 1] > x[2 * k]))
            return k;
    return n;
}

START_TEST(sigkill_leaves_readable_file)
{
    const char *out = tu_tmp("killed.h5");
    const char *bin = getenv("BALLFILM_BIN");
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        freopen("/dev/null", "w", stdout);
        freopen("/dev/null", "w", stderr);
        execl(bin ? bin : "bin/ballfilm", "ballfilm", "run",
              tu_repo("runs/two_balls_B.ini"), "-o", out, "-q", "--set",
              "scene.t_end=1e5", "--set", "scene.output_every=10", "--set",
              "scene.flush_seconds=0.02", (char *)NULL);
        _exit(127);
    }
    /* killed once its file holds a few hundred flushed rows (read while it
     * is written, which it can be once it is in SWMR mode, 50 ms into the
     * run: h5out.h; a read that fails is retried) */
    char marker[600];
    snprintf(marker, sizeof marker, "%s.part", out);
    tu_wait_for_file(marker, 0);
    size_t seen = tu_wait_for_rows(marker, "/time", 300);
    /* a run's file is readable while it is written (its lock does not
     * keep HDF5 readers out: outpath.c, bf_path_lock) */
    ck_assert_msg(seen > 300, "the running output never read back");
    kill(pid, SIGKILL);
    int status;
    waitpid(pid, &status, 0);
    ck_assert(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    bf_err err = {0};
    double *t, *step, *x;
    size_t n, n1, ns, ns1, nx, nx1;
    /* a killed run leaves its file as OUT.part */
    out = tu_result(out);
    ck_assert_msg(strstr(out, ".part"), "%s", out);
    ck_assert_msg(bf_h5_read(out, "/time", &t, &n, &n1, &err) == BF_OK, "%s",
                  err.msg);
    ck_assert_msg(bf_h5_read(out, "/step", &step, &ns, &ns1, &err) == BF_OK,
                  "%s", err.msg);
    ck_assert(bf_h5_read(out, "/balls/position", &x, &nx, &nx1, &err) == BF_OK);
    /* rows were flushed, all datasets agree, and every row is a real row */
    ck_assert_msg(n > 100, "only %zu rows survived", n);
    ck_assert(ns == n && nx == n && nx1 == 2);
    size_t bad = first_unreal_row(t, step, x, n);
    ck_assert_msg(bad == n, "row %zu of %zu is step %g at t = %g", bad, n,
                  bad < n ? step[bad] : 0.0, bad < n ? t[bad] : 0.0);
    free(t);
    free(step);
    free(x);
}
END_TEST

/* What run_killed_at counts: the writes to the output file after it
 * entered SWMR mode, in a long run that flushes every millisecond; or the
 * writes of checkpoints (one every 1000 steps, t_end 20 s, a flush every
 * 512 KiB of rows), a kill between two flushes before SWMR mode. */
enum killed_run { FLUSHING_RUN, CHECKPOINTING_RUN };

/* bin/ballfilm on runs/two_balls_B.ini writing `out`, with
 * tests/killwrite.c preloaded to kill it before write k of `what`.
 * Returns the wait status. */
static int run_killed_at(const char *shim, const char *out, int k,
                         enum killed_run what)
{
    const char *bin = getenv("BALLFILM_BIN");
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        char at[32], asan[512];
        snprintf(at, sizeof at, "%d", k);
        /* the sanitizers' runtime wants to be loaded first */
        const char *a = getenv("ASAN_OPTIONS");
        snprintf(asan, sizeof asan, "%s%sverify_asan_link_order=0",
                 a ? a : "", a && *a ? ":" : "");
        setenv("ASAN_OPTIONS", asan, 1);
        setenv("BF_KILL_AT_WRITE", at, 1);
        if (what == CHECKPOINTING_RUN) {
            setenv("BF_KILL_IN", ".ckpt.tmp", 1);
            /* outside SWMR mode whatever the machine's speed: the output
             * enters it SWMR_AFTER (0.05 s) of wall time after appending
             * began, which a loaded machine under the sanitizers passed
             * before the 40th write of the checkpoints */
            setenv("BF_FREEZE_COARSE_CLOCK", "1", 1);
        }
        setenv("LD_PRELOAD", shim, 1);
        if (!freopen("/dev/null", "w", stdout) ||
            !freopen("/dev/null", "w", stderr))
            _exit(126);
        const char *scene = tu_repo("runs/two_balls_B.ini");
        const char *prog = bin ? bin : "bin/ballfilm";
        if (what == FLUSHING_RUN)
            execl(prog, "ballfilm", "run", scene, "-o", out, "-q", "--set",
                  "scene.t_end=1e5", "--set", "scene.output_every=10",
                  "--set", "scene.flush_seconds=0.001", (char *)NULL);
        else
            execl(prog, "ballfilm", "run", scene, "-o", out, "-q", "--set",
                  "scene.t_end=20", "--set", "scene.checkpoint_every=1000",
                  "--set", "scene.flush_seconds=1e9", (char *)NULL);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    return status;
}

/* A kill inside a flush.  tests/killwrite.c, preloaded into the program,
 * kills it before its K-th write to the file after the file entered SWMR
 * mode (h5out.h, bf_out_start_appending); a flush of this run is about 35
 * to 50 writes (the rows, the chunk indices, the lengths, the superblock,
 * the flush log), so K = 1, 3, ..., 95 falls in every part of two or
 * three flushes.  Before SWMR mode a kill among a flush's writes left
 * files that did not open ("addr overflow"), or datasets of different
 * lengths and rows of zeros, at about a third of these places. */
START_TEST(kill_at_every_write_keeps_the_file)
{
    const char *shim = getenv("BALLFILM_KILLWRITE");
    ck_assert_msg(shim && access(shim, R_OK) == 0,
                  "BALLFILM_KILLWRITE (build/tests/killwrite.so, made by "
                  "make build-tests) is not set or not there: %s",
                  shim ? shim : "(unset)");
    const char *out = tu_tmp("killwrite.h5");
    char part[600];
    snprintf(part, sizeof part, "%s.part", out);
    for (int k = 1; k <= 95; k += 2) {
        unlink(part);
        int status = run_killed_at(shim, out, k, FLUSHING_RUN);
        ck_assert_msg(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL,
                      "write %d: the run was not killed (status %d)", k,
                      status);
        bf_err err = {0};
        double *t, *step, *x;
        size_t n, n1, ns, ns1, nx, nx1;
        ck_assert_msg(bf_h5_read(part, "/time", &t, &n, &n1, &err) == BF_OK,
                      "write %d: %s", k, err.msg);
        ck_assert_msg(bf_h5_read(part, "/step", &step, &ns, &ns1, &err) ==
                          BF_OK,
                      "write %d: %s", k, err.msg);
        ck_assert_msg(bf_h5_read(part, "/balls/position", &x, &nx, &nx1,
                                 &err) == BF_OK,
                      "write %d: %s", k, err.msg);
        /* the rows of one flush in every dataset, every row a real one */
        ck_assert_msg(n > 0 && ns == n && nx == n && nx1 == 2,
                      "write %d: %zu, %zu and %zu rows", k, n, ns, nx);
        size_t bad = first_unreal_row(t, step, x, n);
        ck_assert_msg(bad == n, "write %d: row %zu of %zu is step %g at t = %g",
                      k, bad, n, bad < n ? step[bad] : 0.0,
                      bad < n ? t[bad] : 0.0);
        /* what `ballfilm info` lists: the same rows, and not the log */
        bf_h5_dataset *list;
        size_t nl;
        ck_assert(bf_h5_list(part, &list, &nl, &err) == BF_OK);
        for (size_t j = 0; j < nl; j++) {
            ck_assert_str_ne(list[j].path, "/flushed_rows");
            if (!strcmp(list[j].path, "/time") ||
                !strcmp(list[j].path, "/balls/velocity"))
                ck_assert_uint_eq(list[j].dims[0], n);
        }
        free(list);
        free(t);
        free(step);
        free(x);
    }
    /* killed before SWMR mode, between two flushes (inside the writes of
     * a checkpoint, a few checkpoints into the run): the file keeps HDF5's
     * open-for-writing mark, the program's readers read past it, and
     * --restart continues from the last whole checkpoint to the
     * uninterrupted run's datasets */
    char ckpt[700];
    snprintf(ckpt, sizeof ckpt, "%s.ckpt", out);
    unlink(part);
    unlink(ckpt);
    int status = run_killed_at(shim, out, 40, CHECKPOINTING_RUN);
    ck_assert(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    unsigned char sb[12] = {0};
    FILE *f = fopen(part, "rb");
    ck_assert(f && fread(sb, 1, sizeof sb, f) == sizeof sb);
    fclose(f);
    ck_assert_msg(sb[8] >= 2 && (sb[11] & 0x05) == 0x01,
                  "superblock %d, flags %#x: not marked open for writing "
                  "outside SWMR mode", sb[8], sb[11]);
    bf_err err = {0};
    double *t;
    size_t n, n1;
    ck_assert_msg(bf_h5_read(part, "/time", &t, &n, &n1, &err) == BF_OK, "%s",
                  err.msg);
    free(t);
    char *msg = NULL;
    int rc = tu_run(NULL, &msg, "run", "--restart", out, "-q", NULL);
    ck_assert_msg(rc == 0, "restart: exit %d\n%s", rc, msg);
    free(msg);
    const char *full = tu_tmp("killwrite_full.h5");
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/two_balls_B.ini"),
                            "-o", full, "-q", "--set", "scene.t_end=20",
                            "--set", "scene.checkpoint_every=1000", "--set",
                            "scene.flush_seconds=1e9", NULL),
                     0);
    tu_same_datasets(out, full);
}
END_TEST

/* A full disk (simulated with RLIMIT_FSIZE: writes beyond 2 MiB fail with
 * EFBIG) ends the run with status 5 and a message, not a crash or a silent
 * truncated file; an unwritable path is refused at the start. */
START_TEST(full_disk_and_bad_path)
{
    const char *out = tu_tmp("full.h5");
    const char *bin = getenv("BALLFILM_BIN");
    const char *errf = tu_tmp("full.err");
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {2u << 20, 2u << 20};
        setrlimit(RLIMIT_FSIZE, &rl);
        if (!freopen("/dev/null", "w", stdout) || !freopen(errf, "w", stderr))
            _exit(126);
        execl(bin ? bin : "bin/ballfilm", "ballfilm", "run",
              tu_repo("runs/two_balls_B.ini"), "-o", out, "-q", "--set",
              "scene.output_every=1", "--set", "scene.flush_seconds=0.05",
              (char *)NULL);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 5,
                  "status %d (expected exit 5)", status);
    FILE *f = fopen(errf, "r");
    char line[1024] = "";
    ck_assert(f && fgets(line, sizeof line, f));
    fclose(f);
    ck_assert_msg(strstr(line, "I/O error") && strstr(line, "step") &&
                      strstr(line, "disk full"),
                  "%s", line);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    "/nonexistent-dir/x.h5", NULL);
    ck_assert_int_eq(rc, 5);
    ck_assert_msg(strstr(err, "/nonexistent-dir/x.h5"), "%s", err);
    free(err);
}
END_TEST

/* the program's peak resident memory in MiB, from its summary line */
static double peak_mib(const char *t_end)
{
    char *out = NULL, set[64];
    snprintf(set, sizeof set, "scene.t_end=%s", t_end);
    int rc = tu_run(&out, NULL, "run", tu_repo("runs/two_balls_B.ini"), "-q",
                    "-o", tu_tmp("mem.h5"), "--set", set, NULL);
    ck_assert_msg(rc == 0, "exit %d", rc);
    const char *p = out ? strstr(out, "peak memory:") : NULL;
    ck_assert_msg(p, "no peak memory line in %s", out ? out : "(nothing)");
    double mib = strtod(p + strlen("peak memory:"), NULL);
    free(out);
    return mib;
}

/* A long run needs no more memory than a short one: the rows go to the
 * file as they come (at most 512 KiB buffered), the chunk cache holds one
 * chunk per series and the return map is not kept in memory.  The shipped two-ball scene at t_end = 10 s and
 * 1000 s (1e5 steps and 1e7, 1e5 output rows, 20000 return-map points):
 * peaks within 2 MiB of each other (before: 8 and 34 MiB).  Not under the
 * sanitizers, whose shadow memory grows with what is allocated and freed. */
START_TEST(memory_does_not_grow_with_the_run)
{
    if (getenv("BALLFILM_SANITIZED"))
        return;
    const double a = peak_mib("10"), b = peak_mib("1000");
    ck_assert_msg(b - a < 2.0, "peak memory %.1f MiB at t_end = 10 s, %.1f "
                  "MiB at 1000 s", a, b);
}
END_TEST

Suite *suite_h5out(void)
{
    Suite *s = suite_create("h5out");
    TCase *tc = tu_tcase("io");
    tcase_add_test(tc, roundtrip_exact);
    tcase_add_test(tc, run_file_layout);
    tcase_add_test(tc, sigkill_leaves_readable_file);
    tcase_add_test(tc, kill_at_every_write_keeps_the_file);
    tcase_add_test(tc, full_disk_and_bad_path);
    tcase_add_test(tc, memory_does_not_grow_with_the_run);
    suite_add_tcase(s, tc);
    return s;
}
