/* particle_state.c: the state of the Greenspan particle models as arrays
 * (model.h's state and set_state; greenspan.h). */
#include <math.h>
#include <string.h>

#include "models/greenspan.h"
#include "models/state_names.h"
#include "io/dataset_paths.h"

#define P_X BF_DS_PARTICLES_X
#define P_Y BF_DS_PARTICLES_Y
#define P_VX BF_DS_PARTICLES_VX
#define P_VY BF_DS_PARTICLES_VY
#define VDOC_HALF(c)                                                           \
    c " velocity at t - dt/2 (leapfrog half step; the initial velocity in "   \
      "row 0)"

static const bf_series_spec particle_series[] = {
    {.path = BF_DS_PARTICLES_STEP, .unit = "1", .is_int = 1,
     .kind = BF_SK_SNAPSHOT, .role = BF_SR_STEP, .when = BF_PO_STEP,
     .doc = "step of each row of the per-particle datasets",
     .slot = BF_SLOT(bf_particle_out, step)},
    {.path = P_X, .unit = "cm", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_POSITION_X, .per = "particle", .when = BF_PO_POS,
     .doc = "x of every particle", .slot = BF_SLOT(bf_particle_out, x)},
    {.path = P_Y, .unit = "cm", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_POSITION_Y, .per = "particle", .when = BF_PO_POS,
     .doc = "y of every particle", .slot = BF_SLOT(bf_particle_out, y)},
    {.path = P_VX, .unit = "cm/s", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_VELOCITY, .per = "particle", .when = BF_PO_VEL,
     .doc = "x velocity at t", .slot = BF_SLOT(bf_particle_out, vx)},
    {.path = P_VY, .unit = "cm/s", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_VELOCITY, .per = "particle", .when = BF_PO_VEL,
     .doc = "y velocity at t", .slot = BF_SLOT(bf_particle_out, vy)},
    {.path = P_VX, .unit = "cm/s", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_VELOCITY_HALF, .per = "particle", .when = BF_PO_VEL_HALF,
     .doc = VDOC_HALF("x"), .slot = BF_SLOT(bf_particle_out, vx)},
    {.path = P_VY, .unit = "cm/s", .kind = BF_SK_SNAPSHOT,
     .role = BF_SR_VELOCITY_HALF, .per = "particle", .when = BF_PO_VEL_HALF,
     .doc = VDOC_HALF("y"), .slot = BF_SLOT(bf_particle_out, vy)},
    {.path = BF_DS_PARTICLES_MASS, .unit = "g", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "particle",
     .doc = "particle masses (pair strengths, gravity)"},
};
enum { PS_MASS = BF_NSERIES(particle_series) - 1 };

const bf_series_table bf_particle_series = {"particles", particle_series,
                                            BF_NSERIES(particle_series)};

bf_status bf_particles_output_open(bf_particle_out *po, bf_out *out,
                                   const bf_particles *p, unsigned on,
                                   bf_err *err)
{
    const bf_series_extent ext[] = {{"particle", p->n}};
    bf_status st = bf_out_open_table(out, particle_series,
                                     BF_NSERIES(particle_series), po, ext, 1,
                                     on, err);
    return st ? st
              : bf_out_table_array(out, &particle_series[PS_MASS], p->m, p->n,
                                   err);
}

int bf_particles_output_row(const bf_particle_out *po, const bf_particles *p,
                            int64_t step)
{
    int fail = 0;
    if (po->step)
        fail |= bf_series_append_i64(po->step, &step) != BF_OK;
    if (po->x)
        fail |= (bf_series_append(po->x, p->x) |
                 bf_series_append(po->y, p->y)) != BF_OK;
    if (po->vx)
        fail |= (bf_series_append(po->vx, p->vx) |
                 bf_series_append(po->vy, p->vy)) != BF_OK;
    return fail;
}

int bf_particles_output_part(const bf_particle_out *po, const bf_particles *p,
                             int first, int64_t step)
{
    int fail = 0;
    if (first && po->step)
        fail |= bf_series_append_i64(po->step, &step) != BF_OK;
    if (po->x)
        fail |= (bf_series_append_part(po->x, p->x, p->n) |
                 bf_series_append_part(po->y, p->y, p->n)) != BF_OK;
    if (po->vx)
        fail |= (bf_series_append_part(po->vx, p->vx, p->n) |
                 bf_series_append_part(po->vy, p->vy, p->n)) != BF_OK;
    return fail;
}

/* the state's names are the datasets' without the leading slash */
static const char *const names[4] = {P_X + 1, P_Y + 1, P_VX + 1, P_VY + 1};

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
