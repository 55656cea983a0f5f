/* coupled_impl.h: what the files of the coupled model share (private to
 * src/models): its state, and the functions of coupled_symmetry.c (the
 * forced mirror symmetry), coupled_events.c (peaks, return map, symmetry
 * break) and coupled_lyapunov.c (the Lyapunov shadow).  coupled.c
 * composes the model and its step and calls them; they call nothing of
 * coupled.c, and coupled_events.c only the symmetry error of
 * coupled_symmetry.c.
 */
#ifndef BALLFILM_MODELS_COUPLED_IMPL_H
#define BALLFILM_MODELS_COUPLED_IMPL_H

#include <stddef.h>
#include <stdio.h>

#include "ballfilm/h5out.h"
#include "ballfilm/model.h"
#include "coupling/coupling.h"
#include "diag/lyapsum.h"
#include "models/balls_out.h"
#include "models/ballsys.h"
#include "models/filmsys.h"

/* the levels of the balls' symmetry error whose first crossing is kept
 * (cm; coupled_events.c) */
enum { BF_COUPLED_NSYM = 4 };
extern const double bf_coupled_sym_levels[BF_COUPLED_NSYM];

/* [coupled] scheme and the keys of its ARKODE schemes (coupled_whole.c). */
enum { BF_COUPLED_SPLIT = 0, BF_COUPLED_ARKODE = 1, BF_COUPLED_MRI = 2 };
typedef struct bf_coupled_whole_keys {
    int scheme;     /* BF_COUPLED_* */
    int table;      /* ERK table (integrators/arkode.h) */
    long mri_order; /* 3, 4 */
    double rtol, atol, max_step;
    long max_steps;
} bf_coupled_whole_keys;

typedef struct bf_coupled_whole bf_coupled_whole;

/* The keys of [coupled]. */
typedef struct coupled_keys {
    int film;        /* 0 dynamic, 1 static */
    const char *film_every; /* steps, or "auto" */
    double multirate_tol;   /* cm/s^2 */
    long film_every_max;    /* steps */
    double probe;    /* cm */
    long map_ball, map_pivot, peak_ball; /* 1-based; 0: the default */
    int symmetrize, timing;
    bf_coupled_whole_keys whole; /* scheme and its ARKODE keys */
} coupled_keys;
extern const bf_section_spec bf_coupled_spec;

/* One coupled system (the run, or its Lyapunov shadow). */
typedef struct coupled_model {
    bf_filmsys *fs;
    /* [lyapunov]: the running sum and the shadow system (NULL: off) */
    bf_lyap_sum *ly;
    struct coupled_model *shadow;
    bf_ballsys *sys;
    bf_coupling *cpl;
    /* scheme = arkode, mri: the whole system's integrator (NULL: split) */
    bf_coupled_whole *whole;
    int dynamic, timing, sym;
    long every;             /* film_every = K (fixed multirate) */
    /* film_every = auto (coupled_multirate.c): the current film step, a
     * window of win_k ball steps from step win_start, and its record */
    int adaptive;
    double mr_tol;          /* largest coupling-acceleration lag, cm/s^2 */
    long mr_kmax, nsteps;   /* largest K allowed; the run's steps */
    long win_start, win_k;
    double mr_stable;       /* the film's stable limit (s), evaluated */
    long mr_stable_at;      /* again at the film step ending here */
    double *acc_old;        /* coupling acceleration of the balls at the
                               window's end in the film before its step
                               [nb], and after it [nb] */
    double mr_stat[6];      /* windows, sum of K, smallest and largest K,
                               largest lag (cm/s^2), windows over mr_tol */
    bf_series *kser;        /* /coupled/film_every */
    const struct coupled_model *leader; /* a Lyapunov shadow: the run whose
                                           film steps it takes (else NULL) */
    size_t nb, map_ball, map_pivot, peak_ball;
    double probe;
    double *mucpl;          /* mu_cpl (3.11) handed to the film step */
    double *x0, *v0;        /* ball state at the start of the step */
    size_t nodes;           /* the film's nodes (mucpl's length) */
    double sym_t[BF_COUPLED_NSYM]; /* first time the ball symmetry error
                                      exceeded each level */
    double cpu[3];          /* wall s: balls, film, coupling (timing) */
    /* symmetrize: largest relative corrections (film A, film u, ball x,
     * ball v) since the last row [0..3] and over the run [4..7] */
    double sym_correction[8];
    long nmap, npeak;
    /* with bf_run_ctx keep_map (not in a shadow): the return map's x, v
     * of every point found, for bf_results (a sweep's
     * statistics of the map without reading the file back; 16 B a point) */
    int keep_map;
    double *map_x, *map_v;
    size_t map_kept, map_cap;
    bf_balls_out bo;
    bf_series *probe_s, *symb, *symf, *map, *peaks, *symc_s;
} coupled_model;

/* ---- coupled_symmetry.c ---- */

/* Refuse [coupled] symmetrize = yes unless the set-up is mirror symmetric,
 * naming the key that breaks it (fk: the [film] keys). */
bf_status bf_coupled_check_symmetric(const coupled_model *m,
                                     const bf_film_keys *fk, bf_err *err);
/* Project n positions (or velocities) onto the odd states; the largest
 * change relative to max |a|. */
double bf_coupled_mirror_odd(double *a, size_t n);
/* Keep the larger corrections c[0..k-1] in acc[q] and acc[q + 4]. */
void bf_coupled_keep_max(double *acc, const double *c, int k);
/* max_i |x_i + x_(n-1-i)|, cm */
double bf_coupled_symmetry_error(const double *x, size_t n);

/* ---- coupled_events.c ---- */

/* The events of the step t -> t + dt (peaks, return map, symmetry break),
 * from m->x0, m->v0 (the start) and the balls (the end). */
bf_status bf_coupled_events(coupled_model *m, double t, double dt,
                            bf_err *err);

/* ---- coupled_multirate.c ---- */

/* film_every = auto: set up the first window (K = 1) for tolerance tol
 * (cm/s^2), K at most kmax, a run of nsteps steps. */
bf_status bf_coupled_mr_init(coupled_model *m, double tol, long kmax,
                             long nsteps, bf_err *err);
/* Whether the film's window starts at step n, and the number of ball steps
 * K of the film step that ends with step n (0: none ends there). */
int bf_coupled_window_starts(const coupled_model *m, long n);
long bf_coupled_window_ends(const coupled_model *m, long n);
/* Around the film step that ends with step n (balls at its end): before
 * it, the balls' coupling acceleration in the old film; after it (the
 * coupling refreshed), the lag and the next window's K. */
void bf_coupled_mr_before(coupled_model *m);
void bf_coupled_mr_after(coupled_model *m, long n, double dt);
/* The row of the output series /coupled/film_every (coupled.c opens it),
 * the record in the report and the state in checkpoints (prefix: the
 * entry's name). */
int bf_coupled_mr_output_row(coupled_model *m);
void bf_coupled_mr_report(const coupled_model *m, FILE *f);
bf_status bf_coupled_mr_save(const coupled_model *m, bf_ckpt *ck,
                             const char *name, bf_err *err);
bf_status bf_coupled_mr_load(coupled_model *m, const bf_ckpt *ck,
                             const char *name, bf_err *err);

/* ---- coupled_whole.c ---- */

/* scheme = arkode or mri: ARKODE on the balls and the film in
 * method-of-lines form as one system (m's balls, film and coupling made;
 * the film never stepped by its own scheme).  Refuses what it does not
 * serve, naming the key: a static film, symmetrize, [lyapunov], film_every
 * other than 1, a [film] scheme other than invariant.  dt: [scene] dt. */
bf_status bf_coupled_whole_create(coupled_model *m,
                                  const bf_coupled_whole_keys *k,
                                  const char *film_every, int film_scheme,
                                  double dt, bf_err *err);
void bf_coupled_whole_free(bf_coupled_whole *w);
/* The step t -> t + dt of balls and film (m->x0, m->v0 hold the start);
 * the coupling refreshed to the film at its end. */
bf_status bf_coupled_whole_step(coupled_model *m, double t, double dt,
                                bf_err *err);
void bf_coupled_whole_counters(const bf_coupled_whole *w, bf_counters *c);
/* "arkode ERK DORMAND_PRINCE_7_4_5 rtol=... (whole system)" and the
 * nominal order. */
void bf_coupled_whole_describe(const bf_coupled_whole *w, char *buf,
                               size_t cap, int *order);
void bf_coupled_whole_report(const bf_coupled_whole *w, FILE *f);
/* Checkpoints: the next initial step and the counters (name: the model's
 * entry, "coupled"). */
bf_status bf_coupled_whole_save(const bf_coupled_whole *w, bf_ckpt *ck,
                                const char *name, bf_err *err);
bf_status bf_coupled_whole_load(bf_coupled_whole *w, const bf_ckpt *ck,
                                const char *name, bf_err *err);

/* ---- coupled_lyapunov.c ---- */

/* The running sum of [lyapunov] (m->ly) for the run m. */
bf_status bf_coupled_lyap_init(coupled_model *m, const bf_model_setup *setup,
                               bf_err *err);
/* The shadow m->shadow, freshly built, gets its initial displacement. */
void bf_coupled_lyap_seed(coupled_model *m);
/* After run and shadow took step n (t -> t + dt): renormalise when due. */
bf_status bf_coupled_lyap_renormalise(coupled_model *m, long n, double t,
                                      double dt, bf_err *err);

#endif
