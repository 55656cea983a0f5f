/* filmsys.h: a film built from the keys of [film], with its initial
 * state, output and diagnostics (private to the models).  This is the
 * component shared by the "film" model (the kink, Yasuda sec. 3.4) and the
 * coupled ball-film model (sec. 3.5), as ballsys.h is for balls.
 *
 * Output (HDF5):
 *   /film/x [nodes]                         node positions, once
 *   at every [film] profile_every:
 *   /film/time [rows]                       s
 *   /film/h, /film/psi, /film/u_d, /film/u_c [rows x nodes]
 *   at every [scene] output_every row (aligned with /time):
 *   /film/mass_d, /film/mass_c              integral alpha_k h dx, cm^2
 *   /film/max_u                             max |u_k|, cm/s
 *   /film/min_alpha                         smallest volume fraction
 *   /film/kink_error                        max |psi - kink| (initial = kink)
 *   /film/limited_faces                     cumulative limiter count
 */
#ifndef BALLFILM_FILMSYS_H
#define BALLFILM_FILMSYS_H

#include <stdio.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/film.h"
#include "ballfilm/h5out.h"
#include "ballfilm/model.h"
#include "ballfilm/series.h"
#include "ballfilm/params.h"

/* The keys of [film]. */
typedef struct bf_film_keys {
    double length, dx;   /* cm */
    double h0;           /* cm */
    double rho_d, rho_c; /* g/cm^3 */
    double nu;           /* cm^2/s */
    double g;            /* cm/s^2 */
    double a, b;         /* g/(cm s^2) */
    double gamma;        /* g cm/s^2 */
    int initial;         /* 0 kink, 1 uniform, 2 file */
    double center;       /* cm */
    double psi0;
    const char *file;
    double perturbation;
    int perturbation_mode; /* 0 positive, 1 signed */
    long seed;
    int mu_taylor;  /* 0 midpoint, 1 um, 2 uk (bf_film_mu_taylor) */
    int positivity; /* 0 limit, 1 stop */
    double vanish;
    int force_dt;
    bf_interval profile_every;
    /* the time integrator: the invariant scheme, or ARKODE on the same
     * grid in method-of-lines form (film_mol.h) */
    int scheme;        /* BF_FILM_SCHEME_* */
    int table;         /* arkode: ERK table (integrators/arkode.h) */
    long imex_order;   /* arkode-imex: 3, 4, 5 */
    int imex_implicit; /* bf_film_mol_split */
    double rtol, atol, max_step;
    long max_steps;
} bf_film_keys;

enum { BF_FILM_SCHEME_INVARIANT = 0, BF_FILM_SCHEME_ARKODE = 1,
       BF_FILM_SCHEME_IMEX = 2 };

extern const bf_section_spec bf_filmsys_spec; /* [film] */

typedef struct bf_filmsys bf_filmsys;

/* The memory of a film of keys k (model.h, memory), with `extra` more
 * doubles per node for what the caller keeps beside it (the coupling's
 * arrays), times `copies` (a Lyapunov shadow is a second film). */
void bf_filmsys_memory(const bf_film_keys *k, double extra, int copies,
                       bf_mem_need *need);

/* Build the film of the keys and its initial state, for the run `run`
 * (its dt, length and output interval).  The film will step by
 * film_every x dt (0: never, a static film).  Bad keys are named
 * (bf_fail_key). */
bf_status bf_filmsys_create(bf_filmsys **out, const bf_film_keys *k,
                            const bf_run_ctx *run, long film_every,
                            bf_err *err);
void bf_filmsys_free(bf_filmsys *fs);
/* The film's step is chosen by its driver step by step (the coupled
 * model's film_every = auto, or with film_every 0 its whole-system
 * schemes): the report names no fixed film step. */
void bf_filmsys_step_varies(bf_filmsys *fs);

/* The largest [scene] dt the film's step allows (model.h's stable_dt):
 * film_every x dt must not exceed the film's stable limit of its initial
 * state; with film_every > 1 the limit names [coupled] film_every.  No
 * limit for a static film or with [film] force_dt. */
void bf_filmsys_stable_dt(const bf_filmsys *fs, bf_dt_limit *lim);

/* The state as arrays (model.h's state): film/h (cm), film/psi (1),
 * film/u_d, film/u_c (cm/s) on the nodes, settable or not, and the nodes'
 * positions film/x (cm, never settable).  Setting one
 * before the first step replaces it among the initial arrays and hands
 * all four to the film again (bf_film_set_state, which checks them,
 * naming the node; the velocities at the walls are zero); on failure the
 * state is unchanged. */
size_t bf_filmsys_state(bf_filmsys *fs, bf_state_var *vars, size_t cap,
                        int settable);
bf_status bf_filmsys_set(bf_filmsys *fs, const char *name, const double *v,
                         size_t n, bf_err *err);

bf_film *bf_filmsys_film(bf_filmsys *fs);
/* Whether the scene started from the analytic kink, and its centre (cm). */
int bf_filmsys_has_kink(const bf_filmsys *fs, double *x0);
/* L-infinity distance of psi from the analytic kink (NAN without one). */
double bf_filmsys_kink_error(const bf_filmsys *fs);
/* Largest relative change of either phase total since t = 0. */
double bf_filmsys_mass_drift(const bf_filmsys *fs);

/* One film step of dt with the coupling's mu_cpl (nodes 0..N; NULL:
 * none): bf_film_step_invariant, or with [film] scheme = arkode or
 * arkode-imex ARKODE's steps over dt on the film in method-of-lines form
 * (mu_cpl held over dt), the state checked after it. */
bf_status bf_filmsys_step(bf_filmsys *fs, double dt, const double *mu_cpl,
                          bf_err *err);

/* The film's time integrator: [film] scheme, and a description of it
 * ("invariant (mu_taylor midpoint)", "arkode ERK VERNER_8_5_6 rtol=...")
 * with its nominal order in time (1 for the invariant scheme, whose
 * first-order term is O(dt dx^2), docs/models/film.md). */
int bf_filmsys_scheme(const bf_filmsys *fs);
/* The phase volume fluxes alpha_k h u_k on the nodes (cm^2/s), k = 0: d,
 * 1: c, of the current state (the convergence study compares them instead
 * of u_k: where a phase is absent its velocity is a convention); the
 * array is the filmsys's, valid until the next call.  NULL: out of
 * memory. */
const double *bf_filmsys_phase_flux(bf_filmsys *fs, int k);
void bf_filmsys_describe(const bf_filmsys *fs, char *buf, size_t cap,
                         int *order);
/* The counters of its time integration: ARKODE's (steps, evaluations of
 * the right-hand side, rejected steps, Newton iterations), or for the
 * invariant scheme its steps, each counted as one evaluation. */
void bf_filmsys_counters(const bf_filmsys *fs, bf_counters *c);

/* Its datasets (series.h): /film/x, the profiles at [film] profile_every
 * and the diagnostics at every output row. */
extern const bf_series_table bf_filmsys_series;
bf_status bf_filmsys_output_open(bf_filmsys *fs, bf_out *out, bf_err *err);
bf_status bf_filmsys_output_row(bf_filmsys *fs, long n, double t, bf_err *err);
void bf_filmsys_report(const bf_filmsys *fs, FILE *f);

/* Checkpoint under names starting with prefix + "film" (prefix "" for the
 * run's film, "lyapunov." for the coupled model's shadow film). */
bf_status bf_filmsys_save(const bf_filmsys *fs, bf_ckpt *ck,
                          const char *prefix, bf_err *err);
bf_status bf_filmsys_load(bf_filmsys *fs, const bf_ckpt *ck,
                          const char *prefix, bf_err *err);

#endif
