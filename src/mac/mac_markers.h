/* mac_markers.h: the marker particles of the MAC solver, the cell flags
 * and the density corrected from them (mac_markers.c; private).  Built on
 * mac_grid.c. */
#ifndef BALLFILM_MAC_MARKERS_H
#define BALLFILM_MAC_MARKERS_H

#include "mac/mac_grid.h"

/* How a corrector pass moves the markers: FIRST moves every one and keeps
 * the pass as the reference of the step; CELLS (a later pass before the
 * final one: only the cells the markers land in are needed) leaves
 * unmoved the markers that cannot change cell since the reference; ALL
 * moves every one (the final pass: every position). */
typedef enum bf_mac_move {
    BF_MAC_MOVE_FIRST,
    BF_MAC_MOVE_CELLS,
    BF_MAC_MOVE_ALL
} bf_mac_move;
/* Move the markers from their positions at t = n dt with the current face
 * velocities (into m->xn, m->yn, their cells into m->mcell); returns the
 * moves held at a wall (of the moved markers: exact for FIRST and ALL).
 * Every mode gives every marker the cell a full move gives it. */
long bf_mac_move_markers(bf_mac *m, bf_mac_move mode);
/* BF_EUNSTABLE naming the first marker whose new position is not finite. */
bf_status bf_mac_markers_finite(const bf_mac *m, bf_err *err);
/* Cell flags and densities from the moved markers; returns 1 if a cell
 * density changed. */
int bf_mac_correct_density(bf_mac *m);
/* After the final pass: markers entering, leaving, lost; positions
 * committed.  BF_EUNSTABLE when no slot is free for a new IN marker. */
bf_status bf_mac_reflag_markers(bf_mac *m, bf_err *err);
/* Number of empty cells enclosed by fluid, and the first of them. */
int bf_mac_find_void(bf_mac *m, int *vi, int *vj);

#endif
