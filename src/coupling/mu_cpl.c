/* mu_cpl.c: the coupling chemical potential of the balls on the film,
 * Yasuda eq. 3.11 (see mu_cpl.h):
 *   mu_cpl(x_i) = sum_p 8 pi R_p^2 V0 exp(-|x_i - r_p|/r0) (psi_i - psi_s).
 * exp(-|x_i - r|/r0) = exp(-kappa t_r) E^(j-i) left of the ball (cell j,
 * local coordinate t_r) and exp(-kappa (1 - t_r)) E^(i-j-1) right of it,
 * from the coupling's table of powers of E (no exp per node; the two exp()
 * per ball are those of the coupling's anchors when the ball has not moved
 * since bf_coupling_prepare: the same numbers).  Nodes where the kernel is
 * below 2^-64 (beyond K cells) get nothing.
 *
 * Hot loops: GCC's "cheap" vectoriser cost model and clones for AVX-512
 * and AVX2, as in coupling.c (element-wise, no reordered reductions: the
 * same bits on every clone).
 */
#include "coupling/mu_cpl.h"

#include <math.h>

static const double PI = 3.14159265358979323846;

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("vect-cost-model=cheap")
#define MU_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define MU_CLONES
#endif
#define HOT static inline __attribute__((always_inline))

/* kernel weights of mu_cpl added for one ball: k[i] += cl E^(j-i) for
 * i <= j, cr E^(i-j-1) for i > j */
HOT void mu_pass(long N, long K, long j, double cl, double cr,
                 const double *restrict pw, const double *restrict pwr,
                 double *restrict k)
{
    /* E^(j-i) = pwr[N-1-j+i] for i = i0..j (j <= N-1); nodes with
     * E^(j-i) < 2^-64 get nothing */
    const long i0 = j - K > 0 ? j - K : 0, i1 = j + 1 + K < N ? j + 1 + K : N;
    const double *restrict wl = pwr + (N - 1 - j);
    for (long i = i0; i <= j; i++)
        k[i] += cl * wl[i];
    const double *restrict wr = pw - (j + 1);
    for (long i = j + 1; i <= i1; i++)
        k[i] += cr * wr[i];
}

/* mu_cpl left of cell jmin (CL E^(jmin-i)) and right of cell jmax
 * (CR E^(i-jmax-1)), zero where the kernel is below 2^-64; the cells in
 * between are the caller's */
HOT void mu_sides(long N, long K, long jmin, long jmax, double CL, double CR,
                  double psis, const double *restrict pw,
                  const double *restrict pwr, const double *restrict psi,
                  double *restrict mu)
{
    const long i0 = jmin - K > 0 ? jmin - K : 0;
    const long i1 = jmax + 1 + K < N ? jmax + 1 + K : N;
    for (long i = 0; i < i0; i++)
        mu[i] = 0.0;
    const double *restrict wl = pwr + (N - 1 - jmin);
    for (long i = i0; i <= jmin; i++)
        mu[i] = CL * wl[i] * (psi[i] - psis);
    const double *restrict wr = pw - (jmax + 1);
    for (long i = jmax + 1; i <= i1; i++)
        mu[i] = CR * wr[i] * (psi[i] - psis);
    for (long i = i1 + 1; i <= N; i++)
        mu[i] = 0.0;
}

/* mu_cpl = (sum of the kernels, in mu) (psi - psi_s) */
HOT void mu_final(long n, double psis, const double *restrict psi,
                  double *restrict mu)
{
    for (long i = 0; i < n; i++)
        mu[i] = mu[i] * (psi[i] - psis);
}

MU_CLONES
void bf_coupling_mu(const bf_coupling *c, size_t nb, const double *x,
                    const double *R, double *mu)
{
    const bf_coupling_grid *g = bf_coupling_grid_of(c);
    const long N = g->N;
    const double psis = bf_coupling_params_of(c)->psi_s;
    const double V0 = bf_coupling_params_of(c)->V0;
    const double *psi = bf_film_psi(bf_coupling_film(c));
    enum { MAXB = 64 };
    long jb[MAXB];
    double cl[MAXB], cr[MAXB];
    int inside = nb > 0 && nb <= MAXB;
    long jmin = N, jmax = 0;
    for (size_t p = 0; inside && p < nb; p++) {
        double t;
        jb[p] = bf_coupling_locate(g, x[p], &t);
        inside = t >= 0.0 && t <= 1.0;
        double a = 8.0 * PI * R[p] * R[p] * V0;
        /* exp(-(r - x_j)/r0) and exp(-(x_j+1 - r)/r0), from prepare if
         * the ball is where it was then (the same numbers) */
        double el, er;
        if (!bf_coupling_prepared_exp(c, p, x[p], &el, &er)) {
            el = exp(-g->kappa * t);
            er = exp(-g->kappa * (1.0 - t));
        }
        cl[p] = a * el;
        cr[p] = a * er;
        jmin = jb[p] < jmin ? jb[p] : jmin;
        jmax = jb[p] > jmax ? jb[p] : jmax;
    }
    if (inside) {
        /* all balls in the film: left of the leftmost ball's cell the
         * kernels add up to CL E^(jmin-i), right of the rightmost to
         * CR E^(i-jmax-1); between them, ball by ball */
        double CL = 0.0, CR = 0.0;
        for (size_t p = 0; p < nb; p++) {
            CL += cl[p] * g->pw[jb[p] - jmin];
            CR += cr[p] * g->pw[jmax - jb[p]];
        }
        mu_sides(N, g->K, jmin, jmax, CL, CR, psis, g->pw, g->pwr, psi, mu);
        for (long i = jmin + 1; i <= jmax; i++) {
            double k = 0.0;
            for (size_t p = 0; p < nb; p++)
                k += i <= jb[p] ? cl[p] * g->pw[jb[p] - i]
                                : cr[p] * g->pw[i - jb[p] - 1];
            mu[i] = k * (psi[i] - psis);
        }
        return;
    }
    /* a ball outside the film (or very many balls): ball by ball, the
     * kernels' sum in mu */
    double *k = mu;
    for (long i = 0; i <= N; i++)
        k[i] = 0.0;
    for (size_t p = 0; p < nb; p++) {
        double t;
        long j = bf_coupling_locate(g, x[p], &t);
        double a = 8.0 * PI * R[p] * R[p] * V0;
        if (t < 0.0) {
            /* left of the film: exp(-(x_i - r)/r0) = exp(kappa t) E^i */
            double e = a * exp(g->kappa * t);
            for (long i = 0; i <= N; i++)
                k[i] += e * g->pw[i];
        } else if (t > 1.0) {
            /* right of it: exp(-(r - x_i)/r0) = exp(-kappa (t-1)) E^(N-i) */
            double e = a * exp(-g->kappa * (t - 1.0));
            for (long i = 0; i <= N; i++)
                k[i] += e * g->pw[N - i];
        } else {
            mu_pass(N, g->K, j, a * exp(-g->kappa * t),
                    a * exp(-g->kappa * (1.0 - t)), g->pw, g->pwr, k);
        }
    }
    mu_final(N + 1, psis, psi, mu);
}

#undef HOT
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC pop_options
#endif
