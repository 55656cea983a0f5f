/* particles.h: storage for 2-D point particles, shared by Greenspan's
 * particle fluids (1972, 1973) and the marker particles of the MAC solver.
 *
 * Struct of arrays, so that force loops vectorise and a model can hand one
 * coordinate array to a routine.  Units CGS (cm, cm/s, g) unless the scene
 * says otherwise (Greenspan's examples are dimensionless).
 */
#ifndef BALLFILM_PARTICLES_H
#define BALLFILM_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/error.h"

enum {
    BF_PART_FIXED = 1u << 0 /* immobile (wall particles, listing's P2, P9) */
};

typedef struct bf_particles {
    size_t n;
    double *x, *y;   /* position */
    double *vx, *vy; /* velocity */
    double *m;       /* mass */
    int32_t *tag;    /* model-defined label: fluid 1/2, marker flag, ... */
    uint32_t *flags; /* BF_PART_* */
} bf_particles;

/* Allocate n particles, all fields zero. */
bf_status bf_particles_init(bf_particles *p, size_t n, bf_err *err);
void bf_particles_free(bf_particles *p);

/* sum of m |v|^2 / 2 over the particles that are not fixed */
double bf_particles_kinetic(const bf_particles *p);
/* 1 if every position and velocity is finite; else 0 and *bad = index */
int bf_particles_finite(const bf_particles *p, size_t *bad);

/* Checkpoint every field under names starting with `prefix`. */
bf_status bf_particles_save(const bf_particles *p, bf_ckpt *ck,
                            const char *prefix, bf_err *err);
bf_status bf_particles_load(bf_particles *p, const bf_ckpt *ck,
                            const char *prefix, bf_err *err);

#endif
