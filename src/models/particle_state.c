/* particle_state.c: the state of the Greenspan particle models as arrays
 * (model.h's state and set_state; greenspan.h). */
#include <math.h>
#include <string.h>

#include "models/greenspan.h"
#include "models/state_names.h"

static const char *const names[4] = {"particles/x", "particles/y",
                                     "particles/vx", "particles/vy"};

size_t bf_particles_state_vars(bf_particles *p, bf_state_var *vars,
                               size_t cap)
{
    static const char *const units[4] = {"cm", "cm", "cm/s", "cm/s"};
    double *data[4] = {p->x, p->y, p->vx, p->vy};
    for (size_t k = 0; k < 4 && k < cap; k++)
        vars[k] = (bf_state_var){names[k], units[k], p->n, data[k], 1};
    return 4;
}

bf_status bf_particles_set_var(bf_particles *p, const bf_box *box,
                               const char *name, const double *v, size_t n,
                               bf_err *err)
{
    const size_t k = bf_state_index(names, 4, name);
    if (k == 4 || n != p->n)
        return bf_fail(err, BF_EINPUT, "%s: not an array of the %zu "
                       "particles", name, p->n);
    /* the box's sides along the array's axis (positions only) */
    const double lo = box ? (k == 0 ? box->ax : box->ay) : -INFINITY;
    const double hi = box ? (k == 0 ? box->bx : box->by) : INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(v[i]))
            return bf_fail(err, BF_EINPUT, "%s: particle %zu: %g is not "
                           "finite", name, i + 1, v[i]);
        if (k < 2 && !(v[i] >= lo && v[i] <= hi))
            return bf_fail(err, BF_EINPUT, "%s: particle %zu at %g is "
                           "outside the box [%g, %g]", name, i + 1, v[i],
                           lo, hi);
    }
    double *dst[4] = {p->x, p->y, p->vx, p->vy};
    memcpy(dst[k], v, n * sizeof *v);
    return BF_OK;
}

void bf_particles_pack(const bf_particles *p, double *y)
{
    const double *src[4] = {p->x, p->y, p->vx, p->vy};
    for (size_t k = 0; k < 4; k++)
        memcpy(y + k * p->n, src[k], p->n * sizeof *y);
}

void bf_particles_unpack(bf_particles *p, const double *y)
{
    double *dst[4] = {p->x, p->y, p->vx, p->vy};
    for (size_t k = 0; k < 4; k++)
        memcpy(dst[k], y + k * p->n, p->n * sizeof *y);
}
