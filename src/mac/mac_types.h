/* mac_types.h: the types of the MAC solver that its interface (mac.h)
 * and its internals (mac_grid.h) share: cell and particle flags, the
 * [mac] parameters, the counters (private; declares no functions, so
 * that neither header includes the other). */
#ifndef BALLFILM_MAC_TYPES_H
#define BALLFILM_MAC_TYPES_H

#include <stdint.h>

/* Cell flags IC of the listing (line 2339, corrected: the code sets the
 * left wall to 2 and the outflow cells to 3).  FREESLIP is not in the
 * listing: a slip wall for the uniform-flow check. */
enum {
    BF_MAC_NOSLIP = 1,
    BF_MAC_IN = 2,
    BF_MAC_OUT = 3,
    BF_MAC_FREESLIP = 4,
    BF_MAC_FULL = 10,
    BF_MAC_SUR = 11,
    BF_MAC_EMP = 12
};

/* Particle flags F of the listing (line 2418). */
enum {
    BF_MAC_AVAIL = 1, /* free slot */
    BF_MAC_PIN = 2,   /* in the IN column, waiting to enter */
    BF_MAC_POUT = 3,  /* in an OUT cell, leaving */
    BF_MAC_REG = 4    /* in the fluid */
};

/* The values of [mac] problem, update and pressure_solver: the index of
 * the choice in the key's list (bf_mac_spec). */
typedef enum bf_mac_problem {
    BF_MAC_RESERVOIR = 0, /* PROGRAM STRATRES: IN left, sink in the bottom */
    BF_MAC_REST = 1,      /* the same fluid in a closed tank: nothing moves */
    BF_MAC_UNIFORM = 2    /* uniform horizontal stream, IN left, OUT right */
} bf_mac_problem;

/* Velocity update and the pressure equation solved with it. */
typedef enum bf_mac_update {
    /* (3.11)/(3.12) "modified" update with (3.10) as printed (face
     * densities): the thesis and the listing.  The pressure equation is
     * derived from (3.6)-(3.9), not from the update applied. */
    BF_MAC_PRINTED = 0,
    /* (3.11)/(3.12) with the pressure equation derived from them: the
     * coefficients use cell densities, C = (2dt/dx^2 + 2dt/dy^2)/rho_ij,
     * B1 = dt/(dx^2 rho_{i+1,j} C), ... */
    BF_MAC_CONSISTENT = 1,
    /* (3.6)-(3.9) with (3.10): the unmodified, self-consistent pair. */
    BF_MAC_ORIGINAL = 2
} bf_mac_update;

typedef enum bf_mac_solver {
    BF_MAC_RELAX = 0, /* Gauss-Seidel with the listing's crude/fine tests */
    BF_MAC_DIRECT = 1 /* band Cholesky, checked to a residual tolerance */
} bf_mac_solver;

/* The [mac] section (bf_mac_spec fills it: each member has the C type of
 * its key's kind, int for choices and booleans, long for integers). */
typedef struct bf_mac_params {
    int problem;           /* bf_mac_problem */
    long refine;           /* (14 refine + 2)^2 cells, dx = dy = 0.1/refine */
    int update;            /* bf_mac_update */
    int solver;            /* bf_mac_solver ([mac] pressure_solver) */
    int compare;           /* with RELAX: also solve exactly, record diff */
    double crude_tol;      /* listing .0003 */
    double fine_tol;       /* listing .0002 */
    long max_sweeps;       /* listing 500 */
    double omega;          /* over-relaxation; listing 1 */
    double direct_tol;     /* relative residual of the direct solve */
    long max_passes;       /* corrector passes before the fine pass; 10 */
    int stop_on_oscillation; /* [mac] oscillation = stop: BF_ENOCONV
                                instead of the listing's "OSCILLATING
                                PARTICLE" + forced fine pass */
    int predict;           /* put the prediction (3.13) into R (thesis) */
    double mu, alpha, g;   /* listing .000114, .0000141, -.98 */
    double rho_mean, rho_amp; /* .9985, .0015 (tanh profile) */
    double t_mean, t_amp;  /* 15, 10 */
    int kappa_listing;     /* [mac] conduction = listing: ALPHA*MU/R
                              instead of alpha/rho */
    long out_first;        /* first OUT cell of the 16x16 listing grid: 13 */
    int out_gravity;       /* add rho |g| dy to the OUT ghost pressure */
    int inflow_prescribed; /* [mac] inflow = prescribed: the reservoir's
                              u_in = u0 instead of the copy rule */
    double u0;             /* uniform problem: stream speed */
    int void_fix;          /* empty cells enclosed by fluid become FULL */
    int wall_remove;       /* [mac] wall_markers = remove: markers crossing
                              a wall are removed (the listing); hold: held
                              on the wall */
    long slots;            /* particle slots; 0: 800 refine^2 */
    double max_cfl;        /* stop when |u| dt/dx exceeds this */
} bf_mac_params;

/* Counters, cumulative since t = 0 (masses: particle density times its
 * share dx dy / 4 of a cell). */
typedef struct bf_mac_counts {
    int64_t entered;     /* IN particles that crossed into the fluid */
    int64_t left_out;    /* fluid particles that entered an OUT cell */
    int64_t freed;       /* OUT particles that left the grid (slot freed) */
    int64_t backflow;    /* fluid particles that went back into the IN column */
    int64_t lost;        /* fluid particles that crossed a wall or the top */
    int64_t in_clamped;  /* IN particles held at the ring's outer edge */
    int64_t held;        /* fluid particle moves stopped at a wall */
    int64_t voids;       /* cells filled by void_fix (final passes) */
    int64_t oscillations; /* steps whose corrector loop hit max_passes */
    int64_t passes;      /* corrector passes (pressure solves) */
    int64_t sweeps;      /* Gauss-Seidel sweeps */
    int64_t max_sweeps_step; /* largest sweeps in one pressure solve */
    double mass_in, mass_out, mass_back, mass_lost;
    double max_gs_dp;    /* compare: max |P_gs - P_exact| / |rho g DEPTH| */
    double max_gs_du;    /* compare: max face-velocity difference */
} bf_mac_counts;

typedef struct bf_mac bf_mac;

#endif
