/* implicit.c: the implicit step of Greenspan 1973, eqs 2.1-2.3, by the
 * listing's relaxed fixed-point iteration or by Newton's method (see
 * implicit.h). */
#include "implicit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_splinalg.h>
#include <gsl/gsl_spmatrix.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct bf_implicit {
    bf_implicit_opts o;
    size_t n, nf;      /* particles, free particles */
    size_t *free_of;   /* index of the k-th free particle */
    double *x0, *y0, *vx0, *vy0, *xi, *yi, *vxi, *vyi, *xn, *yn;
    double *fx, *fy, *r0, *r1;
    /* Newton */
    double *D, *G, *Dt, *Gt, *Jfull; /* iterate, residual, trial ones */
    gsl_matrix *J;
    gsl_vector *b, *delta;
    gsl_permutation *perm;
    gsl_spmatrix *Jt, *Jc;
    gsl_splinalg_itersolve *gmres;
};

void bf_implicit_free(bf_implicit *s)
{
    if (!s)
        return;
    free(s->free_of);
    free(s->x0);
    free(s->y0);
    free(s->vx0);
    free(s->vy0);
    free(s->xi);
    free(s->yi);
    free(s->vxi);
    free(s->vyi);
    free(s->xn);
    free(s->yn);
    free(s->fx);
    free(s->fy);
    free(s->r0);
    free(s->r1);
    free(s->D);
    free(s->G);
    free(s->Gt);
    free(s->Dt);
    free(s->Jfull);
    if (s->J)
        gsl_matrix_free(s->J);
    if (s->b)
        gsl_vector_free(s->b);
    if (s->delta)
        gsl_vector_free(s->delta);
    if (s->perm)
        gsl_permutation_free(s->perm);
    if (s->Jt)
        gsl_spmatrix_free(s->Jt);
    if (s->Jc)
        gsl_spmatrix_free(s->Jc);
    if (s->gmres)
        gsl_splinalg_itersolve_free(s->gmres);
    free(s);
}

bf_status bf_implicit_create(bf_implicit **out, const bf_dforce *f,
                             const bf_implicit_opts *o, bf_err *err)
{
    *out = NULL;
    /* GSL's default handler aborts when an allocation fails; we check
     * every result and fail with a message instead */
    gsl_set_error_handler_off();
    bf_implicit *s = calloc(1, sizeof *s);
    if (!s)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    s->o = *o;
    const size_t n = f->n, k = n ? n : 1;
    s->n = n;
    s->free_of = malloc(k * sizeof *s->free_of);
    double **v[] = {&s->x0, &s->y0, &s->vx0, &s->vy0, &s->xi, &s->yi, &s->vxi,
                    &s->vyi, &s->xn, &s->yn, &s->fx, &s->fy};
    int ok = s->free_of != NULL;
    for (size_t a = 0; a < sizeof v / sizeof v[0]; a++)
        ok &= (*v[a] = malloc(k * sizeof **v[a])) != NULL;
    s->r0 = malloc(k * k * sizeof *s->r0);
    s->r1 = malloc(k * k * sizeof *s->r1);
    ok &= s->r0 && s->r1;
    for (size_t i = 0; i < n; i++)
        if (!f->fixed[i])
            s->free_of[s->nf++] = i;
    if (ok && o->method == BF_IMPLICIT_NEWTON) {
        const size_t N = 2 * (s->nf ? s->nf : 1);
        s->D = malloc(N * sizeof *s->D);
        s->G = malloc(N * sizeof *s->G);
        s->Gt = malloc(N * sizeof *s->Gt);
        s->Dt = malloc(N * sizeof *s->Dt);
        s->Jfull = malloc(4 * k * k * sizeof *s->Jfull);
        s->J = gsl_matrix_alloc(N, N);
        s->b = gsl_vector_alloc(N);
        s->delta = gsl_vector_alloc(N);
        s->perm = gsl_permutation_alloc(N);
        ok &= s->D && s->G && s->Gt && s->Dt && s->Jfull && s->J && s->b && s->delta &&
              s->perm;
        if (ok && o->sparse) {
            s->Jt = gsl_spmatrix_alloc_nzmax(N, N, N * N, GSL_SPMATRIX_COO);
            s->Jc = gsl_spmatrix_alloc_nzmax(N, N, N * N, GSL_SPMATRIX_CSC);
            s->gmres = gsl_splinalg_itersolve_alloc(
                gsl_splinalg_itersolve_gmres, N, N < 50 ? N : 50);
            ok &= s->Jt && s->Jc && s->gmres;
        }
    }
    if (!ok) {
        bf_implicit_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory (implicit solver)");
    }
    *out = s;
    return BF_OK;
}

/* Report a failed solve: where the last iterate still moved. */
static bf_status noconv(bf_err *err, const char *what, int it, double diff,
                        size_t where)
{
    if (!isfinite(diff))
        return bf_fail(err, BF_ENOCONV,
                       "%s diverged after %d iterations (particle %zu is "
                       "not finite)",
                       what, it, where + 1);
    return bf_fail(err, BF_ENOCONV,
                   "%s did not converge in %d iterations: the last iterate "
                   "still moved by %.3g (particle %zu)",
                   what, it, diff, where + 1);
}

static bf_status step_fixed_point(bf_implicit *s, const bf_dforce *f,
                                  const double *mu, double dt, int *iters,
                                  bf_err *err)
{
    const double w = s->o.omega, w1 = 1.0 - w, h = 0.5 * dt;
    const size_t n = s->n;
    memcpy(s->xi, s->x0, n * sizeof *s->xi);
    memcpy(s->yi, s->y0, n * sizeof *s->yi);
    memcpy(s->vxi, s->vx0, n * sizeof *s->vxi);
    memcpy(s->vyi, s->vy0, n * sizeof *s->vyi);
    memcpy(s->xn, s->x0, n * sizeof *s->xn);
    memcpy(s->yn, s->y0, n * sizeof *s->yn);
    double diff = INFINITY;
    size_t where = 0;
    for (int it = 1; it <= s->o.max_iter; it++) {
        for (size_t k = 0; k < s->nf; k++) {
            size_t i = s->free_of[k];
            s->xn[i] = w1 * s->xi[i] + w * (h * (s->vxi[i] + s->vx0[i]) + s->x0[i]);
            s->yn[i] = w1 * s->yi[i] + w * (h * (s->vyi[i] + s->vy0[i]) + s->y0[i]);
        }
        bf_dforce_distances(f, s->xn, s->yn, s->r1);
        bf_dforce_eval(f, s->x0, s->y0, s->r0, s->xn, s->yn, s->r1, s->fx,
                       s->fy);
        diff = 0.0;
        for (size_t k = 0; k < s->nf; k++) {
            size_t i = s->free_of[k];
            double vx = w1 * s->vxi[i] + w * (dt * s->fx[i] / mu[i] + s->vx0[i]);
            double vy = w1 * s->vyi[i] + w * (dt * s->fy[i] / mu[i] + s->vy0[i]);
            double d = fmax(fmax(fabs(s->xn[i] - s->xi[i]),
                                 fabs(s->yn[i] - s->yi[i])),
                            fmax(fabs(vx - s->vxi[i]), fabs(vy - s->vyi[i])));
            if (!(d <= diff)) {
                diff = d;
                where = i;
            }
            s->xi[i] = s->xn[i];
            s->yi[i] = s->yn[i];
            s->vxi[i] = vx;
            s->vyi[i] = vy;
        }
        *iters = it;
        if (!isfinite(diff))
            return noconv(err, "fixed-point iteration", it, diff, where);
        if (diff <= s->o.tol)
            return BF_OK;
    }
    return noconv(err, "fixed-point iteration", s->o.max_iter, diff, where);
}

/* G(D) and whether it is finite; x1 = x0 + D in xn, yn. */
static int residual(bf_implicit *s, const bf_dforce *f, const double *mu,
                    double dt, const double *D, double *G, double *norm)
{
    const double c = 2.0 / (dt * dt);
    for (size_t k = 0; k < s->nf; k++) {
        size_t i = s->free_of[k];
        s->xn[i] = s->x0[i] + D[2 * k];
        s->yn[i] = s->y0[i] + D[2 * k + 1];
    }
    bf_dforce_distances(f, s->xn, s->yn, s->r1);
    bf_dforce_eval(f, s->x0, s->y0, s->r0, s->xn, s->yn, s->r1, s->fx, s->fy);
    double n2 = 0.0;
    for (size_t k = 0; k < s->nf; k++) {
        size_t i = s->free_of[k];
        G[2 * k] = c * mu[i] * (D[2 * k] - dt * s->vx0[i]) - s->fx[i];
        G[2 * k + 1] = c * mu[i] * (D[2 * k + 1] - dt * s->vy0[i]) - s->fy[i];
        n2 += G[2 * k] * G[2 * k] + G[2 * k + 1] * G[2 * k + 1];
    }
    *norm = sqrt(n2);
    return isfinite(n2);
}

/* Solve J delta = -G at D (the positions in xn, yn, distances r1). */
static int newton_direction(bf_implicit *s, const bf_dforce *f,
                            const double *mu, double dt)
{
    const size_t n = s->n, N = 2 * s->nf, Nf = 2 * n;
    const double c = 2.0 / (dt * dt);
    bf_dforce_jacobian(f, s->x0, s->y0, s->r0, s->xn, s->yn, s->r1,
                       s->o.sparse ? s->o.jac_cutoff : 0.0, s->Jfull);
    /* J = (2 mu/dt^2) I - dF/dx^{k+1} on the free unknowns */
    for (size_t a = 0; a < N; a++) {
        size_t ia = 2 * s->free_of[a / 2] + a % 2;
        for (size_t b = 0; b < N; b++) {
            size_t ib = 2 * s->free_of[b / 2] + b % 2;
            double v = -s->Jfull[ia * Nf + ib];
            if (a == b)
                v += c * mu[s->free_of[a / 2]];
            gsl_matrix_set(s->J, a, b, v);
        }
        gsl_vector_set(s->b, a, -s->G[a]);
    }
    if (!s->o.sparse) {
        int sign;
        if (gsl_linalg_LU_decomp(s->J, s->perm, &sign))
            return 0;
        return gsl_linalg_LU_solve(s->J, s->perm, s->b, s->delta) == 0;
    }
    gsl_spmatrix_set_zero(s->Jt);
    if (gsl_spmatrix_d2sp(s->Jt, s->J) || gsl_spmatrix_csc(s->Jc, s->Jt))
        return 0;
    gsl_vector_set_zero(s->delta);
    for (int cycle = 0; cycle < 200; cycle++) {
        int st = gsl_splinalg_itersolve_iterate(s->Jc, s->b, 1e-14, s->delta,
                                                s->gmres);
        if (st == 0)
            return 1;
        if (st != GSL_CONTINUE)
            return 0;
    }
    return 1; /* an inexact direction; the line search decides */
}

static bf_status step_newton(bf_implicit *s, const bf_dforce *f,
                             const double *mu, double dt, int *iters,
                             bf_err *err)
{
    const size_t N = 2 * s->nf;
    double *D = s->D, *G = s->G, *Dt = s->Dt, *Gt = s->Gt, gn, gt;
    for (size_t k = 0; k < s->nf; k++) {
        size_t i = s->free_of[k];
        D[2 * k] = dt * s->vx0[i];
        D[2 * k + 1] = dt * s->vy0[i];
    }
    memcpy(s->xn, s->x0, s->n * sizeof *s->xn);
    memcpy(s->yn, s->y0, s->n * sizeof *s->yn);
    if (!residual(s, f, mu, dt, D, G, &gn))
        return noconv(err, "Newton's method", 0, NAN, 0);
    double diff = INFINITY;
    size_t where = 0;
    for (int it = 1; it <= s->o.max_iter; it++) {
        *iters = it;
        if (N == 0)
            return BF_OK;
        /* r1, xn, yn are those of D (the last residual evaluation) */
        if (!newton_direction(s, f, mu, dt))
            return noconv(err, "Newton's method (singular Jacobian)", it,
                          diff, where);
        const double *dl = s->delta->data;
        /* backtracking: halve the step until |G| decreases */
        double lam = 1.0;
        for (;;) {
            for (size_t a = 0; a < N; a++)
                Dt[a] = D[a] + lam * dl[a];
            int fin = residual(s, f, mu, dt, Dt, Gt, &gt);
            if (fin && (gt < gn || lam < 1e-6))
                break;
            lam *= 0.5;
            if (lam < 1e-12)
                return noconv(err, "Newton's method (line search)", it, diff,
                              where);
        }
        diff = 0.0;
        for (size_t a = 0; a < N; a++) {
            double d = fabs(lam * dl[a]);
            d = fmax(d, 2.0 * d / dt);
            if (!(d <= diff)) {
                diff = d;
                where = s->free_of[a / 2];
            }
            D[a] = Dt[a];
        }
        memcpy(G, Gt, N * sizeof *G);
        gn = gt;
        if (!isfinite(diff))
            return noconv(err, "Newton's method", it, diff, where);
        if (diff <= s->o.tol)
            return BF_OK;
    }
    return noconv(err, "Newton's method", s->o.max_iter, diff, where);
}

bf_status bf_implicit_step(bf_implicit *s, const bf_dforce *f,
                           const double *mu, double *x, double *y, double *vx,
                           double *vy, double dt, int *iters, bf_err *err)
{
    const size_t n = s->n;
    memcpy(s->x0, x, n * sizeof *x);
    memcpy(s->y0, y, n * sizeof *y);
    memcpy(s->vx0, vx, n * sizeof *vx);
    memcpy(s->vy0, vy, n * sizeof *vy);
    bf_dforce_distances(f, s->x0, s->y0, s->r0);
    *iters = 0;
    bf_status st;
    if (s->o.method == BF_IMPLICIT_NEWTON) {
        st = step_newton(s, f, mu, dt, iters, err);
        if (st)
            return st;
        for (size_t k = 0; k < s->nf; k++) {
            size_t i = s->free_of[k];
            x[i] = s->x0[i] + s->D[2 * k];
            y[i] = s->y0[i] + s->D[2 * k + 1];
            vx[i] = 2.0 * s->D[2 * k] / dt - s->vx0[i];
            vy[i] = 2.0 * s->D[2 * k + 1] / dt - s->vy0[i];
        }
        return BF_OK;
    }
    st = step_fixed_point(s, f, mu, dt, iters, err);
    if (st)
        return st;
    for (size_t k = 0; k < s->nf; k++) {
        size_t i = s->free_of[k];
        x[i] = s->xi[i];
        y[i] = s->yi[i];
        vx[i] = s->vxi[i];
        vy[i] = s->vyi[i];
    }
    return BF_OK;
}
