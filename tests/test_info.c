/* test_info.c: `ballfilm info OUT.h5` against the file itself: every
 * dataset the file holds (listed independently through HDF5's own
 * iteration in testutil.c) appears with the shape bf_h5_read finds and
 * the unit its attribute holds; the root attributes (title, model,
 * integrator, status, steps, energy error) are printed as stored; an
 * interrupted run is shown from OUT.h5.part; a file that is not HDF5 is
 * an I/O error (exit 5) naming it; each dataset's kind and role (series.h)
 * are shown; a root attribute that is there but cannot be read is an
 * error naming it, not left out as if absent. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/h5out.h"
#include "testutil.h"

static const char *const scene =
    "[scene]\ntitle = info test\nintegrator = verlet\n"
    "effects = gravity floor\ndt = 1e-4\nt_end = 1\noutput_every = 50\n"
    "[ball.1]\nposition = 0.2\n[return_map]\nenabled = yes\ntrigger = 1\nrecord = 1\n";

/* The line of `out` that starts with `start` (after blanks), or NULL. */
static const char *line_of(const char *out, const char *start)
{
    for (const char *p = out; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : p) {
        const char *q = p;
        while (*q == ' ')
            q++;
        if (!strncmp(q, start, strlen(start)))
            return q;
    }
    return NULL;
}

START_TEST(info_lists_what_the_file_holds)
{
    const char *ini = tu_write("info.ini", scene), *h5 = tu_tmp("info.h5");
    ck_assert(tu_run(NULL, NULL, "run", ini, "-q", "-o", h5, NULL) == 0);
    char *out = NULL;
    ck_assert(tu_run(&out, NULL, "info", h5, NULL) == 0);
    char **names = tu_h5_datasets(h5);
    int count = 0;
    for (char **n = names; *n; n++, count++) {
        char want[512], path[300];
        snprintf(path, sizeof path, "%s%s", (*n)[0] == '/' ? "" : "/", *n);
        const char *l = line_of(out, path);
        ck_assert_msg(l, "%s missing from\n%s", path, out);
        double *d;
        size_t n0, n1;
        bf_err err = {0};
        ck_assert_msg(bf_h5_read(h5, path, &d, &n0, &n1, &err) == BF_OK, "%s",
                      err.msg);
        free(d);
        char *unit = NULL;
        ck_assert(bf_h5_read_attr_str(h5, path, "unit", &unit, &err) ==
                  BF_OK);
        if (n1)
            snprintf(want, sizeof want, "[%zu x %zu]", n0, n1);
        else
            snprintf(want, sizeof want, "[%zu]", n0);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)strcspn(l, "\n"), l);
        ck_assert_msg(strstr(line, want) && strstr(line, unit), "%s: want "
                      "%s and unit %s", line, want, unit);
        free(unit);
    }
    ck_assert(count > 5);
    char expect[64];
    snprintf(expect, sizeof expect, "datasets: %d", count);
    ck_assert_msg(strstr(out, expect), "%s", out);
    ck_assert(strstr(line_of(out, "title:"), "info test"));
    ck_assert(strstr(line_of(out, "model:"), "balls"));
    ck_assert(strstr(line_of(out, "integrator:"), "verlet"));
    ck_assert(strstr(line_of(out, "status:"), "ok"));
    ck_assert(strstr(line_of(out, "steps:"), "10000 (t = 1 s)"));
    ck_assert(strstr(line_of(out, "written by:"), "ballfilm"));
    double e;
    bf_err err = {0};
    ck_assert(bf_h5_read_attr_real(h5, "/", "max_relative_energy_error", &e,
                                   &err) == BF_OK);
    snprintf(expect, sizeof expect, "%.6e", e);
    ck_assert_msg(strstr(line_of(out, "max relative energy error:"), expect),
                  "%s", out);
    tu_free_list(names);
    free(out);
}
END_TEST

START_TEST(info_shows_an_interrupted_run_and_refuses_what_is_not_hdf5)
{
    const char *ini = tu_write("info2.ini", scene), *h5 = tu_tmp("info2.h5");
    ck_assert(tu_run(NULL, NULL, "run", ini, "-q", "-o", h5, "--stop-after",
                     "3000", NULL) == 6);
    char *out = NULL, *errout = NULL;
    ck_assert(tu_run(&out, NULL, "info", h5, NULL) == 0);
    ck_assert_msg(strstr(out, ".part (not finished"), "%s", out);
    ck_assert(strstr(line_of(out, "status:"), "interrupted"));
    ck_assert(strstr(line_of(out, "steps:"), "3000 "));
    free(out);
    ck_assert(tu_run(NULL, &errout, "info", ini, NULL) == 5);
    ck_assert_msg(strstr(errout, "info2.ini") && strstr(errout, "HDF5"), "%s",
                  errout);
    free(errout);
    ck_assert(tu_run(NULL, NULL, "info", NULL) == 2);
}
END_TEST

/* The line of dataset `path` in info's output `out` holds `want`. */
static void dataset_line_has(const char *out, const char *path,
                             const char *want)
{
    char start[300];
    snprintf(start, sizeof start, "%s ", path);
    const char *l = line_of(out, start);
    ck_assert_msg(l, "%s missing from\n%s", path, out);
    char line[1024];
    snprintf(line, sizeof line, "%.*s", (int)strcspn(l, "\n"), l);
    ck_assert_msg(strstr(line, want), "%s: want %s", line, want);
}

/* Replace root attribute `name` of file by a fixed-length UTF-8 string,
 * which the checked reader does not convert (h5check.c reads ASCII). */
static void utf8_root_attr(const char *file, const char *name)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDWR, H5P_DEFAULT);
    ck_assert(f >= 0);
    ck_assert(H5Adelete(f, name) >= 0);
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
    ck_assert(H5Tset_size(t, 8) >= 0 &&
              H5Tset_cset(t, H5T_CSET_UTF8) >= 0);
    hid_t a = H5Acreate2(f, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    ck_assert(a >= 0 && H5Awrite(a, t, "ok\0\0\0\0\0\0") >= 0);
    H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    H5Fclose(f);
}

START_TEST(info_shows_kind_and_role_and_fails_on_unreadable_attributes)
{
    const char *ini = tu_write("info3.ini", scene), *h5 = tu_tmp("info3.h5");
    ck_assert(tu_run(NULL, NULL, "run", ini, "-q", "-o", h5, NULL) == 0);
    char *out = NULL, *errout = NULL;
    ck_assert(tu_run(&out, NULL, "info", h5, NULL) == 0);
    dataset_line_has(out, "/time", "rows/time");
    dataset_line_has(out, "/step", "rows/step");
    dataset_line_has(out, "/balls/position", "rows/position");
    dataset_line_has(out, "/balls/mass", "static/property");
    dataset_line_has(out, "/return_map/time", "events/time");
    free(out);
    /* status is there but unreadable: an I/O error naming it (before, the
     * status line was left out and info exited 0) */
    utf8_root_attr(h5, "status");
    ck_assert_int_eq(tu_run(&out, &errout, "info", h5, NULL), 5);
    ck_assert_msg(strstr(errout, "attribute status") && strstr(errout, h5),
                  "%s", errout);
    free(out);
    free(errout);
}
END_TEST

Suite *suite_info(void)
{
    Suite *s = suite_create("info");
    TCase *tc = tu_tcase("info");
    tcase_add_test(tc, info_lists_what_the_file_holds);
    tcase_add_test(tc, info_shows_an_interrupted_run_and_refuses_what_is_not_hdf5);
    tcase_add_test(tc, info_shows_kind_and_role_and_fails_on_unreadable_attributes);
    suite_add_tcase(s, tc);
    return s;
}
