/* support_gaps.c: the empty bands of the fast method of the support-set
 * gravity (support.h): for every strip the lowest band in which no square
 * overlaps it with positive area, from the gaps between the x-sorted
 * squares of each band (support_impl.h, bf_sup_empty_bands).  A particle
 * with such a band below its top band falls freely (eq. 2.9).
 */
#include <math.h>
#include <string.h>

#include "particles/support_impl.h"

/* The skip list of the strips that no band has taken yet: nxt[p] == p
 * for a strip not taken; the next one not taken, with the path halved. */
static inline uint32_t skip_find(uint32_t *nxt, uint32_t p)
{
    while (nxt[p] != p) {
        nxt[p] = nxt[nxt[p]];
        p = nxt[p];
    }
    return p;
}

/* The strips of sorted positions [p0, p1) that no lower band has taken
 * get band q as their lowest empty band; returns how many. */
static inline size_t take_strips(bf_support *s, uint32_t *nxt, size_t p0,
                                 size_t p1, int q)
{
    size_t got = 0;
    for (uint32_t j = skip_find(nxt, (uint32_t)p0); j < p1;
         j = skip_find(nxt, j + 1)) {
        s->lowe[j] = q;
        nxt[j] = j + 1;
        got++;
    }
    return got;
}

/* For every sorted position, the lowest band q <= mq in which no square
 * overlaps its strip with positive area (lowe), or a value > mq.
 *
 * One pass over the squares in x order finds every band's gaps: f1 > 0
 * exactly in the bands mb..mt (z_{q-1} < t and z_q > b), unless the square
 * has no height, and the gap of band q before square k is [r, l_k] with r
 * the right edge of the band's previous square (r = min(x + d/2, bx) grows
 * with x), which the pass keeps per band (gr; a few KB, in the cache).  A
 * gap that a strip may fit (GAP_FITS) is written down with its band, its
 * left end and p1, the first sorted position whose strip ends beyond its
 * right end l_k (ds > l_k), found by a pointer that only moves forward (l_k
 * grows with k); the band's first gap (-inf, l_first] and last [r_last,
 * +inf) always are.  Then the gaps are taken band by band from the lowest:
 * the strips that fit are the positions p0..p1-1 with gs >= the left end,
 * so p0 is found by galloping down from p1 (as far as there are strips
 * that fit, mostly none), and a strip gets the band unless a lower one
 * took it: the same lowe as looking at every band's squares in x order. */
void bf_sup_empty_bands(bf_support *s, size_t n, int mq)
{
    uint32_t *nxt = s->nxt, *gcnt = s->gcnt, *gord = s->gord,
             *gp1 = s->gp1;
    int32_t *gq = s->gq;
    double *glo = s->glo, *gr = s->gr;
    const int32_t *mb = s->mb, *mt = s->mt;
    const double *ts = s->ts, *bs = s->bs, *ls = s->ls, *rs = s->rs,
                 *gs = s->gs, *ds = s->ds;
    /* the narrowest strip, and the narrowest that the walls do not clip:
     * a clipped strip (gamma = ax or delta = bx) fits only a gap that
     * reaches the wall, so the gaps between two squares are tested
     * against the unclipped width (about dx, where wmin is about dx/2) */
    const double ax = s->p.box.ax, bx = s->p.box.bx;
    double wmin = INFINITY, wint = INFINITY;
    for (size_t k = 0; k < n; k++) {
        double w = ds[k] - gs[k];
        wmin = w < wmin ? w : wmin;
        wint = w < wint && gs[k] > ax && ds[k] < bx ? w : wint;
        s->lowe[k] = mq + 1;
        nxt[k] = (uint32_t)k;
    }
    nxt[n] = (uint32_t)n;
#define GAP_FITS(lo, hi)                                                    \
    ((hi) - (lo) >= ((lo) <= ax || (hi) >= bx ? wmin : wint))
    for (int q = 0; q <= mq + 1; q++) {
        gr[q] = -INFINITY;
        gcnt[q] = 0;
    }
    size_t ng = 0, p1 = 0;
    /* the gap of band q before square k; then k is the band's last */
#define BAND_GAP(q, k)                                                      \
    do {                                                                    \
        const double lo_ = gr[q], hi_ = ls[k];                              \
        if (GAP_FITS(lo_, hi_)) {                                           \
            while (p1 < n && !(ds[p1] > hi_))                               \
                p1++;                                                       \
            glo[ng] = lo_;                                                  \
            gp1[ng] = (uint32_t)p1;                                         \
            gq[ng++] = (q);                                                 \
            gcnt[q]++;                                                      \
        }                                                                   \
        gr[q] = rs[k];                                                      \
    } while (0)
    for (size_t k = 0; k < n; k++) {
        const int qa = mb[k], qb = mt[k] < mq ? mt[k] : mq;
        if (!(ts[k] > bs[k]) || qb < qa)
            continue;
        BAND_GAP(qa, k);
        for (int q = qa + 1; q <= qb; q++)
            BAND_GAP(q, k);
    }
#undef BAND_GAP
    /* every band's last gap, [r_last, +inf) (the whole line if the band
     * has no square) */
    for (int q = 1; q <= mq; q++) {
        glo[ng] = gr[q];
        gp1[ng] = (uint32_t)n;
        gq[ng++] = q;
        gcnt[q]++;
    }
    /* the gaps by band, in x order within a band */
    uint32_t at = 0;
    for (int q = 0; q <= mq; q++) {
        const uint32_t c = gcnt[q];
        gcnt[q] = at;
        at += c;
    }
    for (size_t g = 0; g < ng; g++)
        gord[gcnt[gq[g]]++] = (uint32_t)g;
    size_t left = n;
    for (size_t e = 0; e < ng && left; e++) {
        const uint32_t g = gord[e];
        /* rounding is monotone: a strip of width w fits only if the
         * rounded gap width is >= w */
        const size_t p0 =
            glo[g] == -INFINITY ? 0 : gallop_pos(gs, n, gp1[g], glo[g], 1);
        left -= take_strips(s, nxt, p0, gp1[g], gq[g]);
    }
#undef GAP_FITS
}

