/* plain_mac.c: the thesis's MAC reservoir (PROGRAM STRATRES, the scene
 * runs/stratres.ini at refine 4 with void_fix, as `make stratres` runs its
 * 4x case) written as a straightforward C program that does not use the
 * library: the yardstick of bench/mac_vs_plain.sh (issue 21, item 4).
 *
 * What it does, the same work as
 *   ballfilm run runs/stratres.ini --set mac.refine=4 --set scene.dt=0.0125
 *       --set scene.output_every=40 --set mac.void_fix=true
 * (docs/models/mac.md restates the method): a (14 r + 2)^2 staggered grid
 * with a ring of fictitious cells, marker particles 2 x 2 per cell; each
 * step the momentum without pressure (3.3)/(3.4), the density predictor
 * (3.13), then the corrector loop: the pressure equation (3.10) as printed
 * relaxed by Gauss-Seidel with the crude test (.0003), the velocities by
 * the modified update (3.11)/(3.12) with the boundary conditions (no-slip
 * walls, IN column with the hydrostatic P0 and U(2,J) = U(3,J), the OUT
 * cells of the sink after Welch, the free surface), every marker moved
 * from its position at the start of the step with the bilinear
 * (area-weighted, Fig. 2) velocities of the pass, the cell densities and
 * flags recounted from the markers, enclosed empty cells filled
 * (void_fix), repeated while a cell density changes (at most 10 passes),
 * then the final pass with the fine test (.0002); markers entering,
 * leaving, lost; the temperature (3.14).  Markers crossing a wall are held
 * on it (wall_markers = hold).  The CFL number is checked every pass.  A
 * row of every field and every marker is written every output_every steps
 * (binary through stdio, cheaper than HDF5: the comparison favours this
 * program).  The arithmetic is the library's, in its order, so that both
 * programs move the same markers into the same cells (the cell of a
 * marker is a discontinuous function of its position; a different
 * rounding would change the run): the script checks that both report
 * the same numbers to the last bit.
 *
 * What it does not do: the other problems (tank at rest, uniform stream),
 * the other updates (consistent, original), the direct solver, the
 * listing's other readings (out_first, predict, conduction, out_gravity,
 * inflow, wall_markers = remove), checkpoints, error recovery beyond
 * stopping with a message.  It is written for this one scene, as a
 * competent programmer would write it: global arrays, one loop per step
 * of the algorithm, every marker moved and every pressure coefficient
 * computed in every corrector pass, each relaxation sweep on a copy of
 * the pressure as the listing's PN (the algorithm as the thesis states
 * it).  It does not take ballfilm's shortcuts (docs/performance.md): not
 * moving the markers that cannot change cell before the final pass,
 * keeping the coefficients of cells whose densities did not change,
 * sweeping in place; those are what the comparison measures.
 *
 * usage: plain_mac OUT.bin [REFINE [DT [T_END [OUTPUT_EVERY]]]]
 *        (defaults 4, 0.0125, 10, 40)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* cell flags and marker flags of the listing */
enum { NOSLIP = 1, IN = 2, OUT = 3, FULL = 10, SUR = 11, EMP = 12 };
enum { AVAIL = 1, PIN = 2, POUT = 3, REG = 4 };

/* the scene (runs/stratres.ini, the listing's values) */
static const double MU = 1.14e-4, ALPHA = 1.41e-5, G = -0.98;
static const double RHO_MEAN = 0.9985, RHO_AMP = 0.0015;
static const double T_MEAN = 15, T_AMP = 10;
static const double CRUDE = 3e-4, FINE = 2e-4;
static const int MAX_SWEEPS = 500, MAX_PASSES = 10;

static int NI, NJ, ST, NSUR, NRO, OUT_LO, OUT_HI, NSLOT;
static size_t NCELL;
static double DX, DY, DT, DEPTH, PAREA;
static double *U, *V, *P, *R, *T, *RN, *XI, *ZE, *PN, *A, *B1, *B2, *B3, *B4,
    *TN, *S, *PO, *TO, *RO;
static int *F, *N, *MARK, *QUEUE;
/* markers */
static double *X, *Y, *VX, *VY, *DENS, *XN, *YN;
static int *TAG;
/* counters */
static long long entered, left_out, freed, backflow, lost, in_clamped, held,
    voids, oscillations, passes_total, sweeps_total;
static double mass_in, mass_out, mass_back, mass_lost;
static int last_passes;
static long last_sweeps;
static long voids_pass;

#define IX(i, j) ((size_t)(i) * (size_t)ST + (size_t)(j))

static void *alloc(size_t n, size_t size) {
    void *p = calloc(n, size);
    if (!p) {
        fprintf(stderr, "plain_mac: out of memory\n");
        exit(1);
    }
    return p;
}

static int fluidish(int f) { return f == FULL || f == SUR; }
static int interior(int i, int j) {
    return i >= 2 && i <= NI - 1 && j >= 2 && j <= NJ - 1;
}

/* ------------------------------------------------------------ set-up */

static void setup(int r) {
    NI = NJ = 14 * r + 2;
    ST = NJ + 2;
    NCELL = (size_t)(NI + 2) * (size_t)ST;
    DX = DY = 0.1 / (double)r;
    DEPTH = (double)(NJ - 2) * DY;
    PAREA = 0.25 * DX * DY;
    NSUR = 12 * r + 1;
    NRO = 2 * (NSUR - 1);
    OUT_LO = (13 - 2) * r + 2;
    OUT_HI = OUT_LO + 2 * r - 1;
    NSLOT = 800 * r * r;
    double **d[] = {&U,  &V, &P,  &R,  &T,  &RN, &XI, &ZE,
                    &PN, &A, &B1, &B2, &B3, &B4, &TN, &S};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        *d[k] = alloc(NCELL, sizeof(double));
    F = alloc(NCELL, sizeof(int));
    N = alloc(NCELL, sizeof(int));
    PO = alloc((size_t)NJ + 2, sizeof(double));
    TO = alloc((size_t)NJ + 2, sizeof(double));
    RO = alloc((size_t)NRO + 1, sizeof(double));
    MARK = alloc((size_t)(NI - 2) * (size_t)(NJ - 2), sizeof(int));
    QUEUE = alloc((size_t)(NI - 2) * (size_t)(NJ - 2), sizeof(int));
    double **q[] = {&X, &Y, &VX, &VY, &DENS, &XN, &YN};
    for (size_t k = 0; k < sizeof q / sizeof q[0]; k++)
        *q[k] = alloc((size_t)NSLOT, sizeof(double));
    TAG = alloc((size_t)NSLOT, sizeof(int));

    /* flags: walls, IN column on the left, two OUT cells (x r) below */
    for (int i = 1; i <= NI; i++)
        for (int j = 1; j <= NJ; j++)
            F[IX(i, j)] = (i == 1 || i == NI || j == 1 || j == NJ) ? NOSLIP
                          : j <= NSUR                              ? FULL
                          : j == NSUR + 1                          ? SUR
                                                                   : EMP;
    for (int j = 2; j <= NJ - 1; j++)
        F[IX(1, j)] = IN;
    for (int i = OUT_LO; i <= OUT_HI; i++)
        F[IX(i, 1)] = OUT;

    /* tanh profiles, hydrostatic pressure */
    const double deep = (double)(NSUR - 1) * DY;
    const double th = tanh(0.5 * deep), gabs = fabs(G);
    for (int l = 1; l <= NRO; l++) {
        double y = (0.5 * (double)l - 0.25) * DY;
        RO[l] = RHO_MEAN - RHO_AMP * tanh(y - 0.5 * deep) / th;
    }
    for (int j = 2; j <= NSUR; j++) {
        double yc = ((double)j - 1.5) * DY, yb = (double)(j - 2) * DY;
        TO[j] = T_MEAN + T_AMP * tanh(yc - 0.5 * deep) / th;
        PO[j] = gabs *
                (RHO_MEAN * (deep - yb) -
                 RHO_AMP / th * log(cosh(0.5 * deep) / cosh(yb - 0.5 * deep)));
    }
    for (int i = 1; i <= NI - 1; i++)
        for (int j = 2; j <= NSUR; j++) {
            R[IX(i, j)] = 0.5 * (RO[2 * j - 3] + RO[2 * j - 2]);
            T[IX(i, j)] = TO[j];
            P[IX(i, j)] = PO[j];
        }
    for (int i = 2; i <= NI - 1; i++)
        R[IX(i, NSUR + 1)] = R[IX(i, NSUR)];

    /* markers: two IN markers per row, 2 x 2 per fluid cell */
    int k = 0;
    for (int l = 1; l <= NRO; l++, k++) {
        TAG[k] = PIN;
        X[k] = -0.25 * DX;
        Y[k] = (0.5 * (double)l - 0.25) * DY;
        DENS[k] = RO[l];
    }
    for (int row = 1; row <= NRO; row++)
        for (int col = 1; col <= 2 * (NI - 2); col++, k++) {
            TAG[k] = REG;
            X[k] = (0.5 * (double)col - 0.25) * DX;
            Y[k] = (0.5 * (double)row - 0.25) * DY;
            DENS[k] = RO[row];
        }
    for (; k < NSLOT; k++)
        TAG[k] = AVAIL;
}

/* ------------------------------------------------------------ the step */

static void mirror_density(void) {
    for (int i = 2; i <= NI - 1; i++) {
        R[IX(i, 1)] = R[IX(i, 2)];
        R[IX(i, NJ)] = R[IX(i, NJ - 1)];
    }
    for (int j = 2; j <= NJ - 1; j++) {
        R[IX(1, j)] = R[IX(2, j)];
        R[IX(NI, j)] = R[IX(NI - 1, j)];
    }
}

/* psi and zeta of (3.3)/(3.4), donor-cell corner fluxes */
static void momentum(void) {
    for (int i = 2; i <= NI; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            double rl = 0.5 * (R[IX(i - 1, j)] + R[IX(i, j)]);
            double ur = 0.5 * (U[IX(i + 1, j)] + U[IX(i, j)]);
            double ul = 0.5 * (U[IX(i - 1, j)] + U[IX(i, j)]);
            double vb = 0.5 * (V[IX(i - 1, j)] + V[IX(i, j)]);
            double vt = 0.5 * (V[IX(i - 1, j + 1)] + V[IX(i, j + 1)]);
            double ruvb =
                vb >= 0
                    ? 0.5 * (R[IX(i, j - 1)] + R[IX(i - 1, j - 1)]) *
                          U[IX(i, j - 1)] * vb
                    : 0.5 * (R[IX(i, j)] + R[IX(i - 1, j)]) * U[IX(i, j)] * vb;
            double ruvt =
                vt >= 0
                    ? 0.5 * (R[IX(i, j)] + R[IX(i - 1, j)]) * U[IX(i, j)] * vt
                    : 0.5 * (R[IX(i, j + 1)] + R[IX(i - 1, j + 1)]) *
                          U[IX(i, j + 1)] * vt;
            double dux2 =
                (U[IX(i + 1, j)] - 2.0 * U[IX(i, j)] + U[IX(i - 1, j)]) /
                (DX * DX);
            double duy2 =
                (U[IX(i, j + 1)] - 2.0 * U[IX(i, j)] + U[IX(i, j - 1)]) /
                (DY * DY);
            XI[IX(i, j)] =
                rl * U[IX(i, j)] -
                DT * ((R[IX(i, j)] * ur * ur - R[IX(i - 1, j)] * ul * ul) / DX +
                      (ruvt - ruvb) / DY - MU * (dux2 + duy2));
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ; j++) {
            double rb = 0.5 * (R[IX(i, j - 1)] + R[IX(i, j)]);
            double vt = 0.5 * (V[IX(i, j + 1)] + V[IX(i, j)]);
            double vb = 0.5 * (V[IX(i, j - 1)] + V[IX(i, j)]);
            double ur = 0.5 * (U[IX(i + 1, j)] + U[IX(i + 1, j - 1)]);
            double ul = 0.5 * (U[IX(i, j)] + U[IX(i, j - 1)]);
            double ruvr =
                ur >= 0
                    ? 0.5 * (R[IX(i, j)] + R[IX(i, j - 1)]) * ur * V[IX(i, j)]
                    : 0.5 * (R[IX(i + 1, j)] + R[IX(i + 1, j - 1)]) * ur *
                          V[IX(i + 1, j)];
            double ruvl =
                ul >= 0
                    ? 0.5 * (R[IX(i - 1, j)] + R[IX(i - 1, j - 1)]) * ul *
                          V[IX(i - 1, j)]
                    : 0.5 * (R[IX(i, j)] + R[IX(i, j - 1)]) * ul * V[IX(i, j)];
            double dvx2 =
                (V[IX(i + 1, j)] - 2.0 * V[IX(i, j)] + V[IX(i - 1, j)]) /
                (DX * DX);
            double dvy2 =
                (V[IX(i, j + 1)] - 2.0 * V[IX(i, j)] + V[IX(i, j - 1)]) /
                (DY * DY);
            ZE[IX(i, j)] =
                rb * V[IX(i, j)] -
                DT * ((R[IX(i, j)] * vt * vt - R[IX(i, j - 1)] * vb * vb) / DY +
                      (ruvr - ruvl) / DX - MU * (dvx2 + dvy2) - rb * G);
        }
}

/* (3.13), put into R in FULL cells */
static void predict_density(void) {
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            double rr = R[IX(i, j)];
            RN[IX(i, j)] = rr - DT * (0.5 * (U[IX(i, j)] + U[IX(i + 1, j)]) *
                                          (R[IX(i + 1, j)] - rr) / DX +
                                      0.5 * (V[IX(i, j)] + V[IX(i, j + 1)]) *
                                          (R[IX(i, j + 1)] - rr) / DY);
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++)
            if (F[IX(i, j)] == FULL)
                R[IX(i, j)] = RN[IX(i, j)];
}

/* coefficients of (3.10) in FULL cells, face densities */
static void coefficients(void) {
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            size_t c = IX(i, j);
            if (F[c] != FULL)
                continue;
            double rl = 0.5 * (R[IX(i - 1, j)] + R[c]);
            double rr = 0.5 * (R[IX(i + 1, j)] + R[c]);
            double rt = 0.5 * (R[IX(i, j + 1)] + R[c]);
            double rb = 0.5 * (R[IX(i, j - 1)] + R[c]);
            double num = (XI[c] / rl - XI[IX(i + 1, j)] / rr) / DX +
                         (ZE[c] / rb - ZE[IX(i, j + 1)] / rt) / DY;
            double cc = DT * (1.0 / rl + 1.0 / rr) / (DX * DX) +
                        DT * (1.0 / rt + 1.0 / rb) / (DY * DY);
            A[c] = num / cc;
            B1[c] = (DT / (DX * DX * rr)) / cc;
            B2[c] = (DT / (DX * DX * rl)) / cc;
            B3[c] = (DT / (DY * DY * rt)) / cc;
            B4[c] = (DT / (DY * DY * rb)) / cc;
        }
}

/* free-surface pressure (2.20) in SUR cells */
static void surface_pressure(void) {
    const double sor = 1.0 / sqrt(2.0);
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            if (F[IX(i, j)] != SUR)
                continue;
            int up = F[IX(i, j + 1)] == EMP, rt = F[IX(i + 1, j)] == EMP;
            int lt = F[IX(i - 1, j)] == EMP, dn = F[IX(i, j - 1)] == EMP;
            double px, py;
            if (up && rt)
                px = sor, py = sor;
            else if (up && lt)
                px = -sor, py = sor;
            else if (up)
                px = 0, py = 1;
            else if (rt && dn)
                px = sor, py = -sor;
            else if (rt)
                px = 1, py = 0;
            else if (lt && dn)
                px = -sor, py = -sor;
            else if (lt)
                px = -1, py = 0;
            else if (dn)
                px = 0, py = -1;
            else
                continue;
            double dudx = (U[IX(i + 1, j)] - U[IX(i, j)]) / DX;
            double dvdy = (V[IX(i, j + 1)] - V[IX(i, j)]) / DY;
            double dudy = 0.25 *
                          (U[IX(i + 1, j + 1)] + U[IX(i, j + 1)] -
                           U[IX(i, j - 1)] - U[IX(i + 1, j - 1)]) /
                          DY;
            double dvdx = 0.25 *
                          (V[IX(i + 1, j + 1)] + V[IX(i + 1, j)] -
                           V[IX(i - 1, j + 1)] - V[IX(i - 1, j)]) /
                          DX;
            P[IX(i, j)] =
                2.0 * MU *
                (px * px * dudx + px * py * (dudy + dvdx) + py * py * dvdy);
        }
}

/* Ghost pressure of ring cell (ig,jg) next to interior cell (ic,jc):
 * the IN column holds P0; walls and OUT cells get the pressure for which
 * the update gives the face velocity the boundary prescribes (0 at a
 * wall, Welch's unaccelerated outflow at OUT). */
static void ghost(double *p, int ig, int jg, int ic, int jc) {
    size_t g = IX(ig, jg), c = IX(ic, jc);
    int fg = F[g];
    if (fg == IN) {
        p[g] = PO[jg];
        return;
    }
    double delta, psi, rhof, s;
    if (ig == 1) {
        delta = DX, s = -1, psi = XI[c];
        rhof = 0.5 * (R[IX(ic - 1, jc)] + R[c]);
    } else if (ig == NI) {
        delta = DX, s = 1, psi = XI[IX(ic + 1, jc)];
        rhof = 0.5 * (R[c] + R[IX(ic + 1, jc)]);
    } else if (jg == 1) {
        delta = DY, s = -1, psi = ZE[c];
        rhof = 0.5 * (R[IX(ic, jc - 1)] + R[c]);
    } else {
        delta = DY, s = 1, psi = ZE[IX(ic, jc + 1)];
        rhof = 0.5 * (R[c] + R[IX(ic, jc + 1)]);
    }
    double val = 0.0;
    if (fg == OUT) { /* bottom OUT cell: Welch's pressure offset */
        double rc = R[c];
        int i = ic;
        double ruvr =
            0.5 * rc * U[IX(i + 1, 2)] * (V[IX(i, 2)] + V[IX(i + 1, 2)]);
        double ruvl = 0.5 * rc * U[IX(i, 2)] * (V[IX(i - 1, 2)] + V[IX(i, 2)]);
        double off = DY / DX * (ruvr - ruvl);
        val = psi / rhof - s * DT / delta * off / R[c];
    }
    if (!fluidish(F[c])) {
        p[g] = 0.0;
        return;
    }
    double k = 1.0 / rhof;
    p[g] = p[c] - delta / (DT * k) * s * (val - psi / rhof);
}

static void ghost_pressure(double *p) {
    for (int j = 2; j <= NJ - 1; j++) {
        ghost(p, 1, j, 2, j);
        ghost(p, NI, j, NI - 1, j);
    }
    for (int i = 2; i <= NI - 1; i++) {
        ghost(p, i, 1, i, 2);
        ghost(p, i, NJ, i, NJ - 1);
    }
}

/* Gauss-Seidel on (3.10) until the change per sweep passes the test */
static long relax(int fine) {
    const double tol = fine ? FINE : CRUDE, gd = fabs(G) * DEPTH;
    for (long l = 1;; l++) {
        ghost_pressure(P);
        memcpy(PN, P, NCELL * sizeof *PN);
        for (int i = 2; i <= NI - 1; i++)
            for (int j = 2; j <= NJ - 1; j++) {
                size_t c = IX(i, j);
                if (F[c] == FULL)
                    PN[c] = B1[c] * PN[c + (size_t)ST] +
                            B2[c] * PN[c - (size_t)ST] + B3[c] * PN[c + 1] +
                            B4[c] * PN[c - 1] + A[c];
            }
        double worst = 0;
        for (int i = 2; i <= NI - 1; i++)
            for (int j = 2; j <= NJ - 1; j++) {
                size_t c = IX(i, j);
                if (F[c] != FULL)
                    continue;
                double dp = fabs((PN[c] - P[c]) / (R[c] * gd));
                if (!(dp <= worst))
                    worst = dp;
            }
        memcpy(P, PN, NCELL * sizeof *P);
        if (worst < tol)
            return l;
        if (l >= MAX_SWEEPS) {
            fprintf(stderr, "plain_mac: too many iterations\n");
            exit(4);
        }
    }
}

/* the modified update (3.11)/(3.12) on the face between cells a and b */
static double update(size_t a, size_t b, double psi, double delta) {
    double rf = R[a] + R[b];
    return 2.0 * psi / rf + DT * (P[a] / R[a] - P[b] / R[b]) / delta;
}

static void velocities(void) {
    for (size_t k = 0; k < NCELL; k++)
        U[k] = V[k] = 0.0;
    for (int i = 3; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            int fa = F[IX(i - 1, j)], fb = F[IX(i, j)];
            if ((fa == FULL && fluidish(fb)) || (fb == FULL && fluidish(fa)))
                U[IX(i, j)] = update(IX(i - 1, j), IX(i, j), XI[IX(i, j)], DX);
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 3; j <= NJ - 1; j++) {
            int fa = F[IX(i, j - 1)], fb = F[IX(i, j)];
            if ((fa == FULL && fluidish(fb)) || (fb == FULL && fluidish(fa)))
                V[IX(i, j)] = update(IX(i, j - 1), IX(i, j), ZE[IX(i, j)], DY);
        }
    /* the sink's OUT faces */
    for (int i = 2; i <= NI - 1; i++)
        if (F[IX(i, 1)] == OUT && fluidish(F[IX(i, 2)]))
            V[IX(i, 2)] = update(IX(i, 1), IX(i, 2), ZE[IX(i, 2)], DY);
    /* zero shear between SUR cells */
    const double rxy = DY / DX, ryx = DX / DY;
    for (int i = 3; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            if (F[IX(i - 1, j)] != SUR || F[IX(i, j)] != SUR)
                continue;
            if (F[IX(i - 1, j - 1)] == FULL || F[IX(i, j - 1)] == FULL)
                U[IX(i, j)] =
                    U[IX(i, j - 1)] - rxy * (V[IX(i, j)] - V[IX(i - 1, j)]);
            else if (F[IX(i - 1, j + 1)] == FULL || F[IX(i, j + 1)] == FULL)
                U[IX(i, j)] = U[IX(i, j + 1)] +
                              rxy * (V[IX(i, j + 1)] - V[IX(i - 1, j + 1)]);
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 3; j <= NJ - 1; j++) {
            if (F[IX(i, j - 1)] != SUR || F[IX(i, j)] != SUR)
                continue;
            if (F[IX(i - 1, j - 1)] == FULL || F[IX(i - 1, j)] == FULL)
                V[IX(i, j)] =
                    V[IX(i - 1, j)] - ryx * (U[IX(i, j)] - U[IX(i, j - 1)]);
            else if (F[IX(i + 1, j - 1)] == FULL || F[IX(i + 1, j)] == FULL)
                V[IX(i, j)] = V[IX(i + 1, j)] +
                              ryx * (U[IX(i + 1, j)] - U[IX(i + 1, j - 1)]);
        }
    /* the inflow copies the face on its right */
    for (int j = 2; j <= NJ - 1; j++)
        if (F[IX(1, j)] == IN && fluidish(F[IX(2, j)]))
            U[IX(2, j)] = U[IX(3, j)];
    /* SUR faces towards empty cells: continuity in the SUR cell */
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            if (F[IX(i, j)] != SUR)
                continue;
            int eu = F[IX(i, j + 1)] == EMP, er = F[IX(i + 1, j)] == EMP;
            int el = F[IX(i - 1, j)] == EMP, ed = F[IX(i, j - 1)] == EMP;
            int n = eu + er + el + ed;
            if (!n)
                continue;
            double *vu = &V[IX(i, j + 1)], *ur = &U[IX(i + 1, j)];
            double *ul = &U[IX(i, j)], *vd = &V[IX(i, j)];
            if (n == 2 && !(eu && ed) && !(er && el)) {
                /* a corner: copy the opposite faces */
                if (eu)
                    *vu = *vd;
                if (er)
                    *ur = *ul;
                if (el)
                    *ul = *ur;
                if (ed)
                    *vd = *vu;
                continue;
            }
            if (eu)
                *vu = 0.0;
            if (er)
                *ur = 0.0;
            if (el)
                *ul = 0.0;
            if (ed)
                *vd = 0.0;
            /* the first empty face (above, right, left, below) takes the
             * divergence */
            double d = (U[IX(i + 1, j)] - U[IX(i, j)]) / DX +
                       (V[IX(i, j + 1)] - V[IX(i, j)]) / DY;
            if (eu)
                *vu -= 1.0 * DY * d;
            else if (er)
                *ur -= 1.0 * DX * d;
            else if (el)
                *ul -= -1.0 * DX * d;
            else
                *vd -= -1.0 * DY * d;
        }
    /* ghost faces */
    for (int j = 2; j <= NJ - 1; j++)
        U[IX(NI + 1, j)] = U[IX(NI - 1, j)];
    for (int j = 2; j <= NJ; j++) {
        V[IX(1, j)] = -V[IX(2, j)];
        V[IX(NI, j)] = -V[IX(NI - 1, j)];
    }
    for (int i = 2; i <= NI; i++) {
        int slip = F[IX(i - 1, 1)] == OUT || F[IX(i, 1)] == OUT;
        U[IX(i, 1)] = slip ? U[IX(i, 2)] : -U[IX(i, 2)];
        U[IX(i, NJ)] = -U[IX(i, NJ - 1)];
    }
    for (int j = 1; j <= NJ; j++)
        U[IX(1, j)] = U[IX(3, j)];
    for (int i = 2; i <= NI - 1; i++) {
        V[IX(i, NJ + 1)] = V[IX(i, NJ - 1)];
        if (F[IX(i, 1)] == OUT)
            V[IX(i, 1)] =
                V[IX(i, 2)] + DY / DX * (U[IX(i + 1, 1)] - U[IX(i, 1)]);
        else
            V[IX(i, 1)] = V[IX(i, 3)];
    }
}

static void check_cfl(void) {
    for (int i = 1; i <= NI + 1; i++)
        for (int j = 1; j <= NJ + 1; j++) {
            double u = j <= NJ ? U[IX(i, j)] : 0, v = i <= NI ? V[IX(i, j)] : 0;
            double cu = fabs(u) * DT / DX, cv = fabs(v) * DT / DY;
            if (!isfinite(u) || !isfinite(v) ||
                (i >= 2 && i <= NI && j >= 2 && j <= NJ - 1 && cu > 1.0) ||
                (i >= 2 && i <= NI - 1 && j >= 2 && j <= NJ && cv > 1.0)) {
                fprintf(stderr, "plain_mac: unstable at face (%d,%d)\n", i, j);
                exit(3);
            }
        }
}

/* cell of coordinate x (I = X/DX + 2) */
static int cell_of(double x, double h) { return (int)floor(x / h) + 2; }
static int clampi(int k, int lo, int hi) {
    return k < lo ? lo : k > hi ? hi : k;
}

/* bilinear (area-weighted) velocities, Fig. 2 */
static double interp_u(double x, double y) {
    double fx = x / DX + 2.0, fy = y / DY + 1.5;
    int i = clampi((int)floor(fx), 1, NI),
        j = clampi((int)floor(fy), 1, NJ - 1);
    double ax = fx - (double)i, ay = fy - (double)j;
    return (1 - ax) * (1 - ay) * U[IX(i, j)] + ax * (1 - ay) * U[IX(i + 1, j)] +
           (1 - ax) * ay * U[IX(i, j + 1)] + ax * ay * U[IX(i + 1, j + 1)];
}

static double interp_v(double x, double y) {
    double fx = x / DX + 1.5, fy = y / DY + 2.0;
    int i = clampi((int)floor(fx), 1, NI - 1),
        j = clampi((int)floor(fy), 1, NJ);
    double bx = fx - (double)i, by = fy - (double)j;
    return (1 - bx) * (1 - by) * V[IX(i, j)] + bx * (1 - by) * V[IX(i + 1, j)] +
           (1 - bx) * by * V[IX(i, j + 1)] + bx * by * V[IX(i + 1, j + 1)];
}

/* the largest coordinate below the wall at w still in cell `cell` */
static double inside_of(double w, double h, int cell) {
    double x = w;
    while (cell_of(x, h) > cell)
        x = nextafter(x, -INFINITY);
    return x;
}

/* every marker moved from its position at t = n dt; fluid markers that
 * would cross a wall are held on it */
static long move_markers(void) {
    long nheld = 0;
    for (int k = 0; k < NSLOT; k++) {
        int f = TAG[k];
        if (f == AVAIL)
            continue;
        double x = X[k], y = Y[k], vx = 0, vy = 0;
        if (f == POUT) {
            int i = clampi(cell_of(x, DX), 1, NI),
                j = clampi(cell_of(y, DY), 1, NJ);
            if (j == 1)
                vy = V[IX(i, 2)];
            else if (i == NI)
                vx = U[IX(NI, j)];
        } else {
            vx = interp_u(x, y);
            if (f == REG)
                vy = interp_v(x, y);
        }
        VX[k] = vx;
        VY[k] = vy;
        double xn = x + vx * DT, yn = y + vy * DT;
        if (f == REG) {
            int i = cell_of(xn, DX), j = cell_of(yn, DY), h = 0;
            int jj = clampi(j, 2, NJ - 1);
            if (i < 2 && F[IX(1, jj)] == NOSLIP)
                xn = 0.0, h = 1;
            else if (i > NI - 1 && F[IX(NI, jj)] == NOSLIP)
                xn = inside_of((double)(NI - 2) * DX, DX, NI - 1), h = 1;
            int ii = clampi(cell_of(xn, DX), 2, NI - 1);
            if (j < 2 && F[IX(ii, 1)] == NOSLIP)
                yn = 0.0, h = 1;
            else if (j > NJ - 1 && F[IX(ii, NJ)] == NOSLIP)
                yn = inside_of((double)(NJ - 2) * DY, DY, NJ - 1), h = 1;
            nheld += h;
        }
        XN[k] = xn;
        YN[k] = yn;
    }
    for (int k = 0; k < NSLOT; k++)
        if (TAG[k] != AVAIL && (!isfinite(XN[k]) || !isfinite(YN[k]))) {
            fprintf(stderr, "plain_mac: marker %d not finite\n", k + 1);
            exit(3);
        }
    return nheld;
}

/* breadth-first flood over interior cells that are not FULL, from the
 * EMP cells */
static void flood_from_empty(void) {
    const int nyu = NJ - 2;
    int n = 0;
    memset(MARK, 0, sizeof *MARK * (size_t)(NI - 2) * (size_t)nyu);
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++)
            if (F[IX(i, j)] == EMP) {
                MARK[(i - 2) * nyu + j - 2] = 1;
                QUEUE[n++] = (i - 2) * nyu + j - 2;
            }
    const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
    for (int head = 0; head < n;) {
        int k = QUEUE[head++], i = k / nyu + 2, j = k % nyu + 2;
        for (int d = 0; d < 4; d++) {
            int a = i + di[d], b = j + dj[d];
            if (!interior(a, b) || F[IX(a, b)] == FULL)
                continue;
            int kk = (a - 2) * nyu + b - 2;
            if (!MARK[kk]) {
                MARK[kk] = 1;
                QUEUE[n++] = kk;
            }
        }
    }
}

/* void_fix: empty cells no chain of empty cells joins to an EMP cell
 * become FULL with their neighbours' density */
static long fill_voids(void) {
    long filled = 0;
    flood_from_empty();
    for (int again = 1; again;) {
        again = 0;
        for (int i = 2; i <= NI - 1; i++)
            for (int j = 2; j <= NJ - 1; j++) {
                size_t c = IX(i, j);
                if (F[c] == FULL || MARK[(i - 2) * (NJ - 2) + j - 2])
                    continue;
                size_t nb[4] = {IX(i, j - 1), IX(i + 1, j), IX(i - 1, j),
                                IX(i, j + 1)};
                double s = 0;
                int cnt = 0;
                for (int d = 0; d < 4; d++) {
                    if (N[nb[d]]) {
                        s += S[nb[d]] / N[nb[d]];
                        cnt++;
                    } else if (F[nb[d]] == FULL && R[nb[d]] > 0) {
                        s += R[nb[d]];
                        cnt++;
                    }
                }
                if (!cnt) {
                    again = 1;
                    continue;
                }
                F[c] = FULL;
                R[c] = s / cnt;
                filled++;
            }
    }
    return filled;
}

/* cell flags and densities from the moved markers; 1 if a density changed */
static int correct_density(void) {
    for (size_t c = 0; c < NCELL; c++) {
        N[c] = 0;
        S[c] = 0.0;
    }
    for (int k = 0; k < NSLOT; k++) {
        if (TAG[k] == AVAIL)
            continue;
        int i = cell_of(XN[k], DX), j = cell_of(YN[k], DY);
        if (i < 1 || i > NI || j < 1 || j > NJ)
            continue;
        N[IX(i, j)]++;
        S[IX(i, j)] += DENS[k];
    }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            size_t c = IX(i, j);
            F[c] = N[c] ? FULL
                   : (N[IX(i, j + 1)] || N[IX(i, j - 1)] || N[IX(i + 1, j)] ||
                      N[IX(i - 1, j)])
                       ? SUR
                       : EMP;
        }
    int changed = 0;
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            size_t c = IX(i, j);
            if (!N[c]) {
                R[c] = 0.0;
                continue;
            }
            double q = S[c] / N[c];
            if (q != R[c]) {
                R[c] = q;
                changed = 1;
            }
        }
    voids_pass += fill_voids();
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            size_t c = IX(i, j);
            if (F[c] != SUR)
                continue;
            if (F[IX(i, j - 1)] == FULL) {
                R[c] = R[IX(i, j - 1)];
                continue;
            }
            size_t nb[4] = {IX(i, j - 1), IX(i + 1, j), IX(i - 1, j),
                            IX(i, j + 1)};
            double s = 0;
            int cnt = 0;
            for (int d = 0; d < 4; d++)
                if (N[nb[d]]) {
                    s += S[nb[d]] / N[nb[d]];
                    cnt++;
                }
            R[c] = cnt ? s / cnt : R[IX(i, j - 1)];
        }
    return changed;
}

/* after the final pass: markers entering, leaving, lost; positions kept */
static void reflag_markers(void) {
    for (int k = 0; k < NSLOT; k++) {
        int f = TAG[k];
        if (f == AVAIL)
            continue;
        int i = cell_of(XN[k], DX), j = cell_of(YN[k], DY);
        int inside = i >= 1 && i <= NI && j >= 1 && j <= NJ;
        if (f == PIN) {
            if (i < 2) {
                if (XN[k] < -DX) {
                    XN[k] = -DX;
                    in_clamped++;
                }
                continue;
            }
            TAG[k] = REG;
            entered++;
            mass_in += DENS[k] * PAREA;
            int kk;
            for (kk = 0; kk < NSLOT; kk++)
                if (TAG[kk] == AVAIL)
                    break;
            if (kk == NSLOT) {
                fprintf(stderr, "plain_mac: out of particles\n");
                exit(3);
            }
            TAG[kk] = PIN;
            XN[kk] = XN[k] - 0.5 * DX;
            YN[kk] = YN[k];
            DENS[kk] = DENS[k];
            VX[kk] = VX[k];
            VY[kk] = 0.0;
            continue;
        }
        int in_out_cell = inside && F[IX(i, j)] == OUT;
        if (f == POUT) {
            if (!in_out_cell) {
                TAG[k] = AVAIL;
                freed++;
            }
            continue;
        }
        if (in_out_cell) {
            TAG[k] = POUT;
            left_out++;
            mass_out += DENS[k] * PAREA;
        } else if (!interior(i, j)) {
            TAG[k] = AVAIL;
            if (i == 1 && j >= 2 && j <= NJ - 1 && F[IX(1, j)] == IN) {
                backflow++;
                mass_back += DENS[k] * PAREA;
            } else {
                lost++;
                mass_lost += DENS[k] * PAREA;
            }
        }
    }
    for (int k = 0; k < NSLOT; k++) {
        if (TAG[k] == AVAIL) {
            X[k] = Y[k] = VX[k] = VY[k] = 0.0;
            DENS[k] = XN[k] = YN[k] = 0.0;
        } else {
            X[k] = XN[k];
            Y[k] = YN[k];
        }
    }
}

/* temperature boundary conditions and (3.14), conduction alpha/rho */
static void temperature(void) {
    for (size_t k = 0; k < NCELL; k++)
        if (F[k] == EMP)
            T[k] = 0.0;
    for (int i = 2; i <= NI - 1; i++) {
        T[IX(i, 1)] = T[IX(i, 2)];
        T[IX(i, NJ)] = T[IX(i, NJ - 1)];
    }
    for (int j = 2; j <= NJ - 1; j++) {
        T[IX(NI, j)] = T[IX(NI - 1, j)];
        if (j <= NSUR)
            T[IX(1, j)] = TO[j]; /* the IN column */
    }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            if (F[IX(i, j)] != SUR)
                continue;
            if (F[IX(i, j + 1)] == FULL)
                T[IX(i, j)] = T[IX(i, j + 1)];
            if (F[IX(i + 1, j)] == FULL)
                T[IX(i, j)] = T[IX(i + 1, j)];
            if (F[IX(i - 1, j)] == FULL)
                T[IX(i, j)] = T[IX(i - 1, j)];
            if (F[IX(i, j - 1)] == FULL)
                T[IX(i, j)] = T[IX(i, j - 1)];
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++) {
            if (F[IX(i, j)] != FULL)
                continue;
            double tc = T[IX(i, j)];
            double tl = 0.5 * (T[IX(i - 1, j)] + tc),
                   tr = 0.5 * (T[IX(i + 1, j)] + tc);
            double tt = 0.5 * (T[IX(i, j + 1)] + tc),
                   tb = 0.5 * (T[IX(i, j - 1)] + tc);
            double dtx2 =
                (T[IX(i + 1, j)] - 2.0 * tc + T[IX(i - 1, j)]) / (DX * DX);
            double dty2 =
                (T[IX(i, j + 1)] - 2.0 * tc + T[IX(i, j - 1)]) / (DY * DY);
            TN[IX(i, j)] =
                tc + DT * ((U[IX(i, j)] * tl - U[IX(i + 1, j)] * tr) / DX +
                           (V[IX(i, j)] * tb - V[IX(i, j + 1)] * tt) / DY +
                           ALPHA / R[IX(i, j)] * (dtx2 + dty2));
        }
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++)
            if (F[IX(i, j)] == FULL)
                T[IX(i, j)] = TN[IX(i, j)];
}

/* the eight steps of the thesis */
static void step(void) {
    mirror_density();
    momentum();
    predict_density();
    int fine = 0, itnum = 0, passes = 0;
    long sweeps = 0;
    for (;;) {
        passes++;
        voids_pass = 0;
        mirror_density();
        coefficients();
        surface_pressure();
        sweeps += relax(fine);
        ghost_pressure(P);
        velocities();
        check_cfl();
        long h = move_markers();
        int changed = correct_density();
        if (fine) {
            held += h;
            voids += voids_pass;
            break;
        }
        itnum++;
        if (!changed) {
            fine = 1;
        } else if (itnum >= MAX_PASSES) {
            oscillations++;
            fine = 1;
        }
    }
    reflag_markers();
    temperature();
    passes_total += passes;
    sweeps_total += sweeps;
    last_passes = passes;
    last_sweeps = sweeps;
}

/* ------------------------------------------------------------ output */

/* largest |u|, |v| on faces of fluid cells, |div w| over FULL cells */
static void extremes(double *um, double *vm, double *dm) {
    *um = *vm = *dm = 0;
    for (int i = 2; i <= NI; i++)
        for (int j = 2; j <= NJ - 1; j++)
            if (fluidish(F[IX(i - 1, j)]) || fluidish(F[IX(i, j)]))
                *um = fmax(*um, fabs(U[IX(i, j)]));
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ; j++)
            if (fluidish(F[IX(i, j - 1)]) || fluidish(F[IX(i, j)]))
                *vm = fmax(*vm, fabs(V[IX(i, j)]));
    for (int i = 2; i <= NI - 1; i++)
        for (int j = 2; j <= NJ - 1; j++)
            if (F[IX(i, j)] == FULL) {
                double d = fabs((U[IX(i + 1, j)] - U[IX(i, j)]) / DX +
                                (V[IX(i, j + 1)] - V[IX(i, j)]) / DY);
                if (d > *dm)
                    *dm = d;
            }
}

static double fluid_mass(void) {
    double s = 0;
    for (int k = 0; k < NSLOT; k++)
        if (TAG[k] == REG)
            s += DENS[k] * PAREA;
    return s;
}

static void put_field(FILE *o, const double *f, int ni1, int nj1) {
    for (int i = 1; i <= ni1; i++)
        fwrite(&f[IX(i, 1)], sizeof *f, (size_t)nj1, o);
}

/* one output row: the fields, the markers, counts, masses, diagnostics */
static void write_row(FILE *o) {
    put_field(o, U, NI + 1, NJ);
    put_field(o, V, NI, NJ + 1);
    put_field(o, P, NI, NJ);
    put_field(o, R, NI, NJ);
    put_field(o, T, NI, NJ);
    for (int i = 1; i <= NI; i++)
        for (int j = 1; j <= NJ; j++) {
            int64_t f = F[IX(i, j)];
            fwrite(&f, sizeof f, 1, o);
        }
    fwrite(X, sizeof *X, (size_t)NSLOT, o);
    fwrite(Y, sizeof *Y, (size_t)NSLOT, o);
    fwrite(DENS, sizeof *DENS, (size_t)NSLOT, o);
    int64_t fc[5] = {0};
    for (int k = 0; k < NSLOT; k++) {
        int64_t t = TAG[k];
        fwrite(&t, sizeof t, 1, o);
        fc[TAG[k]]++;
    }
    int64_t counts[8] = {fc[PIN], fc[REG],  fc[POUT], fc[AVAIL],
                         entered, left_out, backflow, lost};
    fwrite(counts, sizeof counts[0], 8, o);
    double mass[4] = {mass_in, mass_out, fluid_mass(), mass_lost};
    fwrite(mass, sizeof mass[0], 4, o);
    double um, vm, dm;
    extremes(&um, &vm, &dm);
    double diag[6] = {
        um, vm, dm, last_passes, (double)last_sweeps, (double)oscillations};
    fwrite(diag, sizeof diag[0], 6, o);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: plain_mac OUT.bin [REFINE [DT [T_END "
                        "[OUTPUT_EVERY]]]]\n");
        return 2;
    }
    int r = argc > 2 ? atoi(argv[2]) : 4;
    DT = argc > 3 ? strtod(argv[3], NULL) : 0.0125;
    double t_end = argc > 4 ? strtod(argv[4], NULL) : 10.0;
    long every = argc > 5 ? atol(argv[5]) : 40;
    if (r < 1 || r > 8 || !(DT > 0) || every < 1) {
        fprintf(stderr, "plain_mac: bad arguments\n");
        return 2;
    }
    long nsteps = lround(t_end / DT);
    setup(r);
    FILE *o = fopen(argv[1], "wb");
    if (!o) {
        perror(argv[1]);
        return 1;
    }
    write_row(o);
    for (long n = 1; n <= nsteps; n++) {
        step();
        if (n % every == 0 || n == nsteps)
            write_row(o);
    }
    if (fclose(o)) {
        perror(argv[1]);
        return 1;
    }
    double um, vm, dm;
    extremes(&um, &vm, &dm);
    printf("plain_mac: %ld steps, passes %lld, sweeps %lld, entered %lld, "
           "into the sink %lld, back %lld, lost %lld, held %lld, voids %lld, "
           "oscillations %lld\n",
           nsteps, passes_total, sweeps_total, entered, left_out, backflow,
           lost, held, voids, oscillations);
    printf("plain_mac: max |u| %.17g, max |v| %.17g, max |div w| %.17g, "
           "fluid mass %.17g, mass in %.17g, mass out %.17g\n",
           um, vm, dm, fluid_mass(), mass_in, mass_out);
    return 0;
}
