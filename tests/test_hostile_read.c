/* test_hostile_read.c: files one does not trust, given to the readers.
 * Real outputs of every model, mutated at the level of HDF5 objects
 * (tests/fuzz_h5.c; the recipes in tests/fuzz/h5_regress/, which also
 * keep the findings of `make fuzz`), go to `info`, `xdmf`, `run --restart`
 * and a film scene with `[film] initial = file` under CPU and file-size
 * limits: never a signal (SIGSEGV, SIGXCPU, SIGXFSZ), the status each
 * recipe names, and a message naming the file.  Also: the sidecar is not
 * written through a symbolic link, `xdmf` and `info` stop on SIGTERM with
 * status 6 leaving no file, an interrupted run does not warn about a
 * sidecar of a file that is not there, and `info` escapes the control
 * characters of the text it prints. */
#define _DEFAULT_SOURCE /* symlink, DT_REG */
#include <dirent.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz_h5.h"
#include "testutil.h"

/* The corpus's directory (its files made as they are needed). */
static const char *corpus(void)
{
    static char dir[4096];
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "%s", tu_tmp("corpus"));
        mkdir(dir, 0700);
    }
    return dir;
}

/* One recipe (words of a line); fails the test with the line. */
static void replay(const char *dir, char **w, int nw, const char *line)
{
    ck_assert_msg(nw >= 4, "bad recipe: %s", line);
    char work[4096];
    snprintf(work, sizeof work, "%s", tu_tmp("work"));
    mkdir(work, 0700);
    char *err = NULL;
    const char *target = "";
    int rc = fh5_run(dir, work, w[1], w[2], (const char *const *)w + 3, &err,
                     &target);
    ck_assert_msg(rc > -1000, "recipe could not be applied (%d): %s", rc,
                  line);
    /* the random run of make fuzz-h5 judges by the same verdict */
    const char *why = fh5_verdict(rc, err, target);
    ck_assert_msg(!why, "%s (exit %d, file %s): %s\n%s", why, rc, target,
                  line, err ? err : "");
    if (strcmp(w[0], "*"))
        ck_assert_msg(rc == atoi(w[0]), "exit %d, want %s: %s\n%s", rc, w[0],
                      line, err ? err : "");
    free(err);
}

/* Every line of every recipe file of tests/fuzz/h5_regress. */
static int replay_all(void)
{
    const char *dir = corpus();
    const char *rdir = tu_repo("tests/fuzz/h5_regress");
    DIR *d = opendir(rdir);
    ck_assert_msg(d != NULL, "no %s", rdir);
    struct dirent *e;
    int lines = 0;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 8 || strcmp(e->d_name + len - 8, ".recipes"))
            continue;
        char path[4096], buf[1024];
        snprintf(path, sizeof path, "%s/%s", rdir, e->d_name);
        FILE *f = fopen(path, "r");
        ck_assert_msg(f != NULL, "cannot read %s", path);
        while (fgets(buf, sizeof buf, f)) {
            buf[strcspn(buf, "\n")] = '\0';
            if (!buf[0] || buf[0] == '#')
                continue;
            char copy[1024], *w[64];
            snprintf(copy, sizeof copy, "%s", buf);
            int nw = 0;
            char *t = strtok(copy, " \t");
            for (; t && nw < 63; t = strtok(NULL, " \t"))
                w[nw++] = t;
            w[nw] = NULL;
            ck_assert_msg(!t, "recipe of more than 63 words: %s", buf);
            replay(dir, w, nw, buf);
            lines++;
        }
        fclose(f);
    }
    closedir(d);
    return lines;
}

START_TEST(mutated_outputs_are_refused_cleanly)
{
    ck_assert_int_gt(replay_all(), 30);
}
END_TEST

/* The reproducer on its own: steps_done as 2e5 doubles. */
START_TEST(info_refuses_an_array_for_a_number)
{
    char work[4096], *err = NULL;
    const char *target;
    snprintf(work, sizeof work, "%s", tu_tmp("w1"));
    mkdir(work, 0700);
    const char *op[] = {"attr_array", "/", "steps_done", "200000", NULL};
    int rc = fh5_run(corpus(), work, "balls", "info", op, &err, &target);
    ck_assert_msg(rc == 2 && strstr(err, "steps_done") &&
                      strstr(err, "balls.h5"),
                  "exit %d: %s", rc, err ? err : "");
    free(err);
}
END_TEST

/* A symbolic link planted at OUT.xmf is not written through. */
START_TEST(xdmf_does_not_follow_a_link)
{
    const char *h5 = tu_tmp("l.h5"), *xmf = tu_tmp("l.xmf"),
               *victim = tu_write("victim.txt", "precious\n");
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", h5, "--set", "scene.t_end=0.5", NULL),
                     0);
    unlink(xmf);
    ck_assert_int_eq(symlink(victim, xmf), 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "xdmf", h5, NULL);
    ck_assert_msg(rc == 5 && strstr(err, "l.xmf"), "exit %d: %s", rc, err);
    free(err);
    char buf[64] = "";
    FILE *f = fopen(victim, "r");
    ck_assert(f && fgets(buf, sizeof buf, f));
    fclose(f);
    ck_assert_str_eq(buf, "precious\n");
    /* a hard link at OUT.xmf: writing it would change its other name */
    unlink(xmf);
    ck_assert_int_eq(link(victim, xmf), 0);
    rc = tu_run(NULL, &err, "xdmf", h5, NULL);
    ck_assert_msg(rc == 5 && strstr(err, "hard link"), "exit %d: %s", rc,
                  err);
    free(err);
    f = fopen(victim, "r");
    ck_assert(f && fgets(buf, sizeof buf, f));
    fclose(f);
    ck_assert_str_eq(buf, "precious\n");
}
END_TEST

/* SIGTERM that arrives as xdmf or info starts: exit 6, no sidecar. */
START_TEST(xdmf_and_info_stop_on_sigterm)
{
    const char *h5 = tu_tmp("s.h5"), *xmf = tu_tmp("s.xmf");
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", h5, "--set", "scene.t_end=0.5", NULL),
                     0);
    unlink(xmf);
    const char *x[] = {"xdmf", h5, "-o", xmf, NULL};
    char *err = NULL;
    int rc = fh5_exec(x, 10, 1LL << 30, 1, &err);
    ck_assert_msg(rc == 6, "xdmf: exit %d: %s", rc, err);
    ck_assert_msg(access(xmf, F_OK) != 0, "xdmf left %s", xmf);
    free(err);
    const char *i[] = {"info", h5, NULL};
    rc = fh5_exec(i, 10, 1LL << 30, 1, &err);
    ck_assert_msg(rc == 6, "info: exit %d: %s", rc, err);
    free(err);
}
END_TEST

/* An interrupted run leaves OUT.h5.part: no warning that OUT.h5 does not
 * open. */
START_TEST(interrupted_run_has_no_sidecar_warning)
{
    const char *h5 = tu_tmp("i.h5");
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-q",
                    "-o", h5, "--stop-after", "10", NULL);
    ck_assert_int_eq(rc, 6);
    ck_assert_msg(!strstr(err, "XDMF"), "%s", err);
    free(err);
}
END_TEST

/* Terminal escape sequences in a file's text are shown, not obeyed. */
START_TEST(info_escapes_control_characters)
{
    const char *h5 = tu_tmp("e.h5");
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", h5, "--set", "scene.t_end=0.5", NULL),
                     0);
    hid_t f = H5Fopen(h5, H5F_ACC_RDWR, H5P_DEFAULT);
    ck_assert(f >= 0);
    H5Adelete(f, "scene.title");
    const char *title = "t\x1b]2;owned\x07\x1b[31m\xc2\x9b" "1m\nstatus: ok";
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
    H5Tset_size(t, H5T_VARIABLE);
    hid_t a = H5Acreate2(f, "scene.title", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    ck_assert(a >= 0 && H5Awrite(a, t, &title) >= 0);
    H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    H5Fclose(f);
    char *out = NULL;
    ck_assert_int_eq(tu_run(&out, NULL, "info", h5, NULL), 0);
    ck_assert_msg(!strchr(out, '\x1b') && !strchr(out, '\x07') &&
                      !strstr(out, "\xc2\x9b"),
                  "raw control characters in: %s", out);
    ck_assert_msg(strstr(out, "\\x1b]2;owned"), "%s", out);
    /* the text's second line is indented under its label */
    ck_assert_msg(!strstr(out, "\nstatus: ok"), "%s", out);
    free(out);
}
END_TEST

Suite *suite_hostile_read(void)
{
    Suite *s = suite_create("hostile_read");
    TCase *c = tu_tcase("hostile_read");
    tcase_add_test(c, mutated_outputs_are_refused_cleanly);
    tcase_add_test(c, info_refuses_an_array_for_a_number);
    tcase_add_test(c, xdmf_does_not_follow_a_link);
    tcase_add_test(c, xdmf_and_info_stop_on_sigterm);
    tcase_add_test(c, interrupted_run_has_no_sidecar_warning);
    tcase_add_test(c, info_escapes_control_characters);
    suite_add_tcase(s, c);
    return s;
}
