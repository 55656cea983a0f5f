/* test_sweep.c: parameter sweeps.  The same cases give bit-identical files
 * run one after another, on a pool of two processes, and on two MPI ranks;
 * a failing case is recorded without stopping the sweep; a sweep run again
 * runs only the cases that did not finish; a sweep of 10^4 values along
 * one axis is defined (its manifest is not cut at a fixed size); the
 * results of a run with an output file and keep_map_points (bf_results,
 * the sweep's result columns) hold the file's return map and Lyapunov
 * exponent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "ballfilm/sim.h"
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

/* Run scene (with sets) to an output file and check that the run's
 * results (bf_results, what a sweep's result columns come from) hold what
 * the file does: with keep_map_points every return-map point, the same
 * bits as the file's (z, v) (zcol, vcol: columns of the datasets zpath,
 * vpath), without it none (the run's memory does not grow), and the
 * Lyapunov exponent of its root attribute. */
static void results_as_file(const char *scene, const char *const *sets,
                            size_t nsets, int keep, const char *out,
                            const char *zpath, const char *vpath,
                            size_t zcol, size_t vcol)
{
    bf_run *r = NULL;
    bf_err err = {0};
    bf_sim_opts opts = {.keep_map_points = keep};
    ck_assert_msg(bf_run_load(&r, bf_catalog_builtin(), tu_repo(scene), sets,
                              nsets, &opts, &err) == BF_OK, "%s", err.msg);
    ck_assert_msg(bf_run_open_output(r, tu_tmp(out), &err) == BF_OK, "%s",
                  err.msg);
    bf_sim *sim = bf_run_sim(r);
    bf_status st = bf_sim_run(sim, &err);
    ck_assert_msg(st == BF_OK, "%s", err.msg);
    ck_assert_msg(bf_sim_close_output(sim, st, NULL, &err) == BF_OK, "%s",
                  err.msg);
    bf_results res;
    bf_sim_results(sim, &res);
    bf_h5_reader *rd;
    ck_assert(bf_h5_reader_open(&rd, tu_tmp(out), &err) == BF_OK);
    double *z, *v, ly;
    size_t nz, nz1, nv, nv1;
    ck_assert(bf_h5_reader_read(rd, zpath, &z, &nz, &nz1, &err) == BF_OK);
    ck_assert(bf_h5_reader_read(rd, vpath, &v, &nv, &nv1, &err) == BF_OK);
    ck_assert(bf_h5_reader_attr_real(rd, "/", "lyapunov_exponent", &ly,
                                     &err) == BF_OK);
    bf_h5_reader_close(rd);
    ck_assert_uint_ge(nz, 2);
    ck_assert(res.has_return_map && res.map_points == nz && nv == nz);
    ck_assert_msg(keep ? res.map_z && res.map_v : !res.map_z && !res.map_v,
                  "%s: with an output file and keep_map_points = %d the "
                  "results hold %s map points", scene, keep,
                  res.map_z ? "the" : "no");
    const size_t sz = nz1 ? nz1 : 1, sv = nv1 ? nv1 : 1; /* 1-D: n1 0 */
    for (size_t k = 0; keep && k < nz; k++)
        ck_assert_msg(res.map_z[k] == z[k * sz + zcol] &&
                          res.map_v[k] == v[k * sv + vcol],
                      "%s: point %zu differs from the file's", scene, k);
    ck_assert(res.has_lyapunov && !memcmp(&ly, &res.lyapunov_exponent,
                                          sizeof ly));
    free(z);
    free(v);
    bf_run_free(r);
}

START_TEST(results_hold_what_the_file_does)
{
    const char *balls[] = {"scene.t_end=5", "lyapunov.enabled=yes"};
    const char *coupled[] = {"scene.t_end=0.2", "lyapunov.enabled=yes"};
    for (int keep = 0; keep < 2; keep++) {
        results_as_file("runs/two_balls_B.ini", balls, 2, keep,
                        "res_balls.h5", "/return_map/z", "/return_map/v", 0,
                        0);
        results_as_file("runs/coupled_fig8.ini", coupled, 2, keep,
                        "res_coupled.h5", "/coupled/return_map",
                        "/coupled/return_map", 1, 2);
    }
}
END_TEST

Suite *suite_sweep(void)
{
    Suite *s = suite_create("sweep");
    TCase *tc = tu_tcase("cases");
    tcase_add_test(tc, serial_pool_and_mpi_identical);
    tcase_add_test(tc, failed_case_recorded_and_rerun_completes_missing);
    tcase_add_test(tc, long_axis_defined_and_checked);
    tcase_add_test(tc, results_hold_what_the_file_does);
    suite_add_tcase(s, tc);
    return s;
}
