/* test_contact.c: the Hertz potentials are the exact antiderivatives of the
 * forces (central finite differences of the energy reproduce the force to
 * truncation error O(h^2)), for the floor and for ball pairs, including the
 * factor 4/5 of the pair term that the paper's eq. 2.8 gets wrong. */
#include <math.h>

#include "models/ballsys.h"
#include "ballfilm/run.h"
#include "contact/hertz.h"
#include "testutil.h"

static const double K = 1e7;

START_TEST(floor_force_is_minus_gradient)
{
    const double R = 0.1;
    /* deformations from tiny to large; FD step small against x */
    for (double x = 1e-4; x < 0.03; x *= 1.7) {
        double z = R - x, h = 1e-4 * x;
        double fd = -(bf_hertz_floor_energy(K, R, z + h) -
                      bf_hertz_floor_energy(K, R, z - h)) /
                    (2 * h);
        double f = bf_hertz_floor_force(K, R, z);
        /* central difference error ~ h^2 f''/6 ~ 1e-8 relative here */
        ck_assert_msg(fabs(fd - f) <= 1e-6 * fabs(f), "x=%g: fd %.12g force %.12g",
                      x, fd, f);
    }
    /* no contact: zero force and energy */
    ck_assert(bf_hertz_floor_force(K, R, R + 1e-9) == 0.0);
    ck_assert(bf_hertz_floor_energy(K, R, R + 1e-9) == 0.0);
}
END_TEST

START_TEST(pair_force_is_minus_gradient)
{
    const double Ri = 0.1, Rj = 0.13;
    for (double x = 1e-4; x < 0.03; x *= 1.7) {
        double d = Ri + Rj - 2 * x, h = 1e-4 * x;
        /* force pushing the pair apart = -dE/dd */
        double fd = -(bf_hertz_pair_energy(K, Ri, Rj, d + h) -
                      bf_hertz_pair_energy(K, Ri, Rj, d - h)) /
                    (2 * h);
        double f = bf_hertz_pair_force(K, Ri, Rj, d);
        ck_assert_msg(fabs(fd - f) <= 1e-6 * fabs(f), "x=%g: fd %.12g force %.12g",
                      x, fd, f);
        /* the paper's (2/5) k x^{5/2} would give exactly half the force */
        double paper = 0.4 * K * pow(x, 2.5);
        ck_assert(fabs(bf_hertz_pair_energy(K, Ri, Rj, d) - 2 * paper) <=
                  1e-12 * paper);
    }
    ck_assert(bf_hertz_pair_force(K, Ri, Rj, Ri + Rj) == 0.0);
}
END_TEST

/* The effects built from a scene give accelerations equal to
 * -grad(potential)/m, the property the energy diagnostics rely on. */
START_TEST(effects_accel_matches_potential)
{
    bf_scene *sc = tu_scene("[scene]\n"
                            "effects = gravity floor contact spring\n"
                            "dt = 1e-4\nt_end = 1e-4\n"
                            "[ball.1]\nposition = 0.15\nmass = 1.2\n"
                            "[ball.2]\nposition = 0.4\nmass = 0.8\n"
                            "radius = 0.1\n"
                            "[spring]\nstiffness = 3\nrest = 0.2\n");
    bf_sim *sim;
    bf_err err = {0};
    ck_assert_msg(bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, NULL, &err) == BF_OK, "%s", err.msg);
    /* positions where both contacts are active */
    double x[2] = {0.092, 0.19}, a[2], xp[2], xm[2];
    bf_ballsys *sys = bf_balls_model_system(bf_sim_model(sim));
    ck_assert_int_eq(bf_effects_accel(sys->eff, sys->neff, &sys->b, 0, x, sys->b.v, a), 0);
    for (int i = 0; i < 2; i++) {
        double h = 1e-7;
        for (int j = 0; j < 2; j++)
            xp[j] = xm[j] = x[j];
        xp[i] += h;
        xm[i] -= h;
        double g = (bf_effects_potential(sys->eff, sys->neff, &sys->b, 0, xp) -
                    bf_effects_potential(sys->eff, sys->neff, &sys->b, 0, xm)) /
                   (2 * h);
        double f = a[i] * sys->b.m[i];
        ck_assert_msg(fabs(-g - f) <= 1e-6 * fabs(f), "ball %d: -dU/dx %.10g, "
                      "m a %.10g", i + 1, -g, f);
    }
    bf_sim_free(sim);
    bf_scene_free(sc);
}
END_TEST

Suite *suite_contact(void)
{
    Suite *s = suite_create("contact");
    TCase *tc = tu_tcase("hertz");
    tcase_add_test(tc, floor_force_is_minus_gradient);
    tcase_add_test(tc, pair_force_is_minus_gradient);
    tcase_add_test(tc, effects_accel_matches_potential);
    suite_add_tcase(s, tc);
    return s;
}
