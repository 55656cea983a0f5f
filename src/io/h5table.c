/* h5table.c: opening a component's series from its table (series.h).
 *
 * Each line becomes one bf_out_series (or, for a static line, one
 * bf_out_array) with the line's path, unit and description, then the
 * attributes a reader needs to use the dataset without knowing the model:
 * "kind" and "role", and where the line has them "columns",
 * "column_units" and "scaled_unit". */
#include <string.h>

#include "ballfilm/series.h"

static const char *const kind_names[] = {"rows", "snapshot", "events",
                                         "static"};
static const char *const role_names[] = {
    "diagnostic", "time",       "step",  "position", "position_x",
    "position_y", "velocity",   "velocity_half_step", "field", "grid",
    "property"};

const char *bf_series_kind_name(bf_series_kind k)
{
    return (size_t)k < sizeof kind_names / sizeof *kind_names ? kind_names[k]
                                                              : "?";
}

const char *bf_series_role_name(bf_series_role r)
{
    return (size_t)r < sizeof role_names / sizeof *role_names ? role_names[r]
                                                              : "?";
}

/* The attributes of series.h beyond unit and description. */
static bf_status describe(bf_out *out, const bf_series_spec *s, bf_err *err)
{
    bf_status st = bf_out_attr_str(out, s->path, "kind",
                                   bf_series_kind_name(s->kind), err);
    if (!st)
        st = bf_out_attr_str(out, s->path, "role",
                             bf_series_role_name(s->role), err);
    if (!st && s->columns)
        st = bf_out_attr_str(out, s->path, "columns", s->columns, err);
    if (!st && s->column_units)
        st = bf_out_attr_str(out, s->path, "column_units", s->column_units,
                             err);
    if (!st && s->scaled_unit)
        st = bf_out_attr_str(out, s->path, "scaled_unit", s->scaled_unit,
                             err);
    return st;
}

/* The columns of line s: its fixed count, or the count of its items. */
static bf_status width_of(const bf_series_spec *s, const bf_series_extent *ext,
                          size_t next, size_t *cols, bf_err *err)
{
    *cols = s->ncols;
    if (!s->per)
        return BF_OK;
    for (size_t k = 0; k < next; k++)
        if (ext[k].per && !strcmp(ext[k].per, s->per)) {
            *cols = ext[k].n;
            return BF_OK;
        }
    return bf_fail(err, BF_EINTERNAL, "%s: no count of the items '%s'",
                   s->path, s->per);
}

bf_status bf_out_open_table(bf_out *out, const bf_series_spec *t, size_t nt,
                            void *owner, const bf_series_extent *ext,
                            size_t next, unsigned on, bf_err *err)
{
    for (size_t k = 0; k < nt; k++) {
        const bf_series_spec *s = &t[k];
        if (s->kind == BF_SK_STATIC || (s->when && !(s->when & on)))
            continue;
        size_t cols;
        bf_status st = width_of(s, ext, next, &cols, err);
        if (st)
            return st;
        bf_series *ser = bf_out_series(out, s->path, cols, s->is_int,
                                       s->unit, s->doc, err);
        if (!ser)
            return err->status;
        memcpy((char *)owner + s->slot, &ser, sizeof ser);
        if ((st = describe(out, s, err)))
            return st;
    }
    return BF_OK;
}

bf_status bf_out_table_array(bf_out *out, const bf_series_spec *s,
                             const double *data, size_t n0, bf_err *err)
{
    bf_status st = bf_out_array(out, s->path, data, n0, s->per ? s->ncols : 0,
                                s->unit, s->doc, err);
    return st ? st : describe(out, s, err);
}
