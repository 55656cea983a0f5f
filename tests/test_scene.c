/* test_scene.c: scene parsing and validation.  Every bad input of the
 * foundation issue gives "FILE:LINE: error: ..." naming the key, through
 * the library and through the program (exit status 2), and never touches
 * an existing output file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "ballfilm/run.h"
#include "testutil.h"

#define GOOD_HEAD                                                              \
    "[scene]\n"              /* 1 */                                           \
    "effects = gravity floor contact\n" /* 2 */                                \
    "dt = 1e-4\n"            /* 3 */                                           \
    "t_end = 0.01\n"         /* 4 */                                           \
    "[ball.1]\n"             /* 5 */                                           \
    "position = 0.2\n"       /* 6 */                                           \
    "mass = 1.2\n"           /* 7 */                                           \
    "[ball.2]\n"             /* 8 */                                           \
    "position = 0.5\n"       /* 9 */

typedef struct bad_case {
    const char *what;
    const char *text;
    const char *where; /* expected "test.ini:LINE" prefix */
    const char *says;  /* expected fragment naming the key */
} bad_case;

static const bad_case bad[] = {
    {"unknown section", GOOD_HEAD "[gravty]\ng = 980\n", "test.ini:10:",
     "[gravty]"},
    {"unknown key", GOOD_HEAD "radius = 0.1\nradus = 0.1\n", "test.ini:11:",
     "[ball.2] radus: unknown key"},
    {"not a number", "[scene]\ndt = fast\nt_end = 1\n[ball.1]\nposition = 1\n",
     "test.ini:2:", "[scene] dt: 'fast' is not a finite real number"},
    {"dt = 0", "[scene]\ndt = 0\nt_end = 1\n[ball.1]\nposition = 1\n",
     "test.ini:2:", "[scene] dt: '0' must be > 0"},
    {"dt < 0", "[scene]\ndt = -1e-3\nt_end = 1\n[ball.1]\nposition = 1\n",
     "test.ini:2:", "must be > 0"},
    {"mass = 0", GOOD_HEAD "mass = 0\n", "test.ini:10:",
     "[ball.2] mass: '0' must be > 0"},
    {"mass < 0", GOOD_HEAD "mass = -1\n", "test.ini:10:", "[ball.2] mass"},
    {"radius = 0", GOOD_HEAD "radius = 0\n", "test.ini:10:",
     "[ball.2] radius: '0' must be > 0"},
    {"overlap", GOOD_HEAD "[ball.3]\nposition = 0.65\n", "test.ini:11:",
     "[ball.3] position: balls 2 and 3 overlap"},
    {"below the floor", "[scene]\neffects = floor\ndt = 1\nt_end = 1\n"
                        "[ball.1]\nposition = 0.05\n",
     "test.ini:6:", "[ball.1] position"},
    {"duplicate key", "[scene]\ndt = 1\ndt = 2\n", "test.ini:3:", "twice"},
    {"missing required", "[scene]\nt_end = 1\n[ball.1]\nposition = 1\n",
     "test.ini:1:", "[scene] dt: required key is missing"},
    {"section of an unused effect", GOOD_HEAD "[spring]\nstiffness = 1\n",
     "test.ini:10:", "[spring]"},
    {"unknown effect", "[scene]\neffects = gravity magnet\ndt = 1\nt_end = 1\n",
     "test.ini:2:", "unknown effect 'magnet'"},
    {"unknown integrator", "[scene]\nintegrator = euler\ndt = 1\nt_end = 1\n",
     "test.ini:2:", "unknown integrator 'euler'"},
    {"syntax", "[scene]\ndt 1\n", "test.ini:2:", "syntax"},
    {"key outside section", "dt = 1\n", "test.ini:1:", "before any"},
    {"gap in balls", GOOD_HEAD "[ball.4]\nposition = 2\n", "test.ini",
     "[ball.3]"},
    {"bad interval", GOOD_HEAD "[scene]\n", "test.ini", ""}, /* see below */
};

START_TEST(bad_inputs_library)
{
    char msg[BF_ERR_MSG];
    for (size_t k = 0; k < sizeof bad / sizeof bad[0] - 1; k++) {
        bf_status st = tu_scene_error(bad[k].text, msg, sizeof msg);
        ck_assert_msg(st == BF_EINPUT, "%s: status %d (%s)", bad[k].what, st, msg);
        ck_assert_msg(!strncmp(msg, bad[k].where, strlen(bad[k].where)),
                      "%s: message '%s' does not start with '%s'", bad[k].what,
                      msg, bad[k].where);
        ck_assert_msg(strstr(msg, bad[k].says), "%s: message '%s' lacks '%s'",
                      bad[k].what, msg, bad[k].says);
        ck_assert_msg(strstr(msg, "error:"), "%s: %s", bad[k].what, msg);
    }
}
END_TEST

START_TEST(good_scene_and_defaults)
{
    bf_scene *sc = tu_scene(GOOD_HEAD);
    ck_assert(bf_scene_real(sc, "ball.2", "mass") == 1.0);    /* default */
    ck_assert(bf_scene_real(sc, "ball.1", "mass") == 1.2);    /* given */
    ck_assert(bf_scene_real(sc, "floor", "k") == 1e7);        /* default */
    ck_assert(bf_scene_real(sc, "gravity", "g") == 980);
    ck_assert_int_eq(bf_scene_count(sc, "ball"), 2);
    ck_assert(!bf_scene_given(sc, "ball.2", "mass"));
    ck_assert(bf_scene_given(sc, "ball.1", "mass"));
    bf_scene_free(sc);
    /* "0.5 s" in a [ball] section is not a key there */
    char msg[BF_ERR_MSG];
    ck_assert(tu_scene_error(GOOD_HEAD "output_every = 0.5 s\n", msg,
                             sizeof msg) == BF_EINPUT);
    /* intervals */
    sc = tu_scene("[scene]\ndt = 0.01\nt_end = 1\noutput_every = 0.5 s\n"
                  "[ball.1]\nposition = 1\n");
    bf_interval iv = bf_scene_interval(sc, "scene", "output_every");
    ck_assert(iv.in_time && iv.time == 0.5);
    bf_scene_free(sc);
    ck_assert(tu_scene_error("[scene]\ndt = 0.01\nt_end = 1\n"
                             "output_every = 3 parsecs\n[ball.1]\nposition=1\n",
                             msg, sizeof msg) == BF_EINPUT);
    ck_assert_msg(strstr(msg, "test.ini:4:") && strstr(msg, "output_every"), "%s",
                  msg);
}
END_TEST

START_TEST(overrides)
{
    bf_scene *sc;
    bf_err err = {0};
    ck_assert(bf_scene_load_string(&sc, "x.ini", GOOD_HEAD, &err) == 0);
    ck_assert(bf_scene_set(sc, "ball.2.mass=0.8", "--set", &err) == 0);
    ck_assert(bf_scene_set(sc, "scene.integrator = verlet", "--set", &err) == 0);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == 0);
    ck_assert(bf_scene_real(sc, "ball.2", "mass") == 0.8);
    ck_assert_str_eq(bf_scene_str(sc, "scene", "integrator"), "verlet");
    /* a bad override names --set */
    ck_assert(bf_scene_set(sc, "scene.dt=-1", "--set", &err) == 0);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "--set") && strstr(err.msg, "dt"), "%s", err.msg);
    ck_assert(bf_scene_set(sc, "nodot=1", "--set", &err) == BF_EINPUT);
    ck_assert(bf_scene_set(sc, "scene.dt", "--set", &err) == BF_EINPUT);
    bf_scene_free(sc);
}
END_TEST

START_TEST(multiline_and_long_lines)
{
    bf_scene *sc;
    bf_err err = {0};
    /* an indented line continues the value */
    ck_assert(bf_scene_load_string(&sc, "m.ini",
                                   "[scene]\neffects = gravity\n  floor\n"
                                   "dt = 1\nt_end = 1\n[ball.1]\nposition = 1\n",
                                   &err) == 0);
    ck_assert(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == 0);
    ck_assert(bf_scene_has_name(sc, "scene", "effects", "floor"));
    bf_scene_free(sc);
    char text[6000] = "[scene]\ntitle = ";
    memset(text + strlen(text), 'x', 5000);
    ck_assert(bf_scene_load_string(&sc, "l.ini", text, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "l.ini:2:") && strstr(err.msg, "too long"), "%s",
                  err.msg);
}
END_TEST

/* ---- through the program: status 2, message on stderr, nothing written */

START_TEST(bad_inputs_program)
{
    char out[512];
    snprintf(out, sizeof out, "%s", tu_tmp("keep.h5"));
    FILE *f = fopen(out, "w");
    fputs("precious", f);
    fclose(f);
    for (size_t k = 0; k < sizeof bad / sizeof bad[0] - 1; k++) {
        const char *path = tu_write("test.ini", bad[k].text);
        char *err = NULL;
        int rc = tu_run(NULL, &err, "run", path, "-o", out, "-q", NULL);
        ck_assert_msg(rc == 2, "%s: exit %d, stderr %s", bad[k].what, rc, err);
        /* the program names the file by the path it was given */
        ck_assert_msg(strstr(err, path) && strstr(err, "error:") &&
                          strstr(err, bad[k].says),
                      "%s: stderr '%s'", bad[k].what, err);
        free(err);
    }
    char buf[32] = "";
    f = fopen(out, "r");
    ck_assert(fgets(buf, sizeof buf, f) != NULL);
    fclose(f);
    ck_assert_str_eq(buf, "precious");
    /* missing scene file */
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_tmp("nope.ini"), "-o", out, NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "nope.ini") && strstr(err, "cannot open"), "%s", err);
    free(err);
    /* bad --set */
    const char *good = tu_write("good.ini", GOOD_HEAD);
    rc = tu_run(NULL, &err, "run", good, "-o", out, "--set", "ball.2.mass=-2",
                NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "--set") && strstr(err, "[ball.2] mass"), "%s", err);
    free(err);
    rc = tu_run(NULL, &err, "run", good, "--frobnicate", NULL);
    ck_assert_int_eq(rc, 2);
    free(err);
    struct stat stt;
    ck_assert(stat(out, &stt) == 0 && stt.st_size == 8);
}
END_TEST

START_TEST(help_lists_every_key)
{
    char *out = NULL;
    int rc = tu_run(&out, NULL, "run", "--help", NULL);
    ck_assert_int_eq(rc, 0);
    /* keys with units and defaults from the same tables the parser uses */
    const char *want[] = {"[scene]", "dt", "t_end", "output_every", "[ball.N]",
                          "mass", "unit g", "[gravity]", "default 980",
                          "[floor]", "[contact]", "[spring]", "mv2m", "verlet"};
    for (size_t k = 0; k < sizeof want / sizeof want[0]; k++)
        ck_assert_msg(strstr(out, want[k]), "help lacks '%s'", want[k]);
    free(out);
}
END_TEST

Suite *suite_scene(void)
{
    Suite *s = suite_create("scene");
    TCase *tc = tu_tcase("parse");
    tcase_add_test(tc, bad_inputs_library);
    tcase_add_test(tc, good_scene_and_defaults);
    tcase_add_test(tc, overrides);
    tcase_add_test(tc, multiline_and_long_lines);
    tcase_add_test(tc, bad_inputs_program);
    tcase_add_test(tc, help_lists_every_key);
    suite_add_tcase(s, tc);
    return s;
}
