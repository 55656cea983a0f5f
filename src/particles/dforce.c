/* dforce.c: Greenspan's discrete pair force, eq. 2.4 (see dforce.h). */
#include "dforce.h"

#include "particles/ipow.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bf_status bf_dforce_init(bf_dforce *f, size_t n, int alpha, int beta,
                         bf_err *err)
{
    memset(f, 0, sizeof *f);
    if (alpha < 2 || beta < 2)
        return bf_fail(err, BF_EINPUT, "exponents alpha = %d, beta = %d must "
                       "be >= 2", alpha, beta);
    size_t k = n ? n : 1;
    f->n = n;
    f->alpha = alpha;
    f->beta = beta;
    f->p = malloc(k * k * sizeof *f->p);
    f->q = malloc(k * k * sizeof *f->q);
    f->m = malloc(k * sizeof *f->m);
    f->gravity = calloc(k, sizeof *f->gravity);
    f->fixed = calloc(k, sizeof *f->fixed);
    if (!f->p || !f->q || !f->m || !f->gravity || !f->fixed) {
        bf_dforce_free(f);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    for (size_t i = 0; i < k * k; i++)
        f->p[i] = f->q[i] = 1.0;
    for (size_t i = 0; i < k; i++)
        f->m[i] = 1.0;
    return BF_OK;
}

void bf_dforce_free(bf_dforce *f)
{
    free(f->p);
    free(f->q);
    free(f->m);
    free(f->gravity);
    free(f->fixed);
    memset(f, 0, sizeof *f);
}

void bf_dforce_s(int nexp, double a, double b, double *s, double *dsdb)
{
    /* T = sum_{k=1}^{n-1} u^{n-k} w^k, Tk = sum k u^{n-k} w^k, u = 1/a,
     * w = 1/b: all terms positive, no cancellation */
    double u = 1.0 / a, w = 1.0 / b;
    double pu[64], pw[64];
    int n = nexp < 63 ? nexp : 63;
    pu[0] = pw[0] = 1.0;
    for (int k = 1; k <= n; k++) {
        pu[k] = pu[k - 1] * u;
        pw[k] = pw[k - 1] * w;
    }
    double T = 0.0, Tk = 0.0;
    for (int k = 1; k <= n - 1; k++) {
        double t = pu[n - k] * pw[k];
        T += t;
        Tk += (double)k * t;
    }
    double ab = a + b;
    *s = T / ab;
    if (dsdb)
        *dsdb = -(Tk * ab / b + T) / (ab * ab);
}

void bf_dforce_distances(const bf_dforce *f, const double *x, const double *y,
                         double *r)
{
    const size_t n = f->n;
    for (size_t i = 0; i < n; i++) {
        r[i * n + i] = 0.0;
        for (size_t j = i + 1; j < n; j++) {
            double d = hypot(x[i] - x[j], y[i] - y[j]);
            r[i * n + j] = r[j * n + i] = d;
        }
    }
}

void bf_dforce_eval(const bf_dforce *f, const double *x0, const double *y0,
                    const double *r0, const double *x1, const double *y1,
                    const double *r1, double *fx, double *fy)
{
    const size_t n = f->n;
    for (size_t i = 0; i < n; i++) {
        fx[i] = fy[i] = 0.0;
        if (f->fixed[i])
            continue;
        double sx = 0.0, sy = 0.0;
        for (size_t j = 0; j < n; j++) {
            if (j == i)
                continue;
            double sa, sb;
            bf_dforce_s(f->alpha, r0[i * n + j], r1[i * n + j], &sa, NULL);
            bf_dforce_s(f->beta, r0[i * n + j], r1[i * n + j], &sb, NULL);
            double c = f->m[j] * (-f->p[i * n + j] * sa + f->q[i * n + j] * sb);
            sx += c * (x1[i] + x0[i] - x1[j] - x0[j]);
            sy += c * (y1[i] + y0[i] - y1[j] - y0[j]);
        }
        fx[i] = f->m[i] * sx;
        fy[i] = f->m[i] * (sy - (f->gravity[i] ? f->g : 0.0));
    }
}

void bf_dforce_jacobian(const bf_dforce *f, const double *x0, const double *y0,
                        const double *r0, const double *x1, const double *y1,
                        const double *r1, double cutoff, double *J)
{
    const size_t n = f->n, N = 2 * n;
    memset(J, 0, N * N * sizeof *J);
    for (size_t i = 0; i < n; i++) {
        if (f->fixed[i])
            continue;
        double *ri = J + 2 * i * N, *rj = ri + N; /* rows x_i and y_i */
        for (size_t j = 0; j < n; j++) {
            if (j == i || (cutoff > 0 && r1[i * n + j] > cutoff))
                continue;
            double a = r0[i * n + j], b = r1[i * n + j];
            double sa, dsa, sb, dsb;
            bf_dforce_s(f->alpha, a, b, &sa, &dsa);
            bf_dforce_s(f->beta, a, b, &sb, &dsb);
            double mm = f->m[i] * f->m[j];
            double c = mm * (-f->p[i * n + j] * sa + f->q[i * n + j] * sb);
            double cp = mm * (-f->p[i * n + j] * dsa + f->q[i * n + j] * dsb);
            /* F_i += c (X_i - X_j); d/dx_i^{k+1}: c I + (X ⊗ R) c'/b */
            double X[2] = {x1[i] + x0[i] - x1[j] - x0[j],
                           y1[i] + y0[i] - y1[j] - y0[j]};
            double R[2] = {(x1[i] - x1[j]) / b, (y1[i] - y1[j]) / b};
            double blk[2][2] = {{c + cp * X[0] * R[0], cp * X[0] * R[1]},
                                {cp * X[1] * R[0], c + cp * X[1] * R[1]}};
            for (int u = 0; u < 2; u++) {
                double *row = u ? rj : ri;
                row[2 * i] += blk[u][0];
                row[2 * i + 1] += blk[u][1];
                row[2 * j] -= blk[u][0];
                row[2 * j + 1] -= blk[u][1];
            }
        }
    }
}

double bf_dforce_pair_energy(const bf_dforce *f, const double *r)
{
    const size_t n = f->n;
    double v = 0.0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            double d = r[i * n + j];
            v += f->m[i] * f->m[j] *
                 (-f->p[i * n + j] / bf_ipow(d, f->alpha - 1) +
                  f->q[i * n + j] / bf_ipow(d, f->beta - 1));
        }
    return v;
}

double bf_dforce_gravity_energy(const bf_dforce *f, const double *y)
{
    double v = 0.0;
    for (size_t i = 0; i < f->n; i++)
        if (f->gravity[i])
            v += f->m[i] * f->g * y[i];
    return v;
}

double bf_dforce_r0(int alpha, int beta, double p, double q)
{
    return pow((double)(beta - 1) * q / ((double)(alpha - 1) * p),
               1.0 / (double)(beta - alpha));
}
