/* nodes.h: the `nodes` quadrature of the coupling integral (Yasuda eq.
 * 3.10), private to the coupling.  The integral is summed at the film's
 * nodes and the node values are interpolated:
 *
 *   I_i  = dx sum_j g_j exp(-|x_j - x_i|/r0),   g = h (psi - psi_s)^2,
 *   I(r) = S(r), dI/dr = S'(r),
 *
 * S the natural cubic spline through (x_i, I_i) (the paper's "third-order
 * spline" read as a spline through node values; F_i = 4 pi R^2 V0 I_i is
 * its F_i = sum_j h_j V(x_j - x_i) (psi_j - psi_s)^2 dx).  Beyond the end
 * nodes S continues as the straight line of its end slope (the natural
 * spline's extension, S'' = 0 there).
 *
 * Its error against the exact integral has two parts: the node sum is the
 * trapezoidal rule on each side of the kernel's kink at x_i, which makes
 * I_i too large by dx^2 g(x_i) / (6 r0) + O(dx^4) (Euler-Maclaurin: the
 * jump 2 g / r0 of the integrand's slope at the kink, times dx^2/12), a
 * smooth error; the spline between the nodes adds an O(dx^4) error that
 * vanishes at the nodes, a ripple with the period of the grid, whose
 * phase is set by where the nodes lie (a node at x = 0 for L = 50 cm, nodes
 * at +-0.05 cm for L = 50.1 cm).
 *
 * Cost: per film level, on the first evaluation, two recurrences over the
 * nodes (a_i = g_i + E a_i-1, b_i = g_i + E b_i+1, E = exp(-dx/r0):
 * I_i = dx (a_i + b_i - g_i)) and one tridiagonal solve; then O(1) per
 * evaluation. */
#ifndef BALLFILM_COUPLING_NODES_H
#define BALLFILM_COUPLING_NODES_H

typedef struct bf_coupling_nodes bf_coupling_nodes;

/* For nodes x_i = x0 + i dx, i = 0..N (N >= 1), kernel range r0 > 0.
 * NULL: out of memory. */
bf_coupling_nodes *bf_coupling_nodes_create(long N, double dx, double r0);
void bf_coupling_nodes_free(bf_coupling_nodes *q);

/* The film has a new level: the node values are recomputed at the next
 * evaluation. */
void bf_coupling_nodes_invalidate(bf_coupling_nodes *q);

/* I(r) and dI/dr from g on the nodes (the g of the current level), r in
 * cell j at t = (r - x_j)/dx (bf_coupling_locate: t outside [0, 1]
 * beyond the end nodes). */
void bf_coupling_nodes_eval(bf_coupling_nodes *q, const double *g, long j,
                            double t, double *I, double *dI);

#endif
