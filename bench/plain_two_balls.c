/* plain_two_balls.c: the shipped scene runs/two_balls_B.ini written as a
 * straightforward C program that does not use the library, the yardstick
 * of bench/two_balls_vs_plain.sh (issue 21): what a competent programmer
 * would write for this one problem.
 *
 * The same work as `ballfilm run runs/two_balls_B.ini`: two balls (lower
 * 0.8 g, upper 1 g, R = 0.1 cm) under gravity (980 cm/s^2), a Hertz floor
 * and a Hertz contact (k = 1e7), MV2M (Yasuda eqs 2.19-2.21, 2.24) at
 * dt = 1e-4 s to t = 1000 s; the total energy after every step, its
 * largest relative error, the run stopped beyond 0.5; the first-return map
 * (the upper ball's z and v at each lowest point of the lower ball, found
 * by the cubic Hermite interpolant of the step, the deepest one per floor
 * contact); a row (t, step, x, v, kinetic, potential and total energy)
 * every 100 steps.  Rows and map points are written in binary with
 * stdio's buffering (cheaper than HDF5: the comparison favours this
 * program).  It prints the number of map points and the largest energy
 * error; its arithmetic is the library's, in the same order, so both are
 * ballfilm's to the last digit (the script checks it): the same work.
 *
 * usage: plain_two_balls OUT.bin [T_END]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define G 980.0
#define K 1e7
#define R 0.1
#define M1 0.8
#define M2 1.0

/* The arithmetic of the library in its order (the effects gravity, floor,
 * contact summed in that order, forces times 1/m, the potentials summed per
 * effect), so that both programs follow the same chaotic trajectory and
 * their map counts and energy errors can be compared exactly. */
static const double IM1 = 1.0 / M1, IM2 = 1.0 / M2;

static double hertz(double d) { return d > 0 ? K * d * sqrt(d) : 0.0; }
static double hertz_energy(double d)
{
    return d > 0 ? 0.4 * K * d * d * sqrt(d) : 0.0;
}

static void accel(const double x[2], double a[2])
{
    double a1 = 0.0, a2 = 0.0;
    a1 -= G;
    a2 -= G;
    if (x[0] < R)
        a1 += hertz(R - x[0]) * IM1;
    if (x[1] < R)
        a2 += hertz(R - x[1]) * IM2;
    double gap = x[1] - x[0];
    if (gap < R + R) {
        double f = hertz(0.5 * (R + R - gap));
        a1 -= f * IM1;
        a2 += f * IM2;
    }
    a[0] = a1;
    a[1] = a2;
}

static double potential(const double x[2])
{
    double grav = 0.0, floor = 0.0, pair = 0.0;
    grav += M1 * G * x[0];
    grav += M2 * G * x[1];
    if (x[0] < R)
        floor += hertz_energy(R - x[0]);
    if (x[1] < R)
        floor += hertz_energy(R - x[1]);
    if (x[1] - x[0] < R + R)
        pair += 2.0 * hertz_energy(0.5 * (R + R - (x[1] - x[0])));
    double u = 0.0;
    u += grav;
    u += floor;
    u += pair;
    return u;
}

static double hermite(double th, double dt, double p0, double d0, double p1,
                      double d1)
{
    double t2 = th * th, t3 = t2 * th;
    return (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + th) * dt * d0 +
           (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * dt * d1;
}

static double hermite_slope(double th, double dt, double p0, double d0,
                            double p1, double d1)
{
    double D = (p1 - p0) / dt;
    return 6 * th * (1 - th) * D + (1 - th) * (1 - 3 * th) * d0 +
           th * (3 * th - 2) * d1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: plain_two_balls OUT.bin [T_END]\n");
        return 2;
    }
    FILE *out = fopen(argv[1], "wb");
    if (!out)
        return 5;
    const double dt = 1e-4, t_end = argc > 2 ? atof(argv[2]) : 1000.0;
    const long nsteps = lround(t_end / dt);
    double x[2] = {0.2, 0.5}, v[2] = {0, 0};
    const double m[2] = {M1, M2};
    double e0 = 0.0;
    e0 += 0.5 * M1 * v[0] * v[0];
    e0 += 0.5 * M2 * v[1] * v[1];
    e0 = e0 + potential(x);
    double max_rel = 0;
    long npoints = 0;
    int pending = 0;
    double cand[4] = {0}; /* t, z, v, z_trigger */
    double a0[2], aV[2], aT[2], xV[2], xT[2];
    const double dt2 = dt * dt, hdt = 0.5 * dt, hdt2 = 0.5 * dt2,
                 edt2 = 0.125 * dt2, dt6 = dt / 6.0, dt26 = dt2 / 6.0;
    for (long n = 0; n < nsteps; n++) {
        const double t = (double)n * dt;
        double x0[2] = {x[0], x[1]}, v0[2] = {v[0], v[1]};
        accel(x, a0);
        for (int i = 0; i < 2; i++) {
            xV[i] = x[i] + (dt * v[i] + hdt2 * a0[i]);
            xT[i] = x[i] + (hdt * v[i] + edt2 * a0[i]);
        }
        accel(xV, aV);
        accel(xT, aT);
        for (int i = 0; i < 2; i++) {
            double dv = dt6 * (a0[i] + aV[i] + 4.0 * aT[i]);
            double dx = dt * v[i] + dt26 * (2.0 * a0[i] + aV[i]);
            x[i] += dx;
            v[i] += dv;
        }
        /* energy */
        double kin = 0.0;
        for (int i = 0; i < 2; i++)
            kin += 0.5 * m[i] * v[i] * v[i];
        double pot = potential(x), e = kin + pot;
        double rel = e0 != 0.0 ? fabs(e - e0) / fabs(e0) : fabs(e - e0);
        if (!(rel <= max_rel))
            max_rel = rel;
        if (!(rel <= 0.5)) {
            fprintf(stderr, "unstable at step %ld\n", n + 1);
            return 3;
        }
        /* return map: a lowest point of the lower ball inside the step */
        if (v0[0] < 0 && v[0] >= 0) {
            double lo = 0, hi = 1;
            for (int k = 0; k < 60; k++) {
                double mid = 0.5 * (lo + hi);
                if (hermite_slope(mid, dt, x0[0], v0[0], x[0], v[0]) < 0)
                    lo = mid;
                else
                    hi = mid;
            }
            double th = 0.5 * (lo + hi), a1[2];
            accel(x, a1);
            double zt = hermite(th, dt, x0[0], v0[0], x[0], v[0]);
            if (!pending || zt < cand[3]) {
                cand[0] = t + th * dt;
                cand[1] = hermite(th, dt, x0[1], v0[1], x[1], v[1]);
                cand[2] = hermite(th, dt, v0[1], a0[1], v[1], a1[1]);
                cand[3] = zt;
            }
            pending = 1;
        }
        if (pending && x[0] >= R) {
            fwrite(cand, sizeof cand, 1, out);
            npoints++;
            pending = 0;
        }
        if ((n + 1) % 100 == 0) {
            double row[9] = {t + dt, (double)(n + 1), x[0], x[1], v[0], v[1],
                             kin, pot, e};
            fwrite(row, sizeof row, 1, out);
        }
    }
    fclose(out);
    printf("plain: %ld steps, %ld return-map points, max relative energy "
           "error %.6e\n", nsteps, npoints, max_rel);
    return 0;
}
