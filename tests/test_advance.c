/* test_advance.c: runs of steps in one call (bf_ballsys_advance, the
 * model hook `advance` and the core loop's runs between events) give
 * exactly what one call per step gives: the same bits of the state, the
 * same counters and force cache, the same failing step, state and message
 * when a run blows up, and the same datasets through the whole program.
 *
 * Independent reference: bf_ballsys_step called once per step with
 * t = n dt, the path every run took before runs existed. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/ballsys.h"
#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "testutil.h"

/* Scenes covering every path of ballsys.c: the two fixed effect lists of
 * the long runs (one ball with gravity and floor; two balls with gravity,
 * floor and contact), any other list (three balls; a spring), for the
 * integrators with runs of their own (Verlet, MV2M) and two without. */
typedef struct scene_case {
    const char *effects, *balls;
} scene_case;
static const scene_case scenes[] = {
    {"gravity floor", "[ball.1]\nposition = 0.2\n"},
    {"gravity floor contact",
     "[ball.1]\nposition = 0.2\nmass = 0.8\n[ball.2]\nposition = 0.5\n"},
    {"gravity floor contact",
     "[ball.1]\nposition = 0.2\nmass = 0.8\n[ball.2]\nposition = 0.5\n"
     "[ball.3]\nposition = 0.8\nmass = 1.3\n"},
    {"gravity floor contact spring",
     "[ball.1]\nposition = 0.2\nmass = 0.8\n[ball.2]\nposition = 0.5\n"
     "[spring]\nstiffness = 3000\nrest = 0.4\n"},
};
static const char *methods[] = {"verlet", "mv2m", "rk4", "impmid", "rkn6",
                                "greenspan73"};

static const char *scene_text(const scene_case *c, const char *method,
                              double dt)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "[scene]\nintegrator = %s\ndt = %.17g\nt_end = 1\n"
             "effects = %s\n%s",
             method, dt, c->effects, c->balls);
    return text;
}

static int same_bits(const double *a, const double *b, size_t n)
{
    return !memcmp(a, b, n * sizeof *a);
}

/* state, counters and force cache of two systems agree bit for bit */
static void assert_same(const bf_ballsys *a, const bf_ballsys *b,
                        const char *what, long n)
{
    size_t nb = a->b.n;
    const bf_integrator *p = a->it, *q = b->it;
    ck_assert_msg(same_bits(a->b.x, b->b.x, nb) && same_bits(a->b.v, b->b.v, nb),
                  "%s: state differs after %ld steps", what, n);
    ck_assert_msg(p->count.steps == q->count.steps &&
                      p->count.evals == q->count.evals &&
                      p->count.rejected == q->count.rejected &&
                      p->count.iterations == q->count.iterations,
                  "%s: counters differ after %ld steps (evals %llu, %llu)",
                  what, n, p->count.evals, q->count.evals);
    ck_assert_msg(p->cache_valid == q->cache_valid &&
                      p->cache_epoch == q->cache_epoch &&
                      (!p->cache_valid ||
                       (same_bits(p->cache_x, q->cache_x, nb) &&
                        same_bits(p->cache_a, q->cache_a, nb))),
                  "%s: force cache differs after %ld steps", what, n);
}

START_TEST(advance_matches_steps)
{
    /* chunks of every size class: one step, short, across contacts */
    static const long chunks[] = {1, 2, 3, 1000, 1, 517, 4096, 7, 9000};
    const double dt = 1e-4;
    for (size_t si = 0; si < sizeof scenes / sizeof *scenes; si++)
        for (size_t mi = 0; mi < sizeof methods / sizeof *methods; mi++) {
            const char *text = scene_text(&scenes[si], methods[mi], dt);
            bf_ballsys *ref = tu_ballsys(text), *run = tu_ballsys(text);
            char what[64];
            snprintf(what, sizeof what, "scene %zu, %s", si, methods[mi]);
            bf_err err = {0};
            long n = 0;
            for (size_t c = 0; c < sizeof chunks / sizeof *chunks; c++) {
                if (c == 5) { /* the force field changed: cache invalid */
                    ref->ode.epoch++;
                    run->ode.epoch++;
                }
                for (long j = 0; j < chunks[c]; j++)
                    ck_assert_msg(bf_ballsys_step(ref, (double)(n + j) * dt,
                                                  dt, &err) == BF_OK,
                                  "%s: %s", what, err.msg);
                long done = -1;
                ck_assert_msg(bf_ballsys_advance(run, n, chunks[c], dt, NULL, &done,
                                                 &err) == BF_OK,
                              "%s: %s", what, err.msg);
                ck_assert_int_eq(done, chunks[c]);
                n += chunks[c];
                assert_same(ref, run, what, n);
            }
            /* k = 0 changes nothing */
            long done = -1;
            ck_assert(bf_ballsys_advance(run, n, 0, dt, NULL, &done, &err) == BF_OK);
            ck_assert_int_eq(done, 0);
            assert_same(ref, run, what, n);
            /* every step counted once (1.46 s: floor and ball contacts) */
            ck_assert_uint_eq(ref->it->count.steps, (unsigned long long)n);
            bf_ballsys_free(ref);
            bf_ballsys_free(run);
        }
}
END_TEST

/* x'' = -x for every ball: a force of the caller's own (tests plug forces
 * in this way); runs then take the generic path one step at a time. */
static int harmonic(void *ctx, double t, const double *x, const double *v,
                    double *a)
{
    (void)t;
    (void)v;
    const bf_ballsys *s = ctx;
    for (size_t i = 0; i < s->b.n; i++)
        a[i] = -x[i];
    return 0;
}

START_TEST(advance_with_callers_force)
{
    for (size_t mi = 0; mi < 2; mi++) {
        const char *text = scene_text(&scenes[1], methods[mi], 1e-2);
        bf_ballsys *ref = tu_ballsys(text), *run = tu_ballsys(text);
        ref->ode.accel = run->ode.accel = harmonic;
        bf_err err = {0};
        for (long j = 0; j < 300; j++)
            ck_assert(bf_ballsys_step(ref, (double)j * 1e-2, 1e-2, &err) == 0);
        long done;
        ck_assert(bf_ballsys_advance(run, 0, 300, 1e-2, NULL, &done, &err) == 0);
        ck_assert_int_eq(done, 300);
        assert_same(ref, run, methods[mi], 300);
        bf_ballsys_free(ref);
        bf_ballsys_free(run);
    }
}
END_TEST

/* Beyond a method's limit the state overflows.  A run must stop at the
 * step where one call per step stops, with its state, counters and
 * message: *done counts the steps before it.  Verlet at dt = 1e-3 on the
 * two balls first becomes non-finite after 7744 steps (velocity inf,
 * position still finite: the case the end-of-run check relies on, see
 * ballsys.c), MV2M at 3e-3 after 14; the three-ball list takes the
 * per-step check of the general run. */
static void blowup(const scene_case *body, const char *method, double dt,
                   long expect_step)
{
    const char *text = scene_text(body, method, dt);
    bf_ballsys *ref = tu_ballsys(text), *run = tu_ballsys(text);
    bf_err eref = {0}, erun = {0};
    long fail = 0;
    for (long j = 0; j < 100000 && !fail; j++)
        if (bf_ballsys_step(ref, (double)j * dt, dt, &eref)) {
            ck_assert_int_eq(eref.status, BF_EUNSTABLE);
            fail = j + 1;
        }
    ck_assert_msg(fail > 0, "%s dt = %g did not blow up", method, dt);
    if (expect_step)
        ck_assert_int_eq(fail, expect_step);
    /* one run that contains the failing step, started a few steps in */
    long done = -1, first = fail > 3 ? 3 : 0;
    for (long j = 0; j < first; j++)
        ck_assert(bf_ballsys_step(run, (double)j * dt, dt, &erun) == BF_OK);
    bf_status st = bf_ballsys_advance(run, first, 100000, dt, NULL, &done, &erun);
    ck_assert_int_eq(st, BF_EUNSTABLE);
    ck_assert_int_eq(first + done, fail - 1);
    ck_assert_str_eq(erun.msg, eref.msg);
    assert_same(ref, run, method, fail);
    bf_ballsys_free(ref);
    bf_ballsys_free(run);
}

START_TEST(advance_stops_at_the_failing_step)
{
    blowup(&scenes[1], "verlet", 1e-3, 7744);
    blowup(&scenes[1], "mv2m", 3e-3, 14);
    /* one ball does not gain enough energy to overflow; thrown at a
     * stiff floor at 1e150 cm/s (a finite initial energy: a faster ball
     * is refused as a scene), its first step ends 1e147 cm below it,
     * where the force k d^{3/2} = 1e100 (1e147)^{3/2} is inf */
    static const scene_case deep = {
        "gravity floor",
        "[floor]\nk = 1e100\n[ball.1]\nposition = 0.2\nvelocity = -1e150\n"};
    blowup(&deep, "verlet", 1e-3, 1);
    blowup(&deep, "mv2m", 1e-3, 1);
    blowup(&scenes[2], "verlet", 3e-3, 0);
    blowup(&scenes[2], "mv2m", 3e-3, 0);
}
END_TEST

/* Through the program: with energy_every = 1 the runs of steps make the
 * energy check after every step themselves (watched runs); with energy
 * checks only at rows the loop hands the model plain runs up to each row.
 * Same datasets (positions, velocities, energies at rows, times and steps
 * of the rows) and the same force evaluations.  (Against one step per
 * call: watched_runs_are_steps below.) */
static void same_through_loop(const char *method)
{
    char a[512], b[512], seta[64];
    snprintf(a, sizeof a, "%s", tu_tmp(method));
    strncat(a, ".steps.h5", sizeof a - strlen(a) - 1);
    snprintf(b, sizeof b, "%s", tu_tmp(method));
    strncat(b, ".runs.h5", sizeof b - strlen(b) - 1);
    snprintf(seta, sizeof seta, "scene.integrator=%s", method);
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char *oa = NULL, *ob = NULL;
    int rc = tu_run(&oa, NULL, "run", scene, "-o", a, "--set", seta, "--set",
                    "scene.t_end=20", "--set", "scene.output_every=1237",
                    "--set", "return_map.enabled=no", "--set",
                    "scene.energy_every=1", NULL);
    ck_assert_int_eq(rc, 0);
    rc = tu_run(&ob, NULL, "run", scene, "-o", b, "--set", seta, "--set",
                "scene.t_end=20", "--set", "scene.output_every=1237", "--set",
                "return_map.enabled=no", "--set", "scene.energy_every=0",
                NULL);
    ck_assert_int_eq(rc, 0);
    tu_same_datasets(a, b);
    const char *ea = strstr(oa, "force evaluations:"),
               *eb = strstr(ob, "force evaluations:");
    ck_assert(ea && eb);
    ck_assert_msg(!strncmp(ea, eb, strcspn(ea, "\n")), "%s\n%s", oa, ob);
    free(oa);
    free(ob);
}

START_TEST(loop_runs_same_datasets)
{
    same_through_loop("verlet");
    same_through_loop("mv2m");
}
END_TEST

/* A blow-up inside a run of the loop: the same step, time and message in
 * a watched run (energy every step) and a plain one (Verlet, dt = 1e-3:
 * step 7744). */
START_TEST(loop_run_fails_at_the_same_step)
{
    const char *scene = tu_repo("runs/two_balls_B.ini");
    char *e1 = NULL, *e2 = NULL;
    int r1 = tu_run(NULL, &e1, "run", scene, "-q", "--set",
                    "scene.integrator=verlet", "--set", "scene.dt=1e-3",
                    "--set", "scene.max_energy_error=0", "--set",
                    "return_map.enabled=no", "--set", "scene.energy_every=1",
                    NULL);
    int r2 = tu_run(NULL, &e2, "run", scene, "-q", "--set",
                    "scene.integrator=verlet", "--set", "scene.dt=1e-3",
                    "--set", "scene.max_energy_error=0", "--set",
                    "return_map.enabled=no", "--set", "scene.energy_every=0",
                    NULL);
    ck_assert_int_eq(r1, 3);
    ck_assert_int_eq(r2, 3);
    ck_assert_msg(strstr(e1, "step 7744 ") && strstr(e1, "non-finite"), "%s",
                  e1);
    ck_assert_str_eq(e1, e2);
    free(e1);
    free(e2);
}
END_TEST

/* The program's run of a scene (text) with the return map and the energy
 * after every step, one step per call (step_by_step) or in watched runs;
 * its datasets in `out`, its status and message returned. */
static bf_status run_scene_file(const char *text, int step_by_step,
                                const char *out, char *msg, size_t cap)
{
    bf_scene *sc;
    bf_err err = {0};
    ck_assert(bf_scene_load_string(&sc, "watch.ini", text, &err) == BF_OK);
    ck_assert_msg(bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK,
                  "%s", err.msg);
    bf_sim_opts opts = {.step_by_step = step_by_step};
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, &opts,
                                    &err) == BF_OK, "%s", err.msg);
    ck_assert(bf_sim_open_output(sim, out, &err) == BF_OK);
    bf_status st = bf_sim_run(sim, &err);
    bf_err cerr = {0};
    ck_assert(bf_sim_close_output(sim, st, &err, &cerr) == BF_OK);
    snprintf(msg, cap, "%s", st ? err.msg : "");
    bf_sim_free(sim);
    bf_scene_free(sc);
    return st;
}

/* Watched runs (integrator.h, bf_ball_watch): the energy check after every
 * step and the return map's events made inside runs of steps give the
 * datasets of one step per call bit for bit (return-map points, energies,
 * states, the run's largest energy error), and a run that exceeds the
 * energy bound or blows up stops at the same step with the same message.
 * Every path: the fixed shapes (one ball; two balls, MV2M and Verlet), any
 * effects (three balls; a spring), a method without runs of its own (RK4). */
START_TEST(watched_runs_are_steps)
{
    static const struct {
        const char *method, *dt, *bound, *t_end;
        int scene;
    } cases[] = {
        {"mv2m", "1e-4", "0.5", "30", 1},   {"verlet", "1e-4", "0.5", "30", 1},
        {"mv2m", "1e-4", "0.5", "20", 0},   {"mv2m", "1e-4", "0.5", "20", 2},
        {"verlet", "1e-4", "0.5", "20", 3}, {"rk4", "1e-4", "0.5", "10", 1},
        /* the energy bound stops these */
        {"verlet", "1e-3", "1e-3", "30", 1}, {"mv2m", "2e-3", "0.05", "30", 2},
        /* and these blow up (no bound); the last two within a few steps
         * of the end of a floor contact (the return map's point, noted in
         * the run that fails, is the output's) */
        {"verlet", "1e-3", "0", "30", 1}, {"verlet", "3e-3", "0", "30", 1},
        {"mv2m", "3e-3", "0", "30", 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char text[1536], a[600], b[600], ma[BF_ERR_MSG], mb[BF_ERR_MSG];
        snprintf(text, sizeof text,
                 "[scene]\nintegrator = %s\ndt = %s\nt_end = %s\n"
                 "effects = %s\noutput_every = 997\nenergy_every = 1\n"
                 "max_energy_error = %s\n[return_map]\nenabled = yes\n"
                 "record = %d\n%s",
                 cases[c].method, cases[c].dt, cases[c].t_end,
                 scenes[cases[c].scene].effects, cases[c].bound,
                 cases[c].scene ? 2 : 1, scenes[cases[c].scene].balls);
        snprintf(a, sizeof a, "%s%zu.h5", tu_tmp("watch_steps"), c);
        snprintf(b, sizeof b, "%s%zu.h5", tu_tmp("watch_runs"), c);
        bf_status sa = run_scene_file(text, 1, a, ma, sizeof ma);
        bf_status sb = run_scene_file(text, 0, b, mb, sizeof mb);
        ck_assert_msg(sa == sb, "case %zu: status %d by steps, %d in runs",
                      c, sa, sb);
        ck_assert_msg(!strcmp(ma, mb), "case %zu:\n%s\n%s", c, ma, mb);
        if (c >= 6)
            ck_assert_msg(sa == BF_EUNSTABLE, "case %zu: status %d", c, sa);
        tu_same_datasets(a, b);
        /* the run's largest energy error, an attribute (every step's) */
        double ea = -1, eb = -2;
        bf_err e = {0};
        ck_assert(bf_h5_read_attr_real(tu_result(a), "/",
                                       "max_relative_energy_error", &ea,
                                       &e) == BF_OK);
        ck_assert(bf_h5_read_attr_real(tu_result(b), "/",
                                       "max_relative_energy_error", &eb,
                                       &e) == BF_OK);
        ck_assert_msg(!memcmp(&ea, &eb, sizeof ea),
                      "case %zu: max energy error %.17g by steps, %.17g in "
                      "runs", c, ea, eb);
    }
}
END_TEST

Suite *suite_advance(void)
{
    Suite *s = suite_create("advance");
    TCase *tc = tu_tcase("runs");
    tcase_add_test(tc, advance_matches_steps);
    tcase_add_test(tc, advance_with_callers_force);
    tcase_add_test(tc, advance_stops_at_the_failing_step);
    tcase_add_test(tc, loop_runs_same_datasets);
    tcase_add_test(tc, loop_run_fails_at_the_same_step);
    tcase_add_test(tc, watched_runs_are_steps);
    suite_add_tcase(s, tc);
    return s;
}
