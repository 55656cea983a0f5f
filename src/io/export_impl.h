/* export_impl.h: the particles of a run's file as the exporters read them
 * (private to src/io: export_file.c, export_h5md.c, export_xyz.c). */
#ifndef BALLFILM_IO_EXPORT_IMPL_H
#define BALLFILM_IO_EXPORT_IMPL_H

#include <hdf5.h>
#include <signal.h>
#include <stdio.h>

#include "ballfilm/error.h"
#include "io/export.h"
#include "io/h5part.h"

/* An observable: a column of a series of the run's rows (/time). */
typedef struct bf_xobs {
    const char *name, *path; /* H5MD name; dataset */
    int column;              /* -1: a 1-D series */
} bf_xobs;

/* The datasets read frame by frame, each opened once (bf_xsrc_read):
 * their paths (the constant strings of bf_xsrc) and handles. */
enum { BF_XSRC_DSETS = 16 };
typedef struct bf_xsrc_dsets {
    const char *path[BF_XSRC_DSETS];
    hid_t id[BF_XSRC_DSETS];
    size_t n;
} bf_xsrc_dsets;

typedef struct bf_xsrc {
    hid_t h5;
    bf_xsrc_dsets *dsets; /* opened datasets (NULL: none kept) */
    const char *file;  /* for messages */
    double bytes;      /* its size on disk */
    bf_h5_flushed *fl; /* a killed run's rows, or NULL */
    const volatile sig_atomic_t *stop;
    const char *group; /* "balls", "greenspan", "markers" */
    int dim;           /* 1 or 2 */
    size_t n, rows;    /* particles, frames */
    const char *pos[2], *vel[2]; /* series [rows x n]; vel[0] NULL: none */
    const char *mass;            /* [n], or NULL */
    const char *species;         /* [n] (tag), [rows x n] (flag), or NULL */
    int species_rows;            /* species is a series */
    int species_fixed;           /* species = 1 + /particles/fixed */
    const char *density;         /* MAC: [rows x n] */
    double *time;                /* [rows] */
    long long *step;             /* [rows] */
    int half_step;   /* velocities v^{k-1/2}: (k - 1/2) dt, row 0 at t 0 */
    double dt;
    const char *unit_len, *unit_vel, *unit_time, *unit_mass, *unit_energy,
        *unit_density;
    bf_xobs obs[4];
    size_t n_obs, obs_rows; /* rows of /time and /step */
} bf_xsrc;

/* Open and check in_path; BF_EINPUT naming what is supported when it has
 * no particles. */
bf_status bf_xsrc_open(bf_xsrc *s, const char *in_path, bf_err *err);
void bf_xsrc_close(bf_xsrc *s);
/* Row k of series path (n values), or all of a 1-D dataset of n values
 * (k ignored), as doubles into buf. */
bf_status bf_xsrc_read(const bf_xsrc *s, const char *path, size_t k,
                       size_t n, double *buf, bf_err *err);
/* The species of row k (n values, from 1). */
bf_status bf_xsrc_species(const bf_xsrc *s, size_t k, double *buf,
                          bf_err *err);
/* BF_INTERRUPTED once the stop flag is set. */
bf_status bf_xsrc_stopped(const bf_xsrc *s, bf_err *err);

bf_status bf_export_h5md(const bf_xsrc *s, const char *h5name,
                         const bf_export_opts *o, bf_err *err);
bf_status bf_export_xyz(const bf_xsrc *s, FILE *f, bf_err *err);

#endif
