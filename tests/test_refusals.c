/* test_refusals.c: what cannot run is refused, and what went wrong is not
 * called success (docs/reliability.md): an energy error beyond the
 * model's bound stops the run, dt > t_end and a non-finite initial state
 * are refused before anything is written, every stop names step, time and
 * cause, and the summary of a blown-up run does not describe its garbage.
 *
 * Each test runs the program the way a user does and checks the exit
 * status, the message and what is (not) on disk. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "ballfilm/h5out.h"
#include "testutil.h"

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* Neither OUT nor OUT.part exists. */
static void nothing_written(const char *out)
{
    char part[700];
    snprintf(part, sizeof part, "%s.part", out);
    ck_assert_msg(!exists(out) && !exists(part), "%s was written", out);
}

/* The reproducer: Verlet at dt = 2.5 s on x'' = -x is far beyond
 * its stability limit (dt < 2); the energy error reached 5.7e47 and the
 * run ended "ok".  The balls' effects are conservative, so the model's
 * bound (0.5) applies by default and stops the run after its first step
 * (error 5.49). */
START_TEST(energy_beyond_the_models_bound_is_unstable)
{
    const char *out = tu_tmp("garbage.h5");
    char *err = NULL, *sum = NULL;
    int rc = tu_run(&sum, &err, "run", tu_repo("runs/harmonic.ini"), "-q",
                    "-o", out, "--set", "scene.integrator=verlet", "--set",
                    "scene.dt=2.5", "--set", "scene.t_end=100", NULL);
    ck_assert_int_eq(rc, 3);
    ck_assert_msg(strstr(err, "step 1 (t = 2.5 s)") &&
                      strstr(err, "relative energy error") &&
                      strstr(err, "bound of this model"),
                  "%s", err);
    ck_assert_msg(!strstr(sum, "wrote"), "%s", sum);
    char *status = NULL;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_str(tu_result(out), "/", "status", &status,
                                  &e) == BF_OK);
    ck_assert_str_eq(status, "unstable");
    free(status);
    free(err);
    free(sum);
    /* switched off, the same run ends (the user asked for it) */
    rc = tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"), "-q", "-o",
                out, "--set", "scene.integrator=verlet", "--set",
                "scene.dt=2.5", "--set", "scene.t_end=100", "--set",
                "scene.energy_bound=no", NULL);
    ck_assert_int_eq(rc, 0);
    /* a bound given replaces the model's: 0 is none, a larger one lets
     * the first steps through */
    rc = tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"), "-q", "-o",
                out, "--set", "scene.integrator=verlet", "--set",
                "scene.dt=2.5", "--set", "scene.t_end=100", "--set",
                "scene.max_energy_error=0", NULL);
    ck_assert_int_eq(rc, 0);
    rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-q", "-o",
                out, "--set", "scene.integrator=verlet", "--set",
                "scene.dt=2.5", "--set", "scene.t_end=100", "--set",
                "scene.max_energy_error=1e6", NULL);
    ck_assert_int_eq(rc, 3);
    ck_assert_msg(strstr(err, "max_energy_error = 1e+06") &&
                      !strstr(err, "step 1 "),
                  "%s", err);
    free(err);
    /* a stable run of the same model is not touched by the bound */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", out, NULL),
                     0);
}
END_TEST

START_TEST(dt_beyond_t_end_refused)
{
    const char *out = tu_tmp("dt_t_end.h5");
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-q",
                    "-o", out, "--set", "scene.dt=2", "--set", "scene.t_end=1",
                    NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "[scene] dt") && strstr(err, "t_end"), "%s",
                  err);
    free(err);
    nothing_written(out);
    /* dt = t_end is one step to t_end exactly */
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", out, "--set", "scene.dt=1", "--set",
                            "scene.t_end=1", "--set",
                            "scene.energy_bound=no", NULL),
                     0);
}
END_TEST

/* A state whose energy overflows is refused before the output exists
 * (it used to be written as row 0 with an infinite energy error, and the
 * run ended "ok"), naming the key. */
START_TEST(non_finite_initial_state_refused)
{
    const char *out = tu_tmp("inf_state.h5");
    static const char *const cases[][2] = {
        {"ball.1.velocity=1e200", "[ball.1] velocity"},
        {"ball.1.position=1e200", "[ball.1] position"},
    };
    for (int k = 0; k < 2; k++) {
        char *err = NULL;
        int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-q",
                        "-o", out, "--set", cases[k][0], NULL);
        ck_assert_int_eq(rc, 2);
        ck_assert_msg(strstr(err, cases[k][1]) && strstr(err, "not finite"),
                      "%s: %s", cases[k][0], err);
        free(err);
        nothing_written(out);
    }
    /* in a scene file the message names its line */
    const char *scene = tu_write(
        "inf_state.ini", "[scene]\nmodel = balls\neffects = gravity\n"
                         "dt = 1e-3\nt_end = 1\n[gravity]\ng = 980\n"
                         "[ball.1]\nposition = 1\nvelocity = -3e200\n");
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "run", scene, "-q", "-o", out, NULL),
                     2);
    ck_assert_msg(strstr(err, "inf_state.ini:10:") &&
                      strstr(err, "[ball.1] velocity"),
                  "%s", err);
    free(err);
    nothing_written(out);
}
END_TEST

/* Two of Greenspan's particles on one spot at t = 0: the repulsion has no
 * direction.  That is the scene's fault: refused (exit 2), naming the
 * particles, the time and the key; it used to stop as "unstable" naming
 * no step or time. */
START_TEST(coinciding_particles_named)
{
    const char *out = tu_tmp("coincide.h5");
    char *err = NULL;
    int rc = tu_run(
        NULL, &err, "run", tu_repo("runs/greenspan72_ex1.ini"), "-q", "-o", out,
        "--set",
        "greenspan72.positions=12.5 87.5  37.5 87.5  62.5 87.5  87.5 87.5 "
        "12.5 62.5  37.5 62.5  62.5 62.5  87.5 62.5 12.5 37.5  37.5 37.5 "
        "62.5 37.5  87.5 37.5 12.5 12.5  37.5 12.5  62.5 12.5  37.5 12.5",
        NULL);
    ck_assert_int_eq(rc, 2);
    ck_assert_msg(strstr(err, "[greenspan72] positions") &&
                      strstr(err, "at t = 0") &&
                      strstr(err, "particles 14 and 16 coincide"),
                  "%s", err);
    free(err);
    nothing_written(out);
}
END_TEST

/* A film forced beyond its stable step blows up: the run stops unstable
 * naming step, time and node, and the summary says so instead of
 * printing the blown-up state's "relative change 0" and kink error next
 * to "max |u| inf". */
START_TEST(blown_up_film_summary)
{
    const char *out = tu_tmp("blowup.h5");
    char *err = NULL, *sum = NULL;
    int rc = tu_run(&sum, &err, "run", tu_repo("runs/kink_steady.ini"), "-q",
                    "-o", out, "--set", "film.force_dt=yes", "--set",
                    "scene.dt=0.05", "--set", "scene.t_end=20", NULL);
    ck_assert_int_eq(rc, 3);
    ck_assert_msg(strstr(err, "step 7 (t = 0.3 s to 0.35 s)") &&
                      strstr(err, "non-finite"),
                  "%s", err);
    ck_assert_msg(strstr(sum, "unstable after 6 steps (t = 0.3 s)") &&
                      !strstr(sum, "relative change") &&
                      !strstr(sum, "kink error") && !strstr(sum, "inf"),
                  "%s", sum);
    free(err);
    free(sum);
}
END_TEST

/* ---- scene text ---- */

/* harmonic.ini with a line of `len` characters after [scene]'s header:
 * a title (key line) or a comment. */
static const char *long_line_scene(const char *name, size_t len, int comment)
{
    char *line = malloc(len + 1);
    const char *lead = comment ? "; " : "title = ";
    size_t l = strlen(lead);
    memcpy(line, lead, l);
    for (size_t k = l; k < len; k++)
        line[k] = (char)('a' + k % 26);
    line[len] = '\0';
    size_t cap = len + 512;
    char *text = malloc(cap);
    snprintf(text, cap,
             "[scene]\n%s\nmodel = balls\neffects = spring\ndt = 0.01\n"
             "t_end = 0.1\n[spring]\nstiffness = 1\n[ball.1]\n"
             "position = 1\n",
             line);
    const char *path = tu_write(name, text);
    free(line);
    free(text);
    return path;
}

/* inih (Debian's build) reads lines of at most 198 characters: up to
 * that a line works (150, 198), a longer key line is refused at its line
 * with the limit and the way round it (199, 5000), a comment line of any
 * length is skipped (it was refused). */
START_TEST(long_lines)
{
    const char *out = tu_tmp("long.h5");
    static const size_t ok_len[] = {150, 198};
    for (int k = 0; k < 2; k++) {
        const char *scene = long_line_scene("long_ok.ini", ok_len[k], 0);
        char *err = NULL;
        int rc = tu_run(NULL, &err, "run", scene, "-q", "-o", out, NULL);
        ck_assert_msg(rc == 0, "%zu: %s", ok_len[k], err);
        free(err);
        /* the whole value arrived */
        char *title = NULL;
        bf_err e = {0};
        ck_assert(bf_h5_read_attr_str(out, "/", "scene.title", &title, &e) ==
                  BF_OK);
        ck_assert_uint_eq(strlen(title), ok_len[k] - strlen("title = "));
        free(title);
    }
    static const size_t bad_len[] = {199, 5000};
    for (int k = 0; k < 2; k++) {
        const char *scene = long_line_scene("long_bad.ini", bad_len[k], 0);
        char *err = NULL;
        ck_assert_int_eq(tu_run(NULL, &err, "run", scene, "-q", "-o",
                                tu_tmp("long_bad.h5"), NULL),
                         2);
        ck_assert_msg(strstr(err, "long_bad.ini:2: error: line too long") &&
                          strstr(err, "at most 198 characters") &&
                          strstr(err, "continuation"),
                      "%zu: %s", bad_len[k], err);
        free(err);
        nothing_written(tu_tmp("long_bad.h5"));
    }
    const char *scene = long_line_scene("long_comment.ini", 5000, 1);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-q", "-o", out, NULL),
                     0);
}
END_TEST

/* A scene must be UTF-8 text: a binary file (the program itself), a NUL
 * byte, a Latin-1 comment or --set value are refused with FILE:LINE (and
 * the column), exit 2; a file name that is not UTF-8 reaches the output's
 * attributes escaped (\xNN), never as invalid UTF-8 tagged UTF-8. */
START_TEST(scene_must_be_text)
{
    const char *out = tu_tmp("text.h5");
    const char *bin = getenv("BALLFILM_BIN");
    char *err = NULL;
    ck_assert_int_eq(tu_run(NULL, &err, "run", bin, "-q", "-o", out, NULL), 2);
    char want[700];
    snprintf(want, sizeof want, "%s:1: error:", bin);
    ck_assert_msg(strstr(err, want), "%s", err);
    free(err);
    nothing_written(out);
    const char *nul = tu_tmp("nul.ini");
    FILE *f = fopen(nul, "wb");
    ck_assert(f && fwrite("[scene]\nmodel = balls\n\0x\n", 1, 26, f) == 26);
    fclose(f);
    ck_assert_int_eq(tu_run(NULL, &err, "run", nul, "-q", "-o", out, NULL), 2);
    ck_assert_msg(strstr(err, "nul.ini:3: error: a NUL byte"), "%s", err);
    free(err);
    const char *latin1 = tu_write(
        "latin1.ini", "[scene]\nmodel = balls\neffects = spring\n"
                      "; 20 \xb0" "C\ndt = 0.01\nt_end = 0.1\n"
                      "[ball.1]\nposition = 1\n");
    ck_assert_int_eq(tu_run(NULL, &err, "run", latin1, "-q", "-o", out, NULL),
                     2);
    ck_assert_msg(strstr(err, "latin1.ini:4: error: not UTF-8") &&
                      strstr(err, "0xb0 at column 6"),
                  "%s", err);
    free(err);
    ck_assert_int_eq(tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"),
                            "-q", "-o", out, "--set", "scene.title=caf\xe9",
                            NULL),
                     2);
    ck_assert_msg(strstr(err, "scene.title: the value is not UTF-8"), "%s",
                  err);
    free(err);
    nothing_written(out);
    /* a scene whose name is Latin-1 */
    char odd[600];
    snprintf(odd, sizeof odd, "%s/caf\xe9.ini", tu_tmpdir());
    FILE *in = fopen(tu_repo("runs/harmonic.ini"), "rb"),
         *cp = fopen(odd, "wb");
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        ck_assert(fwrite(buf, 1, n, cp) == n);
    fclose(in);
    fclose(cp);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", odd, "-q", "-o", out, NULL), 0);
    char *file = NULL;
    bf_err e = {0};
    ck_assert(bf_h5_read_attr_str(out, "/", "scene_file", &file, &e) ==
              BF_OK);
    ck_assert_msg(strstr(file, "caf\\xe9.ini"), "%s", file);
    free(file);
}
END_TEST

/* ---- memory ---- */

static int sanitized(void) { return getenv("BALLFILM_SANITIZED") != NULL; }

/* A Greenspan 1973 scene of n particles in a square (layout = list). */
static const char *g73_scene(const char *name, int n)
{
    size_t cap = (size_t)n * 24 + 256, used = 0;
    char *text = malloc(cap);
    used += (size_t)snprintf(text, cap, "[scene]\nmodel = greenspan73\n"
                             "dt = 1e-4\nt_end = 2e-4\n[greenspan73]\n"
                             "layout = list\npositions =");
    int side = 1;
    while (side * side < n)
        side++;
    for (int i = 0; i < n; i++)
        used += (size_t)snprintf(text + used, cap - used, "%s%g %g\n",
                                 i ? "  " : " ", 1.1 * (i % side),
                                 1.1 * (i / side));
    const char *path = tu_write(name, text);
    free(text);
    return path;
}

/* Memory bombs are refused before anything is allocated, with exit 2, the
 * estimate and the key that sets the size: a film of 1e8 nodes (27 GiB),
 * 5e7 Greenspan 1972 particles (19 GiB), 20000 Greenspan 1973 particles
 * (their N^2 arrays, 18 GiB).  The runs are made under an address-space
 * limit of 8 GiB (ulimit -v), so that the test does not depend on the
 * memory of the machine; without a limit the machine's available memory
 * decides (base/sysmem.h).  Each is refused in set-up, at once (the
 * limit would not let a run allocate anyway). */
START_TEST(memory_bombs_refused)
{
    if (sanitized())
        return; /* RLIMIT_AS and the sanitizers' shadow memory exclude
                   each other; make test covers this */
    const char *out = tu_tmp("bomb.h5");
    struct {
        const char *what;
        const char *argv[12];
        const char *expect;
    } cases[] = {
        {"film",
         {"run", tu_repo("runs/kink_steady.ini"), "-q", "-o", out, "--set",
          "film.dx=5e-7", NULL},
         "[film] dx: 1e+08 nodes"},
        {"greenspan72",
         {"run", tu_repo("runs/greenspan72_large.ini"), "-q", "-o", out,
          "--set", "greenspan72.grid_nx=7071", "--set",
          "greenspan72.grid_ny=7071", NULL},
         "[greenspan72] grid_nx: 5e+07 particles"},
        {"greenspan73",
         {"run", g73_scene("g73_20000.ini", 20000), "-q", "-o", out, NULL},
         "[greenspan73] positions: 20000 particles x 20000 particles"},
    };
    tu_run_limit_as(8LL << 30);
    for (int k = 0; k < 3; k++) {
        char *err = NULL;
        int rc = tu_runv(NULL, &err, cases[k].argv);
        ck_assert_msg(rc == 2, "%s: exit %d\n%s", cases[k].what, rc, err);
        ck_assert_msg(strstr(err, cases[k].expect) && strstr(err, "GiB") &&
                          strstr(err, "ulimit -v"),
                      "%s: %s", cases[k].what, err);
        free(err);
        nothing_written(out);
    }
    /* a smaller film (1e6 nodes, 339 MiB with the program's reserve)
     * under ulimit -v 256 MiB is refused; without the limit it runs */
    const char *small[] = {"run", tu_repo("runs/kink_steady.ini"), "-q", "-o",
                           out, "--set", "film.length=1e5", "--set",
                           "scene.t_end=0.003", "--set", "film.force_dt=yes",
                           NULL};
    tu_run_limit_as(256LL << 20);
    char *err = NULL;
    ck_assert_int_eq(tu_runv(NULL, &err, small), 2);
    ck_assert_msg(strstr(err, "[film] dx: 1e+06 nodes") &&
                      strstr(err, "MiB"),
                  "%s", err);
    free(err);
    nothing_written(out);
    tu_run_limit_as(0);
    ck_assert_int_eq(tu_runv(NULL, NULL, small), 0);
}
END_TEST

/* Under any memory limit a run ends with one of the documented statuses
 * and a message: refused by the estimate (2), or it runs (0); never killed
 * by a signal (HDF5 and GSL crash or abort when their allocations fail,
 * so nothing may reach them short of memory), never a bare status 1.
 * Limits from 40 MiB (below that the dynamic loader itself fails) to
 * 400 MiB, on a coupled run of 1e5 film nodes (about 170 MiB). */
START_TEST(any_memory_limit_documented_status)
{
    if (sanitized())
        return;
    const char *out = tu_tmp("limited.h5");
    const char *argv[] = {"run", tu_repo("runs/coupled_fig8.ini"), "-q", "-o",
                          out, "--set", "film.length=10000", "--set",
                          "scene.t_end=5e-5", NULL};
    int seen[8] = {0};
    for (long mib = 40; mib <= 400; mib += 24) {
        tu_run_limit_as((long long)mib << 20);
        char *err = NULL;
        int rc = tu_runv(NULL, &err, argv);
        ck_assert_msg(rc == 0 || rc == 2 || (rc == 1 && strstr(err, "memory")),
                      "ulimit -v %ld MiB: exit %d\n%s", mib, rc, err);
        if (rc == 2)
            ck_assert_msg(strstr(err, "memory") && strstr(err, "leaves"),
                          "%ld MiB: %s", mib, err);
        seen[rc]++;
        free(err);
    }
    tu_run_limit_as(0);
    ck_assert_msg(seen[0] && seen[2], "refused %d, ran %d", seen[2], seen[0]);
}
END_TEST

Suite *suite_refusals(void)
{
    Suite *s = suite_create("refusals");
    TCase *tc = tu_tcase("refusals");
    tcase_add_test(tc, energy_beyond_the_models_bound_is_unstable);
    tcase_add_test(tc, dt_beyond_t_end_refused);
    tcase_add_test(tc, non_finite_initial_state_refused);
    tcase_add_test(tc, coinciding_particles_named);
    tcase_add_test(tc, blown_up_film_summary);
    tcase_add_test(tc, long_lines);
    tcase_add_test(tc, scene_must_be_text);
    tcase_add_test(tc, memory_bombs_refused);
    tcase_add_test(tc, any_memory_limit_documented_status);
    suite_add_tcase(s, tc);
    return s;
}
