/* walls.c: reflecting, damping container walls (Greenspan 1972 eq. 2.13);
 * see walls.h for the two rules. */
#include "walls.h"

#include <math.h>

static const bf_param walls_params[] = {
    {"omega", BF_AT(bf_walls_keys, omega, BF_REAL), "1", "1",
     "reflected speed / incident speed at a wall, eq. 2.13 (0 < omega <= 1)",
     BF_POS | BF_MAX, 0, 1, NULL},
    {"rule", BF_AT(bf_walls_keys, rule, BF_ENUM), "", "clean",
     "clean: specular reflection of the rest of the step, speed times omega "
     "(the text); fortran: Schubert's WALCOL literally (EPS damping, omega^2 "
     "tangential artefact)",
     0, 0, 0, "clean|fortran"},
    {"eps", BF_AT(bf_walls_keys, eps, BF_REAL), "cm", "1e-3",
     "the listing's EPS in WALCOL (rule = fortran only)", BF_POS, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_walls_spec = BF_SECTION(
    "walls", "container walls that reflect particles (Greenspan 1972 eq. 2.13)",
    walls_params, bf_walls_keys);

void bf_walls_from_keys(bf_walls *w, const bf_walls_keys *k, bf_box box)
{
    w->box = box;
    w->omega = k->omega;
    w->rule = (bf_wall_rule)k->rule;
    w->eps = k->eps;
}

static inline int inside(const bf_box *b, double x, double y)
{
    return x >= b->ax && x <= b->bx && y >= b->ay && y <= b->by;
}

static inline double clampd(double v, double lo, double hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* The clean rule for one particle; returns the number of hits or -1. */
static int reflect_clean(const bf_walls *w, double x0, double y0, double *px,
                         double *py, double *pvx, double *pvy)
{
    const bf_box *b = &w->box;
    const double om = w->omega;
    double x = *px, y = *py, vx = *pvx, vy = *pvy;
    int hits = 0;
    /* the start must be inside; it is, by the invariant, unless the state
     * is broken */
    if (!inside(b, x0, y0))
        return -1;
    while (!inside(b, x, y)) {
        if (!isfinite(x) || !isfinite(y) || hits >= BF_WALLS_MAX_HITS)
            return -1;
        /* fraction of the segment at which each violated wall is met */
        double sx = INFINITY, sy = INFINITY, wx = 0, wy = 0;
        if (x > b->bx) {
            sx = (b->bx - x0) / (x - x0);
            wx = b->bx;
        } else if (x < b->ax) {
            sx = (b->ax - x0) / (x - x0);
            wx = b->ax;
        }
        if (y > b->by) {
            sy = (b->by - y0) / (y - y0);
            wy = b->by;
        } else if (y < b->ay) {
            sy = (b->ay - y0) / (y - y0);
            wy = b->ay;
        }
        int hitx = sx <= sy, hity = sy <= sx;
        double s = hitx ? sx : sy;
        /* impact point H, on the wall exactly, inside the box */
        double hx = hitx ? wx : clampd(x0 + s * (x - x0), b->ax, b->bx);
        double hy = hity ? wy : clampd(y0 + s * (y - y0), b->ay, b->by);
        if (hitx) {
            x = hx - om * (x - hx);
            vx = -om * vx;
        } else {
            x = hx + om * (x - hx);
            vx = om * vx;
        }
        if (hity) {
            y = hy - om * (y - hy);
            vy = -om * vy;
        } else {
            y = hy + om * (y - hy);
            vy = om * vy;
        }
        x0 = hx;
        y0 = hy;
        hits++;
    }
    *px = x;
    *py = y;
    *pvx = vx;
    *pvy = vy;
    return hits;
}

/* Fortran SIGN(EPS, D): |EPS| with the sign of D (+ for D = 0). */
static inline double fsign(double eps, double d)
{
    return d >= 0 ? eps : -eps;
}

/* Schubert's WALCOL for one particle, statement by statement. */
static int reflect_fortran(const bf_walls *w, double x1, double y1, double *px,
                           double *py, double *pvx, double *pvy)
{
    const bf_box *b = &w->box;
    const double om = w->omega, eps = w->eps;
    double x2 = *px, y2 = *py, vx = *pvx, vy = *pvy, t;
    int hits = 0;
    for (;;) {
        if (!isfinite(x2) || !isfinite(y2) || hits >= BF_WALLS_MAX_HITS)
            return -1;
        if (x2 > b->bx || x2 < b->ax) {
            double wall = x2 > b->bx ? b->bx : b->ax;
            t = (y2 - y1) / (x2 - x1 + fsign(eps, x2 - x1));
            x2 = wall - om * (x2 - wall);
            x1 = wall;
            y1 = y2 + (x2 - wall) * t;
            y2 = y1 - om * (x2 - wall) * t;
        } else if (y2 > b->by || y2 < b->ay) {
            double wall = y2 > b->by ? b->by : b->ay;
            t = (x2 - x1) / (y2 - y1 + fsign(eps, y2 - y1));
            y2 = wall - om * (y2 - wall);
            y1 = wall;
            x1 = x2 + (y2 - wall) * t;
            x2 = x1 - om * (y2 - wall) * t;
        } else {
            break;
        }
        /* statement 65: the speed, damped, along the new displacement */
        double speed = om * sqrt(vx * vx + vy * vy);
        double dinv = 1.0 / (sqrt((x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1)) +
                             eps);
        vx = speed * (x2 - x1) * dinv;
        vy = speed * (y2 - y1) * dinv;
        hits++;
    }
    *px = x2;
    *py = y2;
    *pvx = vx;
    *pvy = vy;
    return hits;
}

bf_status bf_walls_apply(const bf_walls *w, bf_particles *p, double *x0,
                         double *y0, unsigned long long *hits, bf_err *err)
{
    return bf_walls_apply_ids(w, p, x0, y0, NULL, hits, NULL, err);
}

bf_status bf_walls_apply_ids(const bf_walls *w, bf_particles *p, double *x0,
                             double *y0, const uint32_t *ids,
                             unsigned long long *hits, size_t *bad,
                             bf_err *err)
{
    const bf_box *b = &w->box;
    unsigned long long total = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (inside(b, p->x[i], p->y[i]))
            continue;
        int h = w->rule == BF_WALL_FORTRAN
                    ? reflect_fortran(w, x0[i], y0[i], &p->x[i], &p->y[i],
                                      &p->vx[i], &p->vy[i])
                    : reflect_clean(w, x0[i], y0[i], &p->x[i], &p->y[i],
                                    &p->vx[i], &p->vy[i]);
        if (h < 0) {
            if (bad)
                *bad = i;
            return bf_fail(err, BF_EUNSTABLE,
                           "particle %zu cannot be brought back into the box "
                           "(from (%.9g, %.9g) to (%.9g, %.9g): non-finite, or "
                           "more than %d wall hits in one step)",
                           (ids ? (size_t)ids[i] : i) + 1, x0[i], y0[i],
                           p->x[i], p->y[i], BF_WALLS_MAX_HITS);
        }
        total += (unsigned long long)h;
    }
    if (hits)
        *hits += total;
    return BF_OK;
}

int bf_box_contains_all(const bf_box *b, const bf_particles *p, size_t *bad)
{
    for (size_t i = 0; i < p->n; i++)
        if (!inside(b, p->x[i], p->y[i])) {
            if (bad)
                *bad = i;
            return 0;
        }
    return 1;
}
