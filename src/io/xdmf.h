/* xdmf.h: an XDMF sidecar for a ballfilm output file, so that ParaView
 * (either of its XDMF readers) and VisIt open the run (private to the io
 * layer and its users).
 *
 * The sidecar is XML that points at the HDF5 datasets by path (with the
 * HDF5 file named relative to the sidecar, so the two move together);
 * only point coordinates are copied into it.  It holds one temporal
 * collection per thing the file describes, with one grid per output row:
 *   film       a 1-D grid on /film/x with psi, h, u_d, u_c (rows of
 *              /film/time; in a run with balls, at the balls' times, each
 *              grid holding the last profile at or before it);
 *   balls      points on the line with velocity, mass and radius (rows of
 *              /time);
 *   particles  points (x, y) with vx, vy, fluid tag, mass and the 1973
 *              wall flags (rows of /particles/step, or of /time);
 *   mac        the staggered MAC grid: p, rho, T and the cell flags on the
 *              cells, u on the vertical faces and v on the horizontal faces
 *              (each on a mesh of its own points), and the markers as
 *              points with density and flag (rows of /time).
 * Which of them a file has is decided by the datasets present.
 */
#ifndef BALLFILM_IO_XDMF_H
#define BALLFILM_IO_XDMF_H

#include <signal.h>
#include <stddef.h>

#include "ballfilm/error.h"

/* Grids per temporal collection at most, by default: a series with more
 * rows is thinned to every k-th row (and the last), which the sidecar
 * says in a comment. */
#define BF_XDMF_MAX_STEPS 2000

/* What a sidecar may cost: BF_XDMF_BUDGET_BYTES plus
 * BF_XDMF_BUDGET_RATIO times the HDF5 file's size on disk.  The sidecar
 * of any file ballfilm writes takes a few times its file at most (a grid
 * of a few hundred bytes for every output row, which takes tens of bytes
 * in the file, or a few even compressed); a file that claims more (a grid
 * of 10^12 cells, a series of 2^34 columns that holds no data) is
 * refused at the start with BF_EINPUT, naming the file and the dataset,
 * and a running check stops one that grows past it. */
#define BF_XDMF_BUDGET_BYTES (16.0 * 1024 * 1024)
#define BF_XDMF_BUDGET_RATIO 256.0

/* Write the sidecar of h5_path to xmf_path with at most max_steps grids
 * per collection (0: one per row).  Every dataset it names is checked
 * first (h5check.h: numbers of rank 1 or 2 that the file can hold, and
 * the numbers of /mac/grid and /film/x consistent with the series that
 * use them).  xmf_path is written in place without following a link; a
 * symbolic link or a file of another user there is refused (BF_EIO).
 * Stops with BF_INTERRUPTED once *stop_flag is set (NULL: never), checked
 * for every grid and in the loops of values written inline.  A sidecar
 * that fails leaves no partial file: one it created is removed, one it
 * wrote over is cut to nothing. */
bf_status bf_xdmf_write_n(const char *h5_path, const char *xmf_path,
                          size_t max_steps,
                          const volatile sig_atomic_t *stop_flag,
                          bf_err *err);
/* OUT.h5 -> OUT.xmf (malloc'd; NULL when out of memory). */
char *bf_xdmf_default_path(const char *h5_path);

#endif
