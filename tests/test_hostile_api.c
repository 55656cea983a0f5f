/* test_hostile_api.c: the C API used wrongly.  Calls in the wrong order,
 * NULL pointers, non-finite arguments and callbacks that return what no
 * status is are refused or reported with a cause (BF_EINPUT, or
 * BF_EINTERNAL for a callback's bug), never a crash and never a success;
 * and a run that blows up writes no non-finite value as a result.
 *
 * Each test makes a call that on a library without these checks crashed
 * (Check runs every test in a process of its own), returned BF_OK, or
 * ended with a status and no cause. */
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "testutil.h"

/* Two balls on a floor, 200 steps. */
static const char *const short_run =
    "[scene]\nintegrator = mv2m\neffects = gravity floor contact\n"
    "dt = 1e-4\nt_end = 0.02\noutput_every = 10\n"
    "[ball.1]\nposition = 0.2\nmass = 0.8\nradius = 0.1\n"
    "[ball.2]\nposition = 0.5\nmass = 1\nradius = 0.1\n";

static bf_run *load(const char *text, const char *const *sets, size_t nsets)
{
    bf_run *r = NULL;
    bf_err err = {0};
    ck_assert_msg(bf_run_from_text(&r, bf_catalog_builtin(), "hostile.ini",
                                   text, sets, nsets, NULL, &err) == BF_OK,
                  "%s", err.msg);
    return r;
}

/* st is BF_EINPUT and the message holds every one of the words. */
static void refused(bf_status st, const bf_err *err, const char *w1,
                    const char *w2)
{
    ck_assert_msg(st == BF_EINPUT, "status %d (%s), not a refusal", st,
                  err->msg);
    ck_assert_msg(strstr(err->msg, w1) && (!w2 || strstr(err->msg, w2)),
                  "the message does not name %s%s%s: %s", w1, w2 ? ", " : "",
                  w2 ? w2 : "", err->msg);
}

/* A string attribute of the root of an HDF5 file, into buf. */
static void root_attr(const char *file, const char *name, char *buf,
                      size_t cap)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert_msg(f >= 0, "cannot open %s", file);
    hid_t a = H5Aopen(f, name, H5P_DEFAULT);
    ck_assert(a >= 0);
    hid_t t = H5Aget_type(a);
    char *s = NULL;
    if (H5Tis_variable_str(t) > 0) {
        ck_assert(H5Aread(a, t, &s) >= 0);
        snprintf(buf, cap, "%s", s ? s : "");
        H5free_memory(s);
    } else {
        size_t n = H5Tget_size(t);
        ck_assert(n < cap);
        memset(buf, 0, cap);
        ck_assert(H5Aread(a, t, buf) >= 0);
    }
    H5Tclose(t);
    H5Aclose(a);
    H5Fclose(f);
}

/* An output opened after the last step would hold no row and say "ok". */
START_TEST(an_output_opened_after_the_run_is_refused)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    ck_assert(bf_sim_run(bf_run_sim(r), &err) == BF_OK);
    const char *out = tu_tmp("late.h5");
    refused(bf_run_open_output(r, out, &err), &err, "bf_sim_open_output",
            "step 200");
    ck_assert(access(out, F_OK) != 0 && access(tu_result(out), F_OK) != 0);
    bf_run_free(r);
    /* after only the heartbeats of t = 0: the row of t = 0 is past */
    r = load(short_run, NULL, 0);
    ck_assert(bf_sim_run_until(bf_run_sim(r), 0.0, &err) == BF_OK);
    refused(bf_run_open_output(r, out, &err), &err, "bf_sim_open_output",
            "before the first step");
    bf_run_free(r);
}
END_TEST

/* A second output would replace the first one's handle and leak it. */
START_TEST(a_second_output_is_refused_and_the_first_is_kept)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    const char *a = tu_tmp("first.h5"), *b = tu_tmp("second.h5");
    ck_assert_msg(bf_run_open_output(r, a, &err) == BF_OK, "%s", err.msg);
    refused(bf_run_open_output(r, b, &err), &err, "bf_sim_open_output",
            "has an output already");
    ck_assert(access(b, F_OK) != 0 && access(tu_result(b), F_OK) != 0);
    bf_status st = bf_sim_run(bf_run_sim(r), &err);
    ck_assert(st == BF_OK);
    ck_assert_msg(bf_sim_close_output(bf_run_sim(r), st, &err, &err) == BF_OK,
                  "%s", err.msg);
    char status[64];
    root_attr(a, "status", status, sizeof status);
    ck_assert_str_eq(status, "ok");
    /* closed: the run is over */
    refused(bf_sim_run(bf_run_sim(r), &err), &err, "bf_sim_run", "closed");
    refused(bf_sim_close_output(bf_run_sim(r), BF_OK, NULL, &err), &err,
            "bf_sim_close_output", "closed already");
    bf_run_free(r);
}
END_TEST

/* A file whose status says ok is taken for the whole run. */
START_TEST(an_output_closed_as_ok_before_t_end_is_refused)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    const char *out = tu_tmp("half.h5");
    ck_assert(bf_run_open_output(r, out, &err) == BF_OK);
    ck_assert(bf_sim_run_until(bf_run_sim(r), 0.01, &err) == BF_OK);
    refused(bf_sim_close_output(bf_run_sim(r), BF_OK, NULL, &err), &err,
            "bf_sim_close_output", "step 100 of 200");
    refused(bf_sim_close_output(bf_run_sim(r), (bf_status)42, NULL, &err),
            &err, "bf_sim_close_output", "42");
    /* refused, the output is still open: the run goes on and ends */
    bf_status st = bf_sim_run(bf_run_sim(r), &err);
    ck_assert(st == BF_OK);
    ck_assert(bf_sim_close_output(bf_run_sim(r), st, NULL, NULL) == BF_OK);
    char status[64];
    root_attr(out, "status", status, sizeof status);
    ck_assert_str_eq(status, "ok");
    bf_run_free(r);
}
END_TEST

START_TEST(null_catalog_sets_and_paths_are_refused)
{
    bf_err err = {0};
    bf_run *r = NULL;
    const char *scene = tu_write("null.ini", short_run);
    const char *const one[] = {"scene.t_end=0.01", NULL};
    const bf_catalog *cat = bf_catalog_builtin();
    refused(bf_run_load(&r, NULL, scene, NULL, 0, NULL, &err), &err,
            "bf_run_load", "catalog");
    refused(bf_run_load(&r, cat, scene, NULL, 2, NULL, &err), &err,
            "bf_run_load", "sets");
    refused(bf_run_load(&r, cat, scene, one, 2, NULL, &err), &err,
            "bf_run_load", "sets[1]");
    refused(bf_run_load(&r, cat, NULL, NULL, 0, NULL, &err), &err,
            "bf_run_load", "NULL");
    refused(bf_run_load(NULL, cat, scene, NULL, 0, NULL, &err), &err,
            "bf_run_load", "result");
    refused(bf_run_from_text(&r, NULL, "x", short_run, NULL, 0, NULL, &err),
            &err, "bf_run_from_text", "catalog");
    refused(bf_run_from_text(&r, cat, "x", short_run, NULL, 3, NULL, &err),
            &err, "bf_run_from_text", "sets");
    refused(bf_run_restart(&r, NULL, tu_tmp("none.h5"), NULL, 0, NULL, &err),
            &err, "bf_run_restart", "catalog");
    refused(bf_run_restart(&r, cat, NULL, NULL, 0, NULL, &err), &err,
            "bf_run_restart", "NULL");
    refused(bf_run_from_scene(&r, cat, NULL, NULL, &err), &err,
            "bf_run_from_scene", "scene");
    refused(bf_catalog_resolve(NULL, NULL, &err), &err, "bf_catalog_resolve",
            "catalog");
    bf_sim *s = NULL;
    refused(bf_sim_from_scene(&s, cat, NULL, NULL, &err), &err,
            "bf_sim_from_scene", "scene");
    /* the message may be left unread: err NULL */
    ck_assert(bf_run_load(&r, NULL, scene, NULL, 0, NULL, NULL) == BF_EINPUT);
    ck_assert(r == NULL);
    bf_run *ok = load(short_run, NULL, 0);
    refused(bf_run_open_output(ok, NULL, &err), &err, "bf_run_open_output",
            "path");
    refused(bf_sim_open_output(bf_run_sim(ok), "", &err), &err,
            "bf_sim_open_output", "empty");
    refused(bf_sim_set(bf_run_sim(ok), "balls/position", NULL, 2, &err), &err,
            "bf_sim_set", "NULL");
    refused(bf_sim_set(bf_run_sim(ok), NULL, NULL, 0, &err), &err,
            "bf_sim_set", "name");
    ck_assert(bf_sim_get(bf_run_sim(ok), NULL, NULL) == NULL);
    ck_assert(bf_sim_state(bf_run_sim(ok), NULL, 5) > 0);
    refused(bf_sim_observe(bf_run_sim(ok), NULL, NULL, &err), &err,
            "bf_sim_observe", "NULL");
    refused(bf_sim_heartbeat(bf_run_sim(ok), 1, NULL, NULL, &err), &err,
            "bf_sim_heartbeat", "fn");
    refused(bf_sim_run(NULL, &err), &err, "bf_sim_run", "sim");
    bf_run_free(ok);
}
END_TEST

START_TEST(non_finite_arguments_are_refused)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    bf_sim *s = bf_run_sim(r);
    refused(bf_sim_run_until(s, NAN, &err), &err, "bf_sim_run_until",
            "t = nan is not finite");
    refused(bf_sim_run_until(s, INFINITY, &err), &err, "bf_sim_run_until",
            "t = inf");
    ck_assert(bf_sim_run_until(s, -INFINITY, NULL) == BF_EINPUT);
    ck_assert_int_eq(bf_sim_steps_done(s), 0);
    const double x[2] = {0.2, NAN};
    refused(bf_sim_set(s, "balls/position", x, 2, &err), &err, "bf_sim_set",
            "balls/position[1] = nan");
    const double three[3] = {0.2, 0.5, 0.8};
    refused(bf_sim_set(s, "balls/position", three, 3, &err), &err,
            "balls/position", "3 given");
    ck_assert(bf_sim_get(s, "no/such/array", NULL) == NULL);
    bf_run_free(r);

    bf_scene *sc = NULL;
    ck_assert(bf_scene_load_string(&sc, "code", "", &err) == BF_OK);
    refused(bf_add_ball(sc, 0.2, 0, NAN, 0.1, NULL, &err), &err,
            "bf_add_ball", "mass = nan");
    refused(bf_add_ball(sc, INFINITY, 0, 1, 0.1, NULL, &err), &err,
            "bf_add_ball", "position = inf");
    ck_assert(!bf_scene_has_section(sc, "ball.1"));
    refused(bf_setf(NULL, &err, "scene.dt=1"), &err, "bf_setf", "scene");
    bf_scene_free(sc);
}
END_TEST

/* [scene] keys filled in code, not validated by a scene. */
START_TEST(keys_filled_in_code_are_checked)
{
    bf_err err = {0};
    bf_scene *sc = tu_scene(short_run);
    bf_setup *setup = NULL;
    void *model = NULL;
    ck_assert_msg(bf_model_from_scene(bf_catalog_builtin(), sc, &setup,
                                      &model, &err) == BF_OK, "%s", err.msg);
    bf_sim_keys k;
    bf_scene_fill(sc, "scene", &bf_sim_scene_spec, &k);
    k.dt = -1e-4; /* a negative step count */
    bf_sim *s = NULL;
    refused(bf_sim_create(&s, &k, bf_setup_model_type(setup), model, NULL,
                          NULL, &err), &err, "dt", "not a finite positive");
    ck_assert(s == NULL); /* the model went with the refusal */
    bf_run_ctx run;
    k.dt = 1e-4;
    k.max_energy_error = NAN;
    refused(bf_sim_run_ctx(&k, &run, &err), &err, "max_energy_error", "nan");
    k.max_energy_error = 0;
    k.energy_every = -3;
    refused(bf_sim_run_ctx(&k, &run, &err), &err, "energy_every", "-3");
    bf_setup_free(setup);
    bf_scene_free(sc);
}
END_TEST

typedef struct odd {
    int calls;
    bf_status ret;
} odd;

static bf_status odd_beat(void *ctx, bf_sim *sim, bf_err *err)
{
    (void)sim;
    (void)err; /* says nothing */
    odd *o = ctx;
    return ++o->calls >= 3 ? o->ret : BF_OK;
}

/* A heartbeat that fails with what is no status, or without a word. */
START_TEST(a_callback_s_odd_status_ends_the_run_with_a_cause)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    odd o = {0, (bf_status)42};
    ck_assert(bf_sim_heartbeat(bf_run_sim(r), 5, odd_beat, &o, &err) ==
              BF_OK);
    bf_status st = bf_sim_run(bf_run_sim(r), &err);
    ck_assert_msg(st == BF_EINTERNAL && strstr(err.msg, "heartbeat") &&
                      strstr(err.msg, "returned 42"),
                  "%d %s", st, err.msg);
    bf_run_free(r);

    r = load(short_run, NULL, 0);
    o = (odd){0, BF_EUNSTABLE};
    const char *out = tu_tmp("odd.h5");
    ck_assert(bf_sim_heartbeat(bf_run_sim(r), 5, odd_beat, &o, &err) ==
              BF_OK);
    ck_assert(bf_run_open_output(r, out, &err) == BF_OK);
    st = bf_sim_run(bf_run_sim(r), &err);
    ck_assert_msg(st == BF_EUNSTABLE && strstr(err.msg, "heartbeat") &&
                      strstr(err.msg, "without saying why"),
                  "%d %s", st, err.msg);
    /* a failed run's state is no result to go on from */
    bf_err e2 = {0};
    refused(bf_sim_steps(bf_run_sim(r), 10, &e2), &e2, "bf_sim_steps",
            "unstable");
    ck_assert(bf_sim_close_output(bf_run_sim(r), st, &err, NULL) == BF_OK);
    char msg[1024];
    root_attr(tu_result(out), "message", msg, sizeof msg);
    ck_assert_msg(strstr(msg, "heartbeat"), "message '%s'", msg);
    bf_run_free(r);
}
END_TEST

static bf_status odd_after(void *self, long n, double t, double dt,
                           bf_err *err)
{
    (void)self;
    (void)t;
    (void)dt;
    (void)err;
    return n == 50 ? (bf_status)-1 : BF_OK;
}

static const bf_observer_type odd_observer = {
    .name = "odd", .flags = BF_OBS_STEPS, .after_step = odd_after};

START_TEST(an_observer_s_odd_status_is_named_and_late_observers_refused)
{
    bf_err err = {0};
    bf_run *r = load(short_run, NULL, 0);
    ck_assert(bf_sim_observe(bf_run_sim(r), &odd_observer, NULL, &err) ==
              BF_OK);
    bf_status st = bf_sim_run(bf_run_sim(r), &err);
    ck_assert_msg(st == BF_EINTERNAL && strstr(err.msg, "observer 'odd'") &&
                      strstr(err.msg, "returned -1"),
                  "%d %s", st, err.msg);
    bf_run_free(r);
    r = load(short_run, NULL, 0);
    ck_assert(bf_run_open_output(r, tu_tmp("late_obs.h5"), &err) == BF_OK);
    refused(bf_sim_observe(bf_run_sim(r), &odd_observer, NULL, &err), &err,
            "bf_sim_observe", "'odd'");
    bf_run_free(r);
}
END_TEST

/* 1 if every value of the 1-D dataset is finite (*n: how many). */
static int dataset_finite(const char *file, const char *path, size_t *n)
{
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert_msg(f >= 0, "cannot open %s", file);
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    ck_assert_msg(d >= 0, "%s: no %s", file, path);
    hid_t sp = H5Dget_space(d);
    hsize_t dims[1] = {0};
    ck_assert(H5Sget_simple_extent_ndims(sp) == 1);
    H5Sget_simple_extent_dims(sp, dims, NULL);
    double *v = malloc((dims[0] ? dims[0] : 1) * sizeof *v);
    ck_assert(v != NULL);
    ck_assert(dims[0] == 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                      H5P_DEFAULT, v) >= 0);
    int ok = 1;
    for (hsize_t i = 0; i < dims[0]; i++)
        ok &= isfinite(v[i]) != 0;
    *n = (size_t)dims[0];
    free(v);
    H5Sclose(sp);
    H5Dclose(d);
    H5Fclose(f);
    return ok;
}

/* Two balls with RK3 at 15 times the scene's step and no energy bound
 * blow up at step 152; the last floor contact before it interpolates the
 * upper ball's velocity from forces that overflowed (-inf). */
START_TEST(a_run_that_blows_up_writes_no_infinite_return_map_point)
{
    const char *out = tu_tmp("blowup.h5");
    char *errout = NULL;
    int rc = tu_run(NULL, &errout, "run", tu_repo("runs/two_balls_B.ini"),
                    "-q", "-o", out, "--set", "scene.integrator=rk3", "--set",
                    "scene.dt=1.5e-3", "--set", "scene.t_end=1", "--set",
                    "scene.max_energy_error=0", "--set",
                    "scene.energy_bound=no", "--set",
                    "scene.output_every=100", NULL);
    ck_assert_msg(rc == 3, "exit %d: %s", rc, errout ? errout : "");
    free(errout);
    const char *names[] = {"/return_map/time", "/return_map/z",
                           "/return_map/v", "/return_map/z_trigger"};
    size_t n = 0;
    for (int k = 0; k < 4; k++)
        ck_assert_msg(dataset_finite(tu_result(out), names[k], &n),
                      "%s holds a non-finite value", names[k]);
    ck_assert_msg(n >= 5, "%zu points: the run blew up elsewhere", n);

    /* without an output the points are kept in memory: the same rule */
    const char *const sets[] = {
        "scene.integrator=rk3", "scene.dt=1.5e-3", "scene.t_end=1",
        "scene.max_energy_error=0", "scene.energy_bound=no",
        "scene.output_every=100", "return_map.enabled=yes"};
    const char *scene = tu_repo("runs/two_balls_B.ini");
    bf_run *r = NULL;
    bf_err err = {0};
    ck_assert_msg(bf_run_load(&r, bf_catalog_builtin(), scene, sets, 7, NULL,
                              &err) == BF_OK, "%s", err.msg);
    ck_assert(bf_sim_run(bf_run_sim(r), &err) == BF_EUNSTABLE);
    bf_results res;
    bf_sim_results(bf_run_sim(r), &res);
    ck_assert(res.map_points >= 5 && res.map_v && res.map_z);
    for (size_t i = 0; i < res.map_points; i++)
        ck_assert_msg(isfinite(res.map_v[i]) && isfinite(res.map_z[i]),
                      "point %zu: z = %g, v = %g", i, res.map_z[i],
                      res.map_v[i]);
    bf_run_free(r);
}
END_TEST

Suite *suite_hostile_api(void)
{
    Suite *s = suite_create("hostile_api");
    TCase *tc = tu_tcase("hostile_api");
    tcase_add_test(tc, an_output_opened_after_the_run_is_refused);
    tcase_add_test(tc, a_second_output_is_refused_and_the_first_is_kept);
    tcase_add_test(tc, an_output_closed_as_ok_before_t_end_is_refused);
    tcase_add_test(tc, null_catalog_sets_and_paths_are_refused);
    tcase_add_test(tc, non_finite_arguments_are_refused);
    tcase_add_test(tc, keys_filled_in_code_are_checked);
    tcase_add_test(tc, a_callback_s_odd_status_ends_the_run_with_a_cause);
    tcase_add_test(tc,
                   an_observer_s_odd_status_is_named_and_late_observers_refused);
    tcase_add_test(tc, a_run_that_blows_up_writes_no_infinite_return_map_point);
    suite_add_tcase(s, tc);
    return s;
}
