/* film.c: the "film" model: the two-phase shallow-water film alone
 * (Yasuda sec. 3.1-3.4: the kink steady state of Fig. 5).  Everything is in
 * the film component (filmsys.h); this file connects it to the time loop.
 */
#include <stdlib.h>

#include "ballfilm/model.h"
#include "models/filmsys.h"
#include "models/studies.h"

static bf_status film_create(void **self, const bf_model_setup *setup,
                             bf_err *err)
{
    bf_filmsys *fs;
    bf_status st = bf_filmsys_create(
        &fs, bf_setup_get(setup, &bf_filmsys_spec, NULL), &setup->run, 1, err);
    if (!st)
        *self = fs;
    return st;
}

static void film_destroy(void *self) { bf_filmsys_free(self); }

static void film_memory(const bf_model_setup *setup, bf_mem_need *need)
{
    bf_filmsys_memory(bf_setup_get(setup, &bf_filmsys_spec, NULL), 0.0, 1,
                      need);
}

static void film_stable_dt(const void *self, bf_dt_limit *lim)
{
    bf_filmsys_stable_dt(self, lim);
}


static bf_status film_step(void *self, long n, double t, double dt, bf_err *err)
{
    (void)n;
    (void)t;
    return bf_filmsys_step(self, dt, NULL, err);
}

static bf_status film_output_open(void *self, bf_out *out, bf_err *err)
{
    return bf_filmsys_output_open(self, out, err);
}

static bf_status film_output_row(void *self, long n, double t, bf_err *err)
{
    return bf_filmsys_output_row(self, n, t, err);
}

static void film_counters(const void *self, bf_counters *c)
{
    /* the invariant scheme takes one step per step and evaluates no
     * forces (its counters stay 0); the ARKODE schemes count theirs */
    if (bf_filmsys_scheme(self) != BF_FILM_SCHEME_INVARIANT)
        bf_filmsys_counters(self, c);
}

static void film_report(const void *self, FILE *f)
{
    bf_filmsys_report(self, f);
}

static bf_status film_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    return bf_filmsys_save(self, ck, "", err);
}

static bf_status film_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    return bf_filmsys_load(self, ck, "", err);
}

static size_t film_state(void *self, bf_state_var *vars, size_t cap)
{
    return bf_filmsys_state(self, vars, cap, 1);
}

static bf_status film_set_state(void *self, const char *name,
                                const double *v, size_t n, bf_err *err)
{
    return bf_filmsys_set(self, name, v, n, err);
}

static const bf_section_spec *const film_specs[] = {&bf_filmsys_spec, NULL};

static const bf_series_table *const film_tables[] = {&bf_filmsys_series,
                                                     NULL};

const bf_model_type bf_model_film = {
    .name = "film",
    .series = film_tables,
    .doc = "two-phase shallow-water film with Ginzburg-Landau phase "
           "separation, invariant scheme (Yasuda sec. 3.1-3.4)",
    .flags = 0,
    .specs = film_specs,
    .create = film_create,
    .destroy = film_destroy,
    .memory = film_memory,
    .stable_dt = film_stable_dt,
    .step = film_step,
    .output_open = film_output_open,
    .output_row = film_output_row,
    .counters = film_counters,
    .report = film_report,
    .checkpoint_save = film_save,
    .checkpoint_load = film_load,
    .state = film_state,
    .set_state = film_set_state,
    .study = &bf_study_film,
};
