/* test_sweep.c: parameter sweeps.  The same cases give bit-identical files
 * run one after another, on a pool of two processes, and on two MPI ranks;
 * a failing case is recorded without stopping the sweep; a sweep run again
 * runs only the cases that did not finish; a sweep of 10^4 values along
 * one axis is defined (its manifest is not cut at a fixed size). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ballfilm/sweep.h"
#include "testutil.h"

#define NCASES 4

static void case_file(char *buf, size_t cap, const char *dir, int k,
                      const char *ext)
{
    snprintf(buf, cap, "%s/case_%05d.%s", dir, k, ext);
}

static int count_lines(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int n = 0, c;
    while ((c = fgetc(f)) != EOF)
        n += c == '\n';
    fclose(f);
    return n;
}

START_TEST(serial_pool_and_mpi_identical)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char d1[512], d2[512], d3[512];
    snprintf(d1, sizeof d1, "%s", tu_tmp("sw_serial"));
    snprintf(d2, sizeof d2, "%s", tu_tmp("sw_pool"));
    snprintf(d3, sizeof d3, "%s", tu_tmp("sw_mpi"));
    ck_assert_int_eq(tu_run(NULL, NULL, "sweep", scene, "--vary",
                            "ball.1.mass=0.5:2.0:4", "--set", "scene.t_end=5",
                            "-o", d1, "-q", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "sweep", scene, "--vary",
                            "ball.1.mass=0.5:2.0:4", "--set", "scene.t_end=5",
                            "-o", d2, "-q", "--jobs", "2", NULL),
                     0);
    char a[600], b[600];
    for (int k = 0; k < NCASES; k++) {
        case_file(a, sizeof a, d1, k, "h5");
        case_file(b, sizeof b, d2, k, "h5");
        tu_same_datasets(a, b);
    }
    snprintf(a, sizeof a, "%s/summary.csv", d1);
    ck_assert_int_eq(count_lines(a), 1 + NCASES);

    const char *mpi = getenv("BALLFILM_MPI_BIN");
    if (getenv("BALLFILM_SANITIZED") || !mpi || access(mpi, X_OK) ||
        system("command -v mpirun >/dev/null 2>&1")) {
        fprintf(stderr, "note: MPI part of the sweep test skipped\n");
        return;
    }
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "mpirun -n 2 --oversubscribe '%s' sweep '%s' --vary "
             "ball.1.mass=0.5:2.0:4 --set scene.t_end=5 -o '%s' -q "
             ">/dev/null 2>&1",
             mpi, scene, d3);
    ck_assert_msg(system(cmd) == 0, "%s failed", cmd);
    for (int k = 0; k < NCASES; k++) {
        case_file(a, sizeof a, d1, k, "h5");
        case_file(b, sizeof b, d3, k, "h5");
        tu_same_datasets(a, b);
    }
    snprintf(b, sizeof b, "%s/summary.csv", d3);
    ck_assert_int_eq(count_lines(b), 1 + NCASES);
}
END_TEST

START_TEST(failed_case_recorded_and_rerun_completes_missing)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char d[512], path[700];
    snprintf(d, sizeof d, "%s", tu_tmp("sw_fail"));
    /* mass -1 is refused by the scene: that case fails, the others run;
     * the sweep's exit status is the failed case's (2, bad input) */
    ck_assert_int_eq(tu_run(NULL, NULL, "sweep", scene, "--vary",
                            "ball.1.mass=-1,0.8,1.2", "--set", "scene.t_end=2",
                            "-o", d, "-q", NULL),
                     2);
    snprintf(path, sizeof path, "%s/summary.csv", d);
    FILE *f = fopen(path, "r");
    char line[4096];
    ck_assert(f && fgets(line, sizeof line, f)); /* header */
    ck_assert(fgets(line, sizeof line, f));
    ck_assert_msg(strstr(line, "0,-1,2,") == line && strstr(line, "mass"),
                  "%s", line);
    ck_assert(fgets(line, sizeof line, f));
    ck_assert_msg(strstr(line, "1,0.80000000000000004,0,") == line, "%s", line);
    fclose(f);
    /* a killed sweep leaves cases without their .done row: only those run
     * again, the finished case files are not touched */
    struct stat before, after;
    case_file(path, sizeof path, d, 1, "h5");
    ck_assert(stat(path, &before) == 0);
    case_file(path, sizeof path, d, 2, "done");
    ck_assert(unlink(path) == 0);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "sweep", scene, "--vary",
                            "ball.1.mass=-1,0.8,1.2", "--set", "scene.t_end=2",
                            "-o", d, NULL),
                     2);
    ck_assert_msg(strstr(err, "2 already done, 1 to run"), "%s", err);
    ck_assert_msg(strstr(err, "case     2"), "%s", err);
    free(err);
    case_file(path, sizeof path, d, 1, "h5");
    ck_assert(stat(path, &after) == 0);
    ck_assert(before.st_mtim.tv_sec == after.st_mtim.tv_sec &&
              before.st_mtim.tv_nsec == after.st_mtim.tv_nsec);
    /* another sweep definition in the same directory is refused */
    ck_assert_int_eq(tu_run(NULL, NULL, "sweep", scene, "--vary",
                            "ball.1.mass=1:2:3", "-o", d, "-q", NULL),
                     2);
}
END_TEST

/* The manifest (sweep.txt) holds every value: with 10^4 values of 20-odd
 * characters it is some 200 KB, where a fixed 16 KB buffer refused any
 * axis of more than about 800 values ("sweep definition too long").  The
 * same definition is accepted again (a rerun), one other value is not. */
START_TEST(long_axis_defined_and_checked)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char d[512], path[700];
    snprintf(d, sizeof d, "%s", tu_tmp("sw_long"));
    const char *vary[] = {"ball.1.mass=0.5:2.0:10000"};
    const char *other[] = {"ball.1.mass=0.5:2.5:10000"};
    bf_sweep sw;
    bf_err err = {0};
    ck_assert_msg(bf_sweep_init(&sw, scene, NULL, 0, vary, 1, d, &err) ==
                      BF_OK,
                  "%s", err.msg);
    ck_assert_int_eq((long)sw.ncases, 10000);
    bf_sweep_free(&sw);
    snprintf(path, sizeof path, "%s/sweep.txt", d);
    struct stat st;
    ck_assert(stat(path, &st) == 0);
    ck_assert_msg(st.st_size > 10000 * 17, "%lld bytes",
                  (long long)st.st_size);
    ck_assert_msg(bf_sweep_init(&sw, scene, NULL, 0, vary, 1, d, &err) ==
                      BF_OK,
                  "%s", err.msg);
    bf_sweep_free(&sw);
    ck_assert_int_eq(bf_sweep_init(&sw, scene, NULL, 0, other, 1, d, &err),
                     BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "holds a different sweep"), "%s", err.msg);
}
END_TEST

Suite *suite_sweep(void)
{
    Suite *s = suite_create("sweep");
    TCase *tc = tu_tcase("cases");
    tcase_add_test(tc, serial_pool_and_mpi_identical);
    tcase_add_test(tc, failed_case_recorded_and_rerun_completes_missing);
    tcase_add_test(tc, long_axis_defined_and_checked);
    suite_add_tcase(s, tc);
    return s;
}
