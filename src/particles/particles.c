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

bf_status bf_particles_save(const bf_particles *p, bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char name[256];
    const double *arr[] = {p->x, p->y, p->vx, p->vy, p->m};
    const char *nm[] = {"x", "y", "vx", "vy", "m"};
    bf_status st;
    snprintf(name, sizeof name, "%s.n", prefix);
    if ((st = bf_ckpt_put_int(ck, name, (int64_t)p->n, err)))
        return st;
    for (int k = 0; k < 5; k++) {
        snprintf(name, sizeof name, "%s.%s", prefix, nm[k]);
        if ((st = bf_ckpt_put(ck, name, arr[k], p->n, err)))
            return st;
    }
    snprintf(name, sizeof name, "%s.tag", prefix);
    if ((st = bf_ckpt_put_bytes(ck, name, p->tag, p->n * sizeof *p->tag, err)))
        return st;
    snprintf(name, sizeof name, "%s.flags", prefix);
    return bf_ckpt_put_bytes(ck, name, p->flags, p->n * sizeof *p->flags, err);
}

bf_status bf_particles_load(bf_particles *p, const bf_ckpt *ck,
                            const char *prefix, bf_err *err)
{
    char name[256];
    double *arr[] = {p->x, p->y, p->vx, p->vy, p->m};
    const char *nm[] = {"x", "y", "vx", "vy", "m"};
    bf_status st;
    int64_t n;
    snprintf(name, sizeof name, "%s.n", prefix);
    if ((st = bf_ckpt_get_int(ck, name, &n, err)))
        return st;
    if (n != (int64_t)p->n)
        return bf_fail(err, BF_EINPUT, "checkpoint has %lld particles, the "
                       "scene %zu", (long long)n, p->n);
    for (int k = 0; k < 5; k++) {
        snprintf(name, sizeof name, "%s.%s", prefix, nm[k]);
        if ((st = bf_ckpt_get(ck, name, arr[k], p->n, err)))
            return st;
    }
    snprintf(name, sizeof name, "%s.tag", prefix);
    if ((st = bf_ckpt_get_bytes(ck, name, p->tag, p->n * sizeof *p->tag, err)))
        return st;
    snprintf(name, sizeof name, "%s.flags", prefix);
    return bf_ckpt_get_bytes(ck, name, p->flags, p->n * sizeof *p->flags, err);
}
