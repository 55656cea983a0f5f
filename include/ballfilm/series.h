/* series.h: a model's output described by data.
 *
 * Every dataset a model component writes is one line of a table of
 * bf_series_spec, declared beside the component (like the checkpoint
 * field tables of checkpoint.h): its path, unit, description, shape,
 * kind, value type and role for readers.  One call opens every series
 * of a table (bf_out_open_table) and stores each bf_series * in the
 * member of its owner that the line names; fixed arrays are written with
 * bf_out_table_array.  Each dataset gets, besides "unit" and
 * "description" (h5out.h), the attributes "kind" and "role" (the names
 * below), and where the line has them "columns" (the names of fixed
 * columns, ", "-separated), "column_units" (one UDUNITS-2 unit per
 * column, "; "-separated) and "scaled_unit" (a model's scaled unit).
 *
 * Units.  "unit" is a unit that UDUNITS-2 parses ("cm", "cm/s", "erg",
 * "1/s", "1" for numbers and counts).  A dataset whose columns have
 * different units has unit "1" and "column_units" gives each column's;
 * readers take a column's unit from "column_units" when it is there.
 * Quantities in a model's scaled units (the MAC model's L, W, R, dT)
 * have unit "1" and the scaled unit in "scaled_unit".
 *
 *   static const bf_series_spec balls_series[] = {
 *       {.path = "/balls/position", .unit = "cm", .doc = "ball centres",
 *        .kind = BF_SK_ROWS, .role = BF_SR_POSITION, .per = "ball",
 *        .slot = BF_SLOT(balls_model, pos)},
 *   };
 *   const bf_series_extent ext[] = {{"ball", n}};
 *   bf_out_open_table(out, balls_series, BF_NSERIES(balls_series), m,
 *                     ext, 1, 0, err);
 *
 * The tables of a model are listed in its type (model.h, series), those
 * of the time loop in bf_sim_series (sim.h), those of an analysis in its
 * type, so that a file's layout can be documented and checked without a
 * run.
 */
#ifndef BALLFILM_SERIES_H
#define BALLFILM_SERIES_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"
#include "ballfilm/h5out.h"

/* What a dataset is, over time. */
typedef enum bf_series_kind {
    BF_SK_ROWS,     /* one row per output row ([scene] output_every) */
    BF_SK_SNAPSHOT, /* one row per snapshot of every item (particles,
                       nodes), at a pace of its own (a step or time axis
                       of the same kind says when) */
    BF_SK_EVENTS,   /* one row per event (return-map points, peaks) */
    BF_SK_STATIC    /* written once (masses, radii, the grid) */
} bf_series_kind;

/* What a reader may do with it. */
typedef enum bf_series_role {
    BF_SR_DIAGNOSTIC, /* a diagnostic quantity */
    BF_SR_TIME,       /* the time axis of the datasets of its kind */
    BF_SR_STEP,       /* the step axis of the datasets of its kind */
    BF_SR_POSITION,   /* positions on a line (balls) */
    BF_SR_POSITION_X, /* point positions, x */
    BF_SR_POSITION_Y, /* point positions, y */
    BF_SR_VELOCITY,   /* velocities at the time of the positions */
    BF_SR_VELOCITY_HALF, /* leapfrog velocities at t - dt/2 */
    BF_SR_FIELD,      /* a field on a grid (nodes, cells, faces) */
    BF_SR_GRID,       /* the grid's coordinates or geometry */
    BF_SR_PROPERTY    /* a property of each item (mass, radius, tag) */
} bf_series_role;

typedef struct bf_series_spec {
    const char *path;  /* the dataset, "/group/name" */
    const char *unit;  /* UDUNITS-2; "1" for numbers */
    const char *doc;
    bf_series_kind kind;
    bf_series_role role;
    int is_int;        /* int64 instead of float64 */
    size_t ncols;      /* fixed columns (0: none, see per) */
    const char *per;   /* NULL, or one column (a static array: one value)
                          per item of this name ("ball", "node",
                          "particle", "cell", ...), counted by the model */
    const char *columns;      /* names of the fixed columns, or NULL */
    const char *column_units; /* their units if they differ, or NULL */
    const char *scaled_unit;  /* the model's scaled unit, or NULL */
    unsigned when;     /* 0: always; else opened when (when & on) != 0 */
    size_t slot;       /* offset of the owner's bf_series * member (not
                          used by static lines) */
} bf_series_spec;

/* The slot of member m of owner type T (checked at compile time to be a
 * bf_series *); lines are written with designated initializers:
 *   {.path = "/film/h", .unit = "cm", .doc = "film height on the nodes",
 *    .kind = BF_SK_SNAPSHOT, .role = BF_SR_FIELD, .per = "node",
 *    .slot = BF_SLOT(bf_filmsys, s_h)},
 * static lines leave .slot out. */
#define BF_SLOT(T, m)                                                          \
    (offsetof(T, m) + 0 * sizeof(&((T *)0)->m == (bf_series **)0))
#define BF_NSERIES(table) (sizeof(table) / sizeof((table)[0]))

/* A component's table, named for listings (`ballfilm info`, the docs
 * check). */
typedef struct bf_series_table {
    const char *name;
    const bf_series_spec *spec;
    size_t n;
} bf_series_table;

/* The number of items `per` names in a run (the model's counts). */
typedef struct bf_series_extent {
    const char *per;
    size_t n;
} bf_series_extent;

/* Open (create, or reopen on restart) every series of table t[0..nt-1]
 * whose `when` is 0 or meets `on`, in the table's order, storing each in
 * the owner's member; static lines are skipped.  A line whose `per` is
 * not among ext[0..next-1] is an internal error naming it. */
bf_status bf_out_open_table(bf_out *out, const bf_series_spec *t, size_t nt,
                            void *owner, const bf_series_extent *ext,
                            size_t next, unsigned on, bf_err *err);
/* Write the static line s: n0 values, one per item (n0 x ncols when it
 * also has fixed columns), or, for a line without items, its ncols
 * values (n0 = ncols). */
bf_status bf_out_table_array(bf_out *out, const bf_series_spec *s,
                             const double *data, size_t n0, bf_err *err);

/* The attribute values of a kind and a role ("rows", "time", ...). */
const char *bf_series_kind_name(bf_series_kind k);
const char *bf_series_role_name(bf_series_role r);

#endif
