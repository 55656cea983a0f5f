/* coupled_events.c: the events of the coupled model inside a step
 * (coupled_impl.h): the maxima of peak_ball's position (/coupled/peaks,
 * Fig. 6C), the first-return map of map_ball when map_pivot is closest to
 * the origin while touching its inner neighbour (/coupled/return_map, Fig.
 * 8A), and the first times the balls' symmetry error exceeds each level
 * (/coupled/symmetry_break).
 * Events are located inside the step: the time by linear interpolation of
 * the velocity's zero, the state there by the cubic Hermite interpolant of
 * the step's end states (diag/hermite.h; linear for v).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "diag/hermite.h"
#include "models/coupled_impl.h"

const double bf_coupled_sym_levels[BF_COUPLED_NSYM] = {1e-12, 1e-9, 1e-6,
                                                       1e-3};

/* Keep the return map's point (x, v) of the run (coupled_impl.h). */
static bf_status keep_map_point(coupled_model *m, double x, double v,
                                bf_err *err)
{
    if (m->map_kept == m->map_cap) {
        size_t cap = m->map_cap ? 2 * m->map_cap : 256;
        double *nx = cap <= SIZE_MAX / sizeof *nx
                         ? realloc(m->map_x, cap * sizeof *nx)
                         : NULL;
        if (nx)
            m->map_x = nx;
        double *nv = nx ? realloc(m->map_v, cap * sizeof *nv) : NULL;
        if (!nv)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        m->map_v = nv;
        m->map_cap = cap;
    }
    m->map_x[m->map_kept] = x;
    m->map_v[m->map_kept++] = v;
    return BF_OK;
}

/* After the step t -> t + dt (the state at its start in m->x0, m->v0). */
bf_status bf_coupled_events(coupled_model *m, double t, double dt, bf_err *err)
{
    const bf_balls *b = &m->sys->b;
    const double *x1 = b->x, *v1 = b->v, *x0 = m->x0, *v0 = m->v0;
    /* peaks: the velocity of peak_ball turns from > 0 to <= 0 */
    size_t q = m->peak_ball;
    if (v0[q] > 0 && v1[q] <= 0) {
        double s = v0[q] / (v0[q] - v1[q]);
        double row[2] = {t + s * dt,
                         bf_hermite(s, dt, x0[q], v0[q], x1[q], v1[q])};
        if (m->peaks && bf_series_append(m->peaks, row))
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        m->npeak++;
    }
    /* return map: the pivot's distance from the origin has a minimum
     * while it touches its inner neighbour */
    size_t p = m->map_pivot;
    double sg = x1[p] >= 0 ? 1.0 : -1.0;
    double s0 = sg * v0[p], s1 = sg * v1[p];
    if (s0 < 0 && s1 >= 0) {
        /* the neighbour towards the origin */
        long in = sg > 0 ? (long)p - 1 : (long)p + 1;
        if (in >= 0 && in < (long)m->nb) {
            double rs = b->R[p] + b->R[in];
            int touch = fabs(x0[p] - x0[in]) < rs || fabs(x1[p] - x1[in]) < rs;
            if (touch) {
                double s = s0 / (s0 - s1);
                size_t r = m->map_ball;
                double row[3] = {t + s * dt,
                                 bf_hermite(s, dt, x0[r], v0[r], x1[r], v1[r]),
                                 v0[r] + s * (v1[r] - v0[r])};
                if (m->map && bf_series_append(m->map, row))
                    return bf_fail(err, BF_EINTERNAL, "out of memory");
                bf_status st = m->keep_map
                                   ? keep_map_point(m, row[1], row[2], err)
                                   : BF_OK;
                if (st)
                    return st;
                m->nmap++;
            }
        }
    }
    double se = bf_coupled_symmetry_error(x1, m->nb);
    for (int k = 0; k < BF_COUPLED_NSYM; k++)
        if (isnan(m->sym_t[k]) && se > bf_coupled_sym_levels[k])
            m->sym_t[k] = t + dt;
    return BF_OK;
}
