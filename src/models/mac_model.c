/* mac_model.c: the "mac" model: the thesis's predictor-corrector MAC
 * solver (src/mac/mac.h) as a model of the time loop.
 *
 * [mac] (its keys: bf_mac_spec, src/mac/mac.c) selects the problem (the
 * stratified reservoir with a point sink of PROGRAM STRATRES, the tank at
 * rest, the uniform stream), the velocity update and pressure solver, and
 * every uncertain reading of the listing (defaults: the listing's most
 * likely reading; docs/models/mac.md lists them).  The explicit terms limit [scene] dt
 * (stable_dt).
 *
 * Output (one row per output time):
 *   /mac/u [(ni+1) nj], /mac/v [ni (nj+1)], /mac/p, /mac/rho, /mac/T,
 *   /mac/flags [ni nj]: fields in the listing's layout, I-major, J fastest;
 *   /mac/particles/x, y, density, flag [slots]: the markers (flag 1 =
 *   free slot, 2 = IN, 3 = OUT, 4 = fluid);
 *   /mac/counts [8]: IN, fluid, OUT particles, free slots, and cumulative
 *   entered, left through the sink, back into the IN column, lost;
 *   /mac/mass [4]: cumulative mass entered, left through the sink, and the
 *   fluid mass now; mass lost;
 *   /mac/diag [6]: max |u|, max |v| on fluid faces, max |div w| in FULL
 *   cells, corrector passes and sweeps of the last step, oscillations.
 */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mac/mac.h"
#include "ballfilm/model.h"
#include "models/mac_model.h"
#include "models/studies.h"
#include "io/dataset_paths.h"

typedef struct mac_model {
    bf_mac *mac;
    bf_mac_params prm; /* the [mac] section it was built from */
    int ni, nj;
    size_t slots;
    bf_series *u, *v, *p, *rho, *temp, *flags;
    bf_series *px, *py, *pd, *pf, *counts, *mass, *diag;
    double *buf;   /* one row of the widest series */
    int64_t *ibuf; /* the same for the integer series */
} mac_model;

const bf_mac *bf_mac_model_solver(void *model)
{
    return ((mac_model *)model)->mac;
}

void bf_mac_model_describe(void *model, char *buf, size_t cap, int *order)
{
    static const char *const updates[3] = {"printed", "consistent",
                                           "original"};
    const mac_model *mm = model;
    snprintf(buf, cap, "MAC update=%s (Euler predictor, projection)",
             updates[mm->prm.update]);
    *order = 1;
}

/* Combinations that cannot work, refused before anything is written (the
 * time-step limits are mac_model_stable_dt's). */
static bf_status check_params(const bf_mac_params *p, bf_err *err)
{
    bf_mac_params def;
    bf_mac_params_default(&def);
    if (p->rho_amp >= p->rho_mean)
        return bf_fail_key(err, BF_EINPUT, "mac", "rho_amp",
                           "rho_amp = %g must be below rho_mean = %g (the "
                           "density must stay positive)",
                           p->rho_amp, p->rho_mean);
    if (p->problem != BF_MAC_RESERVOIR &&
        (p->inflow_prescribed != def.inflow_prescribed ||
         p->out_first != def.out_first || p->out_gravity != def.out_gravity))
        return bf_fail_key(err, BF_EINPUT, "mac", "problem",
                           "inflow, out_first and out_gravity apply to the "
                           "reservoir problem only");
    if ((p->problem == BF_MAC_UNIFORM || p->inflow_prescribed) && p->u0 <= 0)
        return bf_fail_key(err, BF_EINPUT, "mac", "u0",
                           "a prescribed inflow needs u0 > 0 (IN on the "
                           "left)");
    if (p->compare && p->solver != BF_MAC_RELAX)
        return bf_fail_key(err, BF_EINPUT, "mac", "compare",
                           "compare needs pressure_solver = relax");
    return BF_OK;
}

static void mac_model_destroy(void *self)
{
    mac_model *mm = self;
    if (!mm)
        return;
    bf_mac_free(mm->mac);
    free(mm->buf);
    free(mm->ibuf);
    free(mm);
}

/* Per cell about 37 doubles (the solver's 24 fields, flags, counts and
 * coefficient stamps, the output rows of the 6 cell series); the band
 * matrix of the exact pressure solve and its copy, 2 nunk (bw + 1); per
 * particle slot 18 (position, velocity, mass, tag, the solver's 4 and
 * its 3 cell indices, the output rows of the 4 marker series and the row
 * buffers), as mac.c allocates them. */
static void mac_model_memory(const bf_model_setup *setup, bf_mem_need *need)
{
    const bf_mac_params *p = bf_setup_get(setup, &bf_mac_spec, NULL);
    if (!p)
        return;
    double r = (double)p->refine, side = 14.0 * r + 4.0;
    double cells = side * side, unk = 14.0 * r * 14.0 * r;
    double slots = p->slots > 0 ? (double)p->slots : 800.0 * r * r;
    int exact = p->solver == BF_MAC_DIRECT || p->compare;
    need->bytes = 8.0 * (37.0 * cells + (exact ? 2.0 * unk * (14.0 * r + 1.0)
                                               : 0.0) +
                         18.0 * slots);
    snprintf(need->what, sizeof need->what,
             "%.0f cells (refine %ld) and %.3g particle slots", cells,
             p->refine, slots);
    snprintf(need->section, sizeof need->section, "mac");
    snprintf(need->key, sizeof need->key, "%s",
             p->slots > 0 ? "slots" : "refine");
}

static bf_status mac_model_create(void **self, const bf_model_setup *setup,
                                  bf_err *err)
{
    const bf_mac_params *p = bf_setup_get(setup, &bf_mac_spec, NULL);
    bf_status st = check_params(p, err);
    if (st)
        return st;
    mac_model *mm = calloc(1, sizeof *mm);
    if (!mm)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    mm->prm = *p;
    st = bf_mac_create(&mm->mac, p, setup->run.dt, err);
    if (st) {
        free(mm);
        if (st == BF_EINPUT && !err->section[0])
            bf_err_set_key(err, "mac", ""); /* about the section */
        return st;
    }
    bf_mac_dims(mm->mac, &mm->ni, &mm->nj, NULL, NULL);
    mm->slots = bf_mac_particles(mm->mac)->n;
    size_t w = (size_t)(mm->ni + 1) * (size_t)(mm->nj + 1);
    if (mm->slots > w)
        w = mm->slots;
    mm->buf = calloc(w, sizeof *mm->buf);
    mm->ibuf = calloc(w, sizeof *mm->ibuf);
    if (!mm->buf || !mm->ibuf) {
        mac_model_destroy(mm);
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    }
    *self = mm;
    return BF_OK;
}

/* ------------------------------------------------ explicit step limits */

/* A step dt is refused by the explicit viscous and conduction terms when
 * 4 c dt / (rmin h^2) > 1 (c = mu or the conduction coefficient, rmin the
 * smallest density, h = dx = dy), and by a prescribed stream when
 * |u0| dt/dx > max_cfl. */
typedef struct dt_test {
    int cfl;       /* 0: the diffusion test with c; 1: the stream's CFL */
    double c, rmin, h, u0, max_cfl;
} dt_test;

static int refused(const dt_test *k, double dt)
{
    if (!k->cfl)
        return 4.0 * k->c * dt / (k->rmin * k->h * k->h) > 1.0;
    return k->u0 * dt / k->h > k->max_cfl;
}

/* Offer the limit of test k (near `estimate`) to lim: kept if it is the
 * smallest so far (the first on a tie), with its reason and its key.  The
 * limit is the largest dt the test passes, moved from the estimate by an
 * ulp or two, so that the loop refuses exactly the steps it refuses. */
static void offer(bf_dt_limit *lim, const dt_test *k, double estimate,
                  const char *section, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

static void offer(bf_dt_limit *lim, const dt_test *k, double estimate,
                  const char *section, const char *key, const char *fmt, ...)
{
    double dt = estimate;
    while (dt > 0 && refused(k, dt))
        dt = nextafter(dt, 0.0);
    while (dt < DBL_MAX && !refused(k, nextafter(dt, INFINITY)))
        dt = nextafter(dt, INFINITY);
    if (!(dt > 0) || (lim->dt_max > 0 && lim->dt_max <= dt))
        return;
    lim->dt_max = dt;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(lim->why, sizeof lim->why, fmt, ap);
    va_end(ap);
    snprintf(lim->section, sizeof lim->section, "%s", section);
    snprintf(lim->key, sizeof lim->key, "%s", key);
}

/* The smallest of the explicit limits ("" names [scene] dt). */
static void mac_model_stable_dt(const void *self, bf_dt_limit *lim)
{
    const bf_mac_params *p = &((const mac_model *)self)->prm;
    const double h = 0.1 / (double)p->refine;
    const double rmin = p->rho_mean - p->rho_amp;
    const double kap = p->kappa_listing ? p->alpha * p->mu : p->alpha;
    memset(lim, 0, sizeof *lim);
    if (p->mu > 0) {
        const dt_test k = {0, p->mu, rmin, h, 0, 0};
        const double d = rmin * h * h / (4.0 * p->mu);
        offer(lim, &k, d, "", "",
              "the explicit viscous limit h^2 rho/(4 mu) = %g for dx = %g", d,
              h);
    }
    if (kap > 0) {
        const dt_test k = {0, kap, rmin, h, 0, 0};
        const double d = rmin * h * h / (4.0 * kap);
        offer(lim, &k, d, "", "",
              "the explicit conduction limit h^2 rho/(4 alpha) = %g", d);
    }
    if (p->problem == BF_MAC_UNIFORM || p->inflow_prescribed) {
        const dt_test k = {1, 0, rmin, h, fabs(p->u0), p->max_cfl};
        const double d = p->max_cfl * h / fabs(p->u0);
        offer(lim, &k, d, "mac", "u0",
              "the prescribed stream's CFL limit max_cfl dx/u0 = %g (u0 "
              "dt/dx must not exceed max_cfl = %g)",
              d, p->max_cfl);
    }
}

static bf_status mac_model_step(void *self, long n, double t, double dt,
                                bf_err *err)
{
    (void)n;
    (void)t;
    return bf_mac_step(((mac_model *)self)->mac, dt, err);
}

/* The thesis's scaled units (L length, W velocity, R density, dT
 * temperature) are not UDUNITS-2 units: such datasets have unit "1" and
 * the scaled unit in "scaled_unit" (series.h). */
#define FIELD(m, path_, scaled_, per_, doc_)                                   \
    {.path = path_, .unit = "1", .scaled_unit = scaled_, .doc = doc_,         \
     .role = BF_SR_FIELD, .per = per_, .slot = BF_SLOT(mac_model, m)}
#define MARKER(m, path_, scaled_, role_, doc_)                                 \
    {.path = path_, .unit = "1", .scaled_unit = scaled_, .doc = doc_,         \
     .role = role_, .per = "marker slot", .slot = BF_SLOT(mac_model, m)}
static const bf_series_spec mac_series[] = {
    FIELD(u, BF_DS_MAC_U, "W", "u face",
          "horizontal velocity U(I,J), I = 1..ni+1 (left faces), J = 1..nj; "
          "row-major, J fastest"),
    FIELD(v, BF_DS_MAC_V, "W", "v face",
          "vertical velocity V(I,J), I = 1..ni, J = 1..nj+1 (bottom faces)"),
    FIELD(p, BF_DS_MAC_P, "R W^2", "cell", "pressure P(I,J), cell centres"),
    FIELD(rho, BF_DS_MAC_RHO, "R", "cell",
          "cell density R(I,J) (mean of the markers in the cell)"),
    FIELD(temp, BF_DS_MAC_T, "dT", "cell", "temperature T(I,J)"),
    {.path = BF_DS_MAC_FLAGS, .unit = "1", .is_int = 1, .role = BF_SR_FIELD,
     .per = "cell",
     .doc = "cell flags: 1 NOSLIP, 2 IN, 3 OUT, 4 FREESLIP, 10 FULL, 11 SUR, "
            "12 EMP",
     .slot = BF_SLOT(mac_model, flags)},
    MARKER(px, BF_DS_MAC_PARTICLES_X, "L", BF_SR_POSITION_X,
           "marker x (0 for free slots); the fluid is 0 <= x < 1.4"),
    MARKER(py, BF_DS_MAC_PARTICLES_Y, "L", BF_SR_POSITION_Y, "marker y"),
    MARKER(pd, BF_DS_MAC_PARTICLES_DENSITY, "R", BF_SR_PROPERTY,
           "marker density"),
    {.path = BF_DS_MAC_PARTICLES_FLAG, .unit = "1", .is_int = 1,
     .role = BF_SR_PROPERTY, .per = "marker slot",
     .doc = "marker flag: 1 free slot, 2 IN, 3 OUT, 4 fluid",
     .slot = BF_SLOT(mac_model, pf)},
    {.path = "/mac/counts", .unit = "1", .is_int = 1, .ncols = 8,
     .columns = "IN, fluid, OUT, free slots, entered, into the sink, back "
                "into IN, lost",
     .doc = "IN, fluid (REG), OUT particles, free slots; cumulative: entered "
            "the fluid, entered the sink (OUT cells), went back into the IN "
            "column, lost through a wall or the top",
     .slot = BF_SLOT(mac_model, counts)},
    {.path = "/mac/mass", .unit = "1", .scaled_unit = "R L^2", .ncols = 4,
     .columns = "entered, into the sink, fluid now, lost",
     .doc = "cumulative mass entered, cumulative mass into the sink, fluid "
            "mass now (markers x dx dy/4), cumulative mass lost",
     .slot = BF_SLOT(mac_model, mass)},
    {.path = "/mac/diag", .unit = "1", .ncols = 6,
     .columns = "max |u|, max |v|, max |div w|, passes, sweeps, forced fine "
                "passes",
     .scaled_unit = "W; W; W/L; 1; 1; 1",
     .doc = "max |u| and max |v| on fluid faces (W), max |div w| in FULL cells "
            "(W/L), corrector passes and Gauss-Seidel sweeps of the last step, "
            "cumulative forced fine passes (oscillating particle)",
     .slot = BF_SLOT(mac_model, diag)},
    {.path = BF_DS_MAC_GRID, .unit = "1", .kind = BF_SK_STATIC, .ncols = 4,
     .role = BF_SR_GRID, .columns = "ni, nj, dx, dy",
     .scaled_unit = "1; 1; L; L",
     .doc = "ni, nj (cells incl. the ring), dx, dy; cell (I,J) covers x in "
            "[(I-2)dx, (I-1)dx), y in [(J-2)dy, (J-1)dy)"},
};
#undef FIELD
#undef MARKER
enum { MAC_GRID = BF_NSERIES(mac_series) - 1 };
static const bf_series_table mac_table = {"mac", mac_series,
                                          BF_NSERIES(mac_series)};
static const bf_series_table *const mac_tables[] = {&mac_table, NULL};

static bf_status mac_model_output_open(void *self, bf_out *out, bf_err *err)
{
    mac_model *mm = self;
    const size_t ni = (size_t)mm->ni, nj = (size_t)mm->nj;
    const bf_series_extent ext[] = {{"u face", (ni + 1) * nj},
                                    {"v face", ni * (nj + 1)},
                                    {"cell", ni * nj},
                                    {"marker slot", mm->slots}};
    bf_status st = bf_out_open_table(out, mac_series, BF_NSERIES(mac_series),
                                     mm, ext, 4, 0, err);
    if (st)
        return st;
    double dx, dy;
    bf_mac_dims(mm->mac, NULL, NULL, &dx, &dy);
    double grid[4] = {(double)mm->ni, (double)mm->nj, dx, dy};
    return bf_out_table_array(out, &mac_series[MAC_GRID], grid, 4, err);
}

/* Copy field f (defined for I = 1..ni1, J = 1..nj1) into the row buffer. */
static void pack(mac_model *mm, const double *f, int ni1, int nj1)
{
    size_t k = 0;
    for (int i = 1; i <= ni1; i++)
        for (int j = 1; j <= nj1; j++)
            mm->buf[k++] = f[bf_mac_index(mm->mac, i, j)];
}

static bf_status mac_model_output_row(void *self, long n, double t, bf_err *err)
{
    (void)n;
    (void)t;
    mac_model *mm = self;
    const bf_mac *mac = mm->mac;
    const int ni = mm->ni, nj = mm->nj;
    int bad = 0;
    pack(mm, bf_mac_u(mac), ni + 1, nj);
    bad |= bf_series_append(mm->u, mm->buf);
    pack(mm, bf_mac_v(mac), ni, nj + 1);
    bad |= bf_series_append(mm->v, mm->buf);
    pack(mm, bf_mac_p(mac), ni, nj);
    bad |= bf_series_append(mm->p, mm->buf);
    pack(mm, bf_mac_rho(mac), ni, nj);
    bad |= bf_series_append(mm->rho, mm->buf);
    pack(mm, bf_mac_temp(mac), ni, nj);
    bad |= bf_series_append(mm->temp, mm->buf);
    {
        int64_t *ib = mm->ibuf;
        size_t k = 0;
        for (int i = 1; i <= ni; i++)
            for (int j = 1; j <= nj; j++)
                ib[k++] = bf_mac_flags(mac)[bf_mac_index(mac, i, j)];
        bad |= bf_series_append_i64(mm->flags, ib);
    }
    const bf_particles *pt = bf_mac_particles(mac);
    bad |= bf_series_append(mm->px, pt->x);
    bad |= bf_series_append(mm->py, pt->y);
    bad |= bf_series_append(mm->pd, bf_mac_particle_density(mac));
    {
        int64_t *ib = mm->ibuf;
        for (size_t k = 0; k < pt->n; k++)
            ib[k] = pt->tag[k];
        bad |= bf_series_append_i64(mm->pf, ib);
    }
    const bf_mac_counts *c = bf_mac_get_counts(mac);
    int64_t fc[5];
    bf_mac_flag_counts(mac, fc);
    int64_t crow[8] = {fc[BF_MAC_PIN], fc[BF_MAC_REG], fc[BF_MAC_POUT],
                       fc[BF_MAC_AVAIL], c->entered, c->left_out, c->backflow,
                       c->lost};
    bad |= bf_series_append_i64(mm->counts, crow);
    double mrow[4] = {c->mass_in, c->mass_out, bf_mac_fluid_mass(mac),
                      c->mass_lost};
    bad |= bf_series_append(mm->mass, mrow);
    double um, vm, dm;
    int passes;
    long sweeps;
    bf_mac_extremes(mac, &um, &vm, &dm, NULL, NULL);
    bf_mac_last_step(mac, &passes, &sweeps);
    double drow[6] = {um, vm, dm, passes, (double)sweeps,
                      (double)c->oscillations};
    bad |= bf_series_append(mm->diag, drow);
    return bad ? bf_fail(err, BF_EINTERNAL, "out of memory") : BF_OK;
}

static bf_status mac_model_output_close(void *self, bf_out *out, bf_err *err)
{
    const mac_model *mm = self;
    const bf_mac_counts *c = bf_mac_get_counts(mm->mac);
    bf_status st;
    if ((st = bf_out_attr_int(out, "/mac/counts", "oscillations",
                              c->oscillations, err)) ||
        (st = bf_out_attr_int(out, "/mac/counts", "in_clamped", c->in_clamped,
                              err)) ||
        (st = bf_out_attr_int(out, "/mac/counts", "freed", c->freed, err)) ||
        (st = bf_out_attr_int(out, "/mac/counts", "held_at_walls", c->held,
                              err)) ||
        (st = bf_out_attr_int(out, "/mac/diag", "max_sweeps_per_solve",
                              c->max_sweeps_step, err)) ||
        (st = bf_out_attr_real(out, "/mac/diag", "max_gs_minus_exact_dp",
                               c->max_gs_dp, err)))
        return st;
    return bf_out_attr_real(out, "/mac/diag", "max_gs_minus_exact_du",
                            c->max_gs_du, err);
}

static void mac_model_counters(const void *self, bf_counters *c)
{
    const bf_mac_counts *k = bf_mac_get_counts(((const mac_model *)self)->mac);
    c->evals = (unsigned long long)k->passes;
    c->iterations = (unsigned long long)k->sweeps;
}

static void mac_model_report(const void *self, FILE *f)
{
    const mac_model *mm = self;
    const bf_mac *mac = mm->mac;
    const bf_mac_counts *c = bf_mac_get_counts(mac);
    int64_t fc[5];
    bf_mac_flag_counts(mac, fc);
    double um, vm, dm;
    int ic, jc;
    bf_mac_extremes(mac, &um, &vm, &dm, &ic, &jc);
    fprintf(f, "mac: corrector passes (pressure solves) %lld, Gauss-Seidel "
               "sweeps %lld (at most %lld in one solve)\n",
            (long long)c->passes, (long long)c->sweeps,
            (long long)c->max_sweeps_step);
    fprintf(f, "mac: particles now: %lld fluid, %lld IN, %lld OUT, %lld free "
               "slots\n",
            (long long)fc[BF_MAC_REG], (long long)fc[BF_MAC_PIN],
            (long long)fc[BF_MAC_POUT], (long long)fc[BF_MAC_AVAIL]);
    fprintf(f, "mac: entered %lld (mass %.6g), into the sink %lld (mass "
               "%.6g), back into the IN column %lld, lost %lld; fluid mass "
               "%.6g\n",
            (long long)c->entered, c->mass_in, (long long)c->left_out,
            c->mass_out, (long long)c->backflow, (long long)c->lost,
            bf_mac_fluid_mass(mac));
    fprintf(f, "mac: marker moves held at a wall %lld, IN markers held at "
               "the ring's edge %lld, void cells filled %lld\n",
            (long long)c->held, (long long)c->in_clamped,
            (long long)c->voids);
    fprintf(f, "mac: max |u| %.3e, max |v| %.3e, max |div w| %.3e (cell "
               "%d,%d); forced fine passes (oscillating particle) %lld\n",
            um, vm, dm, ic, jc, (long long)c->oscillations);
    if (c->max_gs_dp > 0 || c->max_gs_du > 0)
        fprintf(f, "mac: relaxation vs exact solve: max |dP|/|rho g DEPTH| "
                   "%.3e, max |du| %.3e\n",
                c->max_gs_dp, c->max_gs_du);
}

static bf_status mac_model_save(const void *self, bf_ckpt *ck, bf_err *err)
{
    return bf_mac_save(((const mac_model *)self)->mac, ck, "mac", err);
}

/* A state read from a checkpoint is one a run can have reached: every
 * field value finite, every cell flag one of the listing's (or 0, in the
 * padding around the ring), every marker flag one of the listing's, every
 * marker in use finite and within the grid widened by its own size
 * on each side (a move is less than a cell per step, so no run puts a
 * marker there; the bound keeps x/dx a valid cell index).  A checkpoint
 * that passed its checksum can still hold such values if it was edited
 * and sealed again; refused here, they never reach the solver (a NaN
 * position would be converted to a cell index). */
static bf_status mac_state_valid(const bf_mac *m, bf_err *err)
{
    int ni, nj;
    double dx, dy;
    bf_mac_dims(m, &ni, &nj, &dx, &dy);
    const size_t ncell = (size_t)(ni + 2) * (size_t)(nj + 2);
    const struct {
        const char *name;
        const double *f;
    } fields[] = {{"u", bf_mac_u(m)},   {"v", bf_mac_v(m)},
                  {"p", bf_mac_p(m)},   {"r", bf_mac_rho(m)},
                  {"t", bf_mac_temp(m)}};
    for (size_t q = 0; q < sizeof fields / sizeof *fields; q++)
        for (size_t c = 0; c < ncell; c++)
            if (!isfinite(fields[q].f[c]))
                return bf_fail(err, BF_EINPUT, "checkpoint: mac.%s of cell "
                               "%zu is %g", fields[q].name, c, fields[q].f[c]);
    const int *ic = bf_mac_flags(m);
    for (size_t c = 0; c < ncell; c++)
        if (!(ic[c] == 0 || /* the padding around the ring */
              (ic[c] >= BF_MAC_NOSLIP && ic[c] <= BF_MAC_FREESLIP) ||
              (ic[c] >= BF_MAC_FULL && ic[c] <= BF_MAC_EMP)))
            return bf_fail(err, BF_EINPUT, "checkpoint: mac.ic of cell %zu "
                           "is %d, no cell flag", c, ic[c]);
    const bf_particles *pt = bf_mac_particles(m);
    const double *dens = bf_mac_particle_density(m);
    const double w = (double)ni * dx, h = (double)nj * dy;
    for (size_t k = 0; k < pt->n; k++) {
        if (pt->tag[k] < BF_MAC_AVAIL || pt->tag[k] > BF_MAC_REG)
            return bf_fail(err, BF_EINPUT, "checkpoint: mac.markers.tag of "
                           "marker %zu is %d, no marker flag", k,
                           (int)pt->tag[k]);
        if (pt->tag[k] == BF_MAC_AVAIL)
            continue;
        const double x = pt->x[k], y = pt->y[k];
        if (!(x >= -w && x <= 2 * w && y >= -h && y <= 2 * h) ||
            !isfinite(pt->vx[k]) || !isfinite(pt->vy[k]) ||
            !isfinite(pt->m[k]) || !isfinite(dens[k]))
            return bf_fail(err, BF_EINPUT, "checkpoint: marker %zu at (%g, "
                           "%g) with velocity (%g, %g), mass %g, density %g: "
                           "not finite or far outside the grid", k, x, y,
                           pt->vx[k], pt->vy[k], pt->m[k], dens[k]);
    }
    return BF_OK;
}

static bf_status mac_model_load(void *self, const bf_ckpt *ck, bf_err *err)
{
    const bf_mac *m = ((mac_model *)self)->mac;
    bf_status st = bf_mac_load(((mac_model *)self)->mac, ck, "mac", err);
    return st ? st : mac_state_valid(m, err);
}

static const bf_section_spec *const mac_specs[] = {&bf_mac_spec, NULL};

const bf_model_type bf_model_mac = {
    .name = "mac",
    .series = mac_tables,
    .doc = "stratified viscous fluid, predictor-corrector MAC with markers "
           "(thesis, PROGRAM STRATRES)",
    .flags = 0,
    .specs = mac_specs,
    .create = mac_model_create,
    .destroy = mac_model_destroy,
    .memory = mac_model_memory,
    .stable_dt = mac_model_stable_dt,
    .step = mac_model_step,
    .output_open = mac_model_output_open,
    .output_row = mac_model_output_row,
    .output_close = mac_model_output_close,
    .counters = mac_model_counters,
    .report = mac_model_report,
    .checkpoint_save = mac_model_save,
    .checkpoint_load = mac_model_load,
    .study = &bf_study_mac,
};
