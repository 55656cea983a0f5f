/* balls_out.c: the datasets of balls on a line (balls_out.h). */
#include "models/balls_out.h"
#include "io/dataset_paths.h"

static const bf_series_spec balls_series[] = {
    {.path = BF_DS_BALLS_POSITION, .unit = "cm", .role = BF_SR_POSITION,
     .per = "ball", .doc = "ball centre positions, one column per ball",
     .slot = BF_SLOT(bf_balls_out, pos)},
    {.path = BF_DS_BALLS_VELOCITY, .unit = "cm/s", .role = BF_SR_VELOCITY,
     .per = "ball", .doc = "ball velocities, one column per ball",
     .slot = BF_SLOT(bf_balls_out, vel)},
    {.path = BF_DS_BALLS_MASS, .unit = "g", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "ball", .doc = "ball masses"},
    {.path = BF_DS_BALLS_RADIUS, .unit = "cm", .kind = BF_SK_STATIC,
     .role = BF_SR_PROPERTY, .per = "ball", .doc = "ball radii"},
};
enum { BALLS_MASS = 2, BALLS_RADIUS };

const bf_series_table bf_balls_series = {"balls", balls_series,
                                         BF_NSERIES(balls_series)};

bf_status bf_balls_output_open(bf_balls_out *o, bf_out *out,
                               const bf_balls *b, bf_err *err)
{
    const bf_series_extent ext[] = {{"ball", b->n}};
    bf_status st = bf_out_open_table(out, balls_series,
                                     BF_NSERIES(balls_series), o, ext, 1, 0,
                                     err);
    if (!st)
        st = bf_out_table_array(out, &balls_series[BALLS_MASS], b->m, b->n,
                                err);
    if (!st)
        st = bf_out_table_array(out, &balls_series[BALLS_RADIUS], b->R, b->n,
                                err);
    return st;
}

int bf_balls_output_row(const bf_balls_out *o, const bf_balls *b)
{
    return bf_series_append(o->pos, b->x) || bf_series_append(o->vel, b->v);
}
