/* test_restart.c: runs survive interruption.  A run stopped midway (by
 * --stop-after, or by SIGINT at an arbitrary step) and continued with
 * --restart produces bit for bit the datasets of an uninterrupted run. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "testutil.h"

static const char *const ball_sets[] = {"/time", "/step", "/balls/position",
                                        "/balls/velocity", "/energy/total",
                                        NULL};

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
    tu_same_named(full, part, ball_sets);
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
        if (!freopen("/dev/null", "w", stdout) ||
            !freopen(tu_tmp("sigint.err"), "w", stderr))
            _exit(126);
        execl(bin ? bin : "bin/ballfilm", "ballfilm", "run", scene, "-o", part,
              "-q", (char *)NULL);
        _exit(127);
    }
    struct timespec ts = {0, 200000000};
    nanosleep(&ts, NULL);
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
    tu_same_named(full, part, ball_sets);
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
    tcase_add_test(tc, sigint_checkpoints_and_restart_identical);
    tcase_add_test(tc, restart_errors_are_clear);
    suite_add_tcase(s, tc);
    return s;
}
