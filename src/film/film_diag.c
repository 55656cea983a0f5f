/* film_diag.c: the film's diagnostics (film.h): phase totals, largest
 * speed, smallest volume fraction, positivity-limiter counts.  They read
 * the state and change nothing. */
#include "ballfilm/film.h"

#include <math.h>

#include "film/film_impl.h"

/* Neumaier-compensated trapezoid sum of a[0..N] times dx, so that the
 * diagnostic itself does not add round-off to the conservation check. */
static double trapezoid(const double *a, long N, double dx)
{
    double s = 0.0, c = 0.0;
    for (long i = 0; i <= N; i++) {
        double v = (i == 0 || i == N) ? 0.5 * a[i] : a[i];
        double t = s + v;
        if (fabs(s) >= fabs(v))
            c += (s - t) + v;
        else
            c += (v - t) + s;
        s = t;
    }
    return (s + c) * dx;
}

void bf_film_totals(const bf_film *f, double *mass_d, double *mass_c)
{
    *mass_d = trapezoid(ARR(f, V_AD), f->N, f->p.dx);
    *mass_c = trapezoid(ARR(f, V_AC), f->N, f->p.dx);
}

double bf_film_max_speed(const bf_film *f)
{
    const double *ud = ARR(f, V_UD), *uc = ARR(f, V_UC);
    double m = 0.0;
    for (long i = 0; i <= f->N; i++)
        m = fmax(m, fmax(fabs(ud[i]), fabs(uc[i])));
    return m;
}

double bf_film_min_alpha(const bf_film *f)
{
    const double *ad = ARR(f, V_AD), *ac = ARR(f, V_AC);
    double m = 1.0;
    for (long i = 0; i <= f->N; i++) {
        double h = ad[i] + ac[i];
        m = fmin(m, fmin(ad[i] / h, ac[i] / h));
    }
    return m;
}

void bf_film_limiter_counts(const bf_film *f, unsigned long long *steps,
                            unsigned long long *faces)
{
    *steps = f->lim_steps;
    *faces = f->lim_faces;
}
