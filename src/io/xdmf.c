/* xdmf.c: the XDMF sidecar of an output file (see xdmf.h).
 *
 * Written for both of ParaView's readers (Xdmf3, which File > Open picks,
 * and the legacy XDMF reader): a whole dataset is "FILE.h5:/path"; row k
 * of a [rows x n] series is one item both read (item_row); points are
 * interleaved XY or XYZ written inline, since Xdmf3 crashes on X_Y
 * geometry, on functions (JOIN) and on references shared by grids.  The
 * MAC meshes are curvilinear (2DSMesh): the fields are stored with J (y)
 * fastest, the transpose of XDMF's rectilinear ordering.
 */
#include "io/xdmf.h"
#include "io/xdmf_file.h"
#include "io/h5check.h"
#include "io/h5part.h"
#include "io/dataset_paths.h"
#include "io/xdmf_rows.h"

#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct dset {
    int rank; /* 0: absent */
    int is_int;
    size_t n0, n1;
    const char *whole; /* its DataItem line (item_whole), cached, or NULL */
} dset;

/* What dset_of found, by path: a sidecar names the same datasets in each
 * of up to max_steps grids, and opening a dataset costs more than the
 * rest of a grid (it was a third of a short run's time). */
enum { DSET_CACHE = 64 };
typedef struct dset_cache {
    char *path[DSET_CACHE];
    char *whole[DSET_CACHE];
    dset d[DSET_CACHE];
    size_t n;
} dset_cache;

/* Why the sidecar stopped: the first failure, kept where grids that
 * cannot return one (grid_fn) find it. */
typedef struct xfail {
    bf_status st;
    bf_err *err;
} xfail;

typedef struct xw {
    FILE *f;
    const char *h5name; /* the HDF5 file as given, for messages */
    double bytes;       /* its size on disk */
    double budget;      /* bytes the sidecar may take (budget_of) */
    const volatile sig_atomic_t *stop_flag;
    xfail *fail;
    hid_t h5;
    char *href;       /* the HDF5 file as the sidecar names it (escaped) */
    size_t max_steps; /* grids per collection at most (0: all) */
    double dt;        /* [scene] dt, for rows counted in steps */
    dset_cache *cache;
    bf_h5_flushed *flushed; /* a run's .part: rows of its last flush */
    bf_xdmf_rows *rows;     /* point sets' rows, a block at a time */
} xw;

static dset dset_read(const xw *x, const char *path);
/* 1 (and the sidecar fails) once what was written, and extra bytes more,
 * exceed the budget. */
static int over_budget(const xw *x, double extra);
static char *whole_line(const xw *x, const char *path, const dset *d);

static dset dset_of(const xw *x, const char *path)
{
    dset_cache *c = x->cache;
    for (size_t k = 0; c && k < c->n; k++)
        if (!strcmp(c->path[k], path))
            return c->d[k];
    dset d = dset_read(x, path);
    if (c && c->n < DSET_CACHE && (c->path[c->n] = strdup(path))) {
        c->whole[c->n] = d.rank ? whole_line(x, path, &d) : NULL;
        d.whole = c->whole[c->n];
        c->d[c->n++] = d;
    }
    return d;
}

/* Record the first failure; 1 once there is one. */
static int failed(const xw *x, bf_status st)
{
    if (st && !x->fail->st)
        x->fail->st = st;
    return x->fail->st != BF_OK;
}

/* 1 once the sidecar must stop: a failure, or SIGINT/SIGTERM. */
static int stopped(const xw *x)
{
    if (x->stop_flag && *x->stop_flag && !x->fail->st)
        failed(x, bf_fail(x->fail->err, BF_INTERRUPTED, "interrupted"));
    return x->fail->st != BF_OK;
}

/* A dataset the sidecar names, checked as h5check.h says: numbers of rank
 * 1 or 2 that the file could hold.  Absent: rank 0; anything else fails
 * the sidecar (BF_EINPUT, naming the file and the dataset). */
static dset dset_read(const xw *x, const char *path)
{
    dset d = {0, 0, 0, 0, NULL};
    if (H5Lexists(x->h5, path, H5P_DEFAULT) <= 0)
        return d;
    hid_t id = H5Dopen2(x->h5, path, H5P_DEFAULT);
    if (id < 0) {
        failed(x, bf_fail(x->fail->err, BF_EINPUT, "%s: %s is not a dataset",
                          x->h5name, path));
        return d;
    }
    hsize_t dims[2];
    int rank = 0;
    bf_status st = bf_h5_dataset_rows(id, x->h5name, path, x->flushed,
                                      x->bytes, &rank, dims, NULL,
                                      x->fail->err);
    if (!failed(x, st)) {
        hid_t t = H5Dget_type(id);
        d.rank = rank;
        d.is_int = H5Tget_class(t) == H5T_INTEGER;
        d.n0 = (size_t)dims[0];
        d.n1 = rank == 2 ? (size_t)dims[1] : 0;
        H5Tclose(t);
    }
    H5Dclose(id);
    return d;
}

/* The first n values of a 1-D dataset, as doubles; NULL on failure.  The
 * dataset was checked by dset_read: the values read fit the file.  (Rows
 * of a series come a block at a time: xdmf_rows.h.) */
static double *read_vec(const xw *x, const char *path, size_t n)
{
    double *v = malloc((n ? n : 1) * sizeof *v);
    hid_t id = v ? H5Dopen2(x->h5, path, H5P_DEFAULT) : -1;
    if (id < 0) {
        free(v);
        return NULL;
    }
    hid_t fsp = H5Dget_space(id);
    hsize_t start = 0, count = n;
    H5Sselect_hyperslab(fsp, H5S_SELECT_SET, &start, NULL, &count, NULL);
    hid_t msp = H5Screate_simple(1, &count, NULL);
    herr_t rc = n ? H5Dread(id, H5T_NATIVE_DOUBLE, msp, fsp, H5P_DEFAULT, v)
                  : 0;
    H5Sclose(msp);
    H5Sclose(fsp);
    H5Dclose(id);
    if (rc < 0) {
        free(v);
        return NULL;
    }
    return v;
}

/* The sidecar of a long ball run has ~2000 grids of ~40 lines each:
 * constant text goes out with fputs/fwrite, not through printf's format
 * parser (a few per cent of a short run's time). */
static void indent(const xw *x, int depth)
{
    static const char spaces[] = "                                ";
    size_t n = 2 * (size_t)depth;
    for (; n > sizeof spaces - 1; n -= sizeof spaces - 1)
        fwrite(spaces, 1, sizeof spaces - 1, x->f);
    fwrite(spaces, 1, n, x->f);
}

static void numtype(const xw *x, int is_int)
{
    fputs(is_int ? "NumberType=\"Int\" Precision=\"8\""
                 : "NumberType=\"Float\" Precision=\"8\"",
          x->f);
}

/* n in decimal, as printf's %zu */
static void put_size(const xw *x, size_t n)
{
    char buf[24], *p = buf + sizeof buf;
    do {
        *--p = (char)('0' + n % 10);
        n /= 10;
    } while (n);
    fwrite(p, 1, (size_t)(buf + sizeof buf - p), x->f);
}

/* The DataItem line of a whole dataset (without its indent); NULL when
 * out of memory. */
static char *whole_line(const xw *x, const char *path, const dset *d)
{
    char dims[48];
    if (d->rank == 2)
        snprintf(dims, sizeof dims, "%zu %zu", d->n0, d->n1);
    else
        snprintf(dims, sizeof dims, "%zu", d->n0);
    const char *fmt = "<DataItem Dimensions=\"%s\" NumberType=\"%s\" "
                      "Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n";
    const char *type = d->is_int ? "Int" : "Float";
    int len = snprintf(NULL, 0, fmt, dims, type, x->href, path);
    char *line = len >= 0 ? malloc((size_t)len + 1) : NULL;
    if (line)
        snprintf(line, (size_t)len + 1, fmt, dims, type, x->href, path);
    return line;
}

/* A whole dataset. */
static void item_whole(const xw *x, const char *path, const dset *d,
                       int depth)
{
    indent(x, depth);
    if (d->whole) {
        fputs(d->whole, x->f);
        return;
    }
    fprintf(x->f, "<DataItem Dimensions=\"%zu", d->n0);
    if (d->rank == 2)
        fprintf(x->f, " %zu", d->n1);
    fputs("\" ", x->f);
    numtype(x, d->is_int);
    fprintf(x->f, " Format=\"HDF\">%s:%s</DataItem>\n", x->href, path);
}

/* The shape of a row's values where a mesh wants its own (a structured
 * mesh: the dimensions of its points or cells). */
typedef struct shape {
    int rank;
    size_t d[3];
} shape;

/* Row k of a [rows x n] series, as 1 x n or shaped sh.  One item that
 * both of ParaView's readers read: the Xdmf3 reader (File > Open) takes
 * its text, the dataset with its selection after '|' (start:stride:
 * count:dimensions); the legacy XDMF reader takes Type="HyperSlab" and its
 * two children (start, stride, count; the whole dataset).  An ItemType of
 * HyperSlab would make Xdmf3 build an array of no type, which it skips. */
static void item_row(const xw *x, const char *path, const dset *d, size_t k,
                     const shape *sh, int depth)
{
    indent(x, depth);
    fputs("<DataItem Type=\"HyperSlab\" Dimensions=\"", x->f);
    if (sh) {
        for (int r = 0; r < sh->rank; r++) {
            if (r)
                fputc(' ', x->f);
            put_size(x, sh->d[r]);
        }
    } else {
        fputs("1 ", x->f);
        put_size(x, d->n1);
    }
    fputs("\" ", x->f);
    numtype(x, d->is_int);
    fprintf(x->f, " Format=\"HDF\">%s:%s|", x->href, path);
    put_size(x, k);
    fputs(" 0:1 1:1 ", x->f);
    put_size(x, d->n1);
    fputc(':', x->f);
    put_size(x, d->n0);
    fputc(' ', x->f);
    put_size(x, d->n1);
    fputc('\n', x->f);
    indent(x, depth + 1);
    fputs("<DataItem Dimensions=\"3 2\" NumberType=\"Int\" Format=\"XML\">",
          x->f);
    put_size(x, k);
    fputs(" 0 1 1 1 ", x->f);
    put_size(x, d->n1);
    fputs("</DataItem>\n", x->f);
    item_whole(x, path, d, depth + 1);
    indent(x, depth);
    fputs("</DataItem>\n", x->f);
}

/* An attribute from row k of a series (2-D dataset) or from a whole 1-D
 * dataset; nothing when the dataset is absent. */
static void attribute(const xw *x, const char *name, const char *center,
                      const char *path, size_t k, const shape *sh,
                      int depth)
{
    dset d = dset_of(x, path);
    if (!d.rank)
        return;
    indent(x, depth);
    fputs("<Attribute Name=\"", x->f);
    fputs(name, x->f);
    fputs("\" AttributeType=\"Scalar\" Center=\"", x->f);
    fputs(center, x->f);
    fputs("\">\n", x->f);
    if (d.rank == 2)
        item_row(x, path, &d, k, sh, depth + 1);
    else
        item_whole(x, path, &d, depth + 1);
    indent(x, depth);
    fputs("</Attribute>\n", x->f);
}

/* Points (x, y) of row k of two series, or x only (y = z = 0), as vertex
 * cells.  The coordinates are written inline, interleaved (XY or XYZ):
 * the Xdmf3 reader crashes on X_Y geometry and on functions, and leaves
 * a Polyvertex without its connectivity with no cells. */
static void point_set(const xw *x, const char *px, const char *py, size_t k,
                      int depth)
{
    dset a = dset_of(x, px), b = py ? dset_of(x, py) : a;
    const size_t n = a.n1;
    /* x and y of one point set: as many values in each row */
    if (b.n1 != n) {
        failed(x, bf_fail(x->fail->err, BF_EINPUT, "%s: %s has %zu columns, "
                          "%s %zu (damaged, or not a ballfilm file)",
                          x->h5name, px, n, py, b.n1));
        return;
    }
    /* values written inline: checked before, not found after */
    if (over_budget(x, (double)n * (py ? 8.0 : 6.0)))
        return;
    const double *vx = bf_xdmf_row(x->rows, 0, x->h5, px, k, n, a.n0);
    const double *vy = py ? bf_xdmf_row(x->rows, 1, x->h5, py, k, n, b.n0)
                          : NULL;
    if (!vx || (py && !vy)) {
        failed(x, bf_fail(x->fail->err, BF_EIO, "%s: cannot read row %zu of "
                          "%s", x->h5name, k, py && vx ? py : px));
        return;
    }
    indent(x, depth);
    fputs("<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"", x->f);
    put_size(x, n);
    fputs("\" NodesPerElement=\"1\">\n", x->f);
    indent(x, depth + 1);
    fputs("<DataItem Dimensions=\"", x->f);
    put_size(x, n);
    fputs("\" NumberType=\"Int\" Format=\"XML\">", x->f);
    for (size_t i = 0; i < n && !(!(i & 0xffff) && stopped(x)); i++) {
        if (i)
            fputc(' ', x->f);
        put_size(x, i);
    }
    fputs("</DataItem>\n", x->f);
    indent(x, depth);
    fputs("</Topology>\n", x->f);
    indent(x, depth);
    fputs(py ? "<Geometry GeometryType=\"XY\">\n"
             : "<Geometry GeometryType=\"XYZ\">\n", x->f);
    indent(x, depth + 1);
    fprintf(x->f, "<DataItem Dimensions=\"%zu %d\" NumberType=\"Float\" "
                  "Precision=\"8\" Format=\"XML\">", n, py ? 2 : 3);
    for (size_t i = 0; i < n && !(!(i & 0xffff) && stopped(x)); i++) {
        if (py)
            fprintf(x->f, "%s%.17g %.17g", i ? " " : "", vx[i], vy[i]);
        else
            fprintf(x->f, "%s%.17g 0 0", i ? " " : "", vx[i]);
    }
    fputs("</DataItem>\n", x->f);
    indent(x, depth);
    fputs("</Geometry>\n", x->f);
}

/* ---------------------------------------------------------- collections */

/* The fewest bytes of a grid of a collection (its Grid, Time, Topology
 * and Geometry elements alone take more). */
enum { GRID_BYTES_MIN = 200 };

/* 1 (and the sidecar fails) once what was written exceeds the budget. */
static int over_budget(const xw *x, double extra)
{
    off_t at = ftello(x->f); /* -1 on a pipe, which fills no disk */
    if (at < 0 || (double)at + extra <= x->budget)
        return 0;
    return failed(x, bf_fail(x->fail->err, BF_EINPUT, "%s: its sidecar "
                             "would be larger than %.0f bytes, the most one "
                             "of a file of %.0f bytes may take (damaged, or "
                             "--max-steps thins it)", x->h5name, x->budget,
                             x->bytes));
}

typedef void (*grid_fn)(const xw *x, size_t row, const void *ctx, int depth);

/* A temporal collection of the rows 0, s, 2s, ... and the last one
 * (s = 1 unless there are more rows than max_steps) at the given times. */
static void collection(const xw *x, const char *name, const double *times,
                       size_t rows, grid_fn fn, const void *ctx)
{
    if (!rows)
        return;
    size_t s = 1;
    if (x->max_steps && rows > x->max_steps)
        s = (rows + x->max_steps - 2) / (x->max_steps - 1 ? x->max_steps - 1
                                                          : 1);
    /* a grid takes more than GRID_BYTES_MIN bytes: refused at the start
     * when they could not fit in the budget */
    const double grids = (double)(rows / s + 1);
    if (grids * GRID_BYTES_MIN > x->budget) {
        failed(x, bf_fail(x->fail->err, BF_EINPUT, "%s: %zu rows of %s make "
                          "a sidecar larger than %.0f bytes, the most one of "
                          "a file of %.0f bytes may take (--max-steps "
                          "thins it)", x->h5name, rows, name, x->budget,
                          x->bytes));
        return;
    }
    x->rows->step = s;
    if (s > 1)
        fprintf(x->f, "    <!-- %s: every %zu-th of %zu rows (ballfilm xdmf "
                      "--all for every row) -->\n", name, s, rows);
    fprintf(x->f, "    <Grid Name=\"%s\" GridType=\"Collection\" "
                  "CollectionType=\"Temporal\">\n", name);
    for (size_t k = 0, g = 0; k < rows; k += s, g++) {
        if (k + s >= rows)
            k = rows - 1;
        if (stopped(x) || (!(g & 63) && over_budget(x, 0)))
            return;
        fprintf(x->f, "      <Grid Name=\"%s\" GridType=\"Uniform\">\n"
                      "        <Time Value=\"%.17g\"/>\n", name, times[k]);
        fn(x, k, ctx, 4);
        fputs("      </Grid>\n", x->f);
    }
    fputs("    </Grid>\n", x->f);
}

/* The times of the rows of a series: the 1-D dataset `tpath`, or steps
 * of `spath` times dt. */
static double *row_times(const xw *x, const char *tpath, const char *spath,
                         size_t rows)
{
    double *t = read_vec(x, tpath ? tpath : spath, rows);
    if (t && !tpath)
        for (size_t k = 0; k < rows; k++)
            t[k] *= x->dt;
    return t;
}

static size_t min_rows(const xw *x, const char *const *paths)
{
    size_t rows = SIZE_MAX;
    for (; *paths; paths++) {
        dset d = dset_of(x, *paths);
        if (d.rank && d.n0 < rows)
            rows = d.n0;
    }
    return rows == SIZE_MAX ? 0 : rows;
}

static bf_status timed(const xw *x, const char *name, const char *tpath,
                       const char *spath, const char *const *series,
                       grid_fn fn, const void *ctx, bf_err *err)
{
    const char *need[8];
    size_t m = 0;
    need[m++] = tpath ? tpath : spath;
    for (size_t k = 0; series[k] && m < 7; k++)
        need[m++] = series[k];
    need[m] = NULL;
    size_t rows = min_rows(x, need);
    if (x->fail->st)
        return x->fail->st;
    if (dset_of(x, need[0]).rank != 1)
        return bf_fail(err, BF_EINPUT, "%s: %s is not a list of times (rank "
                       "1) for %s", x->h5name, need[0], name);
    double *t = row_times(x, tpath, spath, rows);
    if (!t)
        return bf_fail(err, BF_EIO, "cannot read the times of %s", name);
    collection(x, name, t, rows, fn, ctx);
    free(t);
    return x->fail->st;
}

/* ---------------------------------------------------------------- film */

/* The film's nodes (n, x_0, dx) and, when the film is written at the
 * times of another series (the coupled model's /time), the profile row
 * of each of its rows. */
typedef struct film_ctx {
    double xs[3];
    const size_t *row;
} film_ctx;

static void film_grid(const xw *x, size_t k, const void *ctx, int depth)
{
    /* a line of n points along x: XDMF orders dimensions Z Y X */
    const film_ctx *fc = ctx;
    const double *xs = fc->xs;
    if (fc->row)
        k = fc->row[k];
    const shape line = {3, {1, 1, (size_t)xs[0]}};
    indent(x, depth);
    fprintf(x->f, "<Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"1 1 "
                  "%zu\"/>\n", line.d[2]);
    indent(x, depth);
    fputs("<Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n", x->f);
    for (int c = 0; c < 2; c++) {
        indent(x, depth + 1);
        fprintf(x->f, "<DataItem Dimensions=\"3\" NumberType=\"Float\" "
                      "Precision=\"8\" Format=\"XML\">%d %d %.17g</DataItem>\n",
                c, c, xs[1 + c]);
    }
    indent(x, depth);
    fputs("</Geometry>\n", x->f);
    static const char *const f[][2] = {
        {"psi", BF_DS_FILM_PSI}, {"h", BF_DS_FILM_H},
        {"u_d", BF_DS_FILM_U_D}, {"u_c", BF_DS_FILM_U_C}};
    for (size_t a = 0; a < sizeof f / sizeof f[0]; a++)
        attribute(x, f[a][0], "Node", f[a][1], k, &line, depth);
}

/* --------------------------------------------------------------- balls */

static void balls_grid(const xw *x, size_t k, const void *ctx, int depth)
{
    (void)ctx;
    point_set(x, BF_DS_BALLS_POSITION, NULL, k, depth);
    attribute(x, "velocity", "Node", BF_DS_BALLS_VELOCITY, k, NULL, depth);
    attribute(x, "mass", "Node", BF_DS_BALLS_MASS, k, NULL, depth);
    attribute(x, "radius", "Node", BF_DS_BALLS_RADIUS, k, NULL, depth);
}

/* ----------------------------------------------------------- particles */

static void particles_grid(const xw *x, size_t k, const void *ctx,
                           int depth)
{
    const char *const *p = ctx; /* x, y, vx, vy */
    point_set(x, p[0], p[1], k, depth);
    attribute(x, "vx", "Node", p[2], k, NULL, depth);
    attribute(x, "vy", "Node", p[3], k, NULL, depth);
    static const char *const f[][2] = {
        {"fluid", BF_DS_PARTICLES_TAG},     {"mass", BF_DS_PARTICLES_MASS},
        {"inertia", BF_DS_PARTICLES_INERTIA}, {"fixed", BF_DS_PARTICLES_FIXED},
        {"gravity", BF_DS_PARTICLES_GRAVITY}};
    for (size_t a = 0; a < sizeof f / sizeof f[0]; a++)
        attribute(x, f[a][0], "Node", f[a][1], k, NULL, depth);
}

static void marker_grid(const xw *x, size_t k, const void *ctx, int depth)
{
    const char *const *p = ctx; /* x, y */
    point_set(x, p[0], p[1], k, depth);
    attribute(x, "density", "Node", BF_DS_MAC_PARTICLES_DENSITY, k, NULL, depth);
    attribute(x, "flag", "Node", BF_DS_MAC_PARTICLES_FLAG, k, NULL, depth);
}

/* ----------------------------------------------------------------- MAC */

/* A mesh of ni1 x nj1 points (I slow, J fast) at x = (I + ox) dx,
 * y = (J + oy) dy, I, J from 0, and the fields on it. */
typedef struct mac_mesh {
    const char *name; /* also the name of its coordinates in the Domain */
    size_t ni1, nj1;
    double ox, oy, dx, dy;
    const char *center;
    const char *const *fields; /* name, path pairs, NULL-terminated */
} mac_mesh;

static void mac_grid(const xw *x, size_t k, const void *ctx, int depth)
{
    const mac_mesh *m = ctx;
    if (over_budget(x, 4.0 * (double)m->ni1 * (double)m->nj1))
        return;
    indent(x, depth);
    fprintf(x->f, "<Topology TopologyType=\"2DSMesh\" Dimensions=\"%zu "
                  "%zu\"/>\n", m->ni1, m->nj1);
    /* the points (x, y) interleaved, in every grid: the Xdmf3 reader
     * crashes on X_Y geometry and on a reference to one DataItem from
     * several grids */
    indent(x, depth);
    fputs("<Geometry GeometryType=\"XY\">\n", x->f);
    indent(x, depth + 1);
    fprintf(x->f, "<DataItem Dimensions=\"%zu %zu 2\" NumberType=\"Float\" "
                  "Precision=\"8\" Format=\"XML\">\n", m->ni1, m->nj1);
    for (size_t i = 0; i < m->ni1 && !stopped(x); i++) {
        indent(x, depth + 1);
        const double xi = ((double)i + m->ox) * m->dx;
        for (size_t j = 0; j < m->nj1; j++)
            fprintf(x->f, " %.17g %.17g", xi, ((double)j + m->oy) * m->dy);
        fputc('\n', x->f);
    }
    indent(x, depth + 1);
    fputs("</DataItem>\n", x->f);
    indent(x, depth);
    fputs("</Geometry>\n", x->f);
    /* the shape of the values: points, or the cells between them */
    const int cells = !strcmp(m->center, "Cell");
    const shape sh = {2, {m->ni1 - (size_t)cells, m->nj1 - (size_t)cells}};
    for (const char *const *f = m->fields; *f; f += 2)
        attribute(x, f[0], m->center, f[1], k, &sh, depth);
}

/* 1 if series `path` is absent or has `values` values a row. */
static int fits_row(const xw *x, const char *path, double values)
{
    dset d = dset_of(x, path);
    return d.rank != 2 || (double)d.n1 == values;
}

static bf_status write_mac(const xw *x, bf_err *err)
{
    dset g = dset_of(x, BF_DS_MAC_GRID);
    double *grid = g.rank == 1 && g.n0 >= 4 ? read_vec(x, BF_DS_MAC_GRID, 4)
                                             : NULL;
    if (x->fail->st)
        return x->fail->st;
    if (!grid)
        return bf_fail(err, BF_EIO, "no readable /mac/grid (ni, nj, dx, dy)");
    const double gi = grid[0], gj = grid[1], dx = grid[2], dy = grid[3];
    free(grid);
    /* the cells the fields hold: ni nj of /mac/p, and the points of the
     * meshes written inline in every grid, 2 (ni + 1) (nj + 1) of each of
     * three, at two bytes at least each */
    double grids = (double)dset_of(x, BF_DS_TIME).n0;
    if (x->max_steps && grids > (double)x->max_steps)
        grids = (double)x->max_steps;
    const double cells = gi * gj,
                 points = 6.0 * (gi + 1.0) * (gj + 1.0) * grids;
    if (!(gi >= 1 && gj >= 1 && gi == floor(gi) && gj == floor(gj) &&
          cells == (double)dset_of(x, BF_DS_MAC_P).n1 && isfinite(dx) &&
          isfinite(dy) &&
          fits_row(x, BF_DS_MAC_U, (gi + 1.0) * gj) &&
          fits_row(x, BF_DS_MAC_V, gi * (gj + 1.0))))
        return bf_fail(err, BF_EINPUT, "%s: /mac/grid (%g, %g, %g, %g) is "
                       "not a grid of the cells of /mac/p (%zu values a "
                       "row)", x->h5name, gi, gj, dx, dy,
                       dset_of(x, BF_DS_MAC_P).n1);
    if (2.0 * points > x->budget)
        return bf_fail(err, BF_EINPUT, "%s: /mac/grid's %g x %g cells in "
                       "%.0f grids make a sidecar larger than %.0f bytes, the "
                       "most one of a file of %.0f bytes may take "
                       "(--max-steps thins it)", x->h5name, gi, gj, grids,
                       x->budget, x->bytes);
    const size_t ni = (size_t)gi, nj = (size_t)gj;
    /* cell (I,J), I, J from 1, covers [(I-2)dx, (I-1)dx) x [(J-2)dy, ...) */
    static const char *const cell_f[] = {"p", BF_DS_MAC_P, "rho", BF_DS_MAC_RHO,
                                         "T", BF_DS_MAC_T, "flags", BF_DS_MAC_FLAGS,
                                         NULL};
    static const char *const u_f[] = {"u", BF_DS_MAC_U, NULL};
    static const char *const v_f[] = {"v", BF_DS_MAC_V, NULL};
    const mac_mesh mesh[3] = {
        {"mac_cells", ni + 1, nj + 1, -1.0, -1.0, dx, dy, "Cell", cell_f},
        {"mac_u", ni + 1, nj, -1.0, -0.5, dx, dy, "Node", u_f},
        {"mac_v", ni, nj + 1, -0.5, -1.0, dx, dy, "Node", v_f},
    };
    static const char *const series[3][5] = {
        {BF_DS_MAC_P, BF_DS_MAC_RHO, BF_DS_MAC_T, BF_DS_MAC_FLAGS, NULL},
        {BF_DS_MAC_U, NULL},
        {BF_DS_MAC_V, NULL}};
    for (int m = 0; m < 3; m++) {
        bf_status st = timed(x, mesh[m].name, BF_DS_TIME, NULL, series[m],
                             mac_grid, &mesh[m], err);
        if (st)
            return st;
    }
    static const char *const mk[] = {BF_DS_MAC_PARTICLES_X, BF_DS_MAC_PARTICLES_Y,
                                     BF_DS_MAC_PARTICLES_DENSITY,
                                     BF_DS_MAC_PARTICLES_FLAG, NULL};
    if (dset_of(x, mk[0]).rank == 2)
        return timed(x, "mac_markers", BF_DS_TIME, NULL, mk, marker_grid, mk,
                     err);
    return BF_OK;
}

/* Every dataset a sidecar may name, checked before anything is written:
 * a file that would fail half way is refused at the start. */
static bf_status check_datasets(const xw *x)
{
    static const char *const all[] = {
        BF_DS_TIME, BF_DS_FILM_X, BF_DS_FILM_TIME, BF_DS_FILM_PSI, BF_DS_FILM_H,
        BF_DS_FILM_U_D, BF_DS_FILM_U_C, BF_DS_BALLS_POSITION, BF_DS_BALLS_VELOCITY,
        BF_DS_BALLS_MASS, BF_DS_BALLS_RADIUS, BF_DS_PARTICLES_X, BF_DS_PARTICLES_Y,
        BF_DS_PARTICLES_VX, BF_DS_PARTICLES_VY, BF_DS_PARTICLES_TAG,
        BF_DS_PARTICLES_MASS, BF_DS_PARTICLES_INERTIA, BF_DS_PARTICLES_FIXED,
        BF_DS_PARTICLES_GRAVITY, BF_DS_PARTICLES_STEP, BF_DS_MAC_GRID, BF_DS_MAC_P,
        BF_DS_MAC_RHO, BF_DS_MAC_T, BF_DS_MAC_FLAGS, BF_DS_MAC_U, BF_DS_MAC_V,
        BF_DS_MAC_PARTICLES_X, BF_DS_MAC_PARTICLES_Y, BF_DS_MAC_PARTICLES_DENSITY,
        BF_DS_MAC_PARTICLES_FLAG, NULL};
    for (const char *const *p = all; *p && !x->fail->st; p++)
        dset_of(x, *p);
    return x->fail->st;
}

/* The film's nodes: n, x_0 and dx of /film/x, checked against the rows of
 * the film's series. */
static bf_status film_nodes(const xw *x, const dset *fx, double xs[3],
                            bf_err *err)
{
    double *xv = read_vec(x, BF_DS_FILM_X, fx->n0);
    if (!xv)
        return bf_fail(err, BF_EIO, "cannot read /film/x");
    xs[0] = (double)fx->n0;
    xs[1] = xv[0];
    xs[2] = (xv[fx->n0 - 1] - xv[0]) / (double)(fx->n0 - 1);
    free(xv);
    static const char *const f[] = {BF_DS_FILM_PSI, BF_DS_FILM_H, BF_DS_FILM_U_D,
                                    BF_DS_FILM_U_C};
    for (int k = 0; k < 4; k++)
        if (!fits_row(x, f[k], xs[0]))
            return bf_fail(err, BF_EINPUT, "%s: %s has %zu values a row, "
                           "/film/x %zu nodes", x->h5name, f[k],
                           dset_of(x, f[k]).n1, fx->n0);
    if (!isfinite(xs[1]) || !isfinite(xs[2]))
        return bf_fail(err, BF_EINPUT, "%s: /film/x holds values that are "
                       "not finite", x->h5name);
    return BF_OK;
}

/* The film of a coupled run at the times of the balls (/time): each grid
 * holds the last profile row at or before its time, so that both blocks
 * are there at every time step (profiles are fewer than rows). */
static bf_status film_at_times(const xw *x, const char *const *film,
                               film_ctx *fc, bf_err *err)
{
    const char *need[7] = {BF_DS_FILM_TIME};
    for (int k = 0; film[k] && k < 5; k++)
        need[k + 1] = film[k];
    const char *const balls[] = {BF_DS_TIME, BF_DS_BALLS_POSITION, NULL};
    const size_t nf = min_rows(x, need), nt = min_rows(x, balls);
    if (x->fail->st)
        return x->fail->st;
    if (dset_of(x, BF_DS_TIME).rank != 1 || dset_of(x, BF_DS_FILM_TIME).rank != 1)
        return bf_fail(err, BF_EINPUT, "%s: /time or /film/time is not a "
                       "list of times (rank 1)", x->h5name);
    if (!nf || !nt)
        return BF_OK;
    double *tf = read_vec(x, BF_DS_FILM_TIME, nf), *t = read_vec(x, BF_DS_TIME, nt);
    size_t *row = malloc(nt * sizeof *row);
    bf_status st = BF_OK;
    if (!tf || !t || !row) {
        st = bf_fail(err, BF_EIO, "cannot read the times of the film");
    } else {
        /* a profile within a millionth of a step of a row is at its time */
        const double eps = 1e-6 * fabs(x->dt);
        for (size_t k = 0, j = 0; k < nt; k++) {
            while (j + 1 < nf && tf[j + 1] <= t[k] + eps)
                j++;
            row[k] = j;
        }
        fc->row = row;
        collection(x, "film", t, nt, film_grid, fc);
        fc->row = NULL;
        st = x->fail->st;
    }
    free(tf);
    free(t);
    free(row);
    return st;
}

static bf_status write_all(xw *x, bf_err *err)
{
    bf_status st = check_datasets(x);
    if (st)
        return st;
    dset fx = dset_of(x, BF_DS_FILM_X);
    const int has_film = dset_of(x, BF_DS_FILM_PSI).rank == 2 && fx.rank == 1 &&
                         fx.n0 >= 2;
    film_ctx fc = {{0, 0, 0}, NULL};
    if (has_film && (st = film_nodes(x, &fx, fc.xs, err)))
        return st;
    fprintf(x->f, "<?xml version=\"1.0\" ?>\n"
                  "<!-- written by ballfilm for %s: open it in ParaView or "
                  "VisIt; it names the datasets of the HDF5 file, which must "
                  "stay beside it -->\n"
                  "<Xdmf Version=\"2.0\">\n  <Domain>\n", x->href);
    static const char *const film[] = {BF_DS_FILM_PSI, BF_DS_FILM_H, BF_DS_FILM_U_D,
                                       BF_DS_FILM_U_C, NULL};
    static const char *const balls[] = {BF_DS_BALLS_POSITION, BF_DS_BALLS_VELOCITY,
                                        NULL};
    /* the nodes x_i = x_0 + i dx, i = 0..n-1 (/film/x) */
    const int has_balls = dset_of(x, BF_DS_BALLS_POSITION).rank == 2;
    if (has_film && has_balls)
        st = film_at_times(x, film, &fc, err);
    else if (has_film)
        st = timed(x, "film", BF_DS_FILM_TIME, NULL, film, film_grid, &fc, err);
    if (!st && has_balls)
        st = timed(x, "balls", BF_DS_TIME, NULL, balls, balls_grid, NULL, err);
    if (!st && dset_of(x, BF_DS_PARTICLES_X).rank == 2) {
        static const char *const p[] = {BF_DS_PARTICLES_X, BF_DS_PARTICLES_Y,
                                        BF_DS_PARTICLES_VX, BF_DS_PARTICLES_VY,
                                        NULL};
        int by_step = dset_of(x, BF_DS_PARTICLES_STEP).rank == 1;
        st = timed(x, "particles", by_step ? NULL : BF_DS_TIME,
                   by_step ? BF_DS_PARTICLES_STEP : NULL, p, particles_grid, p,
                   err);
    }
    if (!st && dset_of(x, BF_DS_MAC_P).rank == 2)
        st = write_mac(x, err);
    fputs("  </Domain>\n</Xdmf>\n", x->f);
    return st;
}

bf_status bf_xdmf_write_n(const char *h5_path, const char *xmf_path,
                          size_t max_steps,
                          const volatile sig_atomic_t *stop_flag,
                          bf_err *err)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    dset_cache cache = {.n = 0};
    xfail fail = {BF_OK, err};
    bf_xdmf_rows rows = {.step = 1};
    xw x = {NULL, h5_path, 0.0, 0.0, stop_flag, &fail, -1, NULL, max_steps,
            0.0, &cache, NULL, &rows};
    if (stop_flag && *stop_flag)
        return bf_fail(err, BF_INTERRUPTED, "%s: interrupted", xmf_path);
    x.h5 = bf_h5_open_read(h5_path);
    if (x.h5 < 0)
        return bf_fail(err, BF_EIO, "%s: cannot open HDF5 file%s", h5_path,
                       bf_h5_open_hint(h5_path));
    x.bytes = bf_h5_file_bytes(h5_path);
    x.budget = BF_XDMF_BUDGET_BYTES + BF_XDMF_BUDGET_RATIO * x.bytes;
    bf_status st = bf_h5_flushed_load(x.h5, h5_path, &x.flushed, err);
    if (!st)
        st = bf_h5_root_number(x.h5, x.h5name, "scene.dt", 1.0, &x.dt, err);
    if (!st && !(x.href = bf_xdmf_href(h5_path, xmf_path)))
        st = bf_fail(err, BF_EIO, "%s: cannot name %s relative to it (is its "
                     "directory there?)", xmf_path, h5_path);
    /* An earlier sidecar is written over in place and cut to the new
     * length at the end, not truncated first: a run written again has a
     * sidecar of about the same size, and the file system then keeps its
     * blocks instead of freeing them and allocating them again (0.75 ms
     * of `ballfilm xdmf` on the AMD machine of docs/performance.md). */
    int fd = -1, created = 0;
    if (!st && !(st = bf_xdmf_open(xmf_path, &fd, &created, err)) &&
        !(x.f = fdopen(fd, "w"))) {
        close(fd);
        if (created)
            unlink(xmf_path);
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    if (!st)
        st = write_all(&x, err);
    if (!st)
        st = fail.st;
    if (!st && stopped(&x))
        st = fail.st;
    if (st && err)
        bf_err_prefix(err, "%s", xmf_path);
    if (x.f)
        st = bf_xdmf_close(x.f, fd, xmf_path, created, st, err);
    free(x.href);
    for (size_t k = 0; k < cache.n; k++) {
        free(cache.path[k]);
        free(cache.whole[k]);
    }
    bf_h5_flushed_free(x.flushed);
    bf_xdmf_rows_free(&rows);
    H5Fclose(x.h5);
    return st;
}

char *bf_xdmf_default_path(const char *h5_path)
{
    size_t n = strlen(h5_path);
    if (n > 3 && !strcmp(h5_path + n - 3, ".h5"))
        n -= 3;
    char *p = malloc(n + 5);
    if (p)
        snprintf(p, n + 5, "%.*s.xmf", (int)n, h5_path);
    return p;
}
