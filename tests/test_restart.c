/* test_restart.c: runs survive interruption.  A run stopped midway (by
 * --stop-after, or by SIGINT at an arbitrary step) and continued with
 * --restart produces bit for bit the datasets of an uninterrupted run. */
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <hdf5.h>

#include "ballfilm/h5out.h"
#include "testutil.h"

START_TEST(stop_and_restart_bit_identical)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("full.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("part.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q", "--set",
                            "scene.t_end=30", "--set", "scene.output_every=37",
                            NULL),
                     0);
    /* stop twice at odd steps, the second time with a periodic checkpoint
     * written in between (the later one must win) */
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", scene, "-o", part, "-q", "--set",
                    "scene.t_end=30", "--set", "scene.output_every=37", "--set",
                    "scene.checkpoint_every=0.5 s", "--stop-after", "123457",
                    NULL);
    ck_assert_msg(rc == 6, "exit %d: %s", rc, err);
    ck_assert_msg(strstr(err, "--restart") != NULL, "%s", err);
    free(err);
    rc = tu_run(NULL, NULL, "run", "--restart", part, "-q", "--stop-after",
                "77777", NULL);
    ck_assert_int_eq(rc, 6);
    rc = tu_run(NULL, &err, "run", "--restart", part, "-q", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    tu_same_datasets(full, part);
}
END_TEST

/* argv of `run SCENE -o OUT COMMON...` into argv (room for 8 more
 * arguments); returns the number of arguments */
static size_t run_argv(const char **argv, const char *scene, const char *out,
                       const char *const *common, size_t ncommon)
{
    size_t n = 0;
    argv[n++] = "run";
    argv[n++] = scene;
    argv[n++] = "-o";
    argv[n++] = out;
    for (size_t k = 0; k < ncommon; k++)
        argv[n++] = common[k];
    argv[n] = NULL;
    return n;
}

/* The same for runs of steps (core loop -> model advance -> ball system,
 * test_advance.c): no per-step analysis and energy checks every 11 steps,
 * so the loop hands the model runs up to the next row, check, checkpoint
 * or stop; the stops and checkpoints fall inside what would otherwise be
 * one run.  Verlet (its carried force is in the checkpoint) and MV2M. */
static void restart_runs(const char *method)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char full[512], part[512], set[64];
    snprintf(full, sizeof full, "%s.full.h5", tu_tmp(method));
    snprintf(part, sizeof part, "%s.part.h5", tu_tmp(method));
    snprintf(set, sizeof set, "scene.integrator=%s", method);
    const char *common[] = {"--set", set, "--set", "scene.t_end=30", "--set",
                            "scene.output_every=3701", "--set",
                            "scene.energy_every=11", "--set",
                            "return_map.enabled=no", "-q"};
    const char *argv[32];
    size_t n = run_argv(argv, scene, full, common,
                        sizeof common / sizeof common[0]);
    ck_assert_int_eq(tu_runv(NULL, NULL, argv), 0);
    argv[3] = part;
    argv[n++] = "--set";
    argv[n++] = "scene.checkpoint_every=0.4567 s";
    argv[n++] = "--stop-after";
    argv[n++] = "123457";
    argv[n] = NULL;
    ck_assert_int_eq(tu_runv(NULL, NULL, argv), 6);
    const char *const again[] = {"run", "--restart", part, "-q",
                                 "--stop-after", "50021", NULL};
    ck_assert_int_eq(tu_runv(NULL, NULL, again), 6);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", part, "-q", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    tu_same_datasets(full, part);
}

START_TEST(runs_of_steps_restart_identical)
{
    restart_runs("verlet");
    restart_runs("mv2m");
}
END_TEST

START_TEST(sigint_checkpoints_and_restart_identical)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("full2.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("part2.h5"));
    const char *bin = getenv("BALLFILM_BIN");
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        /* SIGINT caught even when this runner was started with it
         * ignored, which the program would honour */
        signal(SIGINT, SIG_DFL);
        if (!freopen("/dev/null", "w", stdout) ||
            !freopen(tu_tmp("sigint.err"), "w", stderr))
            _exit(126);
        execl(bin ? bin : "bin/ballfilm", "ballfilm", "run", scene, "-o", part,
              "-q", (char *)NULL);
        _exit(127);
    }
    /* under way: its file holds flushed rows */
    char marker[600];
    snprintf(marker, sizeof marker, "%s.part", part);
    tu_wait_for_file(marker, 8192);
    kill(pid, SIGINT);
    int status;
    waitpid(pid, &status, 0);
    ck_assert_msg(WIFEXITED(status) && WEXITSTATUS(status) == 6,
                  "status %d (expected exit 6: interrupted)", status);
    /* the one-line message says how to continue */
    FILE *f = fopen(tu_tmp("sigint.err"), "r");
    char line[1024] = "";
    ck_assert(f && fgets(line, sizeof line, f));
    fclose(f);
    ck_assert_msg(strstr(line, "ballfilm run --restart"), "%s", line);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", part, "-q", NULL), 0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q", NULL), 0);
    tu_same_datasets(full, part);
}
END_TEST

static double root_attr(const char *file, const char *name)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert(f >= 0);
    double v = NAN;
    hid_t a = H5Aopen(f, name, H5P_DEFAULT);
    ck_assert_msg(a >= 0, "%s: no attribute %s", file, name);
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    H5Fclose(f);
    return v;
}

/* The analyses of the balls model (return map with its pending contact,
 * Lyapunov shadow trajectory and sums) continue bit for bit too.  The
 * lower-heavier scene has contacts with several minima, so a stop can fall
 * inside a contact with a candidate pending. */
START_TEST(return_map_and_lyapunov_restart_identical)
{
    const char *scene = tu_repo("runs/two_balls_A.ini");
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("rm_full.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("rm_part.h5"));
    const char *common[] = {"--set", "scene.t_end=20", "--set",
                            "scene.output_every=53", "--set",
                            "return_map.enabled=yes", "--set",
                            "lyapunov.enabled=yes", "-q"};
    const char *argv[32];
    size_t n = run_argv(argv, scene, full, common,
                        sizeof common / sizeof common[0]);
    ck_assert_int_eq(tu_runv(NULL, NULL, argv), 0);
    /* first stop two steps after the 100th lowest point, i.e. inside that
     * floor contact with its candidate pending (checked in the checkpoint),
     * then at odd steps */
    bf_err herr = {0};
    double *tm;
    size_t nt, nt1;
    ck_assert(bf_h5_read(full, "/return_map/time", &tm, &nt, &nt1, &herr) == 0);
    ck_assert(nt > 100);
    char stop[32];
    snprintf(stop, sizeof stop, "%ld", (long)ceil(tm[100] / 1e-4) + 2);
    free(tm);
    argv[3] = part;
    argv[n++] = "--stop-after";
    argv[n++] = stop;
    argv[n] = NULL;
    ck_assert_int_eq(tu_runv(NULL, NULL, argv), 6);
    char ckpt[600];
    snprintf(ckpt, sizeof ckpt, "%s.ckpt", part);
    double *meta;
    size_t nm, nm1;
    ck_assert(bf_h5_read(ckpt, "/return_map.meta", &meta, &nm, &nm1, &herr) ==
              0);
    ck_assert_msg(nm == 3 && meta[0] == 100 && meta[2] == 1,
                  "checkpoint: %g points, pending %g", meta[0], meta[2]);
    free(meta);
    const char *const again[] = {"run", "--restart", part, "-q",
                                 "--stop-after", "50021", NULL};
    for (int k = 0; k < 3; k++)
        ck_assert_int_eq(tu_runv(NULL, NULL, again), 6);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", part, "-q", NULL);
    ck_assert_msg(rc == 0, "exit %d: %s", rc, err);
    free(err);
    tu_same_datasets(full, part);
    const char *attrs[] = {"lyapunov_exponent", "return_map_points",
                           "return_map_multi_minima"};
    for (int k = 0; k < 3; k++) {
        double a = root_attr(full, attrs[k]), b = root_attr(part, attrs[k]);
        ck_assert_msg(memcmp(&a, &b, sizeof a) == 0, "%s: %.17g vs %.17g",
                      attrs[k], a, b);
    }
    ck_assert(root_attr(full, "return_map_points") > 500);
    ck_assert(root_attr(full, "lyapunov_exponent") > 1);
}
END_TEST

START_TEST(restart_errors_are_clear)
{
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", "--restart", tu_tmp("none.h5"), NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "none.h5.ckpt"), "%s", err);
    free(err);
    rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "--restart",
                tu_tmp("x.h5"), NULL);
    ck_assert_int_eq(rc, 2);
    free(err);
}
END_TEST

Suite *suite_restart(void)
{
    Suite *s = suite_create("restart");
    TCase *tc = tu_tcase("balls");
    tcase_add_test(tc, stop_and_restart_bit_identical);
    tcase_add_test(tc, runs_of_steps_restart_identical);
    tcase_add_test(tc, sigint_checkpoints_and_restart_identical);
    tcase_add_test(tc, restart_errors_are_clear);
    tcase_add_test(tc, return_map_and_lyapunov_restart_identical);
    suite_add_tcase(s, tc);
    return s;
}
