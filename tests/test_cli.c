/* test_cli.c: the command line's conventions, on the program itself:
 * --name=VALUE and --name VALUE, bundled short options (-qo X), -V and
 * --version, `--` ends the options, unknown and incomplete options refused
 * with status 2 naming the option and `ballfilm CMD --help`, and an input
 * file that does not exist refused with status 2 "FILE: no such file"
 * before HDF5 opens it (a file that is there but is not HDF5 stays an I/O
 * error, test_info.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ballfilm/version.h"
#include "testutil.h"

static const char *const scene =
    "[scene]\ntitle = cli test\nintegrator = verlet\neffects = gravity floor\n"
    "dt = 1e-3\nt_end = 0.05\noutput_every = 10\n[ball.1]\nposition = 0.2\n";

static int exists(const char *path)
{
    struct stat st;
    return !stat(path, &st);
}

START_TEST(output_with_equals_and_bundled_short_options)
{
    /* copies: tu_tmp's buffers rotate */
    char ini[600], a[600];
    snprintf(ini, sizeof ini, "%s", tu_write("eq.ini", scene));
    snprintf(a, sizeof a, "%s", tu_tmp("eq_a.h5"));
    const char *b = tu_tmp("eq_b.h5");
    char opt[700];
    snprintf(opt, sizeof opt, "--output=%s", a);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "run", ini, opt, "-q", NULL), 0);
    ck_assert_msg(exists(a), "--output=FILE wrote nothing: %s", err);
    free(err);
    /* -qo FILE: -q and -o with its value in one word and the next */
    ck_assert_int_eq(tu_run(NULL, &err, "run", "-qo", b, ini, NULL), 0);
    ck_assert_msg(exists(b), "-qo FILE wrote nothing: %s", err);
    free(err);
    /* -oFILE */
    char glued[700];
    snprintf(glued, sizeof glued, "-o%s", tu_tmp("eq_c.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", ini, "-q", glued, NULL), 0);
    ck_assert(exists(tu_tmp("eq_c.h5")));
    /* --set=k=v and --set k=v; a unique prefix of a long name */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", ini, "-q", "--out",
                            tu_tmp("eq_d.h5"), "--set=scene.t_end=0.02",
                            "--set", "ball.1.mass=2", NULL), 0);
    ck_assert(exists(tu_tmp("eq_d.h5")));
    /* the other commands: xdmf --output=, sweep --set= and -qo */
    snprintf(opt, sizeof opt, "--output=%s", tu_tmp("eq_a.xmf"));
    ck_assert_int_eq(tu_run(NULL, NULL, "xdmf", a, opt, NULL), 0);
    ck_assert(exists(tu_tmp("eq_a.xmf")));
    ck_assert_int_eq(tu_run(NULL, &err, "sweep", ini, "--vary=ball.1.mass=1,2",
                            "--set=scene.t_end=0.02", "-qo", tu_tmp("sw"),
                            "--jobs=1", NULL), 0);
    ck_assert_msg(exists(tu_tmp("sw/summary.csv")), "%s", err);
    free(err);
}
END_TEST

START_TEST(version_at_the_top_level)
{
    const char *forms[] = {"-V", "--version", "version"};
    for (size_t k = 0; k < 3; k++) {
        char *out = NULL;
        ck_assert_int_eq(tu_run(&out, NULL, forms[k], NULL), 0);
        ck_assert_msg(strstr(out, BF_VERSION), "%s: %s", forms[k], out);
        free(out);
    }
    char *out = NULL;
    ck_assert_int_eq(tu_run(&out, NULL, "--help", NULL), 0);
    ck_assert(strstr(out, "usage: ballfilm") && strstr(out, "[scene]"));
    free(out);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "--frobnicate", NULL), 2);
    ck_assert_msg(strstr(err, "'--frobnicate'") &&
                  strstr(err, "'ballfilm --help'"), "%s", err);
    free(err);
}
END_TEST

/* An operand that begins with '-' after `--`; options may follow the
 * operand and come before `--`. */
START_TEST(double_dash_ends_the_options)
{
    ck_assert_int_eq(chdir(tu_tmpdir()), 0);
    tu_write("-dash.ini", scene);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "run", "-q", "-o", "dash.h5", "--",
                            "-dash.ini", NULL), 0);
    ck_assert_msg(exists("dash.h5"), "%s", err);
    free(err);
    /* after `--` an option-looking word is an operand: a second scene */
    ck_assert_int_eq(tu_run(NULL, &err, "run", "-q", "--", "-dash.ini", "-q",
                            NULL), 2);
    ck_assert_msg(strstr(err, "more than one scene"), "%s", err);
    free(err);
    ck_assert_int_eq(tu_run(NULL, &err, "info", "--", "-none.h5", NULL), 2);
    ck_assert_msg(strstr(err, "-none.h5: no such file"), "%s", err);
    free(err);
}
END_TEST

/* Status 2 and a message naming the option and the command's --help. */
static void refused(const char *want, const char *cmd, const char *const *argv)
{
    char *err = NULL;
    int rc = tu_runv(NULL, &err, argv);
    ck_assert_msg(rc == 2, "%s %s: status %d", cmd, argv[1], rc);
    char help[64];
    snprintf(help, sizeof help, "'ballfilm %s --help'", cmd);
    ck_assert_msg(strstr(err, want) && strstr(err, help), "%s: %s", want, err);
    free(err);
}

START_TEST(unknown_and_incomplete_options_refused)
{
    const char *ini = tu_write("bad.ini", scene);
    const char *h5 = tu_tmp("bad.h5");
    const char *a1[] = {"run", ini, "--frobnicate", NULL};
    refused("unknown option '--frobnicate'", "run", a1);
    const char *a2[] = {"run", ini, "-qz", NULL};
    refused("unknown option '-z'", "run", a2);
    const char *a3[] = {"run", ini, "-o", NULL};
    refused("'-o/--output' needs a value", "run", a3);
    const char *a4[] = {"run", ini, "--quiet=yes", NULL};
    refused("'-q/--quiet' takes no value", "run", a4);
    const char *a5[] = {"sweep", ini, "--vary", "ball.1.mass=1,2", "--jbos",
                        "2", NULL};
    refused("unknown option '--jbos'", "sweep", a5);
    const char *a6[] = {"converge", ini, "--methods", "rk4", "--dt", NULL};
    refused("'--dt' needs a value", "converge", a6);
    const char *a7[] = {"xdmf", h5, "--frames=3", NULL};
    refused("unknown option '--frames'", "xdmf", a7);
    const char *a8[] = {"info", h5, "-x", NULL};
    refused("unknown option '-x'", "info", a8);
    const char *a9[] = {"animate", h5, "--fsp", "3", NULL};
    refused("unknown option '--fsp'", "animate", a9);
    const char *a10[] = {"run", ini, "--s", "x", NULL};
    refused("ambiguous option '--s'", "run", a10);
    ck_assert(!exists(h5));
    /* every command answers --help and -h on stdout */
    const char *cmds[] = {"run", "sweep", "converge", "xdmf", "animate",
                          "info"};
    for (size_t k = 0; k < 6; k++) {
        char *out = NULL;
        ck_assert_int_eq(tu_run(&out, NULL, cmds[k], "-h", NULL), 0);
        ck_assert_msg(strstr(out, "usage: ballfilm ") &&
                      strstr(out, cmds[k]), "%s: %s", cmds[k], out);
        free(out);
    }
}
END_TEST

START_TEST(missing_input_is_bad_input)
{
    const char *missing = tu_tmp("nothing_here.h5");
    const char *cmds[][5] = {
        {"info", missing, NULL},
        {"xdmf", missing, NULL},
        {"animate", missing, NULL},
        {"run", "--restart", missing, "-q", NULL},
    };
    for (size_t k = 0; k < sizeof cmds / sizeof *cmds; k++) {
        char *err = NULL;
        int rc = tu_runv(NULL, &err, cmds[k]);
        ck_assert_msg(rc == 2, "%s: status %d: %s", cmds[k][0], rc, err);
        ck_assert_msg(strstr(err, "nothing_here.h5: no such file"), "%s: %s",
                      cmds[k][0], err);
        free(err);
    }
    /* a directory of the path that is a file: no such file either */
    const char *ini = tu_write("notdir.ini", scene);
    char below[700];
    snprintf(below, sizeof below, "%s/x.h5", ini);
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "info", below, NULL), 2);
    ck_assert_msg(strstr(err, "no such file"), "%s", err);
    free(err);
}
END_TEST

Suite *suite_cli(void)
{
    Suite *s = suite_create("cli");
    TCase *tc = tu_tcase("cli");
    tcase_add_test(tc, output_with_equals_and_bundled_short_options);
    tcase_add_test(tc, version_at_the_top_level);
    tcase_add_test(tc, double_dash_ends_the_options);
    tcase_add_test(tc, unknown_and_incomplete_options_refused);
    tcase_add_test(tc, missing_input_is_bad_input);
    suite_add_tcase(s, tc);
    return s;
}
