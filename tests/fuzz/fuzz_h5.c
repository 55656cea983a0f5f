/* fuzz_h5.c: the random run of the HDF5 reader fuzzer (make fuzz-h5).
 *
 *   fuzz_h5 CORPUS_DIR FINDINGS_DIR
 *
 * For FUZZ_H5_SECONDS (default 300): a real output of one model (the
 * corpus of tests/fuzz_h5.c, made in CORPUS_DIR by $BALLFILM_BIN as
 * needed), one to three mutations of random objects of it with random
 * numbers (edge values among them: 0, -1, 2^31, 2^62, NaN, inf, huge
 * strings), given to one reader (info, xdmf, run --restart or a film scene
 * with [film] initial = file) under CPU, file-size and wall-clock limits.
 * A run that fh5_verdict finds wrong (a signal, an exit status outside
 * 0-6, a sanitizer report, a refusal not naming its file) is printed and
 * appended to FINDINGS_DIR/found-SEED.recipes as a recipe line that the
 * suite hostile_read replays once the file is in tests/fuzz/h5_regress/.
 * The seed is printed; FUZZ_H5_SEED replays the same sequence of cases.
 * Exit status 0 when nothing was found, 1 when something was, 2 on a bad
 * argument or a corpus that could not be made. */
#define _DEFAULT_SOURCE /* DT_REG */
#include <dirent.h>
#include <hdf5.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "fuzz_h5.h"

/* ------------------------------------------------------------ random */

static uint64_t rng_state;

/* splitmix64: one 64-bit state, enough for choosing among a few hundred
 * objects and numbers, and the same sequence on every machine */
static uint64_t rng(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static size_t pick(size_t n) { return n ? (size_t)(rng() % n) : 0; }

#define PICK(a) ((a)[pick(sizeof(a) / sizeof *(a))])

/* Counts (dimensions, rows, widths): small ones, and the ones whose byte
 * sizes overflow 32 or 64 bits. */
static const char *const counts[] = {
    "0",          "1",          "2",           "3",
    "4",          "7",          "64",          "1000",
    "2147483647", "2147483648", "4294967296",  "17179869184",
    "1099511627776", "2305843009213693952", "4611686018427387904",
    "9223372036854775807"};

/* Lengths of attributes written in full (the mutator writes them). */
static const char *const lengths[] = {"0", "1", "2", "3", "100", "65536",
                                      "200000"};

/* Bytes of a string attribute: written in full, or only claimed. */
static const char *const strbytes[] = {"1", "255", "4096", "65535",
                                       "65536", "1048576", "4194304"};

static const char *const doubles[] = {
    "0",      "-0",     "-1",     "1",      "0.5",   "1e-300",
    "5e-324", "1e300",  "-1e300", "1e6",    "-16",   "2147483648",
    "4611686018427387904", "nan", "inf",   "-inf"};

static const char *const integers[] = {
    "0",          "-1",         "1",          "2",
    "3",          "-5",         "100",        "2147483647",
    "2147483648", "4294967296", "4611686018427387904",
    "9223372036854775807", "-9223372036854775808"};

/* ------------------------------------------------------------ objects */

/* What a corpus file holds: its datasets, groups and attributes (as
 * OBJECT NAME), names without white space only (a recipe is words). */
typedef struct {
    char **dsets, **groups, **attr_obj, **attr_name;
    size_t ndsets, ngroups, nattrs;
} objects;

static void push(char ***v, size_t *n, const char *s)
{
    char **t = realloc(*v, (*n + 1) * sizeof *t);
    char *c = strdup(s);
    if (!t || !c) {
        fprintf(stderr, "fuzz_h5: out of memory\n");
        exit(1);
    }
    *v = t;
    (*v)[(*n)++] = c;
}

static int plain(const char *s) { return s[0] && !strpbrk(s, " \t\n\r+#"); }

typedef struct {
    objects *o;
    const char *obj;
} attr_walk;

static herr_t on_attr(hid_t loc, const char *name, const H5A_info_t *info,
                      void *data)
{
    (void)loc;
    (void)info;
    attr_walk *w = data;
    if (plain(name)) {
        size_t n = w->o->nattrs;
        push(&w->o->attr_obj, &n, w->obj);
        push(&w->o->attr_name, &w->o->nattrs, name);
    }
    return 0;
}

static void attrs_of(hid_t f, const char *path, objects *o)
{
    hid_t obj = H5Oopen(f, path, H5P_DEFAULT);
    if (obj < 0)
        return;
    attr_walk w = {o, path};
    H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, NULL, on_attr, &w);
    H5Oclose(obj);
}

static herr_t on_link(hid_t g, const char *name, const H5L_info_t *info,
                      void *data)
{
    objects *o = data;
    char path[4096];
    if (info->type != H5L_TYPE_HARD || !plain(name) ||
        snprintf(path, sizeof path, "/%s", name) >= (int)sizeof path)
        return 0;
    hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d >= 0) {
        H5Dclose(d);
        push(&o->dsets, &o->ndsets, path);
    } else {
        push(&o->groups, &o->ngroups, path);
    }
    attrs_of(g, path, o);
    return 0;
}

static int list_objects(const char *file, objects *o)
{
    memset(o, 0, sizeof *o);
    hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0)
        return -1;
    attrs_of(f, "/", o);
    H5Lvisit(f, H5_INDEX_NAME, H5_ITER_INC, on_link, o);
    H5Fclose(f);
    return o->ndsets + o->nattrs > 0 ? 0 : -1;
}

/* ------------------------------------------------------------ a case */

typedef struct {
    const char *name, *file;   /* corpus name, its file in the corpus dir */
    const char *commands[3];   /* the readers it is given to */
    objects obj;
} corpus_entry;

static corpus_entry corpora[] = {
    {"balls", "balls.h5", {"info", "xdmf", "initial"}, {0}},
    {"film", "film.h5", {"info", "xdmf", "initial"}, {0}},
    {"mac", "mac.h5", {"info", "xdmf", "initial"}, {0}},
    {"coupled", "coupled.h5", {"info", "xdmf", "initial"}, {0}},
    {"g72", "g72.h5", {"info", "xdmf", "initial"}, {0}},
    {"g73", "g73.h5", {"info", "xdmf", "initial"}, {0}},
    {"part", "part.h5.part", {"info", "xdmf", "restart"}, {0}},
    {"ckpt", "part.h5.ckpt", {"restart", "restart", "restart"}, {0}},
};
#define NCORPORA (sizeof corpora / sizeof *corpora)

/* Append one random mutation of an object of `o` to line. */
static void one_mutation(const objects *o, char *line, size_t cap)
{
    const size_t len = strlen(line), a = pick(o->nattrs),
                 d = pick(o->ndsets);
    char *at = line + len;
    cap -= len;
    /* kinds 0-6 change an attribute, 7-12 a dataset, 13-14 the flush
     * log, 15 deletes a group (list_objects found at least one object) */
    int kind;
    do
        kind = (int)pick(o->ngroups ? 16 : 15);
    while ((!o->nattrs && kind < 7) || (!o->ndsets && kind >= 7 && kind < 13));
    const char *obj = o->nattrs ? o->attr_obj[a] : "",
               *name = o->nattrs ? o->attr_name[a] : "",
               *path = o->ndsets ? o->dsets[d] : "";
    switch (kind) {
    case 0:
        snprintf(at, cap, " attr_array %s %s %s", obj, name, PICK(lengths));
        break;
    case 1:
        snprintf(at, cap, " attr_strarray %s %s %s", obj, name,
                 PICK(lengths));
        break;
    case 2:
        snprintf(at, cap, " attr_int %s %s %s", obj, name, PICK(integers));
        break;
    case 3:
        snprintf(at, cap, " attr_double %s %s %s", obj, name, PICK(doubles));
        break;
    case 4:
        snprintf(at, cap, " attr_longstr %s %s %s", obj, name,
                 PICK(strbytes));
        break;
    case 5:
        snprintf(at, cap, " attr_bigstr %s %s %s", obj, name,
                 PICK(strbytes));
        break;
    case 6:
        snprintf(at, cap, " attr_delete %s %s", obj, name);
        break;
    case 7:
        snprintf(at, cap, " dset_claim %s %s %s", path, PICK(counts),
                 pick(2) ? PICK(counts) : "0");
        break;
    case 8:
        snprintf(at, cap, " dset_rank3 %s", path);
        break;
    case 9:
        snprintf(at, cap, " dset_string %s", path);
        break;
    case 10:
        snprintf(at, cap, " dset_set %s %zu %s", path,
                 pick(2) ? pick(4) : pick(100), PICK(doubles));
        break;
    case 11:
        snprintf(at, cap, " dset_resize %s %s %s", path, PICK(counts),
                 pick(2) ? PICK(counts) : "0");
        break;
    case 12:
        snprintf(at, cap, " delete %s", path);
        break;
    case 13:
        snprintf(at, cap, " log_claim %s %s", PICK(counts), PICK(counts));
        break;
    case 14:
        snprintf(at, cap, " log_rows %s", PICK(integers));
        break;
    default: /* a group, never the root */
        snprintf(at, cap, " delete %s", o->groups[pick(o->ngroups)]);
        break;
    }
}

/* A recipe line: "* CORPUS COMMAND OP ARGS [+ OP ARGS [+ OP ARGS]]". */
static const corpus_entry *make_case(char *line, size_t cap)
{
    const corpus_entry *c = &corpora[pick(NCORPORA)];
    snprintf(line, cap, "* %s %s", c->name, c->commands[pick(3)]);
    const size_t n = 1 + pick(3);
    for (size_t k = 0; k < n; k++) {
        if (k)
            snprintf(line + strlen(line), cap - strlen(line), " %s", FH5_AND);
        one_mutation(&c->obj, line, cap);
    }
    return c;
}

/* The files a case left in the work directory (every case starts from
 * none: a restart finds no output of an earlier one). */
static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[4096];
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.' &&
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name) <
                (int)sizeof path)
            unlink(path);
    if (d)
        closedir(d);
}

/* Run the case of `line`; its verdict (NULL when it is right), the exit
 * status in *rc, stderr in *err. */
static const char *run_case(const char *corpus_dir, const char *work,
                            const char *line, int *rc, char **err)
{
    char copy[2048], *w[64];
    int nw = 0;
    snprintf(copy, sizeof copy, "%s", line);
    for (char *t = strtok(copy, " "); t && nw < 63; t = strtok(NULL, " "))
        w[nw++] = t;
    w[nw] = NULL;
    const char *target = "";
    empty_dir(work);
    *rc = fh5_run(corpus_dir, work, w[1], w[2], (const char *const *)w + 3,
                  err, &target);
    return fh5_verdict(*rc, *err, target);
}

/* ------------------------------------------------------------ main */

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static uint64_t the_seed(void)
{
    const char *s = getenv("FUZZ_H5_SEED");
    if (s && *s)
        return strtoull(s, NULL, 10);
    struct timespec t;
    clock_gettime(CLOCK_REALTIME, &t);
    return ((uint64_t)t.tv_sec * 1000003u) ^ (uint64_t)t.tv_nsec ^
           ((uint64_t)getpid() << 32);
}

/* The line of stderr that says what happened, for a one-line report:
 * a sanitizer's (after its line of '='), else the first. */
static void first_line(const char *s, char *out, size_t cap)
{
    const char *san = s ? strstr(s, "ERROR: ") : NULL;
    if (!san && s)
        san = strstr(s, "runtime error:");
    snprintf(out, cap, "%s", san ? san : s ? s : "");
    out[strcspn(out, "\n")] = '\0';
}

static int record(const char *dir, uint64_t seed, const char *line,
                  const char *why, int rc, const char *err)
{
    char path[4096], head[200];
    snprintf(path, sizeof path, "%s/found-%" PRIu64 ".recipes", dir, seed);
    first_line(err, head, sizeof head);
    printf("fuzz_h5: FOUND (%s; status %d): %s\n  %s\n", why, rc, line, head);
    FILE *f = fopen(path, "a");
    if (!f) {
        fprintf(stderr, "fuzz_h5: cannot write %s\n", path);
        return -1;
    }
    fprintf(f, "# %s (status %d): %s\n%s\n", why, rc, head, line);
    fclose(f);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3 || !getenv("BALLFILM_BIN")) {
        fprintf(stderr, "usage: BALLFILM_BIN=PROGRAM BALLFILM_ROOT=REPO "
                        "[FUZZ_H5_SECONDS=N] [FUZZ_H5_SEED=S] fuzz_h5 "
                        "CORPUS_DIR FINDINGS_DIR\n");
        return 2;
    }
    const char *corpus_dir = argv[1], *found_dir = argv[2];
    const char *secs = getenv("FUZZ_H5_SECONDS");
    const double seconds = secs && *secs ? atof(secs) : 300;
    const uint64_t seed = the_seed();
    rng_state = seed;
    char work[4096];
    snprintf(work, sizeof work, "%s/work", corpus_dir);
    mkdir(corpus_dir, 0700);
    mkdir(found_dir, 0700);
    mkdir(work, 0700);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    for (size_t k = 0; k < NCORPORA; k++) {
        char file[4096];
        snprintf(file, sizeof file, "%s/%s", corpus_dir, corpora[k].file);
        if (fh5_make_corpus(corpus_dir, corpora[k].name) ||
            list_objects(file, &corpora[k].obj)) {
            fprintf(stderr, "fuzz_h5: no corpus file %s\n", file);
            return 2;
        }
    }
    printf("fuzz_h5: seed %" PRIu64 " (replay: FUZZ_H5_SEED=%" PRIu64
           "), %g s, findings into %s/found-%" PRIu64 ".recipes\n",
           seed, seed, seconds, found_dir, seed);
    fflush(stdout);
    const double start = now();
    double report = start + 60;
    long cases = 0, unmade = 0, found = 0, status[8] = {0};
    while (now() - start < seconds) {
        char line[2048], *err = NULL;
        int rc;
        make_case(line, sizeof line);
        const char *why = run_case(corpus_dir, work, line, &rc, &err);
        cases++;
        if (rc <= -1000)
            unmade++; /* HDF5 refused the mutation itself */
        else
            status[rc < 0 || rc > 6 ? 7 : rc]++;
        if (why) {
            found++;
            record(found_dir, seed, line, why, rc, err);
        }
        free(err);
        fflush(stdout);
        if (now() > report) {
            printf("fuzz_h5: %.0f s, %ld cases, %ld found\n", now() - start,
                   cases, found);
            fflush(stdout);
            report += 60;
        }
    }
    printf("fuzz_h5: seed %" PRIu64 ": %ld cases in %.0f s (%ld not made: "
           "HDF5 refused the mutation); exit 0: %ld, 1: %ld, 2: %ld, "
           "3: %ld, 4: %ld, 5: %ld, 6: %ld, other: %ld; %ld found\n",
           seed, cases, now() - start, unmade, status[0], status[1],
           status[2], status[3], status[4], status[5], status[6], status[7],
           found);
    if (found)
        printf("fuzz_h5: fix the readers, then keep the cases: copy "
               "%s/found-%" PRIu64 ".recipes into tests/fuzz/h5_regress/ "
               "(replayed by the suite hostile_read)\n",
               found_dir, seed);
    return found ? 1 : 0;
}
