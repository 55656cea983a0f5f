/* balls.h: the "balls" model (balls on a line in space, Yasuda sec. 2) as
 * seen by drivers: its ball system and its analysis results.  A parameter
 * sweep reads the Lyapunov exponent and the number of return-map points of
 * a finished run here (or from the root attributes lyapunov_exponent and
 * return_map_points of its output), without parsing stdout. */
#ifndef BALLFILM_BALLS_H
#define BALLFILM_BALLS_H

#include <stddef.h>

#include "ballfilm/ballsys.h"
#include "ballfilm/returnmap.h"
#include "ballfilm/sim.h"

typedef struct bf_balls_analysis {
    int has_return_map;             /* [return_map] enabled */
    size_t return_map_points;       /* points recorded */
    size_t return_map_multi_minima; /* of which contacts with > 1 minimum */
    int has_lyapunov;               /* [lyapunov] enabled */
    double lyapunov_exponent;       /* 1/s; NAN before the first
                                       renormalisation */
    double lyapunov_time;           /* s, time the estimate refers to */
} bf_balls_analysis;

/* For a sim whose model is "balls" or "coupled" (bf_coupled_sim_analysis):
 * fill *a and return BF_OK; otherwise BF_EINPUT. */
bf_status bf_balls_sim_analysis(bf_sim *sim, bf_balls_analysis *a);

/* The same from the model instance (bf_sim_model), and its return map
 * (NULL when not enabled). */
void bf_balls_model_analysis(const void *balls_model, bf_balls_analysis *a);
const bf_retmap *bf_balls_model_retmap(const void *balls_model);

#endif
