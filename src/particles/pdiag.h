/* pdiag.h: diagnostics of 2-D particle sets shared by the particle models:
 * kinetic energy by label, mean height by label, counts per horizontal
 * layer, the kinetic energy of the centre of mass.  Units: cm, cm/s, g,
 * erg. */
#ifndef BALLFILM_PARTICLES_PDIAG_H
#define BALLFILM_PARTICLES_PDIAG_H

#include <stddef.h>

#include "ballfilm/particles.h"

typedef struct bf_pdiag_group {
    size_t count;  /* particles with the label */
    double kin;    /* sum of m |v|^2 / 2 (not fixed), erg */
    double mean_y; /* mean height, cm (NAN if count = 0) */
    double min_y, max_y;
} bf_pdiag_group;

/* Statistics of the particles whose tag equals `tag`. */
bf_pdiag_group bf_pdiag_group_of(const bf_particles *p, int tag);

/* The same over a set that comes in parts, in index order (the sums are
 * taken in the order of one pass over the whole set: the same bits):
 * start, add each part, end. */
typedef struct bf_pdiag_acc {
    bf_pdiag_group g;
    double sy; /* sum of the heights */
} bf_pdiag_acc;
bf_pdiag_acc bf_pdiag_acc_start(void);
void bf_pdiag_acc_add(bf_pdiag_acc *a, const bf_particles *p, int tag);
bf_pdiag_group bf_pdiag_acc_end(const bf_pdiag_acc *a);

/* Particles with label `tag` (any label if tag < 0) in each of `nl` equal
 * horizontal layers of [y0, y1]; a particle exactly at y1 counts in the top
 * layer.  counts has nl entries. */
void bf_pdiag_layers(const bf_particles *p, int tag, double y0, double y1,
                     size_t nl, double *counts);
/* The same, adding to counts (for a set that comes in parts). */
void bf_pdiag_layers_add(const bf_particles *p, int tag, double y0,
                         double y1, size_t nl, double *counts);

/* |sum m v|^2 / (2 sum m) over the particles that are not fixed: the
 * kinetic energy of the centre-of-mass motion, erg.  `inertia` replaces m
 * when not NULL (models whose update does not divide by m). */
double bf_pdiag_cm_kinetic(const bf_particles *p, const double *inertia);

/* sum inertia |v|^2 / 2 over the particles that are not fixed (inertia NULL:
 * the masses, i.e. bf_particles_kinetic). */
double bf_pdiag_kinetic(const bf_particles *p, const double *inertia);

#endif
