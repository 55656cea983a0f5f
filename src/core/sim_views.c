/* sim_views.c: what the loop shows of a run (see sim.h): the summary,
 * the estimate of the output still to come, and the read-only views for
 * drivers and tests. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/sim_impl.h"

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
        fprintf(f, "max relative energy error: %.6e (checked every %ld steps)"
                   "%s\n",
                s->en.max_rel,
                s->energy_every ? s->energy_every : s->out_every,
                s->has_work ? "; of the balance E - E0 + W_dissipated - "
                              "W_injected"
                            : "");
    if (s->run_status == BF_EUNSTABLE) {
        /* the model's and the analyses' lines describe the final state,
         * which is not a result ("relative change 0" next to "max |u|
         * inf") */
        fprintf(f, "stopped:           unstable after %ld steps (t = %.9g s); "
                   "the final state is not a result, its summary is left "
                   "out\n",
                s->n, (double)s->n * s->dt);
        return;
    }
    if (s->mt->report)
        s->mt->report(s->model, f);
    for (size_t k = 0; k < s->nobs; k++)
        if (s->obs[k].t->report)
            s->obs[k].t->report(s->obs[k].self, f);
}

double bf_sim_output_estimate(const bf_sim *s)
{
    if (!s->out)
        return 0.0;
    double row = 0.0;
    for (size_t k = 0; k < bf_out_nseries(s->out); k++)
        row += 8.0 * (double)bf_series_width(bf_out_series_at(s->out, k));
    double rows = (double)(s->nsteps - s->n) / (double)s->out_every + 1.0;
    return row * rows;
}

void *bf_sim_model(bf_sim *s) { return s->model; }
const bf_model_type *bf_sim_model_type(const bf_sim *s) { return s->mt; }
long bf_sim_steps_done(const bf_sim *s) { return s->n; }
long bf_sim_steps_total(const bf_sim *s) { return s->nsteps; }
double bf_sim_time(const bf_sim *s) { return (double)s->n * s->dt; }
double bf_sim_dt(const bf_sim *s) { return s->dt; }
double bf_sim_max_energy_error(const bf_sim *s)
{
    return s->has_energy ? s->en.max_rel : NAN;
}
double bf_sim_wall_seconds(const bf_sim *s) { return s->wall; }

void bf_sim_counters(const bf_sim *s, bf_counters *c)
{
    memset(c, 0, sizeof *c);
    if (s->mt->counters)
        s->mt->counters(s->model, c);
}

void bf_sim_results(const bf_sim *s, bf_results *r)
{
    memset(r, 0, sizeof *r);
    r->lyapunov_exponent = r->lyapunov_time = NAN;
    if (s->mt->results)
        s->mt->results(s->model, r);
    for (size_t k = 0; k < s->nobs; k++)
        if (s->obs[k].t->results)
            s->obs[k].t->results(s->obs[k].self, r);
}
