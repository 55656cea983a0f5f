/* film_mirror.c: the film's mirror symmetry x -> -x, psi -> -psi (see
 * bf_film_mirror in film.h): the distance of the state from its mirror
 * image and the projection onto the symmetric states. */
#include "ballfilm/film.h"

#include <math.h>

#include "film/film_impl.h"

/* The mean of a and b as 0.5 fl(a + b), exact but for the rounding error
 * of the sum, returned in *e (Knuth's TwoSum: a + b = s + e exactly). */
static double mean2(double a, double b, double *e)
{
    double s = a + b, bb = s - a;
    *e = (a - (s - bb)) + (b - bb);
    return 0.5 * s;
}

/* One pass over the pairs (i, N - i), i <= N - i.  The maxima by
 * comparisons into separate accumulators, not fmax (a library call per
 * value at -O2); h and psi of the pair from the projected contents with
 * the bits film.c's derive() gives (h is a sum, even; psi at N - i is exactly
 * -psi at i), one division per pair.  Costs about 0.8 of a film step
 * (scalar; measured with perf on the Fig. 8 scene). */
void bf_film_mirror(bf_film *f, int apply, double corr[2])
{
    const long N = f->N;
    double *ad = ARR(f, V_AD), *ac = ARR(f, V_AC);
    double *ud = ARR(f, V_UD), *uc = ARR(f, V_UC);
    double *kd = ARR(f, V_KD), *kc = ARR(f, V_KC);
    double *h = ARR(f, V_H), *psi = ARR(f, V_PSI);
    double da = 0.0, du = 0.0, hmax = 0.0, umax = 0.0;
#define KEEP_MAX(m, v) ((m) = (v) > (m) ? (v) : (m))
    for (long i = 0; i <= N - i; i++) {
        long j = N - i;
        /* distance from the mirror image: d at i against c at j, c at i
         * against d at j (the same pair twice when i = j) */
        KEEP_MAX(da, fabs(ad[i] - ac[j]));
        KEEP_MAX(da, fabs(ac[i] - ad[j]));
        KEEP_MAX(du, fabs(ud[i] + uc[j]));
        KEEP_MAX(du, fabs(uc[i] + ud[j]));
        KEEP_MAX(hmax, ad[i] + ac[i]);
        KEEP_MAX(hmax, ad[j] + ac[j]);
        double ua = fabs(ud[i]) > fabs(uc[i]) ? fabs(ud[i]) : fabs(uc[i]);
        double ub = fabs(ud[j]) > fabs(uc[j]) ? fabs(ud[j]) : fabs(uc[j]);
        KEEP_MAX(umax, ua > ub ? ua : ub);
        if (!apply)
            continue;
        double e1, e2;
        /* phase d at i with phase c at j, and phase c at i with phase d
         * at j (the same pair when i = j) */
        double a1 = mean2(ad[i], ac[j], &e1), k1 = 0.5 * ((kd[i] + kc[j]) + e1);
        double a2 = mean2(ac[i], ad[j], &e2), k2 = 0.5 * ((kc[i] + kd[j]) + e2);
        double u1 = 0.5 * (ud[i] - uc[j]), u2 = 0.5 * (uc[i] - ud[j]);
        ad[i] = ac[j] = a1;
        kd[i] = kc[j] = k1;
        ac[i] = ad[j] = a2;
        kc[i] = kd[j] = k2;
        ud[i] = u1;
        uc[j] = -u1;
        uc[i] = u2;
        ud[j] = -u2;
        double hh = a1 + a2, ps = (a1 - a2) / hh;
        h[i] = h[j] = hh;
        psi[j] = 0.0 - ps; /* +0 for psi = 0, as derive() gives */
        psi[i] = ps;
    }
#undef KEEP_MAX
    corr[0] = hmax > 0 ? 0.5 * da / hmax : 0.5 * da;
    corr[1] = umax > 0 ? 0.5 * du / umax : 0.5 * du;
}
