/* test_hostile_stop.c: every command stops on SIGINT with status 6 and
 * leaves no partial file; long ARKODE steps stop and have a budget; no
 * blown-up final state is called success.
 *
 * The children set SIGINT and SIGTERM to their default disposition
 * before exec: `make test` may run with SIGINT ignored (nohup), which a
 * child would inherit. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "testutil.h"

static int exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void pause_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* bin/ballfilm ARGV in the background, stdout to /dev/null, stderr to
 * errf. */
static pid_t start(const char *const *argv, const char *errf)
{
    const char *bin = getenv("BALLFILM_BIN");
    ck_assert_msg(bin != NULL, "BALLFILM_BIN is not set");
    const char *av[32];
    size_t n = 0;
    av[n++] = bin;
    for (size_t k = 0; argv[k] && n < 31; k++)
        av[n++] = argv[k];
    av[n] = NULL;
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        int out = open("/dev/null", O_WRONLY);
        int err = open(errf, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(out, 1);
        dup2(err, 2);
        execv(bin, (char *const *)av);
        _exit(127);
    }
    return pid;
}

/* Exit status of pid, waiting at most `limit` s (then it is killed and
 * the test fails: the command did not stop). */
static int finish_within(pid_t pid, double limit)
{
    const double t0 = now_s();
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (now_s() - t0 > limit) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            ck_abort_msg("the command did not end %g s after SIGINT", limit);
        }
        pause_ms(10);
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *buf = calloc(1, 1 << 16);
    if (f && buf) {
        size_t n = fread(buf, 1, (1 << 16) - 1, f);
        buf[n] = '\0';
    }
    if (f)
        fclose(f);
    return buf;
}

/* SIGINT while the study runs (an ARKODE reference of one long call, then
 * the compared runs): status 6 within seconds, no table written. */
START_TEST(converge_sigint_exits_6_without_output)
{
    char out[600], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("conv.h5"));
    snprintf(errf, sizeof errf, "%s", tu_tmp("conv.err"));
    const char *argv[] = {"converge", tu_repo("runs/harmonic.ini"),
                          "--methods", "verlet,rk4,arkode", "--t-end",
                          "200000", "--repeats", "1", "-q", "-o", out, NULL};
    pid_t pid = start(argv, errf);
    pause_ms(700);
    kill(pid, SIGINT);
    ck_assert_int_eq(finish_within(pid, 10), 6);
    ck_assert(!exists(out));
    char *msg = slurp(errf);
    ck_assert_msg(strstr(msg, "interrupted"), "%s", msg);
    free(msg);
}
END_TEST

/* A coupled step of a million internal ARKODE steps (max_step 1e-300)
 * stops on SIGINT inside the step: status 6 and a checkpoint. */
START_TEST(long_arkode_step_stops_on_sigint)
{
    char out[600], part[700], ck[700], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("ark.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    snprintf(ck, sizeof ck, "%s.ckpt", out);
    snprintf(errf, sizeof errf, "%s", tu_tmp("ark.err"));
    const char *argv[] = {"run", tu_repo("runs/coupled_fig8.ini"), "-o", out,
                          "-q", "--set", "coupled.scheme=arkode", "--set",
                          "coupled.max_step=1e-300", "--set",
                          "coupled.max_steps=1000000", "--set",
                          "scene.t_end=1e-4", NULL};
    pid_t pid = start(argv, errf);
    tu_wait_for_file(part, 0);
    pause_ms(500);
    kill(pid, SIGINT);
    ck_assert_int_eq(finish_within(pid, 10), 6);
    ck_assert(exists(ck));
    char *msg = slurp(errf);
    ck_assert_msg(strstr(msg, "interrupted at step 0"), "%s", msg);
    free(msg);
}
END_TEST

/* Without max_steps given, such a step ends at the default budget per
 * [scene] dt with status 4 naming the key, in seconds (a film of 51
 * nodes here, to stay quick). */
START_TEST(arkode_step_budget_by_default)
{
    char out[600], errf[600];
    snprintf(out, sizeof out, "%s", tu_tmp("budget.h5"));
    snprintf(errf, sizeof errf, "%s", tu_tmp("budget.err"));
    const char *argv[] = {"run", tu_repo("runs/coupled_fig8.ini"), "-o", out,
                          "-q", "--set", "coupled.scheme=arkode", "--set",
                          "coupled.max_step=1e-300", "--set", "film.dx=1",
                          "--set", "scene.t_end=1e-4", NULL};
    pid_t pid = start(argv, errf);
    ck_assert_int_eq(finish_within(pid, 60), 4);
    char *msg = slurp(errf);
    ck_assert_msg(strstr(msg, "[coupled] max_steps"), "%s", msg);
    free(msg);
}
END_TEST

/* SIGINT to animate while it writes the movie: status 6, no movie. */
START_TEST(animate_sigint_exits_6_without_movie)
{
    char h5[600], mp4[600], errf[600];
    snprintf(h5, sizeof h5, "%s", tu_tmp("anim.h5"));
    snprintf(mp4, sizeof mp4, "%s", tu_tmp("anim.gif"));
    snprintf(errf, sizeof errf, "%s", tu_tmp("anim.err"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", h5, "-q", NULL),
                     0);
    const char *argv[] = {"animate", h5, "-o", mp4, "-q", "--frames",
                          "2000", NULL};
    pid_t pid = start(argv, errf);
    tu_wait_for_file(mp4, 0);
    kill(pid, SIGINT);
    ck_assert_int_eq(finish_within(pid, 10), 6);
    ck_assert(!exists(mp4));
}
END_TEST

/* The final state is checked against the energy bound and finiteness
 * whatever energy_every and output_every are: Verlet at dt = 2.5 s on
 * the oscillator ends unstable (it used to end "ok" with an energy error
 * of inf), with the bound off too (a non-finite energy). */
START_TEST(blown_up_final_state_is_unstable)
{
    const char *every[] = {"scene.energy_every=0", "scene.energy_every=7"};
    for (int k = 0; k < 3; k++) {
        char *err = NULL;
        int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                        tu_tmp("blow.h5"), "-q", "--set",
                        "scene.integrator=verlet", "--set", "scene.dt=2.5",
                        "--set", "scene.t_end=1000", "--set",
                        "scene.output_every=100000", "--set", every[k & 1],
                        "--set",
                        k == 2 ? "scene.energy_bound=no"
                               : "scene.energy_bound=yes",
                        NULL);
        ck_assert_msg(rc == 3, "case %d: status %d: %s", k, rc, err);
        ck_assert_msg(strstr(err, "step") && strstr(err, "energy"), "%s",
                      err);
        free(err);
    }
}
END_TEST

Suite *suite_hostile_stop(void)
{
    Suite *s = suite_create("hostile_stop");
    TCase *tc = tu_tcase("stop");
    tcase_add_test(tc, converge_sigint_exits_6_without_output);
    tcase_add_test(tc, long_arkode_step_stops_on_sigint);
    tcase_add_test(tc, arkode_step_budget_by_default);
    tcase_add_test(tc, animate_sigint_exits_6_without_movie);
    tcase_add_test(tc, blown_up_final_state_is_unstable);
    suite_add_tcase(s, tc);
    return s;
}
