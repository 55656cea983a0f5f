/* hertz_pairs.c: Hertz repulsion between particles closer than 2R, all
 * pairs or from the cell list (see hertz_pairs.h).  Every pair is visited
 * once and both accelerations are updated. */
#include "hertz_pairs.h"

#include <math.h>

#include "contact/hertz.h"

static const bf_param hertz_params[] = {
    {"enabled", BF_AT(bf_hertz_keys, enabled, BF_BOOL), "", "no",
     "Hertz repulsion f = k x^{3/2}, x = (2R - r)/2, between particles "
     "closer than 2R (added to the other forces)",
     0, 0, 0, NULL},
    {"k", BF_AT(bf_hertz_keys, k, BF_REAL), "g cm^-1/2 s^-2", "1e7",
     "Hertz constant of the particle-particle contact", BF_POS, 0, 0, NULL},
    {"radius", BF_AT(bf_hertz_keys, radius, BF_REAL), "cm", "0",
     "contact radius R of every particle (0: d/2, half the particle width)",
     BF_NONNEG, 0, 0, NULL},
    {0},
};

const bf_section_spec bf_hertz_spec = BF_SECTION(
    "hertz", "Hertz contact between particles (off by default)", hertz_params,
    bf_hertz_keys);

/* One pair closer than 2R: (dx, dy) = x_i - x_j, r2 = dx^2 + dy^2; the
 * force k x^{3/2} along the line of centres, divided by each mass.
 * Returns 1 (and adds nothing) if the centres coincide. */
static inline int pair(const bf_hertz_pairs *h, double dx, double dy,
                       double r2, double mi, double mj, double *axi,
                       double *ayi, double *axj, double *ayj)
{
    const double r = sqrt(r2);
    if (!(r > 0))
        return 1;
    const double f = bf_hertz_pair_force(h->k, h->R, h->R, r) / r;
    const double tx = dx * f, ty = dy * f;
    *axi += tx / mi;
    *ayi += ty / mi;
    *axj -= tx / mj;
    *ayj -= ty / mj;
    return 0;
}

int bf_hertz_pairs_all(const bf_hertz_pairs *h, const double *x,
                       const double *y, const double *m, size_t n,
                       double *ax, double *ay, size_t *bi, size_t *bj)
{
    const double rc = 2.0 * h->R, rc2 = rc * rc;
    int bad = 0;
    for (size_t j = 0; j < n; j++)
        for (size_t i = j + 1; i < n; i++) {
            const double dx = x[j] - x[i], dy = y[j] - y[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 < rc2 && pair(h, dx, dy, r2, m[j], m[i], &ax[j], &ay[j],
                                 &ax[i], &ay[i]) &&
                !bad) {
                bad = 1;
                *bi = j;
                *bj = i;
            }
        }
    return bad;
}

int bf_hertz_pairs_cells(const bf_hertz_pairs *h, const bf_cells *c,
                         double *ax, double *ay, size_t *bi, size_t *bj)
{
    const double rc = 2.0 * h->R, rc2 = rc * rc;
    const int nx = c->nx, ny = c->ny;
    /* columns (rows) of two particles closer than 2R differ by at most
     * ceil(2R/h); the margin covers the rounding of the cell indices */
    const double q = rc * c->inv_h + 1e-12 * (double)(nx + ny + 1);
    const int reach = q < (double)(nx + ny) ? (int)ceil(q) : nx + ny;
    const double *sx = c->sx, *sy = c->sy, *sw = c->sw;
    int bad = 0;
    for (int cx = 0; cx < nx; cx++)
        for (int cy = 0; cy < ny; cy++) {
            uint32_t a0, a1;
            bf_cells_run(c, cx, cy, cy, &a0, &a1);
            const int ylo = cy - reach < 0 ? 0 : cy - reach,
                      yhi = cy + reach >= ny ? ny - 1 : cy + reach;
            for (uint32_t s = a0; s < a1; s++) {
                const uint32_t i = c->idx[s];
                /* half of the neighbourhood: in its own column the slots
                 * after s up to row cy + reach, then the columns to the
                 * right, rows cy - reach .. cy + reach */
                for (int ox = 0; ox <= reach && cx + ox < nx; ox++) {
                    uint32_t u0, u1;
                    bf_cells_run(c, cx + ox, ox == 0 ? cy : ylo, yhi, &u0,
                                 &u1);
                    for (uint32_t t = ox == 0 ? s + 1 : u0; t < u1; t++) {
                        const double dx = sx[s] - sx[t], dy = sy[s] - sy[t];
                        const double r2 = dx * dx + dy * dy;
                        const uint32_t j = c->idx[t];
                        if (r2 < rc2 &&
                            pair(h, dx, dy, r2, sw[s], sw[t], &ax[i], &ay[i],
                                 &ax[j], &ay[j]) &&
                            !bad) {
                            bad = 1;
                            *bi = i;
                            *bj = j;
                        }
                    }
                }
            }
        }
    return bad;
}
