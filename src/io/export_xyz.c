/* export_xyz.c: a run's particles as extended XYZ (see export.h): one
 * frame per output row,
 *   N
 *   Properties=species:S:1:pos:R:3:velo:R:3 Time=t step=k pbc="F F F" ...
 *   H x y z vx vy vz
 * Species k is written as the element of atomic number k (1 H, 2 He, 3
 * Li, 4 Be: a label, as readers want element names); missing coordinates
 * are 0.  Units and what the velocities are go in the comment line. */
#include "io/export_impl.h"

#include <stdlib.h>
#include <string.h>

static const char *const element[] = {"X", "H", "He", "Li", "Be", "B",
                                      "C", "N", "O", "F", "Ne"};

static bf_status frame(const bf_xsrc *s, FILE *f, size_t k, double *const *b,
                       bf_err *err)
{
    /* b: x, y, vx, vy, species, density */
    bf_status st = BF_OK;
    const char *const paths[5] = {s->pos[0], s->pos[1], s->vel[0], s->vel[1],
                                  s->density};
    const int slot[5] = {0, 1, 2, 3, 5};
    for (int c = 0; c < 5 && !st; c++)
        if (paths[c])
            st = bf_xsrc_read(s, paths[c], k, s->n, b[slot[c]], err);
    if (!st)
        st = bf_xsrc_species(s, k, b[4], err);
    if (st)
        return st;
    fprintf(f, "%zu\nProperties=species:S:1:pos:R:3%s%s Time=%.17g "
               "step=%lld pbc=\"F F F\" length_unit=\"%s\" time_unit=\"%s\"",
            s->n, s->vel[0] ? ":velo:R:3" : "",
            s->density ? ":density:R:1" : "", s->time[k], s->step[k],
            s->unit_len, s->unit_time);
    if (s->vel[0])
        fprintf(f, " velocity_unit=\"%s\"", s->unit_vel);
    if (s->density)
        fprintf(f, " density_unit=\"%s\"", s->unit_density);
    if (s->half_step)
        fprintf(f, " velo_time=%.17g velo=\"leapfrog half-step velocity "
                   "v^(k-1/2)%s\"",
                s->step[k] ? s->time[k] - 0.5 * s->dt : s->time[k],
                s->step[k] ? "" : ", the initial velocity at step 0");
    fprintf(f, " group=%s\n", s->group);
    for (size_t i = 0; i < s->n; i++) {
        const double sp = b[4][i];
        const char *name = sp >= 0 && sp < 11 && sp == (double)(int)sp
                               ? element[(int)sp]
                               : "X";
        fprintf(f, "%s %.17g %.17g 0", name, b[0][i],
                s->dim > 1 ? b[1][i] : 0.0);
        if (s->vel[0])
            fprintf(f, " %.17g %.17g 0", b[2][i], s->dim > 1 ? b[3][i] : 0.0);
        if (s->density)
            fprintf(f, " %.17g", b[5][i]);
        fputc('\n', f);
    }
    return BF_OK;
}

bf_status bf_export_xyz(const bf_xsrc *s, FILE *f, bf_err *err)
{
    double *b[6];
    bf_status st = BF_OK;
    for (int c = 0; c < 6; c++)
        if (!(b[c] = calloc(s->n ? s->n : 1, sizeof *b[c])))
            st = bf_fail(err, BF_EINTERNAL, "out of memory");
    for (size_t k = 0; !st && k < s->rows; k++) {
        st = bf_xsrc_stopped(s, err);
        if (!st)
            st = frame(s, f, k, b, err);
        if (!st && ferror(f))
            st = bf_fail(err, BF_EIO, "writing failed (disk full?)");
    }
    for (int c = 0; c < 6; c++)
        free(b[c]);
    return st;
}
