/* export_h5md.c: a run's particles as H5MD 1.1 (see export.h).
 *
 *   /h5md                  version 1 1; author (name), creator (name,
 *                          version); modules/units
 *   /particles/G/box       dimension, boundary ("none" each)
 *   /particles/G/position  value [frames x N x D], step, time
 *   /particles/G/velocity  the same (Greenspan 1972: its own times)
 *   /particles/G/mass      [N]; species [N] (MAC: a time series)
 *   /observables/E         value, step, time of the run's rows
 * Units are H5MD unit attributes ("cm s-1"). */
#include "io/export_impl.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/version.h"
#include "io/dataset_paths.h"

typedef struct h5w {
    const bf_xsrc *s;
    const bf_export_opts *o;
    int dim; /* D written */
    double len_scale, vel_scale;
    const char *unit_len, *unit_vel;
    bf_err *err;
    int bad; /* an HDF5 call failed */
} h5w;

/* A text attribute, variable-length UTF-8 (h5py reads it as str, which
 * MDAnalysis needs of a unit). */
static void attr_text(h5w *w, hid_t loc, const char *name, const char *v)
{
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    hid_t a = H5Acreate2(loc, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
    w->bad |= a < 0 || H5Awrite(a, t, &v) < 0;
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
}

static void attr_ints(h5w *w, hid_t loc, const char *name, const int *v,
                      hsize_t n)
{
    hid_t sp = n ? H5Screate_simple(1, &n, NULL) : H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, H5T_STD_I32LE, sp, H5P_DEFAULT,
                         H5P_DEFAULT);
    w->bad |= a < 0 || H5Awrite(a, H5T_NATIVE_INT, v) < 0;
    if (a >= 0)
        H5Aclose(a);
    H5Sclose(sp);
}

static hid_t group(h5w *w, hid_t loc, const char *name)
{
    hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    w->bad |= g < 0;
    return g;
}

/* A dataset of rank dims written whole from buf (native type mem). */
static hid_t dataset(h5w *w, hid_t loc, const char *name, hid_t file_type,
                     int rank, const hsize_t *dims, hid_t mem,
                     const void *buf, const char *unit)
{
    hid_t sp = H5Screate_simple(rank, dims, NULL), pl = H5Pcreate(
                                                        H5P_DATASET_CREATE);
    hsize_t chunk[3] = {1, dims[rank > 1 ? 1 : 0], rank > 2 ? dims[2] : 1};
    if (rank > 1 && dims[0] && dims[1])
        H5Pset_chunk(pl, rank, chunk);
    hid_t d = H5Dcreate2(loc, name, file_type, sp, H5P_DEFAULT, pl,
                         H5P_DEFAULT);
    w->bad |= d < 0;
    if (d >= 0 && buf && dims[0])
        w->bad |= H5Dwrite(d, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0;
    if (d >= 0 && unit)
        attr_text(w, d, "unit", unit);
    H5Pclose(pl);
    H5Sclose(sp);
    return d;
}

/* step and time of a time series in g: rows of steps and times. */
static void step_time(h5w *w, hid_t g, size_t rows, const long long *step,
                      const double *time)
{
    hsize_t n = rows;
    H5Dclose(dataset(w, g, "step", H5T_STD_I64LE, 1, &n, H5T_NATIVE_LLONG,
                     step, NULL));
    H5Dclose(dataset(w, g, "time", H5T_IEEE_F64LE, 1, &n, H5T_NATIVE_DOUBLE,
                     time, w->s->unit_time));
}

/* A time series `name` in g of the particles: per frame, the D series
 * paths[0..] scaled (paths[c] NULL: 0), or one series (d = 0: [frames x
 * N]).  Its step and time those of the frames, or hard links to those of
 * `linked` (NULL: written). */
static bf_status particle_series(h5w *w, hid_t g, const char *name,
                                 const char *const *paths, int d,
                                 double scale, const char *unit,
                                 const char *linked, const double *time,
                                 int species)
{
    const bf_xsrc *s = w->s;
    hid_t e = group(w, g, name);
    const int cols = d ? d : 1;
    hsize_t dims[3] = {s->rows, s->n, (hsize_t)cols};
    hid_t v = dataset(w, e, "value", species ? H5T_STD_I32LE
                                             : H5T_IEEE_F64LE,
                      d ? 3 : 2, dims, 0, NULL, unit);
    double *row = malloc((s->n ? s->n : 1) * sizeof *row),
           *frame = calloc((s->n ? s->n : 1) * (size_t)cols, sizeof *frame);
    bf_status st = row && frame ? BF_OK
                                : bf_fail(w->err, BF_EINTERNAL, "out of memory");
    hid_t fsp = H5Dget_space(v);
    hsize_t cnt[3] = {1, s->n, (hsize_t)cols};
    hid_t msp = H5Screate_simple(d ? 3 : 2, cnt, NULL);
    for (size_t k = 0; !st && !w->bad && k < s->rows; k++) {
        if ((st = bf_xsrc_stopped(s, w->err)))
            break;
        for (int c = 0; c < cols && !st; c++) {
            if (species)
                st = bf_xsrc_species(s, k, row, w->err);
            else if (c < s->dim && paths[c])
                st = bf_xsrc_read(s, paths[c], k, s->n, row, w->err);
            else
                continue; /* a coordinate the run has not: 0 */
            for (size_t i = 0; !st && i < s->n; i++)
                frame[i * (size_t)cols + (size_t)c] = row[i] * scale;
        }
        hsize_t start[3] = {k, 0, 0};
        if (!st && s->n) {
            H5Sselect_hyperslab(fsp, H5S_SELECT_SET, start, NULL, cnt, NULL);
            w->bad |= H5Dwrite(v, H5T_NATIVE_DOUBLE, msp, fsp, H5P_DEFAULT,
                               frame) < 0;
        }
    }
    H5Sclose(msp);
    H5Sclose(fsp);
    H5Dclose(v);
    free(row);
    free(frame);
    if (linked) {
        char p[64];
        snprintf(p, sizeof p, "%s/step", linked);
        w->bad |= H5Lcreate_hard(g, p, e, "step", H5P_DEFAULT,
                                 H5P_DEFAULT) < 0;
        snprintf(p, sizeof p, "%s/time", linked);
        w->bad |= H5Lcreate_hard(g, p, e, "time", H5P_DEFAULT,
                                 H5P_DEFAULT) < 0;
    } else {
        step_time(w, e, s->rows, s->step, time);
    }
    H5Gclose(e);
    return st;
}

/* The run's rows' observables: value, step, time. */
static bf_status observables(h5w *w, hid_t file)
{
    const bf_xsrc *s = w->s;
    if (!s->n_obs)
        return BF_OK;
    const size_t r = s->obs_rows;
    double *t = malloc((r ? r : 1) * sizeof *t),
           *v = malloc((r ? r : 1) * 8 * sizeof *v);
    long long *step = malloc((r ? r : 1) * sizeof *step);
    bf_status st = t && v && step ? BF_OK
                                  : bf_fail(w->err, BF_EINTERNAL,
                                            "out of memory");
    if (!st)
        st = bf_xsrc_read(s, BF_DS_TIME, 0, r, t, w->err);
    if (!st)
        st = bf_xsrc_read(s, BF_DS_STEP, 0, r, v, w->err);
    for (size_t k = 0; !st && k < r; k++)
        step[k] = (long long)v[k];
    hid_t obs = st ? -1 : group(w, file, "observables");
    for (size_t k = 0; !st && k < s->n_obs; k++) {
        const bf_xobs *o = &s->obs[k];
        if (o->column < 0) {
            st = bf_xsrc_read(s, o->path, 0, r, v, w->err);
        } else { /* a column of a [rows x c] series, row by row */
            for (size_t j = 0; !st && j < r; j++) {
                double row[8];
                if (!(j & 1023) && (st = bf_xsrc_stopped(s, w->err)))
                    break;
                st = bf_xsrc_read(s, o->path, j, (size_t)o->column + 1, row,
                                  w->err);
                v[j] = row[o->column];
            }
        }
        if (st)
            break;
        hid_t g = group(w, obs, o->name);
        hsize_t n = r;
        H5Dclose(dataset(w, g, "value", H5T_IEEE_F64LE, 1, &n,
                         H5T_NATIVE_DOUBLE, v, s->unit_energy));
        step_time(w, g, r, step, t);
        H5Gclose(g);
    }
    if (obs >= 0)
        H5Gclose(obs);
    free(t);
    free(v);
    free(step);
    return st;
}

static void header(h5w *w, hid_t file)
{
    hid_t h = group(w, file, "h5md");
    static const int version[2] = {1, 1}, units[2] = {1, 0};
    attr_ints(w, h, "version", version, 2);
    hid_t a = group(w, h, "author");
    const char *user = getenv("USER");
    attr_text(w, a, "name", user && *user ? user : "unknown");
    H5Gclose(a);
    hid_t c = group(w, h, "creator");
    attr_text(w, c, "name", "ballfilm");
    attr_text(w, c, "version", bf_version_string());
    H5Gclose(c);
    hid_t m = group(w, h, "modules");
    hid_t u = group(w, m, "units");
    attr_ints(w, u, "version", units, 2);
    attr_text(w, u, "system", w->o->mdanalysis ? "SI" : "cgs");
    H5Gclose(u);
    H5Gclose(m);
    H5Gclose(h);
}

static bf_status particles(h5w *w, hid_t file)
{
    const bf_xsrc *s = w->s;
    hid_t ps = group(w, file, "particles"), g = group(w, ps, s->group);
    hid_t box = group(w, g, "box");
    attr_ints(w, box, "dimension", &w->dim, 0);
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, 5);
    hsize_t nd = (hsize_t)w->dim;
    hid_t sp = H5Screate_simple(1, &nd, NULL);
    hid_t a = H5Acreate2(box, "boundary", t, sp, H5P_DEFAULT, H5P_DEFAULT);
    w->bad |= a < 0 || H5Awrite(a, t, "none\0none\0none") < 0;
    H5Aclose(a);
    H5Sclose(sp);
    H5Tclose(t);
    H5Gclose(box);
    bf_status st = particle_series(w, g, "position", s->pos, w->dim,
                                   w->len_scale, w->unit_len, NULL, s->time,
                                   0);
    if (!st && s->vel[0] && !s->half_step)
        st = particle_series(w, g, "velocity", s->vel, w->dim, w->vel_scale,
                             w->unit_vel, "position", NULL, 0);
    if (!st && s->vel[0] && s->half_step) {
        /* leapfrog: row k holds v^{k-1/2}, at (k - 1/2) dt; row 0 the
         * initial velocity v^0, at t = 0 */
        double *t = malloc((s->rows ? s->rows : 1) * sizeof *t);
        if (!t)
            return bf_fail(w->err, BF_EINTERNAL, "out of memory");
        for (size_t k = 0; k < s->rows; k++)
            t[k] = s->step[k] ? s->time[k] - 0.5 * s->dt : s->time[k];
        st = particle_series(w, g, "velocity", s->vel, w->dim, w->vel_scale,
                             w->unit_vel, NULL, t, 0);
        free(t);
        hid_t v = H5Gopen2(g, "velocity", H5P_DEFAULT);
        if (v >= 0) {
            attr_text(w, v, "description", "leapfrog half-step velocities: "
                      "the row of step k holds v^(k-1/2), at time (k - 1/2) "
                      "dt (its time dataset); the row of step 0 the initial "
                      "velocity v^0");
            H5Gclose(v);
        }
    }
    if (!st && s->species_rows)
        st = particle_series(w, g, "species", (const char *const[]){NULL, NULL},
                             0, 1.0, NULL, "position", NULL, 1);
    if (!st && s->density)
        st = particle_series(w, g, "density",
                             (const char *const[]){s->density, NULL}, 0, 1.0,
                             s->unit_density, "position", NULL, 0);
    double *one = malloc((s->n ? s->n : 1) * sizeof *one);
    hsize_t n = s->n;
    if (!st && !one)
        st = bf_fail(w->err, BF_EINTERNAL, "out of memory");
    if (!st && s->mass && !(st = bf_xsrc_read(s, s->mass, 0, s->n, one,
                                               w->err)))
        H5Dclose(dataset(w, g, "mass", H5T_IEEE_F64LE, 1, &n,
                         H5T_NATIVE_DOUBLE, one, s->unit_mass));
    if (!st && !s->species_rows && !(st = bf_xsrc_species(s, 0, one, w->err)))
        H5Dclose(dataset(w, g, "species", H5T_STD_I32LE, 1, &n,
                         H5T_NATIVE_DOUBLE, one, NULL));
    free(one);
    H5Gclose(g);
    H5Gclose(ps);
    return st;
}

bf_status bf_export_h5md(const bf_xsrc *s, const char *h5name,
                         const bf_export_opts *o, bf_err *err)
{
    h5w w = {s, o, o->mdanalysis ? 3 : s->dim, 1.0, 1.0, s->unit_len,
             s->unit_vel, err, 0};
    if (o->mdanalysis) {
        w.len_scale = 1e7; /* cm -> nm */
        w.vel_scale = 1e-2; /* cm s-1 -> m s-1 */
        w.unit_len = "nm";
        w.unit_vel = "m s-1";
    }
    hid_t file = H5Fcreate(h5name, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file < 0)
        return bf_fail(err, BF_EIO, "cannot create the HDF5 file");
    header(&w, file);
    bf_status st = particles(&w, file);
    if (!st)
        st = observables(&w, file);
    if (H5Fclose(file) < 0)
        w.bad = 1;
    if (!st && w.bad)
        st = bf_fail(err, BF_EIO, "writing the H5MD file failed (disk "
                     "full?)");
    return st;
}
