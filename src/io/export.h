/* export.h: a run's particles in formats other programs read (private to
 * the io layer and the command line; `ballfilm export`).
 *
 * The particles of a run's file -- the balls of a balls or coupled run
 * (dimension 1), Greenspan's particles (greenspan72, greenspan73;
 * dimension 2) or the MAC markers -- are written as
 *   H5MD 1.1    /h5md (version, author, creator), /particles/<group>/
 *               {position, velocity, species, mass, box} with their time
 *               series (value, step, time) and H5MD units, energies under
 *               /observables (MDAnalysis, VMD's H5MD plugin, h5py);
 *   extxyz      one frame per output row: species, position and velocity
 *               as properties, the time in the comment line (OVITO, ASE).
 * The input is read through the checked reader (h5check.h: every dataset
 * of the class, rank and shape expected, and no more rows than the file
 * can hold; a killed run's file up to its last complete flush).  The
 * output is written to OUT.tmp, opened without following a link
 * (outpath.h), and renamed onto OUT at the end: a failure or SIGINT /
 * SIGTERM leaves no partial file. */
#ifndef BALLFILM_IO_EXPORT_H
#define BALLFILM_IO_EXPORT_H

#include <signal.h>

#include "ballfilm/error.h"

typedef enum { BF_EXPORT_H5MD, BF_EXPORT_EXTXYZ } bf_export_format;

typedef struct bf_export_opts {
    bf_export_format format;
    /* H5MD for MDAnalysis 2.4, which reads only 3-D boxes and lengths in
     * nm or Angstrom: dimension 3 (missing coordinates 0), positions in
     * nm, velocities in m s-1 (CGS runs only). */
    int mdanalysis;
} bf_export_opts;

/* Export the particles of in_path to out_path.  BF_EINPUT: no such file,
 * not a run's file, a file without particles (naming what is supported),
 * damaged datasets, out_path the input itself; BF_EIO: a symbolic link or
 * another user's file at out_path, or writing failed; BF_INTERRUPTED once
 * *stop_flag is set (NULL: never), checked for every row. */
bf_status bf_export(const char *in_path, const char *out_path,
                    const bf_export_opts *o,
                    const volatile sig_atomic_t *stop_flag, bf_err *err);

#endif
