/* test_film.c: the two-phase film and its invariant scheme (Yasuda sec.
 * 3.1-3.4), checked against what must hold independently of the scheme:
 *
 * - conservation: the totals of alpha_k h telescope (flux form, mirrored
 *   walls), so they are constant to round-off over 1e5 steps (1e-12);
 * - lake at rest: a uniform film at rest produces no flux at all, bit for
 *   bit (a wrong ghost or an asymmetric wall term would move it);
 * - the steady kink: u = 0 and (P +- mu) constant is the discrete steady
 *   state, so the run converges to the solution of mu_i = 0 (computed here
 *   by Newton's method, independently of the scheme) and that solution
 *   differs from tanh(x/sqrt 2) by O(dx^2): the ratio for halved dx is 4
 *   within 5 %;
 * - observed orders: dx order of a dynamic solution in [1.7, 2.3]; in dt
 *   the Lax-Wendroff time error of the midpoint variant without viscosity
 *   is O(dt dx^2) (its dt-differences shrink ~4x when dx is halved), the
 *   printed reading's is O(dt) (they do not shrink) -- see README;
 * - stability: the estimated limit is sharp for gravity waves (0.98 of it
 *   runs, 1.05 of it blows up), dt = 0.01 is refused naming the limit and
 *   with force_dt the run stops naming step, time and node;
 * - volume fractions: with the default handling they stay in [0, 1] for
 *   perturbations 1e-4 .. 1e-2, and the perturbed kink stays within 1e-3
 *   of the analytic kink past the time (~268 s) at which the unhandled
 *   scheme drives a fraction negative (which the same test shows);
 * - restart bit for bit; same seed, same bits; a film from a file.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/film.h"
#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "models/filmsys.h"
#include "testutil.h"

static bf_film_params params(double L, double dx)
{
    bf_film_params p = {.length = L, .dx = dx, .rho_d = 1, .rho_c = 1,
                        .nu = 0.01, .g = 980, .a = 1, .b = 1, .gamma = 1,
                        .mu_taylor = BF_FILM_MU_MIDPOINT, .limit_positive = 1,
                        .vanish = 1e-8};
    return p;
}

static bf_film *film_new(const bf_film_params *p)
{
    bf_film *f;
    bf_err err = {0};
    ck_assert_msg(bf_film_create(&f, p, &err) == BF_OK, "%s", err.msg);
    return f;
}

/* set h, psi, u_d, u_c from functions of x */
typedef double (*prof_fn)(double x);
static void film_set(bf_film *f, prof_fn h, prof_fn psi, prof_fn ud,
                     prof_fn uc)
{
    size_t n = bf_film_nodes(f);
    const double *x = bf_film_x(f);
    double *b = calloc(4 * n, sizeof *b);
    for (size_t i = 0; i < n; i++) {
        b[i] = h(x[i]);
        b[n + i] = psi(x[i]);
        b[2 * n + i] = ud ? ud(x[i]) : 0;
        b[3 * n + i] = uc ? uc(x[i]) : 0;
    }
    bf_err err = {0};
    ck_assert_msg(bf_film_set_state(f, b, b + n, b + 2 * n, b + 3 * n, &err) ==
                      BF_OK,
                  "%s", err.msg);
    free(b);
}

static void film_run(bf_film *f, double dt, long steps)
{
    bf_err err = {0};
    for (long s = 0; s < steps; s++)
        ck_assert_msg(bf_film_step_invariant(f, dt, NULL, &err) == BF_OK,
                      "step %ld: %s", s + 1, err.msg);
}

static double one(double x) { (void)x; return 1.0; }
static double kink(double x) { return tanh(x / sqrt(2.0)); }
/* a smooth disturbance of everything (for dynamic checks) */
static double dyn_h(double x) { return 1 + 1e-3 * exp(-(x - 1) * (x - 1)); }
static double dyn_psi(double x)
{
    return tanh(x / sqrt(2.0)) + 0.05 * exp(-(x + 0.5) * (x + 0.5)) /
                                     cosh(x / sqrt(2.0));
}
static double dyn_ud(double x) { return 0.02 * exp(-x * x); }
static double dyn_uc(double x) { return -0.01 * exp(-(x - 0.5) * (x - 0.5)); }

static double maxdiff(const double *a, const double *b, size_t n, size_t sb)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i * sb]));
    return m;
}

/* ------------------------------------------------------------ conservation */

START_TEST(phase_totals_conserved_1e5_steps)
{
    /* the perturbed kink with a gravity wave and phase velocities on top,
     * so that every flux term is active; 1e5 steps of 1e-3 s */
    bf_film_params p = params(50, 0.1);
    bf_film *f = film_new(&p);
    film_set(f, dyn_h, dyn_psi, dyn_ud, dyn_uc);
    double d0, c0, d, c;
    bf_film_totals(f, &d0, &c0);
    film_run(f, 1e-3, 100000);
    bf_film_totals(f, &d, &c);
    double rd = fabs(d - d0) / d0, rc = fabs(c - c0) / c0;
    ck_assert_msg(rd < 1e-12 && rc < 1e-12, "relative drift %.3e %.3e", rd,
                  rc);
    ck_assert(bf_film_max_speed(f) > 0); /* it did move */
    bf_film_free(f);
}
END_TEST

/* ------------------------------------------------------------ lake at rest */

static double psi08(double x) { (void)x; return 0.8; }
static double psi0(double x) { (void)x; return 0.0; }

START_TEST(lake_at_rest_bit_for_bit)
{
    /* psi = 0.8 (stable mixture) and psi = 0 (inside the spinodal, where
     * any disturbance would grow): both stay exactly at rest */
    prof_fn psis[2] = {psi08, psi0};
    for (int k = 0; k < 2; k++) {
        for (int v = 0; v < 3; v++) {
            bf_film_params p = params(20, 0.1);
            p.mu_taylor = (bf_film_mu_taylor)v;
            bf_film *f = film_new(&p);
            film_set(f, one, psis[k], NULL, NULL);
            size_t n = bf_film_nodes(f);
            double *h0 = malloc(n * sizeof *h0), *p0 = malloc(n * sizeof *p0);
            memcpy(h0, bf_film_h(f), n * sizeof *h0);
            memcpy(p0, bf_film_psi(f), n * sizeof *p0);
            film_run(f, 1e-3, 10000);
            ck_assert_msg(bf_film_max_speed(f) == 0.0, "psi %g variant %d: "
                          "max |u| = %g", psis[k](0), v, bf_film_max_speed(f));
            ck_assert(memcmp(h0, bf_film_h(f), n * sizeof *h0) == 0);
            ck_assert(memcmp(p0, bf_film_psi(f), n * sizeof *p0) == 0);
            free(h0);
            free(p0);
            bf_film_free(f);
        }
    }
}
END_TEST

/* ------------------------------------------------------------ the kink */

/* The discrete steady kink: mu_i = -a psi + b psi^3 - gamma d2psi = 0 on
 * the nodes with mirrored walls, odd about the centre node (the odd
 * symmetry removes the translation mode that makes the full problem
 * singular), by Newton's method with a tridiagonal solve.  Independent of
 * the scheme: only the steady-state equations are used. */
static void discrete_kink(const bf_film_params *p, size_t n, double *psi)
{
    const long N = (long)n - 1, c = N / 2, m = N - c; /* unknowns c+1..N */
    const double gl = p->gamma / (p->dx * p->dx);
    double *r = malloc(m * sizeof *r), *dg = malloc(m * sizeof *dg),
           *lo = malloc(m * sizeof *lo), *up = malloc(m * sizeof *up);
    for (long i = 0; i <= N; i++)
        psi[i] = tanh((-0.5 * p->length + (double)i * p->dx) / sqrt(2.0));
    psi[c] = 0.0;
    for (int it = 0; it < 50; it++) {
        double rn = 0;
        for (long k = 0; k < m; k++) {
            long i = c + 1 + k;
            double pl = psi[i - 1], pr = i < N ? psi[i + 1] : psi[N - 1];
            double s = psi[i];
            r[k] = s * (p->b * s * s - p->a) - gl * (pr - 2 * s + pl);
            dg[k] = 3 * p->b * s * s - p->a + 2 * gl;
            lo[k] = k > 0 ? -gl : 0;
            up[k] = i < N ? -gl : 0;
            if (i == N)
                lo[k] = -2 * gl;
            rn = fmax(rn, fabs(r[k]));
        }
        if (rn < 1e-14)
            break;
        /* Thomas: solve J d = r, psi -= d */
        for (long k = 1; k < m; k++) {
            double w = lo[k] / dg[k - 1];
            dg[k] -= w * up[k - 1];
            r[k] -= w * r[k - 1];
        }
        r[m - 1] /= dg[m - 1];
        for (long k = m - 2; k >= 0; k--)
            r[k] = (r[k] - up[k] * r[k + 1]) / dg[k];
        for (long k = 0; k < m; k++)
            psi[c + 1 + k] -= r[k];
    }
    for (long k = 1; k <= m; k++)
        psi[c - k] = -psi[c + k];
    free(r);
    free(dg);
    free(lo);
    free(up);
}

START_TEST(steady_kink_error_is_dx2)
{
    double e[3];
    const double dxs[3] = {0.1, 0.05, 0.025};
    for (int k = 0; k < 3; k++) {
        bf_film_params p = params(50, dxs[k]);
        bf_film *f = film_new(&p);
        size_t n = bf_film_nodes(f);
        double *psi = malloc(n * sizeof *psi);
        discrete_kink(&p, n, psi);
        e[k] = 0;
        for (size_t i = 0; i < n; i++)
            e[k] = fmax(e[k], fabs(psi[i] - bf_film_kink(&p, 0, bf_film_x(f)[i])));
        free(psi);
        bf_film_free(f);
    }
    for (int k = 0; k < 2; k++)
        ck_assert_msg(fabs(e[k] / e[k + 1] - 4.0) < 0.2,
                      "errors %.4e %.4e %.4e: ratio %.3f", e[0], e[1], e[2],
                      e[k] / e[k + 1]);
    ck_assert_msg(e[0] > 2e-4 && e[0] < 4e-4, "dx = 0.1 error %g", e[0]);
}
END_TEST

START_TEST(run_converges_to_discrete_kink_and_stays)
{
    /* from the analytic kink (no perturbation) the scheme relaxes to the
     * discrete steady state; 40 s at dt = 2.5e-4 */
    bf_film_params p = params(50, 0.1);
    bf_film *f = film_new(&p);
    film_set(f, one, kink, NULL, NULL);
    size_t n = bf_film_nodes(f);
    double *psi = malloc(n * sizeof *psi);
    discrete_kink(&p, n, psi);
    film_run(f, 2.5e-4, 160000);
    /* the remaining wobble (gravity and separation waves, damped only by
     * nu k^2) decays like 1/t; after 40 s it must be below 1 % of the
     * discretisation error, so that the error a run prints is that of the
     * discrete steady state */
    double d = maxdiff(bf_film_psi(f), psi, n, 1), e = 0;
    for (size_t i = 0; i < n; i++)
        e = fmax(e, fabs(psi[i] - bf_film_kink(&p, 0, bf_film_x(f)[i])));
    ck_assert_msg(d < 0.01 * e, "max |psi - discrete kink| = %g after 40 s "
                  "(discretisation error %g)", d, e);
    /* started exactly there, it stays there */
    double *h = malloc(n * sizeof *h);
    for (size_t i = 0; i < n; i++)
        h[i] = 1.0;
    double *z = calloc(n, sizeof *z);
    bf_err err = {0};
    ck_assert(bf_film_set_state(f, h, psi, z, z, &err) == BF_OK);
    film_run(f, 1e-3, 10000);
    ck_assert_msg(bf_film_max_speed(f) < 1e-10, "max |u| %g",
                  bf_film_max_speed(f));
    ck_assert(maxdiff(bf_film_psi(f), psi, n, 1) < 1e-12);
    free(h);
    free(z);
    free(psi);
    bf_film_free(f);
}
END_TEST

/* ------------------------------------------------------------ orders */

/* psi after T = 0.5 s of the dynamic problem on L = 20 */
static bf_film *dyn_run(double dx, double dt, double nu, int variant)
{
    bf_film_params p = params(20, dx);
    p.nu = nu;
    p.mu_taylor = (bf_film_mu_taylor)variant;
    p.vanish = 0;
    bf_film *f = film_new(&p);
    film_set(f, dyn_h, dyn_psi, dyn_ud, dyn_uc);
    film_run(f, dt, lround(0.5 / dt));
    return f;
}

START_TEST(observed_order_in_dx)
{
    /* dt = 5e-5 (its error is below 1e-7, the dx differences above 1e-5);
     * the nodes of each grid are nodes of the next */
    const double dxs[3] = {0.1, 0.05, 0.025};
    bf_film *f[3];
    for (int k = 0; k < 3; k++)
        f[k] = dyn_run(dxs[k], 5e-5, 0.01, BF_FILM_MU_MIDPOINT);
    size_t n0 = bf_film_nodes(f[0]), n1 = bf_film_nodes(f[1]);
    const double *(*get[3])(const bf_film *) = {bf_film_psi, bf_film_h,
                                                bf_film_u_d};
    for (int q = 0; q < 3; q++) {
        double e1 = maxdiff(get[q](f[0]), get[q](f[1]), n0, 2);
        double e2 = maxdiff(get[q](f[1]), get[q](f[2]), n1, 2);
        double order = log2(e1 / e2);
        ck_assert_msg(order > 1.7 && order < 2.3, "field %d: %.3e %.3e: order "
                      "%.2f", q, e1, e2, order);
    }
    for (int k = 0; k < 3; k++)
        bf_film_free(f[k]);
}
END_TEST

/* |psi(dt) - psi(dt/2)| at fixed dx */
static double dt_diff(double dx, int variant)
{
    bf_film *a = dyn_run(dx, 5e-4, 0, variant);
    bf_film *b = dyn_run(dx, 2.5e-4, 0, variant);
    double d = maxdiff(bf_film_psi(a), bf_film_psi(b), bf_film_nodes(a), 1);
    bf_film_free(a);
    bf_film_free(b);
    return d;
}

START_TEST(time_error_structure)
{
    /* Without viscosity the midpoint variant's time error at fixed dx is
     * the Lax-Wendroff O(dt dx^2) term: halving dx divides the
     * dt-differences by ~4 (measured 4.3 to 5.6).  The printed reading
     * (um) has an O(dt) error that does not shrink with dx. */
    double m1 = dt_diff(0.1, BF_FILM_MU_MIDPOINT);
    double m2 = dt_diff(0.05, BF_FILM_MU_MIDPOINT);
    double u1 = dt_diff(0.1, BF_FILM_MU_UM);
    double u2 = dt_diff(0.05, BF_FILM_MU_UM);
    ck_assert_msg(m1 / m2 > 3.0, "midpoint: %.3e -> %.3e", m1, m2);
    ck_assert_msg(u1 / u2 > 0.8 && u1 / u2 < 1.25, "um: %.3e -> %.3e", u1, u2);
    ck_assert_msg(u2 > 10 * m2, "um %.3e vs midpoint %.3e", u2, m2);
}
END_TEST

/* ------------------------------------------------------------ stability */

/* The estimated limit names `what`, lies in [lo, hi], `below` of it runs
 * `steps` steps, and 1.05 of it blows up within 2000 steps. */
static void check_sharp(double dx, prof_fn psi, const char *what, double lo,
                        double hi, double below, long steps)
{
    bf_film_params p = params(50, dx);
    bf_film *f = film_new(&p);
    film_set(f, dx > 0.05 ? dyn_h : one, psi, NULL, NULL);
    char why[256];
    double lim = bf_film_stable_dt(f, why, sizeof why);
    ck_assert_msg(strstr(why, what), "%s", why);
    ck_assert_msg(lim > lo && lim < hi, "limit %g", lim);
    film_run(f, below * lim, steps);
    bf_film_free(f);
    f = film_new(&p);
    film_set(f, dx > 0.05 ? dyn_h : one, psi, NULL, NULL);
    bf_err err = {0};
    bf_status st = BF_OK;
    for (long s = 0; s < 2000 && !st; s++)
        st = bf_film_step_invariant(f, 1.05 * lim, NULL, &err);
    ck_assert_msg(st == BF_EUNSTABLE, "1.05 x the limit did not blow up");
    ck_assert_msg(strstr(err.msg, "node"), "%s", err.msg);
    bf_film_free(f);
}

START_TEST(stable_dt_estimate_is_sharp_for_gravity_waves)
{
    /* dx / sqrt(g h) = 3.19e-3 s, a little less with the viscous term */
    check_sharp(0.1, dyn_psi, "gravity", 3.1e-3, 3.2e-3, 0.98, 20000);
}
END_TEST

START_TEST(stable_dt_estimate_is_sharp_for_phase_separation)
{
    /* at dx = 0.025 the separation mode at the kink centre decides
     * (dt <= dx sqrt(rho/(2 beta m)) = 3.1e-4 s < dx/sqrt(g h) = 8e-4 s) */
    check_sharp(0.025, kink, "phase-separation", 3.0e-4, 3.2e-4, 0.95, 5000);
}
END_TEST

/* The models' step limit (filmsys): [scene] dt below the film's limit for
 * film_every = 1; for film_every = K the largest dt whose film step K dt
 * does not exceed it, naming [coupled] film_every; none for a static film
 * or with force_dt. */
START_TEST(film_step_limit_of_the_models)
{
    bf_film_keys k;
    bf_err err = {0};
    ck_assert(bf_params_defaults(&bf_filmsys_spec, &k, &err) == BF_OK);
    const bf_run_ctx run = {1e-3, 1.0, 1000, 1, 0};
    const long every[] = {1, 3, 7, 0};
    for (int q = 0; q < 5; q++) {
        k.force_dt = q == 4;
        const long K = q == 4 ? 1 : every[q];
        bf_filmsys *fs;
        ck_assert(bf_filmsys_create(&fs, &k, &run, K, &err) == BF_OK);
        double L = bf_film_stable_dt(bf_filmsys_film(fs), NULL, 0);
        bf_dt_limit lim = {0};
        bf_filmsys_stable_dt(fs, &lim);
        if (K == 0 || k.force_dt) {
            ck_assert(lim.dt_max == 0);
        } else {
            const double d = lim.dt_max, up = nextafter(d, 1.0);
            ck_assert_msg((double)K * d <= L && (double)K * up > L,
                          "K = %ld: %.17g", K, d);
            ck_assert_str_eq(lim.section, K > 1 ? "coupled" : "");
            ck_assert_str_eq(lim.key, K > 1 ? "film_every" : "");
            ck_assert_msg(strstr(lim.why, "film's stable limit") &&
                              (K == 1 || strstr(lim.why, "film step")),
                          "%s", lim.why);
        }
        bf_filmsys_free(fs);
    }
}
END_TEST

static const char *kink_scene =
    "[scene]\nmodel = film\ndt = 1e-3\nt_end = 1\noutput_every = 0.5 s\n"
    "[film]\nperturbation = 1e-4\n";

START_TEST(large_dt_refused_or_stopped)
{
    char msg[2048];
    /* refused before anything is written, naming the limit */
    char text[512];
    snprintf(text, sizeof text, "%s", kink_scene);
    char *d = strstr(text, "dt = 1e-3");
    memcpy(d, "dt = 1e-2", 9);
    ck_assert_int_eq(tu_scene_error(text, msg, sizeof msg), BF_EINPUT);
    ck_assert_msg(strstr(msg, "test.ini:3:") && strstr(msg, "[scene] dt") &&
                      strstr(msg, "stable limit 0.00318") &&
                      strstr(msg, "gravity"),
                  "%s", msg);
    /* forced: the program stops at the blow-up with step, time and node */
    const char *path = tu_write("dt01.ini", text);
    char *errout = NULL;
    int rc = tu_run(NULL, &errout, "run", path, "-o", tu_tmp("dt01.h5"), "-q",
                    "--set", "film.force_dt=true", NULL);
    ck_assert_msg(rc == 3, "exit %d: %s", rc, errout);
    ck_assert_msg(strstr(errout, "step ") && strstr(errout, "t = ") &&
                      strstr(errout, "film node "),
                  "%s", errout);
    free(errout);
}
END_TEST

/* ------------------------------------------------------------ fractions */

/* Run a film scene in-process; returns the sim (film model inside). */
static bf_sim *run_film_scene(const char *text, const char *const *sets,
                              bf_status *st, bf_err *err, bf_scene **scp)
{
    bf_scene *sc;
    ck_assert(bf_scene_load_string(&sc, "test.ini", text, err) == BF_OK);
    for (; sets && *sets; sets++)
        ck_assert_msg(bf_scene_set(sc, *sets, "--set", err) == BF_OK, "%s",
                      err->msg);
    ck_assert_msg(bf_catalog_resolve(bf_catalog_builtin(), sc, err) == BF_OK, "%s", err->msg);
    bf_sim *sim;
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, err) == BF_OK, "%s", err->msg);
    *st = bf_sim_run(sim, err);
    *scp = sc;
    return sim;
}

START_TEST(fractions_stay_in_range_with_large_perturbations)
{
    const char *amps[] = {"film.perturbation=1e-4", "film.perturbation=1e-3",
                          "film.perturbation=1e-2"};
    const char *modes[] = {"film.perturbation_mode=positive",
                           "film.perturbation_mode=signed"};
    int limited = 0;
    for (int a = 0; a < 3; a++)
        for (int m = 0; m < 2; m++) {
            const char *sets[] = {amps[a], modes[m], "scene.t_end=60", NULL};
            bf_err err = {0};
            bf_status st;
            bf_scene *sc;
            bf_sim *sim = run_film_scene(kink_scene, sets, &st, &err, &sc);
            ck_assert_msg(st == BF_OK, "%s %s: %s", amps[a], modes[m], err.msg);
            bf_filmsys *fs = bf_sim_model(sim);
            bf_film *f = bf_filmsys_film(fs);
            ck_assert(bf_film_min_alpha(f) >= 0.0);
            ck_assert_msg(bf_filmsys_mass_drift(fs) < 1e-12, "drift %g",
                          bf_filmsys_mass_drift(fs));
            unsigned long long ls, lf;
            bf_film_limiter_counts(f, &ls, &lf);
            limited += ls > 0;
            bf_sim_free(sim);
            bf_scene_free(sc);
        }
    ck_assert_msg(limited > 0, "the limiter never acted: the test does not "
                               "exercise it");
}
END_TEST

START_TEST(unhandled_fraction_goes_negative_in_stop_mode)
{
    /* clipped signed perturbation: some nodes start with alpha = 0, and
     * without the limiter the first outflow makes a fraction negative */
    const char *sets[] = {"film.perturbation_mode=signed",
                          "film.positivity=stop", "film.vanish=0", NULL};
    bf_err err = {0};
    bf_status st;
    bf_scene *sc;
    bf_sim *sim = run_film_scene(kink_scene, sets, &st, &err, &sc);
    ck_assert_int_eq(st, BF_EUNSTABLE);
    ck_assert_msg(strstr(err.msg, "outside [0, 1]") && strstr(err.msg, "node"),
                  "%s", err.msg);
    bf_sim_free(sim);
    bf_scene_free(sc);
}
END_TEST

START_TEST(perturbed_kink_stays_converged_past_300s)
{
    /* The shorter version of the 1000 s acceptance run (make figures):
     * with the default handling the perturbed kink stays within 1e-3 of
     * the analytic kink with all fractions in [0, 1]; without it (stop at
     * a negative fraction, no vanishing-phase rule) the same run fails at
     * about 268 s, which is what makes this test able to fail. */
    const char *ok[] = {"scene.t_end=300", "scene.output_every=10 s", NULL};
    bf_err err = {0};
    bf_status st;
    bf_scene *sc;
    bf_sim *sim = run_film_scene(kink_scene, ok, &st, &err, &sc);
    ck_assert_msg(st == BF_OK, "%s", err.msg);
    bf_filmsys *fs = bf_sim_model(sim);
    double e = bf_filmsys_kink_error(fs);
    ck_assert_msg(e < 1e-3, "kink error %g at 300 s", e);
    ck_assert(bf_film_min_alpha(bf_filmsys_film(fs)) >= 0);
    bf_sim_free(sim);
    bf_scene_free(sc);

    const char *bad[] = {"scene.t_end=300", "film.positivity=stop",
                         "film.vanish=0", NULL};
    sim = run_film_scene(kink_scene, bad, &st, &err, &sc);
    ck_assert_int_eq(st, BF_EUNSTABLE);
    double t = bf_sim_time(sim);
    ck_assert_msg(t > 200 && t < 300, "failed at %g s", t);
    bf_sim_free(sim);
    bf_scene_free(sc);
}
END_TEST

/* ------------------------------------------------------------ scenes */

START_TEST(same_seed_same_bits)
{
    const char *s1[] = {"scene.t_end=0.001", NULL};
    const char *s2[] = {"scene.t_end=0.001", "film.seed=2", NULL};
    bf_err err = {0};
    bf_status st;
    bf_scene *sa, *sb, *sc;
    bf_sim *a = run_film_scene(kink_scene, s1, &st, &err, &sa);
    bf_sim *b = run_film_scene(kink_scene, s1, &st, &err, &sb);
    bf_sim *c = run_film_scene(kink_scene, s2, &st, &err, &sc);
    bf_film *fa = bf_filmsys_film(bf_sim_model(a));
    bf_film *fb = bf_filmsys_film(bf_sim_model(b));
    bf_film *fc = bf_filmsys_film(bf_sim_model(c));
    size_t n = bf_film_nodes(fa);
    ck_assert(memcmp(bf_film_psi(fa), bf_film_psi(fb), n * sizeof(double)) ==
              0);
    ck_assert(memcmp(bf_film_psi(fa), bf_film_psi(fc), n * sizeof(double)) !=
              0);
    bf_sim_free(a);
    bf_sim_free(b);
    bf_sim_free(c);
    bf_scene_free(sa);
    bf_scene_free(sb);
    bf_scene_free(sc);
}
END_TEST

START_TEST(scene_validation)
{
    char msg[1024];
    ck_assert_int_eq(tu_scene_error("[scene]\nmodel = film\ndt = 1e-3\n"
                                    "t_end = 1\n[film]\nlength = 50.05\n",
                                    msg, sizeof msg),
                     BF_EINPUT);
    ck_assert_msg(strstr(msg, "[film] dx") && strstr(msg, "whole number"),
                  "%s", msg);
    ck_assert_int_eq(tu_scene_error("[scene]\nmodel = film\ndt = 1e-3\n"
                                    "t_end = 1\n[film]\na = 2\nb = 1\n",
                                    msg, sizeof msg),
                     BF_EINPUT);
    ck_assert_msg(strstr(msg, "[film] b") && strstr(msg, "psi_e"), "%s", msg);
    ck_assert_int_eq(tu_scene_error("[scene]\nmodel = film\ndt = 1e-3\n"
                                    "t_end = 1\n[film]\ninitial = file\n",
                                    msg, sizeof msg),
                     BF_EINPUT);
    ck_assert_msg(strstr(msg, "[film] file"), "%s", msg);
    ck_assert_int_eq(tu_scene_error("[scene]\nmodel = film\ndt = 1e-3\n"
                                    "t_end = 1\neffects = contact\n",
                                    msg, sizeof msg),
                     BF_EINPUT);
}
END_TEST

static const char *const film_sets[] = {"/time", "/film/time", "/film/h",
                                        "/film/psi", "/film/u_d", "/film/u_c",
                                        "/film/mass_d", "/film/max_u",
                                        "/film/kink_error", NULL};

static void same_datasets(const char *a, const char *b, const char *const *nm)
{
    bf_err err = {0};
    for (; *nm; nm++) {
        double *da, *db;
        size_t a0, a1, b0, b1;
        ck_assert_msg(bf_h5_read(a, *nm, &da, &a0, &a1, &err) == 0, "%s",
                      err.msg);
        ck_assert_msg(bf_h5_read(b, *nm, &db, &b0, &b1, &err) == 0, "%s",
                      err.msg);
        ck_assert_msg(a0 == b0 && a1 == b1, "%s: shapes differ", *nm);
        ck_assert_msg(memcmp(da, db, a0 * (a1 ? a1 : 1) * sizeof *da) == 0,
                      "%s differs", *nm);
        free(da);
        free(db);
    }
}

START_TEST(restart_bit_identical)
{
    const char *scene = tu_repo("runs/kink_steady.ini");
    char full[512], part[512];
    snprintf(full, sizeof full, "%s", tu_tmp("kfull.h5"));
    snprintf(part, sizeof part, "%s", tu_tmp("kpart.h5"));
    const char *t = "scene.t_end=20", *o = "scene.output_every=0.37 s",
               *pe = "film.profile_every=1.1 s";
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", full, "-q", "--set",
                            t, "--set", o, "--set", pe, NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", part, "-q", "--set",
                            t, "--set", o, "--set", pe, "--stop-after", "7777",
                            NULL),
                     6);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", part, "-q", NULL),
                     0);
    same_datasets(full, part, film_sets);
}
END_TEST

START_TEST(initial_state_from_file)
{
    const char *scene = tu_repo("runs/kink_steady.ini");
    char first[512], second[512], both[512];
    snprintf(first, sizeof first, "%s", tu_tmp("kf1.h5"));
    snprintf(second, sizeof second, "%s", tu_tmp("kf2.h5"));
    snprintf(both, sizeof both, "%s", tu_tmp("kf12.h5"));
    char fileset[600];
    snprintf(fileset, sizeof fileset, "film.file=%s", first);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", first, "-q",
                            "--set", "scene.t_end=2", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", second, "-q",
                            "--set", "scene.t_end=2", "--set",
                            "film.initial=file", "--set", fileset, "--set",
                            "film.perturbation=0", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", scene, "-o", both, "-q",
                            "--set", "scene.t_end=4", NULL),
                     0);
    /* 2 s + 2 s from the file = 4 s in one go (the state is h, psi and
     * the velocities; alpha h is rebuilt from h and psi, which may differ
     * in the last bit, so compare to round-off) */
    double *a, *b;
    size_t a0, a1, b0, b1;
    bf_err err = {0};
    ck_assert(bf_h5_read(second, "/film/psi", &a, &a0, &a1, &err) == 0);
    ck_assert(bf_h5_read(both, "/film/psi", &b, &b0, &b1, &err) == 0);
    ck_assert(a1 == b1);
    double d = maxdiff(a + (a0 - 1) * a1, b + (b0 - 1) * b1, a1, 1);
    ck_assert_msg(d < 1e-12, "psi differs by %g", d);
    free(a);
    free(b);
}
END_TEST

Suite *suite_film(void)
{
    Suite *s = suite_create("film");
    TCase *tc = tu_tcase("scheme");
    tcase_add_test(tc, phase_totals_conserved_1e5_steps);
    tcase_add_test(tc, lake_at_rest_bit_for_bit);
    tcase_add_test(tc, steady_kink_error_is_dx2);
    tcase_add_test(tc, run_converges_to_discrete_kink_and_stays);
    tcase_add_test(tc, observed_order_in_dx);
    tcase_add_test(tc, time_error_structure);
    tcase_add_test(tc, stable_dt_estimate_is_sharp_for_gravity_waves);
    tcase_add_test(tc, stable_dt_estimate_is_sharp_for_phase_separation);
    suite_add_tcase(s, tc);
    tc = tu_tcase("scenes");
    tcase_add_test(tc, large_dt_refused_or_stopped);
    tcase_add_test(tc, film_step_limit_of_the_models);
    tcase_add_test(tc, fractions_stay_in_range_with_large_perturbations);
    tcase_add_test(tc, unhandled_fraction_goes_negative_in_stop_mode);
    tcase_add_test(tc, perturbed_kink_stays_converged_past_300s);
    tcase_add_test(tc, same_seed_same_bits);
    tcase_add_test(tc, scene_validation);
    tcase_add_test(tc, restart_bit_identical);
    tcase_add_test(tc, initial_state_from_file);
    suite_add_tcase(s, tc);
    return s;
}
