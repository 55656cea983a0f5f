/* test_lyapunov_events.c: the Lyapunov estimate of a ball system whose
 * steps are split at contact events ([integrator] events = yes): the
 * shadow trajectory must be split at its own onsets and releases, as the
 * run is (src/models/ballsys_events.c, bf_ballsys_step_twin).
 *
 * The scene: a ball on a table vibrating as A sin(w t), w = 2 pi f, with
 * restitution e, started on the period-1 orbit of the hard-impact theory
 * (docs/models/vibrating_table.md; one impact per table period at the
 * phase phi* = arccos(Gamma_1 / Gamma), leaving the table at u* = g T / 2,
 * T = 1/f).  Linearised, the map from one impact (time t_k, outgoing
 * velocity u_k) to the next is
 *
 *   J = [[1, T/D], [S, e^2 + S T/D]],
 *
 * D = g T/2 + sdot* the relative impact speed, S = (1 + e) sddot* (the
 * table's velocity and acceleration at phi*); det J = e^2 (the flight
 * keeps the flux (u - sdot) dt du, the impact multiplies it by e twice:
 * once for du, once through the ratio of relative speeds).  At A =
 * 0.08 cm, f = 20 Hz, e = 0.5 (Gamma = 1.289) its trace is -0.441, so
 * the multipliers are complex, |mu| = e, and the separation of two nearby
 * orbits shrinks by e per period: lambda = f ln e = -13.86 1/s.
 *
 * What the estimate gives in a finite time.  The shadow starts (and is
 * re-seeded, lyapsum.h) along a fixed direction, and its distance is
 * measured in (x, tau v) at the renormalisations, once every two table
 * periods; there the complex multipliers rotate the separation on an
 * ellipse, so |J^k d| = e^k |d| r_k with 1/kappa <= r_k <= kappa, kappa
 * the condition number of J's eigenvectors in those coordinates (5.07
 * with the default tau = 0.01 s, measured 45 ms after an impact).  The
 * estimate telescopes over each stretch between re-seeds to
 * log(d_end / d0) = (impacts) ln e + eps, |eps| <= ln kappa, so after t
 * seconds with c stretches |lambda - f ln e| <= c ln kappa / t.  A re-seed
 * comes when d < 1e-4 d0, at least (ln 1e4 - ln kappa) / ln(1/e) = 11
 * impacts after the last: in t = 1 s (20 impacts) c <= 2, and the bound
 * is 2 ln 5.07 / 1 s = 3.25 1/s.  The soft floor's contact (0.35 % of a
 * period at k = 1e10) moves the orbit by 1e-3 rad of phase, far below.
 *
 * Split at the run's events instead of its own, or not at all, the
 * shadow's impacts are integrated across the kink of the contact force:
 * each inserts an O(1) jump into the separation, and the estimate was
 * +83 to +107 1/s on this orbit (a positive exponent for a stable
 * orbit). */
#include <math.h>
#include <stdio.h>

#include "ballfilm/sim.h"
#include "testutil.h"

static const double PI = 3.14159265358979323846;
static const double E = 0.5, F = 20.0, G = 980.0, A = 0.08; /* 1, Hz, cm/s^2, cm */
static const double R = 0.1;                                /* cm */

static const char *scene =
    "[scene]\n"
    "model = balls\n"
    "integrator = rk4\n"
    "effects = gravity floor\n"
    "dt = 2e-6\n"
    "t_end = 1\n"
    "output_every = 0\n"
    "energy_every = 0\n"
    "[integrator]\n"
    "events = yes\n"
    "[lyapunov]\n"
    "enabled = yes\n"
    "[gravity]\n"
    "g = 980\n"
    "[floor]\n"
    "k = 1e10\n"
    "restitution = 0.5\n"
    "amplitude = 0.08\n"
    "frequency = 20\n"
    "[ball.1]\n"
    "mass = 1\n"
    "radius = 0.1\n";

START_TEST(stable_period_one_orbit_contracts_at_e_per_period)
{
    const double w = 2 * PI * F, T = 1 / F;
    const double gam = A * w * w / G, gam1 = PI * (1 - E) / (1 + E);
    const double phi = acos(gam1 / gam), u = G * T / 2;
    /* t = 0 is T - phi/w after the last impact on the orbit */
    const double tf = T - phi / w;
    char x0[64], v0[64];
    snprintf(x0, sizeof x0, "ball.1.position=%.17g",
             A * sin(phi) + R + u * tf - 0.5 * G * tf * tf);
    snprintf(v0, sizeof v0, "ball.1.velocity=%.17g", u - G * tf);
    bf_sim *sim = tu_run_scene(scene, x0, v0, NULL);
    bf_results r;
    bf_sim_results(sim, &r);
    const double theory = F * log(E), bound = 2 * log(5.07) / 1.0;
    printf("lyapunov_events: vibrating table at its period-1 orbit: "
           "lambda %.4f 1/s (f ln e = %.4f, allowed +-%.2f)\n",
           r.lyapunov_exponent, theory, bound);
    fflush(stdout);
    ck_assert(r.has_lyapunov);
    ck_assert_msg(fabs(r.lyapunov_exponent - theory) <= bound,
                  "lambda = %g 1/s, expected f ln e = %g within %g",
                  r.lyapunov_exponent, theory, bound);
    bf_sim_free(sim);
}
END_TEST

Suite *suite_lyapunov_events(void)
{
    Suite *s = suite_create("lyapunov_events");
    TCase *tc = tcase_create("orbit");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, stable_period_one_orbit_contracts_at_e_per_period);
    suite_add_tcase(s, tc);
    return s;
}
