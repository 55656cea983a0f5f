/* export_file.c: the particles of a run's file, read through the checked
 * reader, and the output file of `ballfilm export` (see export.h). */
#include "io/export_impl.h"
#include "io/h5check.h"
#include "io/outpath.h"
#include "io/dataset_paths.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Dataset path checked as h5check.h says: rank `rank`, numbers, rows (of
 * the last complete flush of a killed run) the file can hold.  Its rows
 * and columns (0 for rank 1) in *rows, *cols. */
static bf_status check(const bf_xsrc *s, const char *path, int rank,
                       size_t *rows, size_t *cols, bf_err *err)
{
    if (H5Lexists(s->h5, path, H5P_DEFAULT) <= 0)
        return bf_fail(err, BF_EINPUT, "%s: has no dataset %s", s->file,
                       path);
    hid_t d = H5Dopen2(s->h5, path, H5P_DEFAULT);
    if (d < 0)
        return bf_fail(err, BF_EINPUT, "%s: %s is not a dataset", s->file,
                       path);
    int r = 0;
    hsize_t dims[2];
    bf_status st = bf_h5_dataset_rows(d, s->file, path, s->fl, s->bytes, &r,
                                      dims, NULL, err);
    if (!st && r != rank)
        st = bf_fail(err, BF_EINPUT, "%s: %s has rank %d, not %d", s->file,
                     path, r, rank);
    H5Dclose(d);
    if (!st) {
        *rows = (size_t)dims[0];
        *cols = rank == 2 ? (size_t)dims[1] : 0;
    }
    return st;
}

static int has(const bf_xsrc *s, const char *path)
{
    return path && H5Lexists(s->h5, path, H5P_DEFAULT) > 0;
}

/* Dataset path of s, opened at its first read and kept open for the
 * frames after it; *own: the caller closes it (no room to keep it). */
static hid_t dataset(const bf_xsrc *s, const char *path, int *own)
{
    bf_xsrc_dsets *c = s->dsets;
    for (size_t k = 0; c && k < c->n; k++)
        if (!strcmp(c->path[k], path)) {
            *own = 0;
            return c->id[k];
        }
    hid_t d = H5Dopen2(s->h5, path, H5P_DEFAULT);
    *own = !(d >= 0 && c && c->n < BF_XSRC_DSETS);
    if (!*own) {
        c->path[c->n] = path;
        c->id[c->n++] = d;
    }
    return d;
}

bf_status bf_xsrc_read(const bf_xsrc *s, const char *path, size_t k,
                       size_t n, double *buf, bf_err *err)
{
    int own;
    hid_t d = dataset(s, path, &own);
    hid_t fsp = d < 0 ? -1 : H5Dget_space(d);
    const int rank = fsp < 0 ? 0 : H5Sget_simple_extent_ndims(fsp);
    hsize_t start[2] = {rank == 2 ? k : 0, 0}, count[2] = {1, n};
    if (rank == 1)
        count[0] = n;
    hid_t msp = H5Screate_simple(rank == 2 ? 2 : 1, count, NULL);
    herr_t rc = -1;
    if ((rank == 1 || rank == 2) &&
        H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, count,
                            NULL) >= 0)
        rc = n ? H5Dread(d, H5T_NATIVE_DOUBLE, msp, fsp, H5P_DEFAULT, buf)
               : 0;
    H5Sclose(msp);
    if (fsp >= 0)
        H5Sclose(fsp);
    if (d >= 0 && own)
        H5Dclose(d);
    return rc < 0 ? bf_fail(err, BF_EIO, "%s: cannot read row %zu of %s",
                            s->file, k, path)
                  : BF_OK;
}

bf_status bf_xsrc_species(const bf_xsrc *s, size_t k, double *buf,
                          bf_err *err)
{
    if (!s->species) {
        for (size_t i = 0; i < s->n; i++)
            buf[i] = 1;
        return BF_OK;
    }
    bf_status st = bf_xsrc_read(s, s->species, k, s->n, buf, err);
    for (size_t i = 0; !st && s->species_fixed && i < s->n; i++)
        buf[i] = 1 + (buf[i] != 0);
    return st;
}

bf_status bf_xsrc_stopped(const bf_xsrc *s, bf_err *err)
{
    return s->stop && *s->stop ? bf_fail(err, BF_INTERRUPTED, "interrupted")
                               : BF_OK;
}

/* Which particles the file holds, their series and units. */
static bf_status choose(bf_xsrc *s, bf_err *err)
{
    static const bf_xobs energies[] = {
        {"kinetic_energy", BF_DS_ENERGY_KINETIC, -1},
        {"potential_energy", BF_DS_ENERGY_POTENTIAL, -1},
        {"total_energy", BF_DS_ENERGY_TOTAL, -1}};
    s->unit_len = "cm";
    s->unit_vel = "cm s-1";
    s->unit_time = "s";
    s->unit_mass = "g";
    s->unit_energy = "erg";
    if (has(s, BF_DS_BALLS_POSITION)) {
        s->group = "balls";
        s->dim = 1;
        s->pos[0] = BF_DS_BALLS_POSITION;
        s->vel[0] = BF_DS_BALLS_VELOCITY;
        s->mass = BF_DS_BALLS_MASS;
    } else if (has(s, BF_DS_PARTICLES_X)) {
        s->group = "greenspan";
        s->dim = 2;
        s->pos[0] = BF_DS_PARTICLES_X;
        s->pos[1] = BF_DS_PARTICLES_Y;
        s->vel[0] = BF_DS_PARTICLES_VX;
        s->vel[1] = BF_DS_PARTICLES_VY;
        s->mass = BF_DS_PARTICLES_MASS;
        /* only Greenspan 1972 writes /particles/step: its leapfrog keeps
         * half-step velocities only (docs/models/greenspan72.md) */
        s->half_step = has(s, BF_DS_PARTICLES_STEP);
        if (has(s, BF_DS_PARTICLES_TAG)) {
            s->species = BF_DS_PARTICLES_TAG;
        } else if (has(s, BF_DS_PARTICLES_FIXED)) {
            s->species = BF_DS_PARTICLES_FIXED;
            s->species_fixed = 1;
        }
        if (s->half_step) {
            static const bf_xobs g72[] = {
                {"kinetic_energy", BF_DS_DIAG_KINETIC, 0}};
            s->obs[0] = g72[0];
            s->n_obs = 1;
        }
    } else if (has(s, BF_DS_MAC_PARTICLES_X)) {
        s->group = "markers";
        s->dim = 2;
        s->pos[0] = BF_DS_MAC_PARTICLES_X;
        s->pos[1] = BF_DS_MAC_PARTICLES_Y;
        s->species = BF_DS_MAC_PARTICLES_FLAG;
        s->species_rows = 1;
        s->density = BF_DS_MAC_PARTICLES_DENSITY;
        /* the thesis's scaled units: length L, velocity W, density R */
        s->unit_len = "L";
        s->unit_time = "L W-1";
        s->unit_density = "R";
    } else {
        return bf_fail(err, BF_EINPUT, "%s: holds no particles; export "
                       "supports the balls of balls and coupled runs, the "
                       "particles of greenspan72 and greenspan73 runs and the "
                       "markers of mac runs", s->file);
    }
    if (!s->n_obs && strcmp(s->group, "markers"))
        for (size_t k = 0; k < 3; k++)
            if (has(s, energies[k].path))
                s->obs[s->n_obs++] = energies[k];
    return BF_OK;
}

/* The series' shapes, the frames and their times and steps. */
static bf_status shapes(bf_xsrc *s, bf_err *err)
{
    size_t rows = SIZE_MAX, r, c, n = 0;
    const char *series[6] = {s->pos[0], s->pos[1], s->vel[0], s->vel[1],
                             s->species_rows ? s->species : NULL,
                             s->density};
    bf_status st = BF_OK;
    for (int k = 0; k < 6 && !st; k++) {
        if (!series[k])
            continue;
        if ((st = check(s, series[k], 2, &r, &c, err)))
            break;
        if (k && c != n)
            st = bf_fail(err, BF_EINPUT, "%s: %s has %zu columns, %s %zu",
                         s->file, series[k], c, s->pos[0], n);
        n = c;
        rows = r < rows ? r : rows;
    }
    const char *one[2] = {s->mass, s->species_rows ? NULL : s->species};
    for (int k = 0; k < 2 && !st; k++)
        if (one[k] && !(st = check(s, one[k], 1, &r, &c, err)) && r != n)
            st = bf_fail(err, BF_EINPUT, "%s: %s has %zu values for %zu "
                         "particles", s->file, one[k], r, n);
    const char *tpath = s->half_step ? BF_DS_PARTICLES_STEP : BF_DS_TIME;
    size_t trows = 0, srows = 0;
    if (!st)
        st = check(s, tpath, 1, &trows, &c, err);
    if (!st && !s->half_step)
        st = check(s, BF_DS_STEP, 1, &srows, &c, err);
    if (st)
        return st;
    s->obs_rows = s->half_step ? 0 : (trows < srows ? trows : srows);
    rows = trows < rows ? trows : rows;
    if (!s->half_step)
        rows = srows < rows ? srows : rows;
    s->n = n;
    s->rows = rows;
    s->time = malloc((rows ? rows : 1) * sizeof *s->time);
    s->step = malloc((rows ? rows : 1) * sizeof *s->step);
    double *v = malloc((rows ? rows : 1) * sizeof *v);
    if (!s->time || !s->step || !v) {
        free(v);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    st = bf_xsrc_read(s, s->half_step ? tpath : BF_DS_STEP, 0, rows, v, err);
    for (size_t k = 0; !st && k < rows; k++) {
        s->step[k] = (long long)v[k];
        s->time[k] = v[k] * s->dt;
    }
    if (!st && !s->half_step)
        st = bf_xsrc_read(s, BF_DS_TIME, 0, rows, s->time, err);
    free(v);
    return st;
}

/* The observables' shapes: rows of /time, /step and every observable. */
static bf_status observables(bf_xsrc *s, bf_err *err)
{
    size_t r, c;
    if (s->n_obs && s->half_step) {
        size_t t = 0, p = 0;
        bf_status st = check(s, BF_DS_TIME, 1, &t, &c, err);
        if (!st)
            st = check(s, BF_DS_STEP, 1, &p, &c, err);
        if (st)
            return st;
        s->obs_rows = t < p ? t : p;
    }
    for (size_t k = 0; k < s->n_obs; k++) {
        const bf_xobs *o = &s->obs[k];
        bf_status st = check(s, o->path, o->column < 0 ? 1 : 2, &r, &c, err);
        if (st)
            return st;
        if (o->column >= 0 && (size_t)o->column >= c)
            return bf_fail(err, BF_EINPUT, "%s: %s has no column %d",
                           s->file, o->path, o->column);
        s->obs_rows = r < s->obs_rows ? r : s->obs_rows;
    }
    return BF_OK;
}

bf_status bf_xsrc_open(bf_xsrc *s, const char *in_path, bf_err *err)
{
    struct stat sb;
    s->h5 = -1;
    s->file = in_path;
    if (stat(in_path, &sb))
        return bf_fail(err, BF_EINPUT, "%s: %s", in_path, strerror(errno));
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    s->h5 = bf_h5_open_read(in_path);
    /* without room for the handles, every read opens its dataset */
    s->dsets = calloc(1, sizeof *s->dsets);
    if (s->h5 < 0)
        return bf_fail(err, BF_EINPUT, "%s: not an HDF5 file that opens%s",
                       in_path, bf_h5_open_hint(in_path));
    s->bytes = bf_h5_file_bytes(in_path);
    bf_status st = bf_h5_flushed_load(s->h5, in_path, &s->fl, err);
    if (!st)
        st = bf_h5_root_number(s->h5, s->file, "scene.dt", 1.0, &s->dt, err);
    if (!st)
        st = choose(s, err);
    if (!st)
        st = shapes(s, err);
    if (!st)
        st = observables(s, err);
    return st;
}

void bf_xsrc_close(bf_xsrc *s)
{
    free(s->time);
    free(s->step);
    bf_h5_flushed_free(s->fl);
    for (size_t k = 0; s->dsets && k < s->dsets->n; k++)
        H5Dclose(s->dsets->id[k]);
    free(s->dsets);
    if (s->h5 >= 0)
        H5Fclose(s->h5);
}

/* ------------------------------------------------------------ the output */

/* The export into the file of descriptor fd (OUT.tmp). */
static bf_status write_out(const bf_xsrc *s, int fd, const bf_export_opts *o,
                           bf_err *err)
{
    if (o->format == BF_EXPORT_H5MD) {
        char name[32];
        return bf_export_h5md(s, bf_path_h5_name(fd, name, sizeof name), o,
                              err);
    }
    int fd2 = dup(fd);
    FILE *f = fd2 < 0 ? NULL : fdopen(fd2, "w");
    if (!f) {
        if (fd2 >= 0)
            close(fd2);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    bf_status st = bf_export_xyz(s, f, err);
    const int bad = ferror(f) | fflush(f) | fsync(fd2);
    if ((fclose(f) | bad) && !st)
        st = bf_fail(err, BF_EIO, "writing failed (disk full?)");
    return st;
}

bf_status bf_export(const char *in_path, const char *out_path,
                    const bf_export_opts *o,
                    const volatile sig_atomic_t *stop_flag, bf_err *err)
{
    struct stat sb;
    if (stop_flag && *stop_flag)
        return bf_fail(err, BF_INTERRUPTED, "interrupted");
    if (!lstat(out_path, &sb) && S_ISLNK(sb.st_mode))
        return bf_fail(err, BF_EIO, "%s: is a symbolic link; the export is "
                       "not written through one (remove it)", out_path);
    if (bf_path_same_file(in_path, out_path))
        return bf_fail(err, BF_EINPUT, "%s: is the input file %s; give "
                       "another -o", out_path, in_path);
    bf_xsrc s;
    memset(&s, 0, sizeof s);
    s.stop = stop_flag;
    bf_status st = bf_xsrc_open(&s, in_path, err);
    if (!st && o->mdanalysis && strcmp(s.unit_len, "cm"))
        st = bf_fail(err, BF_EINPUT, "%s: --mdanalysis: the %s' lengths in "
                     "%s have no conversion to nm", in_path, s.group,
                     s.unit_len);
    if (!st)
        st = bf_path_check_replaceable(out_path, err);
    size_t len = strlen(out_path);
    char *tmp = st ? NULL : malloc(len + 5);
    int fd = -1;
    if (!st && !tmp)
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st) {
        snprintf(tmp, len + 5, "%s.tmp", out_path);
        if ((fd = bf_path_open_own(tmp, err)) < 0)
            st = BF_EIO;
        else if (ftruncate(fd, 0))
            st = bf_fail(err, BF_EIO, "%s: cannot truncate", tmp);
    }
    if (!st)
        st = write_out(&s, fd, o, err);
    if (!st && rename(tmp, out_path))
        st = bf_fail(err, BF_EIO, "%s: cannot rename %s onto it: %s",
                     out_path, tmp, strerror(errno));
    if (st && fd >= 0) {
        struct stat now;
        if (!fstat(fd, &sb) && !lstat(tmp, &now) && now.st_dev == sb.st_dev &&
            now.st_ino == sb.st_ino)
            unlink(tmp);
    }
    if (fd >= 0)
        close(fd);
    free(tmp);
    bf_xsrc_close(&s);
    return st;
}
