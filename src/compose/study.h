/* study.h: what the convergence driver (converge.c) needs to know of a
 * model to study its time integrators: one bf_study_type per model, in
 * its own file (study_balls.c, study_film.c, ...), listed in study.c.
 * Private to the composition layer.
 *
 * The driver builds the model of each method's scene (run.h,
 * bf_model_from_scene) and advances it through its bf_model_type (step,
 * advance, energy, counters, stable_dt); the study says how a method
 * string names the model's time integrator, which methods are adaptive,
 * what the reference is, and which state values are compared. */
#ifndef BALLFILM_COMPOSE_STUDY_H
#define BALLFILM_COMPOSE_STUDY_H

#include "ballfilm/converge.h"
#include "ballfilm/particles.h"
#include "ballfilm/run.h"
#include "diag/energy.h"

/* The state a study compares, read from a model after a step: groups of
 * values (each one array a of n values, and optionally a second array b
 * of n more, e.g. the x and y of particles), and conserved totals. */
typedef struct bf_study_view {
    size_t ngroups;
    struct {
        const char *name, *unit;
        const double *a, *b;
        size_t n;
    } g[BF_CONVERGE_MAX_GROUPS];
    /* conserved totals (the film's phase totals); ninv = 0: the model's
     * energy, if it has one */
    size_t ninv;
    double inv[4];
} bf_study_view;

typedef struct bf_study_type {
    const char *model;         /* the model's name */
    const char *method_key;    /* the key a method's name sets */
    const char *param_section; /* where a method's key=value go */
    const char *invariant;     /* what the invariant error measures */
    double default_ref_rtol;   /* reference tolerance when none is given */
    double max_ref_rtol;       /* largest reference tolerance allowed */
    /* 0: the reference is an ARKODE run (reference() names it, at the
     * reference tolerance); K > 0: SELF-CONVERGENCE, for a scheme with no
     * ODE form (mac): the reference is the method reference() names (the
     * compared one) at the fixed step [scene] dt / K, its estimated error
     * the difference to the run at [scene] dt / (2K), which is the
     * reference's rows. */
    int self_reference;
    /* Optional: the assignments ("section.key=value", one or two) that a
     * method's name makes (NULL: method_key=name); returns how many. */
    size_t (*method_sets)(const char *name, char sets[2][96]);
    /* 1 if the method of the resolved scene sc steps adaptively */
    int (*adaptive)(const bf_scene *sc);
    /* The reference's method string for this study (the driver sets its
     * tolerances and largest step), chosen so that it shares no table
     * with the compared methods (unless o->ref_may_be_compared). */
    bf_status (*reference)(const bf_scene *sc, const bf_converge_opts *o,
                           char *method, size_t cap, bf_err *err);
    /* default largest internal step of adaptive runs, s (0: none) */
    double (*max_step)(const bf_scene *sc);
    /* the compared state of a model built from a method's scene */
    void (*view)(void *model, bf_study_view *v);
    /* one-line description of the model's integrator and its nominal
     * order (0: unknown) */
    void (*describe)(void *model, char *buf, size_t cap, int *order);
    /* Optional: check the energy after every internal step of an
     * adaptive integrator (balls): returns what to free after the run. */
    void *(*watch)(void *model, bf_energy_diag *d);
    /* Optional: notes printed under the table (appended to buf). */
    void (*notes)(const bf_scene *sc, char *buf, size_t cap);
} bf_study_type;

/* The study of the scene's model (NULL: none). */
const bf_study_type *bf_study_of(const char *model);
/* Why a model of the catalog has no study (NULL: no reason known). */
const char *bf_study_why_not(const char *model);

/* Shared by the particle studies: the view of the positions (group x,
 * cm: x and y of every particle) and, with velocities != 0, of the
 * velocities (group v, cm/s). */
void bf_study_particles_view(const bf_particles *p, int velocities,
                             bf_study_view *v);

/* Shared by the balls and coupled studies (study_balls.c): the balls'
 * groups x (cm) and v (cm/s) appended to v. */
void bf_study_balls_groups(const bf_balls *b, bf_study_view *v);
/* The largest internal step of adaptive ball runs: 10 x [scene] dt on a
 * scene with Hertz contacts (effects floor or contact), else 0 (none). */
double bf_study_hertz_max_step(const bf_scene *sc);

/* Shared by the film and coupled studies (study_film.c): the film's
 * groups psi (1), h (cm), q_d, q_c (cm^2/s) appended to v, and its phase
 * totals as the invariants; the note on a randomly perturbed start. */
struct bf_filmsys;
void bf_study_film_groups(struct bf_filmsys *fs, bf_study_view *v);
void bf_study_perturbation_note(const bf_scene *sc, char *buf, size_t cap);

/* Shared by the studies: the reference table among candidates (ARKODE
 * names, in order of preference) that no compared method uses.  A method
 * uses a table when its name is one of `names` (NULL-terminated: the
 * model's ARKODE integrators) and its table= key names the table, or it
 * sets none and defaults[k] (the default table of names[k]) is that
 * table.  With o->ref_table the table is checked instead of chosen. */
bf_status bf_study_pick_table(const bf_converge_opts *o,
                              const char *const *names,
                              const char *const *defaults,
                              const char *const *candidates, size_t ncand,
                              const char **table, bf_err *err);

/* The reference method of a study whose reference is the model's `arkode`
 * integrator with its table set by table=: "arkode:table=T:max_steps=
 * 2000000000" + extra, T the first of VERNER_8_5_6, DORMAND_PRINCE_7_4_5,
 * CASH_KARP_6_4_5 that no compared method uses (names and defaults as in
 * bf_study_pick_table). */
bf_status bf_study_arkode_reference(const bf_converge_opts *o,
                                    const char *const *names,
                                    const char *const *defaults,
                                    const char *extra, char *method,
                                    size_t cap, bf_err *err);
/* The same for a model whose only ARKODE integrator is `arkode` with the
 * default table DORMAND_PRINCE_7_4_5 (the film, greenspan73): a study's
 * reference function. */
bf_status bf_study_arkode_erk(const bf_scene *sc, const bf_converge_opts *o,
                              char *method, size_t cap, bf_err *err);

#endif
