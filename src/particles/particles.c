/* particles.c: 2-D particle storage (see particles.h). */
#include "ballfilm/particles.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

bf_status bf_particles_init(bf_particles *p, size_t n, bf_err *err)
{
    size_t k = n ? n : 1;
    p->n = n;
    p->x = calloc(k, sizeof *p->x);
    p->y = calloc(k, sizeof *p->y);
    p->vx = calloc(k, sizeof *p->vx);
    p->vy = calloc(k, sizeof *p->vy);
    p->m = calloc(k, sizeof *p->m);
    p->tag = calloc(k, sizeof *p->tag);
    p->flags = calloc(k, sizeof *p->flags);
    if (!p->x || !p->y || !p->vx || !p->vy || !p->m || !p->tag || !p->flags) {
        bf_particles_free(p);
        return bf_fail(err, BF_EINTERNAL, "out of memory (%zu particles)", n);
    }
    return BF_OK;
}

void bf_particles_free(bf_particles *p)
{
    free(p->x);
    free(p->y);
    free(p->vx);
    free(p->vy);
    free(p->m);
    free(p->tag);
    free(p->flags);
    p->x = p->y = p->vx = p->vy = p->m = NULL;
    p->tag = NULL;
    p->flags = NULL;
    p->n = 0;
}

double bf_particles_kinetic(const bf_particles *p)
{
    double k = 0.0;
    for (size_t i = 0; i < p->n; i++)
        if (!(p->flags[i] & BF_PART_FIXED))
            k += 0.5 * p->m[i] * (p->vx[i] * p->vx[i] + p->vy[i] * p->vy[i]);
    return k;
}

int bf_particles_finite(const bf_particles *p, size_t *bad)
{
    for (size_t i = 0; i < p->n; i++)
        if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->vx[i]) ||
            !isfinite(p->vy[i])) {
            if (bad)
                *bad = i;
            return 0;
        }
    return 1;
}

/* Every array of the storage (the count is checked first, with a message
 * that names both numbers). */
static const bf_field particle_state[] = {
    BF_FIELD_PTR(bf_particles, x, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(bf_particles, y, BF_F_DOUBLE, n, "cm"),
    BF_FIELD_PTR(bf_particles, vx, BF_F_DOUBLE, n, "cm/s"),
    BF_FIELD_PTR(bf_particles, vy, BF_F_DOUBLE, n, "cm/s"),
    BF_FIELD_PTR(bf_particles, m, BF_F_DOUBLE, n, "g"),
    BF_FIELD_PTR(bf_particles, tag, BF_F_I32, n, "1"),
    BF_FIELD_PTR(bf_particles, flags, BF_F_U32, n, "1"),
};

bf_status bf_particles_save(const bf_particles *p, bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char name[256];
    snprintf(name, sizeof name, "%s.n", prefix);
    bf_status st = bf_ckpt_put_int(ck, name, (int64_t)p->n, err);
    if (!st)
        st = bf_ckpt_put_fields(ck, prefix, particle_state,
                                BF_NFIELDS(particle_state), p, err);
    return st;
}

bf_status bf_particles_load(bf_particles *p, const bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char name[256];
    int64_t n;
    snprintf(name, sizeof name, "%s.n", prefix);
    bf_status st = bf_ckpt_get_int(ck, name, &n, err);
    if (st)
        return st;
    if (n != (int64_t)p->n)
        return bf_fail(err, BF_EINPUT, "checkpoint has %lld particles, the "
                       "scene %zu", (long long)n, p->n);
    return bf_ckpt_get_fields(ck, prefix, particle_state,
                              BF_NFIELDS(particle_state), p, err);
}
