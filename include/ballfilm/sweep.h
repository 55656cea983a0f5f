/* sweep.h: parameter sweeps — one scene run for every combination of a few
 * varied keys, each case in its own HDF5 file, a summary table at the end.
 *
 * The library side is the same for the serial program, the local process
 * pool and the MPI program (src/cli/cmd_sweep.c): a case is identified by
 * its index, runs entirely in one call (bf_sweep_run_case) with its own
 * scene and simulation objects (no shared mutable state), and records its
 * summary row in DIR/case_NNNNN.done, written atomically when the case
 * ends.  A sweep run again skips the cases that have a .done file, so a
 * killed sweep completes only what is missing, except the cases whose row
 * records a failure to write (BF_EIO: a full disk, a quota), which it runs
 * again (bf_sweep_case_pending).  DIR/sweep.txt ties the
 * directory to one sweep: the scene's path and a hash of its contents,
 * the overrides, the varied values; a rerun after an edit of the scene is
 * refused instead of reusing results of the old scene.
 */
#ifndef BALLFILM_SWEEP_H
#define BALLFILM_SWEEP_H

#include <stddef.h>
#include <signal.h>
#include <stdio.h>

#include "ballfilm/error.h"
#include "ballfilm/scene.h"

#define BF_SWEEP_MAX_VARY 8
#define BF_SWEEP_FILL_BINS 50

typedef struct bf_sweep_axis {
    char key[256];  /* "section.key" */
    size_t n;       /* number of values */
    double *values;
} bf_sweep_axis;

typedef struct bf_sweep {
    char scene_path[1024];
    char dir[1024];
    bf_scene *base; /* scene with the fixed overrides applied (unresolved) */
    bf_sweep_axis axis[BF_SWEEP_MAX_VARY];
    size_t naxis;
    size_t ncases;
    /* set asynchronously (a signal) to stop the running case like an
     * interrupted run; NULL: none */
    const volatile sig_atomic_t *stop_flag;
} bf_sweep;

/* One summary row (what rank 0 gathers). */
typedef struct bf_sweep_row {
    long index;
    double values[BF_SWEEP_MAX_VARY];
    int status;            /* bf_status of the case */
    double wall;           /* s of wall time for the case */
    double lyapunov;       /* largest Lyapunov exponent (1/s) or NAN */
    double map_points;     /* number of return-map points or NAN */
    double map_fill;       /* fraction of the map's bounding box visited
                              (see bf_sweep_map_fill) or NAN */
    double energy_error;   /* max relative energy error or NAN */
    long steps;
    char message[512];
} bf_sweep_row;

/* Parse "section.key=START:STOP:COUNT" (COUNT values, ends included) or
 * "section.key=v1,v2,...". */
bf_status bf_sweep_parse_axis(bf_sweep_axis *ax, const char *spec, bf_err *err);

/* Set up a sweep over `scene_path` with fixed overrides `sets` into `dir`
 * (created if needed; if it holds another sweep, refused). */
bf_status bf_sweep_init(bf_sweep *sw, const char *scene_path,
                        const char *const *sets, size_t nsets,
                        const char *const *vary, size_t nvary, const char *dir,
                        bf_err *err);
void bf_sweep_free(bf_sweep *sw);

/* Parameter values of case k (row-major: the last axis varies fastest). */
void bf_sweep_case_values(const bf_sweep *sw, long k, double *values);
/* 1 if case k already has its summary row on disk (then *row is filled). */
int bf_sweep_case_done(const bf_sweep *sw, long k, bf_sweep_row *row);

/* Which recorded failures a rerun of a sweep runs again. */
typedef enum bf_sweep_retry {
    /* only failures to write (BF_EIO): the disk may have room now; a bad
     * value, an unstable run or a missed convergence would fail the same
     * way again */
    BF_SWEEP_RETRY_IO = 0,
    /* every failed case (any status but BF_OK), e.g. after the program
     * was rebuilt or memory was made available */
    BF_SWEEP_RETRY_FAILED = 1
} bf_sweep_retry;

/* 1 if case k is to be run: it has no summary row yet (never run, killed
 * or interrupted), or its row records a failure that `retry` runs again.
 * *row receives the recorded row when there is one (row->index is -1
 * otherwise), so that the caller can say why a case runs again. */
int bf_sweep_case_pending(const bf_sweep *sw, long k, bf_sweep_retry retry,
                          bf_sweep_row *row);
/* Run case k from scratch and write its .done row.  A failing case is not
 * an error of the sweep: its status and message go into the row.  A case
 * stopped by sw->stop_flag writes no .done row (a rerun runs it again) and
 * returns BF_INTERRUPTED. */
bf_status bf_sweep_run_case(const bf_sweep *sw, long k, bf_sweep_row *row,
                            bf_err *err);

/* Fraction of the bounding box of the points (z_k, v_k) that they visit,
 * counted on a B x B grid with B = sqrt(n/4) clamped to [5,
 * BF_SWEEP_FILL_BINS], i.e. about four points per bin, so that the number
 * does not depend on how many points a run collected: near 1 - e^-4 for a
 * map that fills its box evenly (chaos), about 1/B for closed curves
 * (quasi-periodic motion), in between for islands and bands.  NAN for
 * fewer than 2 points. */
double bf_sweep_map_fill(const double *z, const double *v, size_t n);

/* Serialise a row as one CSV line (no newline) and back. */
void bf_sweep_row_format(const bf_sweep *sw, const bf_sweep_row *row, char *buf,
                         size_t cap);
int bf_sweep_row_parse(const bf_sweep *sw, const char *line, bf_sweep_row *row);

/* Write DIR/summary.h5 and DIR/summary.csv from all rows (ordered by case). */
bf_status bf_sweep_write_summary(const bf_sweep *sw, const bf_sweep_row *rows,
                                 bf_err *err);

#endif
