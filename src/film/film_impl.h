/* film_impl.h: the film's storage, shared by the files of src/film (the
 * scheme film.c, the diagnostics film_diag.c, the mirror projection
 * film_mirror.c, the state and checkpoint film_state.c); private.
 *
 * Layout: every node array has one ghost each side (index -1..N+1), face
 * arrays hold face i+1/2 at index i (-1..N); all in one allocation, each
 * array 64-byte aligned at index 0 (see film.c).
 */
#ifndef BALLFILM_FILM_IMPL_H
#define BALLFILM_FILM_IMPL_H

#include "ballfilm/film.h"

enum {
    /* node arrays */
    V_X, V_AD, V_AC, V_UD, V_UC, V_H, V_PSI, V_MU, V_WD, V_WC,
    V_AD1, V_AC1, V_UD1, V_UC1, V_H1, V_PSI1, V_MU1,
    /* round-off compensation of alpha_k h (see update_loop), old and new */
    V_KD, V_KC, V_KD1, V_KC1,
    /* face arrays */
    V_FD, V_FC, V_GD, V_GC,
    V_COUNT
};

struct bf_film {
    bf_film_params p;
    long N;      /* intervals; nodes 0..N */
    size_t len;  /* allocated length of each array (N + 3) */
    double *mem;
    double *v[V_COUNT]; /* each points at index 0 (ghost at -1) */
    double *zero;       /* mu_cpl of a step given none: zeros */
    unsigned long long lim_steps, lim_faces;
};

#define ARR(f, k) ((f)->v[k])

#endif
