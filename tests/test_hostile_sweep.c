/* test_hostile_sweep.c: a sweep whose cases failed on a full disk runs
 * them again when rerun once there is room, and says so; the other
 * failures stay recorded unless --retry-failed is given.  Summaries say
 * "never" and "not measured" instead of printing NaN.  A program started
 * with SIGINT ignored (a script's background job) keeps ignoring it and
 * still stops on SIGTERM. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "testutil.h"

static const char *bin(void)
{
    const char *b = getenv("BALLFILM_BIN");
    return b ? b : "bin/ballfilm";
}

static int finish(pid_t pid)
{
    int status;
    ck_assert(waitpid(pid, &status, 0) == pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/* The first line of a file (without its newline) into buf. */
static void first_line(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "r");
    ck_assert_msg(f != NULL, "%s", path);
    ck_assert_msg(fgets(buf, (int)cap, f) != NULL, "%s is empty", path);
    fclose(f);
    buf[strcspn(buf, "\n")] = '\0';
}

static void case_file(char *buf, size_t cap, const char *dir, int k,
                      const char *ext)
{
    snprintf(buf, cap, "%s/case_%05d.%s", dir, k, ext);
}

/* The status column of a case's .done row (the field after the value of
 * the one varied key). */
static int done_status(const char *dir, int k)
{
    char path[700], line[4096];
    case_file(path, sizeof path, dir, k, "done");
    first_line(path, line, sizeof line);
    const char *p = strchr(line, ',');
    ck_assert(p && (p = strchr(p + 1, ',')));
    return atoi(p + 1);
}

#define SCENE "runs/two_balls_B.ini"
#define VARY "ball.1.mass=-1,0.8,1.2"

/* The sweep of this file's tests: case 0 is bad input (mass -1), cases 1
 * and 2 run; `extra` is one more option or NULL. */
static int sweep(const char *dir, char **err, const char *extra)
{
    return tu_run(NULL, err, "sweep", tu_repo(SCENE), "--vary", VARY, "--set",
                  "scene.t_end=2", "-o", dir, extra, NULL);
}

/* Cases that failed to write (a file-size limit of 32 KiB stands for a
 * full disk; their files need about 80 KiB) are run again by a plain
 * rerun once there is room, which says so, and end with the files of a
 * sweep that never failed; the case refused as bad input keeps its row
 * (it would fail again) until --retry-failed, which the messages name. */
START_TEST(io_failed_cases_retried_on_rerun)
{
    char d[512], good[512], errf[600], path[700], line[4096];
    snprintf(d, sizeof d, "%s", tu_tmp("hs_full"));
    snprintf(good, sizeof good, "%s", tu_tmp("hs_good"));
    snprintf(errf, sizeof errf, "%s", tu_tmp("hs_full.err"));
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {32u << 10, 32u << 10};
        setrlimit(RLIMIT_FSIZE, &rl);
        if (!freopen("/dev/null", "w", stdout) || !freopen(errf, "w", stderr))
            _exit(126);
        execl(bin(), "ballfilm", "sweep", tu_repo(SCENE), "--vary", VARY,
              "--set", "scene.t_end=2", "-o", d, "-q", (char *)NULL);
        _exit(127);
    }
    const int rc = finish(pid);
    ck_assert_msg(rc == 2 || rc == 5, "exit %d", rc);
    ck_assert_int_eq(done_status(d, 0), 2);
    ck_assert_int_eq(done_status(d, 1), 5);
    ck_assert_int_eq(done_status(d, 2), 5);
    FILE *f = fopen(errf, "r");
    ck_assert(f != NULL);
    size_t n = fread(line, 1, sizeof line - 1, f);
    line[n] = '\0';
    fclose(f);
    ck_assert_msg(strstr(line, "2 cases failed to write") &&
                      strstr(line, "run the same command again"),
                  "%s", line);
    ck_assert_msg(strstr(line, "--retry-failed"), "%s", line);

    /* room again: the plain rerun runs the two cases that failed to
     * write, on a pool of two processes, and says why */
    struct stat before, after;
    case_file(path, sizeof path, d, 0, "done");
    ck_assert(stat(path, &before) == 0);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "sweep", tu_repo(SCENE), "--vary",
                            VARY, "--set", "scene.t_end=2", "-o", d, "--jobs",
                            "2", NULL),
                     2);
    ck_assert_msg(strstr(err, "1 already done, 2 to run") &&
                      strstr(err, "2 of them again after a failure to write"),
                  "%s", err);
    ck_assert_msg(strstr(err, "1 case failed") &&
                      strstr(err, "--retry-failed") &&
                      !strstr(err, "failed to write"),
                  "%s", err);
    free(err);
    ck_assert_int_eq(done_status(d, 1), 0);
    ck_assert_int_eq(done_status(d, 2), 0);
    ck_assert(stat(path, &after) == 0);
    ck_assert(before.st_mtim.tv_sec == after.st_mtim.tv_sec &&
              before.st_mtim.tv_nsec == after.st_mtim.tv_nsec);
    /* the same files as a sweep that never failed */
    ck_assert_int_eq(sweep(good, NULL, "-q"), 2);
    char a[700], b[700];
    for (int k = 1; k <= 2; k++) {
        case_file(a, sizeof a, d, k, "h5");
        case_file(b, sizeof b, good, k, "h5");
        tu_same_datasets(a, b);
    }
    snprintf(path, sizeof path, "%s/summary.csv", d);
    FILE *csv = fopen(path, "r");
    ck_assert(csv && fgets(line, sizeof line, csv)); /* header */
    ck_assert(fgets(line, sizeof line, csv));        /* case 0 */
    ck_assert(fgets(line, sizeof line, csv));
    ck_assert_msg(strstr(line, "1,0.80000000000000004,0,") == line, "%s", line);
    fclose(csv);

    /* nothing left to retry by default */
    err = NULL;
    ck_assert_int_eq(sweep(d, &err, NULL), 2);
    ck_assert_msg(strstr(err, "3 already done, 0 to run"), "%s", err);
    free(err);
    /* --retry-failed runs the bad-input case again (it fails again) */
    err = NULL;
    ck_assert_int_eq(sweep(d, &err, "--retry-failed"), 2);
    ck_assert_msg(strstr(err, "2 already done, 1 to run") &&
                      strstr(err, "1 of them again after a failure"),
                  "%s", err);
    free(err);
    ck_assert_int_eq(done_status(d, 0), 2);
}
END_TEST

/* The coupled model's summary of a run too short for the symmetry to
 * break, and of a Lyapunov estimate without a renormalisation yet: each
 * level says "never", the exponent "not measured", no "nan" anywhere. */
START_TEST(summaries_say_never_not_nan)
{
    char *out = NULL, *err = NULL;
    ck_assert_int_eq(tu_run(&out, &err, "run", tu_repo("runs/coupled_fig8.ini"),
                            "--set", "scene.t_end=0.01", "--set",
                            "lyapunov.enabled=yes", "-o",
                            tu_tmp("hs_never.h5"), NULL),
                     0);
    size_t n = strlen(out) + strlen(err) + 2;
    char *all = malloc(n);
    snprintf(all, n, "%s\n%s", out, err);
    ck_assert_msg(strstr(all, "first above 1e-12 cm never, 1e-09 cm never"),
                  "%s", all);
    ck_assert_msg(strstr(all, "lyapunov exponent: not measured"), "%s", all);
    ck_assert_msg(!strstr(all, "nan") && !strstr(all, "NaN"), "%s", all);
    free(all);
    free(out);
    free(err);
}
END_TEST

/* Started with SIGINT ignored (as a shell starts a script's background
 * jobs, so that Ctrl-C stops the script and not them), the program keeps
 * ignoring it; SIGTERM still stops it cleanly (exit 6). */
START_TEST(ignored_sigint_stays_ignored_sigterm_stops)
{
    char out[600], part[700];
    snprintf(out, sizeof out, "%s", tu_tmp("hs_nohup.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        signal(SIGINT, SIG_IGN);
        if (!freopen("/dev/null", "w", stdout) ||
            !freopen("/dev/null", "w", stderr))
            _exit(126);
        execl(bin(), "ballfilm", "run", tu_repo(SCENE), "-o", out, "-q",
              "--set", "scene.t_end=100000", "--set",
              "scene.output_every=1000", (char *)NULL);
        _exit(127);
    }
    tu_wait_for_file(part, 4096);
    kill(pid, SIGINT);
    struct timespec ts = {0, 500000000L};
    nanosleep(&ts, NULL);
    int status;
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == 0)
        kill(pid, SIGTERM);
    ck_assert_msg(done == 0, "SIGINT stopped a program that inherited it "
                             "ignored (exit status %d)",
                  WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    ck_assert_int_eq(finish(pid), 6);
}
END_TEST

Suite *suite_hostile_sweep(void)
{
    Suite *s = suite_create("hostile_sweep");
    TCase *tc = tu_tcase("hostile_sweep");
    tcase_add_test(tc, io_failed_cases_retried_on_rerun);
    tcase_add_test(tc, summaries_say_never_not_nan);
    tcase_add_test(tc, ignored_sigint_stays_ignored_sigterm_stops);
    suite_add_tcase(s, tc);
    return s;
}
