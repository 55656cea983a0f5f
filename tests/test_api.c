/* test_api.c: the library as a program drives it (run.h, sim.h): scenes
 * written in code, initial fields from arrays, heartbeats, running in
 * pieces, and runs in two threads of one process.
 *
 * Every test compares against something the library computes another
 * way: the same scene from INI text (bit for bit), the same run in one
 * piece (bit for bit), the same runs one after the other (bit for bit),
 * or the scene's own initial state (a field set from arrays equal to it
 * gives the scene's run, bit for bit).  A bit-identity test can fail: a
 * heartbeat that ended a run of steps in a different place, a set-up that
 * forgot a cached force or the energy reference, or a run that shared
 * state with another thread would each change the last bits.
 */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/film.h"
#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "testutil.h"

static const char *const two_balls =
    "[scene]\nintegrator = mv2m\neffects = gravity floor contact\n"
    "dt = 1e-4\nt_end = 2\noutput_every = 100\n"
    "[ball.1]\nposition = 0.2\nmass = 1.2\nradius = 0.1\n"
    "[ball.2]\nposition = 0.6\nmass = 1\nradius = 0.1\n"
    "[lyapunov]\nenabled = yes\n";

static bf_run *run_text(const char *text, const char *const *sets,
                        size_t nsets)
{
    bf_run *r;
    bf_err err = {0};
    ck_assert_msg(bf_run_from_text(&r, bf_catalog_builtin(), "api.ini", text,
                                   sets, nsets, NULL, &err) == BF_OK,
                  "%s", err.msg);
    return r;
}

/* The positions and velocities of a balls run, copied. */
static void ball_state(bf_sim *sim, double *x, double *v, size_t n)
{
    size_t nx, nv;
    const double *px = bf_sim_get(sim, "balls/position", &nx);
    const double *pv = bf_sim_get(sim, "balls/velocity", &nv);
    ck_assert(px && pv && nx == n && nv == n);
    memcpy(x, px, n * sizeof *x);
    memcpy(v, pv, n * sizeof *v);
}

START_TEST(a_scene_written_in_code_is_the_scene_of_the_same_text)
{
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load_string(&sc, "code", "", &err) == BF_OK);
    const char *const keys[] = {
        "scene.integrator=mv2m", "scene.effects=gravity floor contact",
        "scene.dt=1e-4", "scene.t_end=2", "scene.output_every=100",
        "lyapunov.enabled=yes"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
        ck_assert_msg(bf_setf(sc, &err, "%s", keys[k]) == BF_OK, "%s",
                      err.msg);
    int i1, i2;
    ck_assert(bf_add_ball(sc, 0.2, 0, 1.2, 0.1, &i1, &err) == BF_OK);
    ck_assert(bf_add_ball(sc, 0.6, 0, 1, 0.1, &i2, &err) == BF_OK);
    ck_assert(i1 == 1 && i2 == 2);
    bf_run *a;
    ck_assert_msg(bf_run_from_scene(&a, bf_catalog_builtin(), sc, NULL,
                                    &err) == BF_OK, "%s", err.msg);
    bf_run *b = run_text(two_balls, NULL, 0);
    ck_assert(bf_sim_run(bf_run_sim(a), &err) == BF_OK);
    ck_assert(bf_sim_run(bf_run_sim(b), &err) == BF_OK);
    double xa[2], va[2], xb[2], vb[2];
    ball_state(bf_run_sim(a), xa, va, 2);
    ball_state(bf_run_sim(b), xb, vb, 2);
    ck_assert(!memcmp(xa, xb, sizeof xa) && !memcmp(va, vb, sizeof va));
    bf_results ra, rb;
    bf_sim_results(bf_run_sim(a), &ra);
    bf_sim_results(bf_run_sim(b), &rb);
    ck_assert(ra.has_lyapunov &&
              !memcmp(&ra.lyapunov_exponent, &rb.lyapunov_exponent,
                      sizeof(double)));
    bf_run_free(a);
    bf_run_free(b);
}
END_TEST

START_TEST(a_key_set_in_code_is_checked_like_a_file)
{
    bf_err err = {0};
    bf_scene *sc;
    ck_assert(bf_scene_load_string(&sc, "code", "", &err) == BF_OK);
    ck_assert(bf_setf(sc, &err, "scene.dt=%g", 1e-3) == BF_OK);
    ck_assert(bf_setf(sc, &err, "scene.t_end=1") == BF_OK);
    ck_assert(bf_add_ball(sc, 1, 0, 1, 0.1, NULL, &err) == BF_OK);
    ck_assert(bf_setf(sc, &err, "ball.1.mas=2") == BF_OK);
    bf_run *r = NULL;
    ck_assert(bf_run_from_scene(&r, bf_catalog_builtin(), sc, NULL, &err) ==
              BF_EINPUT);
    ck_assert(r == NULL);
    ck_assert_msg(strstr(err.msg, "code") && strstr(err.msg, "mas"), "%s",
                  err.msg);
}
END_TEST

/* A film of the Fig. 5 kind, short.  The kink of eq. 3.17 computed here
 * on the nodes (film/x) and set as psi on a uniform film gives the run of
 * the scene's own kink, bit for bit; a wave of height changes the run. */
static const char *const film =
    "[scene]\nmodel = film\ndt = 1e-3\nt_end = 0.2\noutput_every = 20\n"
    "[film]\nlength = 10\ndx = 0.1\ninitial = kink\n";

START_TEST(film_fields_set_from_arrays_are_the_scene_s_fields)
{
    bf_err err = {0};
    bf_run *a = run_text(film, NULL, 0);
    bf_run *b = run_text(film, (const char *const[]){"film.initial=uniform"},
                         1);
    bf_sim *sa = bf_run_sim(a), *sb = bf_run_sim(b);
    size_t n;
    const double *x = bf_sim_get(sb, "film/x", &n);
    ck_assert(x && n == 101);
    const bf_film_params p = {.a = 1, .b = 1, .gamma = 1};
    double *copy = malloc(n * sizeof *copy);
    for (size_t i = 0; i < n; i++)
        copy[i] = bf_film_kink(&p, 0.0, x[i]);
    ck_assert_msg(bf_sim_set(sb, "film/psi", copy, n, &err) == BF_OK, "%s",
                  err.msg);
    ck_assert(bf_sim_run(sa, &err) == BF_OK);
    ck_assert(bf_sim_run(sb, &err) == BF_OK);
    ck_assert(!memcmp(bf_sim_get(sa, "film/psi", NULL),
                      bf_sim_get(sb, "film/psi", NULL), n * sizeof(double)));
    ck_assert(!memcmp(bf_sim_get(sa, "film/u_d", NULL),
                      bf_sim_get(sb, "film/u_d", NULL), n * sizeof(double)));
    for (size_t i = 0; i < n; i++)
        copy[i] = 1.0;
    /* too late now; before the first step a bad value is refused with the
     * node named, and the state is unchanged */
    ck_assert(bf_sim_set(sb, "film/h", copy, n, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "before the first step"), "%s", err.msg);
    bf_run *c = run_text(film, NULL, 0);
    bf_sim *sc = bf_run_sim(c);
    const double h7 = bf_sim_get(sc, "film/h", NULL)[7];
    copy[7] = -1.0;
    ck_assert(bf_sim_set(sc, "film/h", copy, n, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "film/h") && strstr(err.msg, "node 7"),
                  "%s", err.msg);
    ck_assert(bf_sim_get(sc, "film/h", NULL)[7] == h7);
    ck_assert(bf_sim_set(sc, "film/h", copy, n - 1, &err) == BF_EINPUT);
    ck_assert(bf_sim_set(sc, "film/x", copy, n, &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "film/h, film/psi, film/u_d, film/u_c"),
                  "%s", err.msg);
    /* a bump of height: the film moves differently */
    for (size_t i = 0; i < n; i++)
        copy[i] = 1.0 + 0.01 * cos(3.14159265358979323846 * (double)i / (double)(n - 1));
    ck_assert(bf_sim_set(sc, "film/h", copy, n, &err) == BF_OK);
    ck_assert(bf_sim_run(sc, &err) == BF_OK);
    ck_assert(memcmp(bf_sim_get(sa, "film/u_d", NULL),
                     bf_sim_get(sc, "film/u_d", NULL), n * sizeof(double)));
    free(copy);
    bf_run_free(a);
    bf_run_free(b);
    bf_run_free(c);
}
END_TEST

/* Balls: positions set from arrays are checked like [ball.N] positions;
 * set equal to the scene's, the run (with its Lyapunov shadow, seeded
 * anew) is the scene's; set elsewhere, the run and the energy reference
 * start there. */
START_TEST(ball_positions_set_from_arrays)
{
    bf_err err = {0};
    bf_run *a = run_text(two_balls, NULL, 0);
    bf_run *b = run_text(two_balls,
                         (const char *const[]){"ball.2.position=0.9"}, 1);
    bf_sim *sa = bf_run_sim(a), *sb = bf_run_sim(b);
    double x[2] = {0.2, 0.6};
    ck_assert(bf_sim_set(sb, "balls/position", (double[]){0.6, 0.2}, 2,
                         &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "increasing position"), "%s", err.msg);
    ck_assert(bf_sim_set(sb, "balls/position", (double[]){0.05, 0.6}, 2,
                         &err) == BF_EINPUT);
    ck_assert_msg(strstr(err.msg, "penetrates the floor"), "%s", err.msg);
    ck_assert(bf_sim_get(sb, "balls/position", NULL)[1] == 0.9);
    ck_assert_msg(bf_sim_set(sb, "balls/position", x, 2, &err) == BF_OK,
                  "%s", err.msg);
    ck_assert(bf_sim_run(sa, &err) == BF_OK);
    ck_assert(bf_sim_run(sb, &err) == BF_OK);
    double xa[2], va[2], xb[2], vb[2];
    ball_state(sa, xa, va, 2);
    ball_state(sb, xb, vb, 2);
    ck_assert(!memcmp(xa, xb, sizeof xa) && !memcmp(va, vb, sizeof va));
    ck_assert(bf_sim_max_energy_error(sa) == bf_sim_max_energy_error(sb));
    bf_results ra, rb;
    bf_sim_results(sa, &ra);
    bf_sim_results(sb, &rb);
    ck_assert(!memcmp(&ra.lyapunov_exponent, &rb.lyapunov_exponent,
                      sizeof(double)));
    bf_run_free(a);
    bf_run_free(b);
}
END_TEST

/* ---- heartbeats ---- */

typedef struct beats {
    long calls, last_step;
    long steps[64];
    double energy_error;
    long stop_at; /* return BF_INTERRUPTED at this step (0: never) */
} beats;

static bf_status beat(void *ctx, bf_sim *sim, bf_err *err)
{
    (void)err;
    beats *b = ctx;
    if (b->calls < 64)
        b->steps[b->calls] = bf_sim_steps_done(sim);
    b->calls++;
    b->last_step = bf_sim_steps_done(sim);
    b->energy_error = bf_sim_max_energy_error(sim);
    if (b->stop_at && bf_sim_steps_done(sim) == b->stop_at)
        return BF_INTERRUPTED;
    return BF_OK;
}

START_TEST(heartbeats_come_when_asked_and_change_no_bit)
{
    bf_err err = {0};
    /* no [lyapunov]: the loop takes runs of steps, which the heartbeat
     * every 37 steps must end there without changing a bit */
    const char *const sets[] = {"lyapunov.enabled=no"};
    bf_run *a = run_text(two_balls, sets, 1), *b = run_text(two_balls, sets,
                                                            1);
    beats every = {0}, rows = {0};
    ck_assert(bf_sim_heartbeat(bf_run_sim(b), 37, beat, &every, &err) ==
              BF_OK);
    ck_assert(bf_sim_heartbeat(bf_run_sim(b), 0, beat, &rows, &err) == BF_OK);
    ck_assert(bf_sim_heartbeat(bf_run_sim(b), -1, beat, &rows, &err) ==
              BF_EINPUT);
    ck_assert(bf_sim_run(bf_run_sim(a), &err) == BF_OK);
    ck_assert(bf_sim_run(bf_run_sim(b), &err) == BF_OK);
    /* 20000 steps: t = 0 and every 37th step; rows at 0, 100, ..., 20000 */
    ck_assert_int_eq(every.calls, 20000 / 37 + 1);
    ck_assert(every.steps[0] == 0 && every.steps[1] == 37 &&
              every.last_step == 20000 / 37 * 37);
    ck_assert_int_eq(rows.calls, 201);
    ck_assert(rows.steps[1] == 100 && rows.last_step == 20000);
    ck_assert(rows.energy_error == bf_sim_max_energy_error(bf_run_sim(b)));
    double xa[2], va[2], xb[2], vb[2];
    ball_state(bf_run_sim(a), xa, va, 2);
    ball_state(bf_run_sim(b), xb, vb, 2);
    ck_assert(!memcmp(xa, xb, sizeof xa) && !memcmp(va, vb, sizeof va));
    bf_run_free(a);
    bf_run_free(b);
}
END_TEST

/* A run in pieces (run_until, steps), one interrupted by its heartbeat
 * and restarted, all give the datasets of the run in one piece. */
START_TEST(runs_in_pieces_and_restarts_are_the_run_in_one_piece)
{
    bf_err err = {0};
    const char *full = tu_tmp("api_full.h5"), *pieces = tu_tmp("api_pieces.h5"),
               *stopped = tu_tmp("api_stopped.h5");
    bf_run *a = run_text(two_balls, NULL, 0), *b = run_text(two_balls, NULL, 0),
           *c = run_text(two_balls, NULL, 0);
    ck_assert(bf_run_open_output(a, full, &err) == BF_OK);
    ck_assert(bf_run_open_output(b, pieces, &err) == BF_OK);
    ck_assert(bf_run_open_output(c, stopped, &err) == BF_OK);
    bf_status st = bf_sim_run(bf_run_sim(a), &err);
    ck_assert(bf_sim_close_output(bf_run_sim(a), st, &err, &err) == BF_OK);
    bf_sim *sb = bf_run_sim(b);
    ck_assert(bf_sim_run_until(sb, 0.55, &err) == BF_OK);
    ck_assert_int_eq(bf_sim_steps_done(sb), 5500);
    ck_assert(bf_sim_steps(sb, 777, &err) == BF_OK);
    ck_assert_int_eq(bf_sim_steps_done(sb), 6277);
    ck_assert(bf_sim_run_until(sb, 0.1, &err) == BF_OK); /* in the past */
    ck_assert_int_eq(bf_sim_steps_done(sb), 6277);
    ck_assert(bf_sim_run_until(sb, 99.0, &err) == BF_OK); /* to t_end */
    ck_assert_int_eq(bf_sim_steps_done(sb), 20000);
    ck_assert(bf_sim_close_output(sb, BF_OK, &err, &err) == BF_OK);
    beats stop = {.stop_at = 4321};
    ck_assert(bf_sim_heartbeat(bf_run_sim(c), 1, beat, &stop, &err) == BF_OK);
    st = bf_sim_run(bf_run_sim(c), &err);
    ck_assert_msg(st == BF_INTERRUPTED && strstr(err.msg, "checkpoint"),
                  "%d %s", st, err.msg);
    ck_assert(bf_sim_close_output(bf_run_sim(c), st, &err, &err) == BF_OK);
    bf_run_free(c);
    ck_assert_msg(bf_run_restart(&c, bf_catalog_builtin(), stopped, NULL, 0,
                                 NULL, &err) == BF_OK, "%s", err.msg);
    ck_assert_int_eq(bf_sim_steps_done(bf_run_sim(c)), 4321);
    st = bf_sim_run(bf_run_sim(c), &err);
    ck_assert(bf_sim_close_output(bf_run_sim(c), st, &err, &err) == BF_OK);
    ck_assert(st == BF_OK);
    tu_same_datasets(full, pieces);
    tu_same_datasets(full, stopped);
    bf_run_free(a);
    bf_run_free(b);
    bf_run_free(c);
}
END_TEST

/* ---- two runs in two threads ---- */

typedef struct job {
    const char *text, *out; /* out NULL: no output file */
    double x[2], v[2], lyap;
    bf_status st;
    char msg[BF_ERR_MSG];
} job;

static void *run_job(void *arg)
{
    job *j = arg;
    bf_err err = {0};
    bf_run *r = NULL;
    j->st = bf_run_from_text(&r, bf_catalog_builtin(), "thread.ini", j->text,
                             NULL, 0, NULL, &err);
    if (!j->st && j->out)
        j->st = bf_run_open_output(r, j->out, &err);
    if (!j->st) {
        j->st = bf_sim_run(bf_run_sim(r), &err);
        if (j->out) {
            bf_err cerr = {0};
            bf_status cst = bf_sim_close_output(bf_run_sim(r), j->st, &err,
                                                &cerr);
            if (!j->st)
                j->st = cst;
        }
    }
    if (!j->st) {
        const double *x = bf_sim_get(bf_run_sim(r), "balls/position", NULL);
        const double *v = bf_sim_get(bf_run_sim(r), "balls/velocity", NULL);
        memcpy(j->x, x, sizeof j->x);
        memcpy(j->v, v, sizeof j->v);
        bf_results res;
        bf_sim_results(bf_run_sim(r), &res);
        j->lyap = res.lyapunov_exponent;
    }
    snprintf(j->msg, sizeof j->msg, "%s", err.msg);
    bf_run_free(r);
    return NULL;
}

/* Two different scenes at once, with and without output files (HDF5 is
 * serialised by the library's lock), against the same two one after the
 * other: the same bits, the same files. */
START_TEST(two_runs_in_two_threads_do_not_interfere)
{
    /* a flush at every row of 10 steps: the two threads are in HDF5
     * nearly all the time (without the lock HDF5's shared state breaks:
     * failed writes, corrupt files or a crash) */
    char one[1024], other[1100];
    const char *rows = strstr(two_balls, "output_every = 100\n");
    snprintf(one, sizeof one, "%.*soutput_every = 10\nflush_seconds = 1e-9\n%s",
             (int)(rows - two_balls), two_balls,
             rows + strlen("output_every = 100\n"));
    snprintf(other, sizeof other, "%s[contact]\nk = 5e6\n", one);
    for (int with_output = 0; with_output < 2; with_output++) {
        job seq[2] = {{.text = one}, {.text = other}};
        job par[2] = {{.text = one}, {.text = other}};
        if (with_output) {
            seq[0].out = tu_tmp("seq0.h5");
            seq[1].out = tu_tmp("seq1.h5");
            par[0].out = tu_tmp("par0.h5");
            par[1].out = tu_tmp("par1.h5");
        }
        run_job(&seq[0]);
        run_job(&seq[1]);
        pthread_t th[2];
        for (int k = 0; k < 2; k++)
            ck_assert(!pthread_create(&th[k], NULL, run_job, &par[k]));
        for (int k = 0; k < 2; k++)
            ck_assert(!pthread_join(th[k], NULL));
        for (int k = 0; k < 2; k++) {
            ck_assert_msg(seq[k].st == BF_OK && par[k].st == BF_OK, "%s %s",
                          seq[k].msg, par[k].msg);
            ck_assert(!memcmp(seq[k].x, par[k].x, sizeof seq[k].x) &&
                      !memcmp(seq[k].v, par[k].v, sizeof seq[k].v) &&
                      !memcmp(&seq[k].lyap, &par[k].lyap, sizeof(double)));
            if (with_output)
                tu_same_datasets(seq[k].out, par[k].out);
        }
        /* and the two scenes are different runs */
        ck_assert(memcmp(seq[0].x, seq[1].x, sizeof seq[0].x));
    }
}
END_TEST

Suite *suite_api(void)
{
    Suite *s = suite_create("api");
    TCase *tc = tu_tcase("api");
    tcase_add_test(tc, a_scene_written_in_code_is_the_scene_of_the_same_text);
    tcase_add_test(tc, a_key_set_in_code_is_checked_like_a_file);
    tcase_add_test(tc, film_fields_set_from_arrays_are_the_scene_s_fields);
    tcase_add_test(tc, ball_positions_set_from_arrays);
    tcase_add_test(tc, heartbeats_come_when_asked_and_change_no_bit);
    tcase_add_test(tc, runs_in_pieces_and_restarts_are_the_run_in_one_piece);
    tcase_add_test(tc, two_runs_in_two_threads_do_not_interfere);
    suite_add_tcase(s, tc);
    return s;
}
