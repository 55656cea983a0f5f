/* fuzz_ckpt.c: the checkpoint fuzz case (see fuzz_ckpt.h).  Everything
 * runs in this process through the library, as `ballfilm run --restart`
 * does, so that a sanitizer sees every access. */
#include "fuzz_ckpt.h"

#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/checkpoint.h"
#include "ballfilm/run.h"
#include "ballfilm/sim.h"

struct bf_fuzz_ckpt {
    char out[1024], full[1024], part[1100], ckpath[1100], edit[1100];
    unsigned char *ck, *partbytes;
    size_t nck, npart;
    bf_ckpt *parsed;
};

static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, len = 0;
    unsigned char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + len, 1, cap - len, f)) > 0) {
        len += got;
        if (len == cap) {
            unsigned char *nb = realloc(buf, cap *= 2);
            if (!nb) {
                free(buf);
                buf = NULL;
            }
            buf = nb;
        }
    }
    fclose(f);
    *n = len;
    return buf;
}

static int spill(const char *path, const unsigned char *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int bad = n && fwrite(data, 1, n, f) != n;
    return fclose(f) || bad ? -1 : 0;
}

/* Run a scene to `out`, stopped after `stop` steps (0: to the end); the
 * status of the run (or of its set-up). */
static bf_status run_scene(const char *scene, const char *const *sets,
                           const char *out, long stop, bf_err *err)
{
    size_t nsets = 0;
    while (sets && sets[nsets])
        nsets++;
    bf_sim_opts opts = {.stop_after = stop};
    bf_run *r = NULL;
    bf_status st = bf_run_load(&r, bf_catalog_builtin(), scene, sets, nsets,
                               &opts, err);
    if (!st)
        st = bf_run_open_output(r, out, err);
    if (!st) {
        bf_err cerr = {0};
        st = bf_sim_run(bf_run_sim(r), err);
        bf_status cst = bf_sim_close_output(bf_run_sim(r), st, err, &cerr);
        if (!st && cst)
            *err = cerr;
        st = st ? st : cst;
    }
    bf_run_free(r);
    return st;
}

bf_fuzz_ckpt *bf_fuzz_ckpt_new(const char *dir, const char *name,
                               const char *scene, const char *const *sets,
                               long stop, char *why, size_t cap)
{
    bf_fuzz_ckpt *fc = calloc(1, sizeof *fc);
    if (!fc)
        return NULL;
    snprintf(fc->out, sizeof fc->out, "%s/%s.h5", dir, name);
    snprintf(fc->full, sizeof fc->full, "%s/%s_full.h5", dir, name);
    snprintf(fc->part, sizeof fc->part, "%s.part", fc->out);
    snprintf(fc->ckpath, sizeof fc->ckpath, "%s.ckpt", fc->out);
    snprintf(fc->edit, sizeof fc->edit, "%s.edit", fc->out);
    bf_err err = {0};
    bf_status st = run_scene(scene, sets, fc->full, 0, &err);
    if (st) {
        snprintf(why, cap, "%s: the uninterrupted run: %s", name, err.msg);
        goto fail;
    }
    st = run_scene(scene, sets, fc->out, stop, &err);
    if (st != BF_INTERRUPTED) {
        snprintf(why, cap, "%s: the run to stop after %ld steps: status %d %s",
                 name, stop, st, err.msg);
        goto fail;
    }
    fc->ck = slurp(fc->ckpath, &fc->nck);
    fc->partbytes = slurp(fc->part, &fc->npart);
    if (!fc->ck || !fc->partbytes ||
        bf_ckpt_read(&fc->parsed, fc->ckpath, &err)) {
        snprintf(why, cap, "%s: cannot read its checkpoint: %s", name,
                 err.msg);
        goto fail;
    }
    return fc;
fail:
    bf_fuzz_ckpt_free(fc);
    return NULL;
}

void bf_fuzz_ckpt_free(bf_fuzz_ckpt *fc)
{
    if (!fc)
        return;
    free(fc->ck);
    free(fc->partbytes);
    bf_ckpt_free(fc->parsed);
    free(fc);
}

const unsigned char *bf_fuzz_ckpt_file(const bf_fuzz_ckpt *fc, size_t *n)
{
    *n = fc->nck;
    return fc->ck;
}

size_t bf_fuzz_ckpt_entries(const bf_fuzz_ckpt *fc)
{
    return bf_ckpt_count(fc->parsed);
}

/* ---- comparing two outputs ---- */

typedef struct names {
    char **v;
    size_t n, cap;
} names;

static herr_t collect(hid_t obj, const char *name, const H5O_info_t *info,
                      void *op)
{
    (void)obj;
    names *l = op;
    if (info->type != H5O_TYPE_DATASET)
        return 0;
    size_t len = strlen(name);
    if (len >= 4 && !strcmp(name + len - 4, "wall"))
        return 0; /* wall-clock times differ between any two runs */
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 32;
        char **nv = realloc(l->v, l->cap * sizeof *nv);
        if (!nv)
            return -1;
        l->v = nv;
    }
    l->v[l->n++] = strdup(name);
    return 0;
}

/* The raw bytes of dataset `name` of file f (malloc'd), NULL if none. */
static unsigned char *raw(hid_t f, const char *name, size_t *bytes)
{
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    if (d < 0)
        return NULL;
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
    hssize_t np = H5Sget_simple_extent_npoints(sp);
    size_t size = H5Tget_size(t);
    *bytes = np > 0 ? (size_t)np * size : 0;
    unsigned char *buf = malloc(*bytes ? *bytes : 1);
    if (buf && *bytes && H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
        free(buf);
        buf = NULL;
    }
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return buf;
}

/* 1 if a and b hold the same datasets with the same bits. */
static int same_datasets(const char *a, const char *b)
{
    hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
    names la = {0}, lb = {0};
    int same = fa >= 0 && fb >= 0 &&
               H5Ovisit(fa, H5_INDEX_NAME, H5_ITER_INC, collect, &la) >= 0 &&
               H5Ovisit(fb, H5_INDEX_NAME, H5_ITER_INC, collect, &lb) >= 0 &&
               la.n == lb.n;
    for (size_t k = 0; same && k < la.n; k++) {
        size_t na = 0, nb = 0;
        unsigned char *ra = raw(fa, la.v[k], &na), *rb = raw(fb, la.v[k], &nb);
        same = ra && rb && na == nb && !memcmp(ra, rb, na);
        free(ra);
        free(rb);
    }
    for (size_t k = 0; k < la.n; k++)
        free(la.v[k]);
    for (size_t k = 0; k < lb.n; k++)
        free(lb.v[k]);
    free(la.v);
    free(lb.v);
    if (fa >= 0)
        H5Fclose(fa);
    if (fb >= 0)
        H5Fclose(fb);
    return same;
}

/* ---- one case ---- */

void bf_fuzz_ckpt_run(bf_fuzz_ckpt *fc, const unsigned char *data, size_t n,
                      long max_steps, bf_fuzz_outcome *o)
{
    memset(o, 0, sizeof *o);
    unlink(fc->out); /* the result of an earlier case */
    if (spill(fc->part, fc->partbytes, fc->npart) ||
        spill(fc->ckpath, data, n)) {
        o->status = BF_EIO;
        snprintf(o->msg, sizeof o->msg, "cannot write the case's files");
        return;
    }
    bf_err err = {0};
    bf_sim_opts opts = {.stop_after = max_steps};
    bf_run *r = NULL;
    o->status = bf_run_restart(&r, bf_catalog_builtin(), fc->out, NULL, 0,
                               &opts, &err);
    if (!o->status) {
        o->restarted = 1;
        bf_sim *sim = bf_run_sim(r);
        bf_err cerr = {0};
        o->status = bf_sim_run(sim, &err);
        bf_status cst = bf_sim_close_output(sim, o->status, &err, &cerr);
        if (!o->status && cst) {
            o->status = cst;
            err = cerr;
        }
    }
    bf_run_free(r);
    snprintf(o->msg, sizeof o->msg, "%s", o->status ? err.msg : "");
    o->same = o->restarted && o->status == BF_OK &&
              same_datasets(fc->out, fc->full);
}

int bf_fuzz_ckpt_allowed(const bf_fuzz_outcome *o, char *why, size_t cap)
{
    bf_status s = o->status;
    int ok = o->restarted ? s == BF_OK || s == BF_EUNSTABLE ||
                                s == BF_ENOCONV || s == BF_INTERRUPTED
                          : s == BF_EINPUT;
    if (ok && s != BF_OK && !o->msg[0])
        ok = 0;
    if (!ok)
        snprintf(why, cap, "%s with status %d (%s): %s",
                 o->restarted ? "continued" : "refused", (int)s,
                 bf_status_name(s), o->msg[0] ? o->msg : "no message");
    return ok;
}

/* ---- edits ---- */

typedef struct entry {
    const char *name;
    const char *kind;
    size_t n;
    unsigned char *data; /* n elements of 8 bytes (real, int) or 1 */
    int dropped;
} entry;

static size_t width(const char *kind)
{
    return !strcmp(kind, "real") || !strcmp(kind, "int") ? 8 : 1;
}

/* special values: of integers (counts and indices at their limits and
 * off by one) and of reals (non-finite, extreme, nearly the same) */
static int64_t special_int(int64_t v, unsigned k)
{
    /* wrapping arithmetic (v may be at a limit itself) */
    const uint64_t u = (uint64_t)v;
    const int64_t t[16] = {0,
                           1,
                           -1,
                           2,
                           (int64_t)(u + 1),
                           (int64_t)(u - 1),
                           (int64_t)(2 * u),
                           (int64_t)(0 - u),
                           INT32_MAX,
                           INT32_MIN,
                           1LL << 31,
                           1LL << 40,
                           INT64_MAX,
                           INT64_MIN,
                           1000000000000000LL,
                           v / 2};
    return t[k % 16];
}

static double special_real(double x, unsigned k)
{
    const double t[12] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 1e308,
                          -1e308, 5e-324, 2 * x, -x, x + 1, x * (1 + 1e-15)};
    return t[k % 12];
}

static void edit_one(entry *e, size_t i, unsigned op, unsigned v)
{
    size_t w = width(e->kind);
    switch (op % 6) {
    case 0: /* a special value in element i (a byte of a string) */
        if (!e->n)
            break;
        i %= e->n;
        if (!strcmp(e->kind, "int")) {
            int64_t x;
            memcpy(&x, e->data + 8 * i, 8);
            x = special_int(x, v);
            memcpy(e->data + 8 * i, &x, 8);
        } else if (!strcmp(e->kind, "real")) {
            double x;
            memcpy(&x, e->data + 8 * i, 8);
            x = special_real(x, v);
            memcpy(e->data + 8 * i, &x, 8);
        } else {
            e->data[i] = (unsigned char)(v ? v : '0');
        }
        break;
    case 1: /* dropped */
        e->dropped = 1;
        break;
    case 2: /* one element shorter */
        if (e->n)
            e->n--;
        break;
    case 3: { /* one element longer */
        unsigned char *nd = realloc(e->data, (e->n + 1) * w + 1);
        if (!nd)
            break;
        e->data = nd;
        memset(e->data + e->n * w, 0, w + 1);
        e->n++;
        break;
    }
    case 4: /* another kind, the same bytes where they fit */
        e->kind = !strcmp(e->kind, "int") ? "real" : "int";
        if (w == 1) {
            size_t n8 = e->n / 8;
            e->n = n8;
        }
        break;
    case 5: /* empty */
        e->n = 0;
        break;
    }
}

void bf_fuzz_ckpt_edit(const bf_fuzz_ckpt *fc, const unsigned char *prog,
                       size_t nprog, unsigned char **out, size_t *nout)
{
    *out = NULL;
    *nout = 0;
    size_t ne = bf_ckpt_count(fc->parsed);
    entry *es = calloc(ne ? ne : 1, sizeof *es);
    if (!es)
        return;
    for (size_t k = 0; k < ne; k++) {
        const void *d;
        es[k].name = bf_ckpt_entry(fc->parsed, k, &es[k].kind, &es[k].n, &d);
        size_t bytes = es[k].n * width(es[k].kind);
        es[k].data = malloc(bytes + 1);
        if (es[k].data)
            memcpy(es[k].data, d, bytes + (width(es[k].kind) == 1));
    }
    for (size_t p = 0; ne && p + 6 <= nprog; p += 6) {
        size_t k = ((size_t)prog[p] | (size_t)prog[p + 1] << 8) % ne;
        size_t i = (size_t)prog[p + 2] | (size_t)prog[p + 3] << 8;
        if (es[k].data)
            edit_one(&es[k], i, prog[p + 4], prog[p + 5]);
    }
    bf_ckpt *ck = bf_ckpt_new();
    bf_err err = {0};
    int bad = !ck;
    for (size_t k = 0; !bad && k < ne; k++) {
        entry *e = &es[k];
        if (e->dropped || !e->data || !strcmp(e->name, "checksum"))
            continue;
        if (!strcmp(e->kind, "real"))
            bad = bf_ckpt_put(ck, e->name, (const double *)e->data, e->n,
                              &err) != BF_OK;
        else if (!strcmp(e->kind, "int"))
            bad = bf_ckpt_put_i64(ck, e->name, (const int64_t *)e->data, e->n,
                                  &err) != BF_OK;
        else if (!strcmp(e->kind, "str")) {
            e->data[e->n] = '\0';
            bad = bf_ckpt_put_str(ck, e->name, (const char *)e->data, &err) !=
                  BF_OK;
        } else
            bad = bf_ckpt_put_bytes(ck, e->name, e->data, e->n, &err) !=
                  BF_OK;
    }
    if (!bad && bf_ckpt_write(ck, fc->edit, &err) == BF_OK)
        *out = slurp(fc->edit, nout);
    bf_ckpt_free(ck);
    for (size_t k = 0; k < ne; k++)
        free(es[k].data);
    free(es);
}

/* ---- a fuzzer's input ---- */

void bf_fuzz_ckpt_damage(const bf_fuzz_ckpt *fc, const unsigned char *prog,
                         size_t nprog, unsigned char **out, size_t *nout)
{
    *nout = fc->nck;
    *out = malloc(fc->nck ? fc->nck : 1);
    if (!*out)
        return;
    memcpy(*out, fc->ck, fc->nck);
    for (size_t p = 0; p + 4 <= nprog && fc->nck; p += 4) {
        size_t at = ((size_t)prog[p] | (size_t)prog[p + 1] << 8 |
                     (size_t)prog[p + 2] << 16) %
                    fc->nck;
        if (prog[p + 3])
            (*out)[at] ^= prog[p + 3];
        else if (at < *nout)
            *nout = at;
    }
}

int bf_fuzz_ckpt_input(bf_fuzz_ckpt *fc, const unsigned char *in, size_t n,
                       long max_steps, bf_fuzz_outcome *o, char *why,
                       size_t cap)
{
    memset(o, 0, sizeof *o);
    if (n < 1)
        return 1;
    int edit = in[0] & 1;
    unsigned char *file = NULL;
    size_t nfile = 0;
    if (edit)
        bf_fuzz_ckpt_edit(fc, in + 1, n - 1, &file, &nfile);
    else
        bf_fuzz_ckpt_damage(fc, in + 1, n - 1, &file, &nfile);
    if (!file)
        return 1; /* nothing to try (the edits could not be written) */
    bf_fuzz_ckpt_run(fc, file, nfile, max_steps, o);
    int same_bytes = nfile == fc->nck && !memcmp(file, fc->ck, nfile);
    free(file);
    if (!bf_fuzz_ckpt_allowed(o, why, cap))
        return 0;
    /* damage is refused, or changed nothing that matters: the run goes
     * on as the uninterrupted one */
    if (!edit && o->restarted && !o->same) {
        snprintf(why, cap, "a damaged checkpoint was accepted and the run "
                 "differs from the uninterrupted one (status %d: %s)",
                 (int)o->status, o->msg);
        return 0;
    }
    if (same_bytes && !o->same) {
        snprintf(why, cap, "the real checkpoint did not give the "
                 "uninterrupted run (status %d: %s)", (int)o->status, o->msg);
        return 0;
    }
    return 1;
}

/* ---- the models fuzzed ---- */

/* A short run of each model, stopped part-way (its checkpoint is the one
 * damaged and edited), with its analyses' and its shadow's state. */
static const struct {
    const char *name, *scene;
    const char *sets[8];
    long stop, steps;
} models[] = {
    {"balls", "runs/two_balls_B.ini",
     {"scene.t_end=0.05", "scene.output_every=50", "lyapunov.enabled=yes",
      NULL},
     230, 500},
    {"film", "runs/kink_steady.ini",
     {"film.length=10", "scene.t_end=0.05", "scene.output_every=10",
      "film.profile_every=20", NULL},
     23, 50},
    {"coupled", "runs/coupled_fig8.ini",
     {"film.length=10", "scene.t_end=5e-4", "scene.output_every=10",
      "lyapunov.enabled=yes", "lyapunov.renormalise_every=7", NULL},
     23, 50},
    {"greenspan72", "runs/greenspan72_ex1.ini", {"scene.t_end=0.05", NULL},
     23, 50},
    {"greenspan73", "runs/greenspan73_hex_v300.ini", {"scene.t_end=0.2", NULL},
     4, 10},
    {"mac", "runs/mac_rest.ini", {"scene.t_end=0.5", NULL}, 4, 10},
};

size_t bf_fuzz_ckpt_nmodels(void) { return sizeof models / sizeof *models; }

bf_fuzz_ckpt *bf_fuzz_ckpt_model(const char *root, const char *dir, size_t k,
                                 const char **name, long *steps, char *why,
                                 size_t cap)
{
    k %= bf_fuzz_ckpt_nmodels();
    char scene[2048];
    snprintf(scene, sizeof scene, "%s/%s", root, models[k].scene);
    *name = models[k].name;
    *steps = models[k].steps;
    return bf_fuzz_ckpt_new(dir, models[k].name, scene, models[k].sets,
                            models[k].stop, why, cap);
}
