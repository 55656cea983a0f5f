/* balls_out.h: the datasets of balls on a line, shared by the models
 * balls and coupled (series.h; private to src/models). */
#ifndef BALLFILM_MODELS_BALLS_OUT_H
#define BALLFILM_MODELS_BALLS_OUT_H

#include "ballfilm/effect.h"
#include "ballfilm/series.h"
#include "io/dataset_paths.h"

typedef struct bf_balls_out {
    bf_series *pos, *vel;
} bf_balls_out;

extern const bf_series_table bf_balls_series;

/* Open /balls/position and /balls/velocity and write /balls/mass and
 * /balls/radius. */
bf_status bf_balls_output_open(bf_balls_out *o, bf_out *out,
                               const bf_balls *b, bf_err *err);
/* Append the balls' state; nonzero when a buffer could not grow. */
int bf_balls_output_row(const bf_balls_out *o, const bf_balls *b);

#endif
