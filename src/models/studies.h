/* studies.h: the convergence studies of the built-in models (study.h),
 * one per model in its own file (study_balls.c, study_film.c, ...),
 * pointed to by the model's descriptor, and what they share (studies.c).
 * Private to the models. */
#ifndef BALLFILM_MODELS_STUDIES_H
#define BALLFILM_MODELS_STUDIES_H

#include "ballfilm/effect.h"
#include "ballfilm/model.h"
#include "ballfilm/particles.h"
#include "ballfilm/study.h"

extern const bf_study_type bf_study_balls;
extern const bf_study_type bf_study_coupled;
extern const bf_study_type bf_study_film;
extern const bf_study_type bf_study_greenspan72;
extern const bf_study_type bf_study_greenspan73;
extern const bf_study_type bf_study_mac;

/* Shared by the particle studies: the view of the positions (group x,
 * cm: x and y of every particle) and, with velocities != 0, of the
 * velocities (group v, cm/s). */
void bf_study_particles_view(const bf_particles *p, int velocities,
                             bf_study_view *v);

/* Shared by the balls and coupled studies (study_balls.c): the balls'
 * groups x (cm) and v (cm/s) appended to v. */
void bf_study_balls_groups(const bf_balls *b, bf_study_view *v);
/* The largest internal step of adaptive ball runs: 10 x [scene] dt on a
 * scene with Hertz contacts, else 0 (none). */
double bf_study_hertz_max_step(const bf_model_setup *s);

/* Shared by the film and coupled studies (study_film.c): the film's
 * groups psi (1), h (cm), q_d, q_c (cm^2/s) appended to v, and its phase
 * totals as the invariants; the notes on the reference's grid and on a
 * randomly perturbed start, from the setup's [film] keys. */
struct bf_filmsys;
void bf_study_film_groups(struct bf_filmsys *fs, bf_study_view *v);
void bf_study_perturbation_note(const bf_model_setup *s, char *buf,
                                size_t cap);
/* The film's [film] dx of the setup, cm. */
double bf_study_film_dx(const bf_model_setup *s);

/* Shared by the studies: the reference table among candidates (ARKODE
 * names, in order of preference) that no compared method uses.  A method
 * uses a table when its name is one of `names` (NULL-terminated: the
 * model's ARKODE integrators) and its table= key names the table, or it
 * sets none and defaults[k] (the default table of names[k]) is that
 * table.  With o->ref_table the table is checked instead of chosen. */
bf_status bf_study_pick_table(const bf_study_methods *o,
                              const char *const *names,
                              const char *const *defaults,
                              const char *const *candidates, size_t ncand,
                              const char **table, bf_err *err);

/* The reference method of a study whose reference is the model's `arkode`
 * integrator with its table set by table=: "arkode:table=T:max_steps=
 * 2000000000" + extra, T the first of VERNER_8_5_6, DORMAND_PRINCE_7_4_5,
 * CASH_KARP_6_4_5 that no compared method uses (names and defaults as in
 * bf_study_pick_table). */
bf_status bf_study_arkode_reference(const bf_study_methods *o,
                                    const char *const *names,
                                    const char *const *defaults,
                                    const char *extra, char *method,
                                    size_t cap, bf_err *err);
/* The same for a model whose only ARKODE integrator is `arkode` with the
 * default table DORMAND_PRINCE_7_4_5 (the film, greenspan73): a study's
 * reference function. */
bf_status bf_study_arkode_erk(const bf_model_setup *s,
                              const bf_study_methods *o, char *method,
                              size_t cap, bf_err *err);

#endif
