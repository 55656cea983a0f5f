/* study.h: what the convergence study (`ballfilm converge`, converge.h)
 * needs to know of a model to study its time integrators.  A model that
 * supports the study points to its bf_study_type from its descriptor
 * (model.h, bf_model_type.study); the driver of the composition layer
 * asks nothing else of it.
 *
 * The driver builds the model of each method's scene and advances it
 * through its bf_model_type (step, advance, energy, counters,
 * stable_dt); the study says how a method string names the model's time
 * integrator, which methods are adaptive, what the reference is, and
 * which state values are compared.  Its hooks see the model's filled
 * structs (bf_model_setup) or the model built from them, never a scene.
 */
#ifndef BALLFILM_STUDY_H
#define BALLFILM_STUDY_H

#include <stddef.h>

#include "ballfilm/error.h"
#include "ballfilm/model.h"

enum { BF_STUDY_MAX_GROUPS = 6 };

/* The state a study compares, read from a model after a step: groups of
 * values (each one array a of n values, and optionally a second array b
 * of n more, e.g. the x and y of particles), and conserved totals. */
typedef struct bf_study_view {
    size_t ngroups;
    struct {
        const char *name, *unit;
        const double *a, *b;
        size_t n;
    } g[BF_STUDY_MAX_GROUPS];
    /* conserved totals (the film's phase totals); ninv = 0: the model's
     * energy, if it has one */
    size_t ninv;
    double inv[4];
} bf_study_view;

/* What the choice of a reference depends on: the compared method strings
 * ("name:key=value:..."), a reference table the user gave (NULL: the
 * study chooses) and whether a compared method may share it. */
typedef struct bf_study_methods {
    const char *const *methods;
    size_t n;
    const char *ref_table;
    int ref_may_be_compared;
} bf_study_methods;

/* Called by the model after every internal step of an adaptive
 * integrator with the energy then (erg). */
typedef void (*bf_study_energy_fn)(void *ctx, double energy);

typedef struct bf_study_type {
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
    /* 1 if the method of the setup s steps adaptively */
    int (*adaptive)(const bf_model_setup *s);
    /* The reference's method string for this study (the driver sets its
     * tolerances and largest step), chosen so that it shares no table
     * with the compared methods (unless m->ref_may_be_compared). */
    bf_status (*reference)(const bf_model_setup *s, const bf_study_methods *m,
                           char *method, size_t cap, bf_err *err);
    /* Optional: default largest internal step of adaptive runs, s (0:
     * none). */
    double (*max_step)(const bf_model_setup *s);
    /* the compared state of a model built from a method's scene */
    void (*view)(void *self, bf_study_view *v);
    /* one-line description of the model's integrator and its nominal
     * order (0: unknown) */
    void (*describe)(void *self, char *buf, size_t cap, int *order);
    /* Optional: report the energy to check(ctx, E) after every internal
     * step of an adaptive integrator (balls); returns what to free after
     * the run (NULL: out of memory, no check). */
    void *(*watch)(void *self, bf_study_energy_fn check, void *ctx);
    /* Optional: notes printed under the table (appended to buf). */
    void (*notes)(const bf_model_setup *s, char *buf, size_t cap);
} bf_study_type;

#endif
