/* sim.c: the time loop (see sim.h).
 *
 * Time is t = n dt with n the step counter, never a running sum, so the
 * time of step 10^7 carries no accumulated round-off.
 */
#include "ballfilm/sim.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ballfilm/version.h"

static const bf_param scene_params[] = {
    {"title", BF_STR, "", "", "free text describing the scene", 0, 0, 0, NULL},
    {"model", BF_STR, "", "balls",
     "what is simulated (see Models below)", 0, 0, 0, NULL},
    {"integrator", BF_STR, "", "mv2m",
     "time integrator for ball models (see Integrators below)", 0, 0, 0, NULL},
    {"effects", BF_NAMES, "", "",
     "ball effects to switch on, e.g. 'gravity floor contact' (see Effects "
     "below); nothing else is computed",
     0, 0, 0, NULL},
    {"dt", BF_REAL, "s", NULL, "time step", BF_POS, 0, 0, NULL},
    {"t_end", BF_REAL, "s", NULL,
     "final time; the run takes ceil(t_end/dt) steps", BF_POS, 0, 0, NULL},
    {"output_every", BF_INTERVAL, "steps | s", "1",
     "output interval: 'N' steps or 'T s' of simulated time (rounded to "
     "whole steps); the final state is always written",
     0, 0, 0, NULL},
    {"energy_every", BF_INT, "steps", "1",
     "check the energy every N steps (0: only at output rows)", BF_NONNEG, 0,
     0, NULL},
    {"max_energy_error", BF_REAL, "1", "0",
     "stop the run when the relative energy error exceeds this (0: no "
     "bound)",
     BF_NONNEG, 0, 0, NULL},
    {"flush_seconds", BF_REAL, "s (wall)", "5",
     "wall-clock interval between HDF5 flushes (what a killed run keeps)",
     BF_POS, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_sim_scene_spec = {
    "scene", "what to simulate and how long (every scene has it)",
    scene_params};

struct bf_sim {
    const bf_scene *sc;
    const bf_model_type *mt;
    void *model;
    bf_sim_opts opts;
    double dt, t_end;
    long nsteps, n;
    long out_every, energy_every;
    double energy_bound, flush_seconds;
    bf_out *out;
    bf_series *s_time, *s_step, *s_ek, *s_ep, *s_et;
    long last_row; /* step of the last output row, -1 if none */
    int has_energy;
    double e0, max_rel;
    double wall;
    double prog_last;
};

static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

bf_status bf_sim_create(bf_sim **out, const bf_scene *sc,
                        const bf_sim_opts *opts, bf_err *err)
{
    *out = NULL;
    bf_sim *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->sc = sc;
    if (opts)
        s->opts = *opts;
    s->dt = bf_scene_real(sc, "scene", "dt");
    s->t_end = bf_scene_real(sc, "scene", "t_end");
    double steps = ceil(s->t_end / s->dt * (1.0 - 1e-12));
    if (!(steps < 9e15)) {
        free(s);
        return bf_scene_fail(sc, err, "scene", "t_end",
                             "t_end/dt = %g steps is too many", steps);
    }
    s->nsteps = (long)steps;
    bf_interval iv = bf_scene_interval(sc, "scene", "output_every");
    if (iv.in_time) {
        double k = floor(iv.time / s->dt + 0.5);
        s->out_every = k < 1 ? 1 : (long)k;
    } else {
        s->out_every = iv.steps < 1 ? 1 : iv.steps;
    }
    s->energy_every = bf_scene_int(sc, "scene", "energy_every");
    s->energy_bound = bf_scene_real(sc, "scene", "max_energy_error");
    s->flush_seconds = bf_scene_real(sc, "scene", "flush_seconds");
    s->mt = bf_model_find(bf_scene_str(sc, "scene", "model"));
    if (!s->mt) {
        free(s);
        return bf_fail(err, BF_EINTERNAL, "model vanished from the registry");
    }
    bf_status st = s->mt->create(&s->model, sc, err);
    if (st) {
        free(s);
        return st;
    }
    s->last_row = -1;
    s->has_energy = s->mt->energy != NULL;
    s->max_rel = 0.0;
    if (s->has_energy) {
        double k, p;
        s->mt->energy(s->model, 0.0, &k, &p);
        s->e0 = k + p;
    }
    *out = s;
    return BF_OK;
}

void bf_sim_free(bf_sim *s)
{
    if (!s)
        return;
    if (s->out)
        bf_out_close(s->out, NULL);
    if (s->mt && s->mt->destroy)
        s->mt->destroy(s->model);
    free(s);
}

/* ------------------------------------------------------------- output */

typedef struct visit_ctx {
    bf_out *out;
    bf_err *err;
} visit_ctx;

static int write_param(void *ctx, const char *name, const char *value,
                       const char *unit, int is_default)
{
    visit_ctx *v = ctx;
    char aname[600];
    double r;
    bf_status st;
    /* numbers as numbers, everything else as text */
    if (bf_parse_real(value, &r))
        st = bf_out_attr_real(v->out, "/", name, r, v->err);
    else
        st = bf_out_attr_str(v->out, "/", name, value, v->err);
    if (st)
        return 1;
    snprintf(aname, sizeof aname, "%s.unit", name);
    if (bf_out_attr_str(v->out, "/", aname, unit, v->err))
        return 1;
    if (is_default) {
        snprintf(aname, sizeof aname, "%s.default", name);
        if (bf_out_attr_int(v->out, "/", aname, 1, v->err))
            return 1;
    }
    return 0;
}

bf_status bf_sim_open_output(bf_sim *s, const char *path, bf_err *err)
{
    bf_status st = bf_out_create(&s->out, path, err);
    if (st)
        return st;
    bf_out *o = s->out;
    if ((st = bf_out_attr_str(o, "/", "version", bf_version_string(), err)) ||
        (st = bf_out_attr_str(o, "/", "scene_file", bf_scene_path(s->sc), err)) ||
        (st = bf_out_attr_str(o, "/", "scene_text", bf_scene_text(s->sc), err)) ||
        (st = bf_out_attr_str(o, "/", "status", "running", err)))
        return st;
    visit_ctx v = {o, err};
    if (bf_scene_visit(s->sc, write_param, &v))
        return err->status ? err->status : BF_EIO;
    s->s_time = bf_out_series(o, "/time", 0, 0, "s", "simulated time of each "
                              "output row (t = step dt)", err);
    if (!s->s_time)
        return err->status;
    s->s_step = bf_out_series(o, "/step", 0, 1, "1", "step number of each "
                              "output row", err);
    if (!s->s_step)
        return err->status;
    if (s->has_energy) {
        s->s_ek = bf_out_series(o, "/energy/kinetic", 0, 0, "erg",
                                "kinetic energy", err);
        s->s_ep = s->s_ek ? bf_out_series(o, "/energy/potential", 0, 0, "erg",
                                          "potential energy of all effects",
                                          err)
                          : NULL;
        s->s_et = s->s_ep ? bf_out_series(o, "/energy/total", 0, 0, "erg",
                                          "kinetic + potential", err)
                          : NULL;
        if (!s->s_et)
            return err->status;
    }
    if (s->mt->output_open && (st = s->mt->output_open(s->model, o, err)))
        return st;
    return bf_out_flush(o, err);
}

static bf_status write_row(bf_sim *s, bf_err *err)
{
    if (!s->out || s->last_row == s->n)
        return BF_OK;
    double t = (double)s->n * s->dt;
    int64_t step = s->n;
    if (bf_series_append(s->s_time, &t) ||
        bf_series_append_i64(s->s_step, &step))
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (s->has_energy) {
        double k, p, e;
        s->mt->energy(s->model, t, &k, &p);
        e = k + p;
        if (bf_series_append(s->s_ek, &k) || bf_series_append(s->s_ep, &p) ||
            bf_series_append(s->s_et, &e))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    bf_status st = BF_OK;
    if (s->mt->output_row)
        st = s->mt->output_row(s->model, s->n, t, err);
    if (!st)
        st = bf_out_maybe_flush(s->out, s->flush_seconds, err);
    s->last_row = s->n;
    return st;
}

/* relative energy error now; updates the maximum */
static double check_energy(bf_sim *s)
{
    double k, p;
    s->mt->energy(s->model, (double)s->n * s->dt, &k, &p);
    double e = k + p;
    double rel = s->e0 != 0.0 ? fabs(e - s->e0) / fabs(s->e0) : fabs(e - s->e0);
    if (!(rel <= s->max_rel)) /* also catches NaN */
        s->max_rel = isnan(rel) ? INFINITY : rel;
    return rel;
}

static void progress(bf_sim *s, double t0, int final)
{
    double now = wall_now();
    if (!final && now - s->prog_last < 0.25)
        return;
    s->prog_last = now;
    double frac = s->nsteps ? (double)s->n / (double)s->nsteps : 1.0;
    double el = now - t0;
    double rate = el > 0 ? (double)s->n / el : 0.0;
    double eta = rate > 0 ? (double)(s->nsteps - s->n) / rate : 0.0;
    fprintf(stderr, "\r  t = %-12.6g s  %5.1f%%  %9.3g steps/s  ETA %7.1f s",
            (double)s->n * s->dt, 100.0 * frac, rate, eta);
    if (s->has_energy)
        fprintf(stderr, "  max dE/E %.2e", s->max_rel);
    fprintf(stderr, "   ");
    if (final)
        fprintf(stderr, "\n");
    fflush(stderr);
}

bf_status bf_sim_run(bf_sim *s, bf_err *err)
{
    bf_status st = BF_OK;
    double t0 = wall_now();
    s->prog_last = t0;
    if (s->n == 0 && (st = write_row(s, err)))
        return st;
    const long every = s->out_every, eevery = s->energy_every;
    while (s->n < s->nsteps) {
        if (s->opts.stop_flag && *s->opts.stop_flag) {
            st = bf_fail(err, BF_INTERRUPTED,
                         "interrupted at step %ld (t = %.9g s)", s->n,
                         (double)s->n * s->dt);
            break;
        }
        double t = (double)s->n * s->dt;
        st = s->mt->step(s->model, s->n, t, s->dt, err);
        if (st) {
            bf_err_prefix(err, "step %ld (t = %.9g s to %.9g s)", s->n + 1, t,
                          (double)(s->n + 1) * s->dt);
            break;
        }
        s->n++;
        if (s->has_energy && eevery && s->n % eevery == 0) {
            double rel = check_energy(s);
            if (s->energy_bound > 0 && !(rel <= s->energy_bound)) {
                st = bf_fail(err, BF_EUNSTABLE,
                             "step %ld (t = %.9g s): relative energy error %.3g "
                             "exceeds [scene] max_energy_error = %g; the time "
                             "step is too large for this integrator",
                             s->n, (double)s->n * s->dt, rel, s->energy_bound);
                break;
            }
        }
        if (s->n % every == 0 || s->n == s->nsteps) {
            if (s->has_energy && !eevery)
                check_energy(s);
            if ((st = write_row(s, err)))
                break;
        }
        if (s->opts.progress && (s->n & 1023) == 0)
            progress(s, t0, 0);
    }
    if (s->opts.progress)
        progress(s, t0, 1);
    s->wall += wall_now() - t0;
    return st;
}

bf_status bf_sim_close_output(bf_sim *s, bf_status run_status,
                              const bf_err *run_err, bf_err *err)
{
    if (!s->out)
        return BF_OK;
    bf_out *o = s->out;
    bf_status st = BF_OK;
    if (s->mt->output_close)
        st = s->mt->output_close(s->model, o, err);
    bf_counters c;
    bf_sim_counters(s, &c);
    if (!st)
        st = bf_out_attr_str(o, "/", "status", bf_status_name(run_status), err);
    if (!st)
        st = bf_out_attr_str(o, "/", "message",
                             run_status && run_err ? run_err->msg : "", err);
    if (!st)
        st = bf_out_attr_int(o, "/", "steps_done", s->n, err);
    if (!st)
        st = bf_out_attr_real(o, "/", "t_final", (double)s->n * s->dt, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "force_evaluations", (int64_t)c.evals, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "rejected_steps", (int64_t)c.rejected, err);
    if (!st)
        st = bf_out_attr_int(o, "/", "iterations", (int64_t)c.iterations, err);
    if (!st && s->has_energy)
        st = bf_out_attr_real(o, "/", "max_relative_energy_error", s->max_rel,
                              err);
    bf_status cst = bf_out_close(o, st ? NULL : err);
    s->out = NULL;
    return st ? st : cst;
}

void bf_sim_summary(const bf_sim *s, FILE *f)
{
    bf_counters c;
    bf_sim_counters(s, &c);
    fprintf(f, "steps:             %ld of %ld (t = %.9g s)\n", s->n, s->nsteps,
            (double)s->n * s->dt);
    fprintf(f, "force evaluations: %llu", c.evals);
    if (s->n)
        fprintf(f, " (%.3g per step)", (double)c.evals / (double)s->n);
    if (c.rejected || c.iterations)
        fprintf(f, ", rejected steps %llu, iterations %llu", c.rejected,
                c.iterations);
    fprintf(f, "\n");
    fprintf(f, "wall time:         %.3f s", s->wall);
    if (s->wall > 0 && s->n)
        fprintf(f, " (%.3g steps/s)", (double)s->n / s->wall);
    fprintf(f, "\n");
    if (s->has_energy)
        fprintf(f, "max relative energy error: %.6e (checked every %ld steps)\n",
                s->max_rel, s->energy_every ? s->energy_every : s->out_every);
    if (s->mt->report)
        s->mt->report(s->model, f);
}

void *bf_sim_model(bf_sim *s) { return s->model; }
const bf_model_type *bf_sim_model_type(const bf_sim *s) { return s->mt; }
long bf_sim_steps_done(const bf_sim *s) { return s->n; }
long bf_sim_steps_total(const bf_sim *s) { return s->nsteps; }
double bf_sim_time(const bf_sim *s) { return (double)s->n * s->dt; }
double bf_sim_dt(const bf_sim *s) { return s->dt; }
double bf_sim_max_energy_error(const bf_sim *s)
{
    return s->has_energy ? s->max_rel : NAN;
}
double bf_sim_wall_seconds(const bf_sim *s) { return s->wall; }

void bf_sim_counters(const bf_sim *s, bf_counters *c)
{
    memset(c, 0, sizeof *c);
    if (s->mt->counters)
        s->mt->counters(s->model, c);
}
