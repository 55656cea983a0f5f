/* sim_series.c: the datasets of the time loop itself (series.h), and the
 * opening of every series of a run: the loop's, the model's and the
 * observers'. */
#include "ballfilm/series.h"
#include "ballfilm/sim.h"
#include "core/sim_impl.h"
#include "io/dataset_paths.h"

enum { ON_ENERGY = 1u << 0, ON_WORK = 1u << 1 };

static const bf_series_spec sim_series[] = {
    {.path = BF_DS_TIME, .unit = "s", .role = BF_SR_TIME,
     .doc = "simulated time of each output row (t = step dt)",
     .slot = BF_SLOT(bf_sim, s_time)},
    {.path = BF_DS_STEP, .unit = "1", .is_int = 1, .role = BF_SR_STEP,
     .doc = "step number of each output row",
     .slot = BF_SLOT(bf_sim, s_step)},
    {.path = BF_DS_ENERGY_KINETIC, .unit = "erg", .when = ON_ENERGY,
     .doc = "kinetic energy", .slot = BF_SLOT(bf_sim, s_ek)},
    {.path = BF_DS_ENERGY_POTENTIAL, .unit = "erg", .when = ON_ENERGY,
     .doc = "potential energy of all effects", .slot = BF_SLOT(bf_sim, s_ep)},
    {.path = BF_DS_ENERGY_TOTAL, .unit = "erg", .when = ON_ENERGY,
     .doc = "kinetic + potential", .slot = BF_SLOT(bf_sim, s_et)},
    /* the work of non-conservative forces (model.h, work): the energy
     * balance E - E0 + W_dissipated - W_injected */
    {.path = "/energy/dissipated", .unit = "erg", .when = ON_WORK,
     .role = BF_SR_DIAGNOSTIC, .doc = "work dissipated since t = 0",
     .slot = BF_SLOT(bf_sim, s_wd)},
    {.path = "/energy/injected", .unit = "erg", .when = ON_WORK,
     .role = BF_SR_DIAGNOSTIC, .doc = "work done by driving since t = 0",
     .slot = BF_SLOT(bf_sim, s_wi)},
};

const bf_series_table bf_sim_series = {"run", sim_series,
                                       BF_NSERIES(sim_series)};

/* Datasets of the loop itself (created, or reopened on restart), then the
 * model's and the observers'. */
bf_status bf_sim_open_series_(bf_sim *s, bf_err *err)
{
    bf_out *o = s->out;
    bf_status st = bf_out_open_table(o, sim_series, BF_NSERIES(sim_series), s,
                                     NULL, 0,
                                     (s->has_energy ? ON_ENERGY : 0) |
                                         (s->has_work ? ON_WORK : 0),
                                     err);
    if (st)
        return st;
    if (s->mt->output_open)
        st = bf_sim_hook_status_(s->mt->output_open(s->model, o, err),
                                 "model", s->mt->name, "output_open", err);
    EACH_OBSERVER(s, st, output_open, o, err);
    return st;
}
