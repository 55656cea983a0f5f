/* scene.c: reading, overriding and validating scene files (see scene.h).
 *
 * inih does the INI syntax.  We feed it through our own line reader so that
 * we know the line number of every key (the Debian build of inih does not
 * pass it to the handler), can tell a continuation line from a duplicate key,
 * and can refuse over-long lines instead of letting inih split them.
 */
#include "ballfilm/scene.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAX_LINE 4096 /* longer lines are refused */
#define MAX_SPECS 64

typedef struct entry {
    char *section, *key, *text;
    char *origin; /* file path or "--set" */
    int line;     /* 0: no line (default or command line) */
    int given;    /* 1: from the file or an override, 0: default */
    const bf_param *param;
    double r;
    long i;
    int b, e;
    double *reals;
    size_t nreals;
    char **names;
    size_t nnames;
    bf_interval iv;
} entry;

typedef struct sect {
    char *name;
    int line;
} sect;

struct bf_scene {
    char *path;
    char *text;
    entry *raw; /* as read, with overrides applied */
    size_t nraw, capraw;
    sect *sects;
    size_t nsects, capsects;
    entry *res; /* resolved: every declared key of every active section */
    size_t nres, capres;
    int resolved;      /* 0 none, 1 root only, 2 complete */
    const bf_section_spec *active[MAX_SPECS];
    size_t nactive;
    char **sets; /* overrides as given */
    size_t nsets;
};

/* ---------------------------------------------------------------- helpers */

static char *xstrdup(const char *s)
{
    char *d = strdup(s ? s : "");
    if (!d) {
        fprintf(stderr, "ballfilm: out of memory\n");
        abort();
    }
    return d;
}

static void *xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q) {
        fprintf(stderr, "ballfilm: out of memory\n");
        abort();
    }
    return q;
}

static void entry_clear_values(entry *e)
{
    free(e->reals);
    e->reals = NULL;
    e->nreals = 0;
    for (size_t k = 0; k < e->nnames; k++)
        free(e->names[k]);
    free(e->names);
    e->names = NULL;
    e->nnames = 0;
}

static void entry_free(entry *e)
{
    free(e->section);
    free(e->key);
    free(e->text);
    free(e->origin);
    entry_clear_values(e);
}

static entry *push_entry(entry **arr, size_t *n, size_t *cap)
{
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 32;
        *arr = xrealloc(*arr, *cap * sizeof **arr);
    }
    entry *e = &(*arr)[(*n)++];
    memset(e, 0, sizeof *e);
    return e;
}

static entry *find_raw(const bf_scene *sc, const char *section, const char *key)
{
    for (size_t k = 0; k < sc->nraw; k++)
        if (!strcmp(sc->raw[k].section, section) && !strcmp(sc->raw[k].key, key))
            return &sc->raw[k];
    return NULL;
}

static const sect *find_sect(const bf_scene *sc, const char *name)
{
    for (size_t k = 0; k < sc->nsects; k++)
        if (!strcmp(sc->sects[k].name, name))
            return &sc->sects[k];
    return NULL;
}

static void add_sect(bf_scene *sc, const char *name, int line)
{
    if (find_sect(sc, name))
        return;
    if (sc->nsects == sc->capsects) {
        sc->capsects = sc->capsects ? 2 * sc->capsects : 16;
        sc->sects = xrealloc(sc->sects, sc->capsects * sizeof *sc->sects);
    }
    sc->sects[sc->nsects].name = xstrdup(name);
    sc->sects[sc->nsects].line = line;
    sc->nsects++;
}

/* "FILE:LINE: error: " or "FILE: error: " */
static bf_status fail_at(bf_err *err, const char *origin, int line,
                         const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static bf_status fail_at(bf_err *err, const char *origin, int line,
                         const char *fmt, ...)
{
    char body[BF_ERR_MSG];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(body, sizeof body, fmt, ap);
    va_end(ap);
    if (line > 0)
        return bf_fail(err, BF_EINPUT, "%s:%d: error: %s", origin, line, body);
    return bf_fail(err, BF_EINPUT, "%s: error: %s", origin, body);
}

/* ----------------------------------------------------------- reading INI */

typedef struct reader {
    const char *p;      /* remaining text */
    int line;           /* line number of the line last handed to inih */
    int cont;           /* that line is a continuation line */
    int too_long;       /* first over-long line, or 0 */
    bf_scene *sc;
    bf_err *err;
    int failed;
    char last_section[256];
    char last_key[256];
} reader;

static char *read_line(char *str, int num, void *stream)
{
    reader *r = stream;
    if (!*r->p)
        return NULL;
    const char *nl = strchr(r->p, '\n');
    size_t len = nl ? (size_t)(nl - r->p) + 1 : strlen(r->p);
    r->line++;
    if (len >= (size_t)num) {
        if (!r->too_long)
            r->too_long = r->line;
        len = 0; /* hand inih an empty line; the error is reported later */
    }
    memcpy(str, r->p, len);
    str[len] = '\0';
    r->p += nl ? (size_t)(nl - r->p) + 1 : strlen(r->p);
    /* A continuation line starts with blanks and has text after them. */
    r->cont = 0;
    if (len && (str[0] == ' ' || str[0] == '\t')) {
        const char *q = str;
        while (*q == ' ' || *q == '\t')
            q++;
        if (*q && *q != '\n' && *q != '\r' && *q != ';' && *q != '#')
            r->cont = 1;
    }
    /* Remember section headers with their line for messages. */
    const char *q = str;
    while (*q == ' ' || *q == '\t')
        q++;
    if (*q == '[') {
        const char *end = strchr(q, ']');
        if (end && end - q - 1 < 255) {
            char name[256];
            size_t nlen = (size_t)(end - q - 1);
            memcpy(name, q + 1, nlen);
            name[nlen] = '\0';
            /* inih strips blanks inside the brackets too */
            char *s = name;
            while (*s == ' ' || *s == '\t')
                s++;
            char *t = s + strlen(s);
            while (t > s && (t[-1] == ' ' || t[-1] == '\t'))
                *--t = '\0';
            add_sect(r->sc, s, r->line);
        }
    }
    return str;
}

static int on_key(void *user, const char *section, const char *name,
                  const char *value)
{
    reader *r = user;
    bf_scene *sc = r->sc;
    if (r->failed)
        return 0;
    if (!*section) {
        r->failed = 1;
        fail_at(r->err, sc->path, r->line,
                "key '%s' appears before any [section]", name);
        return 0;
    }
    entry *old = find_raw(sc, section, name);
    if (old && r->cont && !strcmp(r->last_section, section) &&
        !strcmp(r->last_key, name)) {
        /* continuation of a multi-line value: join with a blank */
        size_t a = strlen(old->text), b = strlen(value);
        old->text = xrealloc(old->text, a + b + 2);
        old->text[a] = ' ';
        memcpy(old->text + a + 1, value, b + 1);
        return 1;
    }
    if (old) {
        r->failed = 1;
        fail_at(r->err, sc->path, r->line,
                "[%s] %s: key given twice (first at line %d)", section, name,
                old->line);
        return 0;
    }
    entry *e = push_entry(&sc->raw, &sc->nraw, &sc->capraw);
    e->section = xstrdup(section);
    e->key = xstrdup(name);
    e->text = xstrdup(value);
    e->origin = xstrdup(sc->path);
    e->line = r->line;
    e->given = 1;
    snprintf(r->last_section, sizeof r->last_section, "%s", section);
    snprintf(r->last_key, sizeof r->last_key, "%s", name);
    return 1;
}

bf_status bf_scene_load_string(bf_scene **out, const char *name,
                               const char *text, bf_err *err)
{
    *out = NULL;
    bf_scene *sc = calloc(1, sizeof *sc);
    if (!sc)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    sc->path = xstrdup(name);
    sc->text = xstrdup(text);
    if (strlen(text) != strlen(sc->text) || memchr(text, '\0', strlen(text))) {
        /* unreachable for C strings; kept for clarity */
    }
    reader r = {.p = sc->text, .sc = sc, .err = err};
    /* inih reads into a buffer of INI_MAX_LINE; our reader is told its size
     * and refuses longer lines, so nothing is silently split. */
    int rc = ini_parse_stream(read_line, &r, on_key, &r);
    if (r.failed) {
        bf_scene_free(sc);
        return BF_EINPUT;
    }
    if (r.too_long) {
        bf_scene_free(sc);
        return fail_at(err, name, r.too_long,
                       "line too long; split the value over continuation "
                       "lines (indented lines continue a value)");
    }
    if (rc != 0) {
        bf_scene_free(sc);
        return fail_at(err, name, rc > 0 ? rc : 0,
                       "syntax error (expected '[section]', 'key = value' or "
                       "a comment)");
    }
    *out = sc;
    return BF_OK;
}

bf_status bf_scene_load(bf_scene **out, const char *path, bf_err *err)
{
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return bf_fail(err, BF_EINPUT, "%s: error: cannot open scene file: %s",
                       path, strerror(errno));
    size_t cap = 4096, n = 0;
    char *buf = xrealloc(NULL, cap);
    size_t got;
    while ((got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (n + 1 == cap) {
            if (cap > (64u << 20)) {
                fclose(f);
                free(buf);
                return bf_fail(err, BF_EINPUT,
                               "%s: error: scene file larger than 64 MiB", path);
            }
            cap *= 2;
            buf = xrealloc(buf, cap);
        }
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return bf_fail(err, BF_EINPUT, "%s: error: cannot read scene file",
                       path);
    }
    buf[n] = '\0';
    if (memchr(buf, '\0', n)) {
        free(buf);
        return bf_fail(err, BF_EINPUT,
                       "%s: error: scene file contains a NUL byte (not text)",
                       path);
    }
    bf_status st = bf_scene_load_string(out, path, buf, err);
    free(buf);
    return st;
}

static void free_resolved(bf_scene *sc)
{
    for (size_t k = 0; k < sc->nres; k++)
        entry_free(&sc->res[k]);
    sc->nres = 0;
    sc->resolved = 0;
    sc->nactive = 0;
}

void bf_scene_free(bf_scene *sc)
{
    if (!sc)
        return;
    free_resolved(sc);
    free(sc->res);
    for (size_t k = 0; k < sc->nraw; k++)
        entry_free(&sc->raw[k]);
    free(sc->raw);
    for (size_t k = 0; k < sc->nsects; k++)
        free(sc->sects[k].name);
    free(sc->sects);
    for (size_t k = 0; k < sc->nsets; k++)
        free(sc->sets[k]);
    free(sc->sets);
    free(sc->path);
    free(sc->text);
    free(sc);
}

size_t bf_scene_overrides(const bf_scene *sc, const char *const **list)
{
    *list = (const char *const *)sc->sets;
    return sc->nsets;
}

bf_scene *bf_scene_clone(const bf_scene *sc)
{
    bf_scene *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->path = xstrdup(sc->path);
    c->text = xstrdup(sc->text);
    for (size_t k = 0; k < sc->nraw; k++) {
        entry *e = push_entry(&c->raw, &c->nraw, &c->capraw);
        e->section = xstrdup(sc->raw[k].section);
        e->key = xstrdup(sc->raw[k].key);
        e->text = xstrdup(sc->raw[k].text);
        e->origin = xstrdup(sc->raw[k].origin);
        e->line = sc->raw[k].line;
        e->given = 1;
    }
    for (size_t k = 0; k < sc->nsects; k++)
        add_sect(c, sc->sects[k].name, sc->sects[k].line);
    for (size_t k = 0; k < sc->nsets; k++) {
        c->sets = xrealloc(c->sets, (c->nsets + 1) * sizeof *c->sets);
        c->sets[c->nsets++] = xstrdup(sc->sets[k]);
    }
    return c;
}

/* ---------------------------------------------------------------- --set */

static int valid_name(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '.' && *s != '-')
            return 0;
    return 1;
}

bf_status bf_scene_set(bf_scene *sc, const char *assignment, const char *origin,
                       bf_err *err)
{
    const char *eq = strchr(assignment, '=');
    if (!eq)
        return bf_fail(err, BF_EINPUT,
                       "%s: error: '%s': expected section.key=value", origin,
                       assignment);
    while (*assignment == ' ' || *assignment == '\t')
        assignment++;
    size_t lhs = (size_t)(eq - assignment);
    while (lhs && (assignment[lhs - 1] == ' ' || assignment[lhs - 1] == '\t'))
        lhs--;
    char name[512];
    if (lhs >= sizeof name)
        return bf_fail(err, BF_EINPUT, "%s: error: name too long", origin);
    memcpy(name, assignment, lhs);
    name[lhs] = '\0';
    char *dot = strrchr(name, '.');
    if (!dot || dot == name || !dot[1])
        return bf_fail(err, BF_EINPUT,
                       "%s: error: '%s': expected section.key=value", origin,
                       assignment);
    *dot = '\0';
    const char *section = name, *key = dot + 1;
    if (!valid_name(section) || !valid_name(key))
        return bf_fail(err, BF_EINPUT,
                       "%s: error: '%s': section and key may contain only "
                       "letters, digits, '_', '-' and '.'",
                       origin, assignment);
    /* inih strips blanks around values; do the same */
    const char *v = eq + 1;
    while (*v == ' ' || *v == '\t')
        v++;
    char *val = xstrdup(v);
    for (size_t n = strlen(val); n && (val[n - 1] == ' ' || val[n - 1] == '\t');)
        val[--n] = '\0';
    entry *e = find_raw(sc, section, key);
    if (!e) {
        e = push_entry(&sc->raw, &sc->nraw, &sc->capraw);
        e->section = xstrdup(section);
        e->key = xstrdup(key);
    } else {
        free(e->text);
        free(e->origin);
    }
    e->text = val;
    e->origin = xstrdup(origin);
    e->line = 0;
    e->given = 1;
    add_sect(sc, section, 0);
    sc->sets = xrealloc(sc->sets, (sc->nsets + 1) * sizeof *sc->sets);
    sc->sets[sc->nsets++] = xstrdup(assignment);
    free_resolved(sc);
    return BF_OK;
}

/* -------------------------------------------------------- value parsing */

int bf_parse_real(const char *text, double *out)
{
    if (!text || !*text)
        return 0;
    char *end;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text)
        return 0;
    while (*end == ' ' || *end == '\t')
        end++;
    if (*end || !isfinite(v) || errno == ERANGE) {
        /* ERANGE on underflow of a tiny number is fine (v is 0 or tiny) */
        if (*end || !isfinite(v) || fabs(v) > 1.0)
            return 0;
    }
    *out = v;
    return 1;
}

int bf_parse_long(const char *text, long *out)
{
    if (!text || !*text)
        return 0;
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    while (*end == ' ' || *end == '\t')
        end++;
    if (!*end && end != text && errno == 0) {
        *out = v;
        return 1;
    }
    /* accept integral reals such as 1e5 */
    double d;
    if (bf_parse_real(text, &d) && d == floor(d) && fabs(d) < 9e15) {
        *out = (long)d;
        return 1;
    }
    return 0;
}

static int parse_bool(const char *t, int *out)
{
    static const char *yes[] = {"true", "yes", "on", "1"};
    static const char *no[] = {"false", "no", "off", "0"};
    for (int k = 0; k < 4; k++) {
        if (!strcasecmp(t, yes[k])) {
            *out = 1;
            return 1;
        }
        if (!strcasecmp(t, no[k])) {
            *out = 0;
            return 1;
        }
    }
    return 0;
}

/* Index of `word` in "a|b|c", or -1. */
static int choice_index(const char *choices, const char *word)
{
    int idx = 0;
    const char *p = choices;
    size_t wl = strlen(word);
    while (p && *p) {
        const char *bar = strchr(p, '|');
        size_t len = bar ? (size_t)(bar - p) : strlen(p);
        if (len == wl && !strncmp(p, word, len))
            return idx;
        idx++;
        p = bar ? bar + 1 : NULL;
    }
    return -1;
}

/* Split on commas and blanks. Returns the number of tokens; *toks is a
 * malloc'd array of malloc'd strings. */
static size_t split_list(const char *text, char ***toks)
{
    size_t n = 0, cap = 8;
    char **t = xrealloc(NULL, cap * sizeof *t);
    const char *p = text;
    for (;;) {
        while (*p == ',' || *p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
            p++;
        if (!*p)
            break;
        const char *q = p;
        while (*q && *q != ',' && *q != ' ' && *q != '\t' && *q != '\n' &&
               *q != '\r')
            q++;
        if (n == cap) {
            cap *= 2;
            t = xrealloc(t, cap * sizeof *t);
        }
        t[n] = xrealloc(NULL, (size_t)(q - p) + 1);
        memcpy(t[n], p, (size_t)(q - p));
        t[n][q - p] = '\0';
        n++;
        p = q;
    }
    *toks = t;
    return n;
}

static void free_toks(char **t, size_t n)
{
    for (size_t k = 0; k < n; k++)
        free(t[k]);
    free(t);
}

static const char *type_name(bf_ptype t)
{
    switch (t) {
    case BF_REAL: return "real";
    case BF_INT: return "integer";
    case BF_BOOL: return "bool";
    case BF_STR: return "text";
    case BF_ENUM: return "choice";
    case BF_NAMES: return "list of names";
    case BF_REALS: return "list of reals";
    case BF_INTERVAL: return "interval";
    }
    return "?";
}

/* Range check of one number; writes the violated condition into `why`. */
static int in_range(const bf_param *p, double v, char *why, size_t n)
{
    if ((p->flags & BF_POS) && !(v > 0)) {
        snprintf(why, n, "must be > 0");
        return 0;
    }
    if ((p->flags & BF_NONNEG) && !(v >= 0)) {
        snprintf(why, n, "must be >= 0");
        return 0;
    }
    if ((p->flags & BF_MIN) && !(v >= p->lo)) {
        snprintf(why, n, "must be >= %g", p->lo);
        return 0;
    }
    if ((p->flags & BF_MAX) && !(v <= p->hi)) {
        snprintf(why, n, "must be <= %g", p->hi);
        return 0;
    }
    return 1;
}

static bf_status where_fail(bf_err *err, const entry *e, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static bf_status where_fail(bf_err *err, const entry *e, const char *fmt, ...)
{
    char body[BF_ERR_MSG];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(body, sizeof body, fmt, ap);
    va_end(ap);
    const char *origin = e->origin ? e->origin : "(default)";
    if (!e->given)
        return fail_at(err, origin, 0, "[%s] %s: default '%s' %s", e->section,
                       e->key, e->text, body);
    return fail_at(err, origin, e->line, "[%s] %s: '%s' %s", e->section,
                   e->key, e->text, body);
}

static bf_status parse_value(entry *e, bf_err *err)
{
    const bf_param *p = e->param;
    char why[128];
    entry_clear_values(e);
    switch (p->type) {
    case BF_REAL:
        if (!bf_parse_real(e->text, &e->r))
            return where_fail(err, e, "is not a finite real number");
        if (!in_range(p, e->r, why, sizeof why))
            return where_fail(err, e, "%s", why);
        return BF_OK;
    case BF_INT:
        if (!bf_parse_long(e->text, &e->i))
            return where_fail(err, e, "is not an integer");
        if (!in_range(p, (double)e->i, why, sizeof why))
            return where_fail(err, e, "%s", why);
        return BF_OK;
    case BF_BOOL:
        if (!parse_bool(e->text, &e->b))
            return where_fail(err, e, "is not true/false (yes/no, on/off, 1/0)");
        return BF_OK;
    case BF_STR:
        return BF_OK;
    case BF_ENUM:
        e->e = choice_index(p->choices, e->text);
        if (e->e < 0)
            return where_fail(err, e, "is not one of %s", p->choices);
        return BF_OK;
    case BF_NAMES: {
        char **t;
        size_t n = split_list(e->text, &t);
        for (size_t k = 0; k < n; k++) {
            if (p->choices && choice_index(p->choices, t[k]) < 0) {
                bf_status st = where_fail(err, e, "contains '%s', not one of %s",
                                          t[k], p->choices);
                free_toks(t, n);
                return st;
            }
            for (size_t j = 0; j < k; j++)
                if (!strcmp(t[j], t[k])) {
                    bf_status st =
                        where_fail(err, e, "names '%s' twice", t[k]);
                    free_toks(t, n);
                    return st;
                }
        }
        e->names = t;
        e->nnames = n;
        return BF_OK;
    }
    case BF_REALS: {
        char **t;
        size_t n = split_list(e->text, &t);
        e->reals = xrealloc(NULL, (n ? n : 1) * sizeof *e->reals);
        e->nreals = n;
        for (size_t k = 0; k < n; k++) {
            if (!bf_parse_real(t[k], &e->reals[k])) {
                bf_status st = where_fail(err, e, "element %zu '%s' is not a "
                                          "finite real number", k + 1, t[k]);
                free_toks(t, n);
                return st;
            }
            if (!in_range(p, e->reals[k], why, sizeof why)) {
                bf_status st = where_fail(err, e, "element %zu %s", k + 1, why);
                free_toks(t, n);
                return st;
            }
        }
        free_toks(t, n);
        return BF_OK;
    }
    case BF_INTERVAL: {
        char **t;
        size_t n = split_list(e->text, &t);
        bf_status st = BF_OK;
        memset(&e->iv, 0, sizeof e->iv);
        if (n == 1 || (n == 2 && !strcmp(t[1], "steps"))) {
            if (!bf_parse_long(t[0], &e->iv.steps) || e->iv.steps < 0)
                st = where_fail(err, e, "is not a number of steps >= 0 "
                                "(write 'T s' for simulated seconds)");
        } else if (n == 2 && !strcmp(t[1], "s")) {
            e->iv.in_time = 1;
            if (!bf_parse_real(t[0], &e->iv.time) || !(e->iv.time >= 0))
                st = where_fail(err, e, "is not a time >= 0 in seconds");
        } else {
            st = where_fail(err, e, "expected 'N' (steps), 'N steps' or "
                            "'T s' (simulated seconds)");
        }
        free_toks(t, n);
        return st;
    }
    }
    return where_fail(err, e, "has an unknown type");
}

/* ----------------------------------------------------------- resolution */

/* Match a section name against a spec name; "ball.N" matches "ball.3" and
 * stores 3 in *idx. */
static int spec_matches(const bf_section_spec *s, const char *section, int *idx)
{
    size_t L = strlen(s->name);
    *idx = 0;
    if (L > 2 && !strcmp(s->name + L - 2, ".N")) {
        if (strncmp(section, s->name, L - 1))
            return 0;
        const char *d = section + L - 1;
        if (!*d || *d == '0')
            return 0;
        for (const char *q = d; *q; q++)
            if (!isdigit((unsigned char)*q))
                return 0;
        if (strlen(d) > 6)
            return 0;
        *idx = atoi(d);
        return 1;
    }
    return !strcmp(s->name, section);
}

static const bf_param *spec_param(const bf_section_spec *s, const char *key)
{
    for (const bf_param *p = s->params; p && p->key; p++)
        if (!strcmp(p->key, key))
            return p;
    return NULL;
}

static void list_keys(const bf_section_spec *s, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const bf_param *p = s->params; p && p->key; p++) {
        if (p->flags & BF_HIDDEN)
            continue;
        int w = snprintf(buf + used, n - used, "%s%s", used ? ", " : "", p->key);
        if (w < 0 || (size_t)w >= n - used)
            break;
        used += (size_t)w;
    }
}

static bf_status resolve_sections(bf_scene *sc, const bf_section_spec *const *specs,
                                  size_t nspecs, bf_err *err)
{
    /* 1. every given entry of these sections must be declared */
    for (size_t k = 0; k < sc->nraw; k++) {
        entry *r = &sc->raw[k];
        const bf_section_spec *s = NULL;
        int idx;
        for (size_t j = 0; j < nspecs && !s; j++)
            if (spec_matches(specs[j], r->section, &idx))
                s = specs[j];
        if (!s)
            continue; /* checked by the caller once all specs are known */
        if (!spec_param(s, r->key)) {
            char keys[768];
            list_keys(s, keys, sizeof keys);
            return fail_at(err, r->origin, r->line,
                           "[%s] %s: unknown key (keys of [%s]: %s)", r->section,
                           r->key, s->name, keys);
        }
    }
    /* 2. for every present section (indexed: every present index), create
     *    resolved entries for all declared keys */
    for (size_t j = 0; j < nspecs; j++) {
        const bf_section_spec *s = specs[j];
        size_t L = strlen(s->name);
        int indexed = L > 2 && !strcmp(s->name + L - 2, ".N");
        int maxidx = indexed ? 0 : 1;
        if (indexed) {
            for (size_t k = 0; k < sc->nsects; k++) {
                int idx;
                if (spec_matches(s, sc->sects[k].name, &idx) && idx > maxidx)
                    maxidx = idx;
            }
            for (size_t k = 0; k < sc->nraw; k++) {
                int idx;
                if (spec_matches(s, sc->raw[k].section, &idx) && idx > maxidx)
                    maxidx = idx;
            }
        }
        for (int idx = 1; idx <= maxidx; idx++) {
            char secname[256];
            if (indexed)
                snprintf(secname, sizeof secname, "%.*s%d", (int)(L - 1),
                         s->name, idx);
            else
                snprintf(secname, sizeof secname, "%s", s->name);
            if (indexed && !find_sect(sc, secname)) {
                return fail_at(err, sc->path, 0,
                               "[%s] is missing: sections [%.*s1], [%.*s2], "
                               "... must be numbered without gaps (the last "
                               "is [%.*s%d])",
                               secname, (int)(L - 1), s->name, (int)(L - 1),
                               s->name, (int)(L - 1), s->name, maxidx);
            }
            for (const bf_param *p = s->params; p && p->key; p++) {
                entry *e = push_entry(&sc->res, &sc->nres, &sc->capres);
                e->section = xstrdup(secname);
                e->key = xstrdup(p->key);
                e->param = p;
                const entry *r = find_raw(sc, secname, p->key);
                if (r) {
                    e->text = xstrdup(r->text);
                    e->origin = xstrdup(r->origin);
                    e->line = r->line;
                    e->given = 1;
                } else if (p->def) {
                    e->text = xstrdup(p->def);
                    e->origin = xstrdup(sc->path);
                    e->given = 0;
                } else {
                    const sect *se = find_sect(sc, secname);
                    return fail_at(err, sc->path, se ? se->line : 0,
                                   "[%s] %s: required key is missing (%s, %s)",
                                   secname, p->key, p->doc, p->unit);
                }
                bf_status st = parse_value(e, err);
                if (st)
                    return st;
            }
        }
    }
    return BF_OK;
}

bf_status bf_scene_resolve_with(bf_scene *sc, const bf_spec_provider *prov,
                                bf_err *err)
{
    free_resolved(sc);
    const bf_section_spec *root[1] = {prov->root};
    if (!find_sect(sc, prov->root->name))
        return fail_at(err, sc->path, 0, "no [%s] section", prov->root->name);
    bf_status st = resolve_sections(sc, root, 1, err);
    if (st)
        return st;
    sc->resolved = 1;
    sc->active[0] = prov->root;
    size_t n = 0;
    const bf_section_spec *more[MAX_SPECS];
    st = prov->select(sc, more, MAX_SPECS - 1, &n, err);
    if (st) {
        free_resolved(sc);
        return st;
    }
    /* every given section must belong to an active spec */
    for (size_t k = 0; k < sc->nsects; k++) {
        const char *name = sc->sects[k].name;
        int idx, ok = spec_matches(prov->root, name, &idx);
        for (size_t j = 0; j < n && !ok; j++)
            ok = spec_matches(more[j], name, &idx);
        if (!ok) {
            const entry *r = NULL;
            for (size_t q = 0; q < sc->nraw && !r; q++)
                if (!strcmp(sc->raw[q].section, name))
                    r = &sc->raw[q];
            int line = sc->sects[k].line ? sc->sects[k].line : (r ? r->line : 0);
            const char *origin = sc->sects[k].line || !r ? sc->path : r->origin;
            free_resolved(sc);
            return fail_at(err, origin, line,
                           "[%s]: unknown section, or a section this scene "
                           "does not use (check [scene] model, effects and "
                           "integrator)",
                           name);
        }
    }
    st = resolve_sections(sc, more, n, err);
    if (st) {
        free_resolved(sc);
        return st;
    }
    for (size_t j = 0; j < n; j++)
        sc->active[1 + j] = more[j];
    sc->nactive = 1 + n;
    sc->resolved = 2;
    return BF_OK;
}

/* ------------------------------------------------------------- accessors */

static const entry *get(const bf_scene *sc, const char *section, const char *key,
                        bf_ptype want)
{
    if (!sc->resolved) {
        fprintf(stderr, "ballfilm: internal error: scene used before resolve\n");
        abort();
    }
    for (size_t k = 0; k < sc->nres; k++) {
        const entry *e = &sc->res[k];
        if (!strcmp(e->section, section) && !strcmp(e->key, key)) {
            if (e->param->type != want &&
                !(want == BF_NAMES && e->param->type == BF_NAMES)) {
                fprintf(stderr,
                        "ballfilm: internal error: [%s] %s read as %s, declared "
                        "%s\n",
                        section, key, type_name(want), type_name(e->param->type));
                abort();
            }
            return e;
        }
    }
    fprintf(stderr, "ballfilm: internal error: [%s] %s is not a resolved key\n",
            section, key);
    abort();
}

double bf_scene_real(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_REAL)->r;
}

long bf_scene_int(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_INT)->i;
}

int bf_scene_bool(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_BOOL)->b;
}

const char *bf_scene_str(const bf_scene *sc, const char *s, const char *k)
{
    for (size_t q = 0; q < sc->nres; q++) {
        const entry *e = &sc->res[q];
        if (!strcmp(e->section, s) && !strcmp(e->key, k) &&
            (e->param->type == BF_STR || e->param->type == BF_ENUM))
            return e->text;
    }
    return get(sc, s, k, BF_STR)->text;
}

int bf_scene_enum(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_ENUM)->e;
}

const double *bf_scene_reals(const bf_scene *sc, const char *s, const char *k,
                             size_t *n)
{
    const entry *e = get(sc, s, k, BF_REALS);
    *n = e->nreals;
    return e->reals;
}

const char *const *bf_scene_names(const bf_scene *sc, const char *s,
                                  const char *k, size_t *n)
{
    const entry *e = get(sc, s, k, BF_NAMES);
    *n = e->nnames;
    return (const char *const *)e->names;
}

int bf_scene_has_name(const bf_scene *sc, const char *s, const char *k,
                      const char *name)
{
    size_t n;
    const char *const *v = bf_scene_names(sc, s, k, &n);
    for (size_t q = 0; q < n; q++)
        if (!strcmp(v[q], name))
            return 1;
    return 0;
}

bf_interval bf_scene_interval(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_INTERVAL)->iv;
}

int bf_scene_has_section(const bf_scene *sc, const char *section)
{
    return find_sect(sc, section) != NULL;
}

int bf_scene_given(const bf_scene *sc, const char *section, const char *key)
{
    return find_raw(sc, section, key) != NULL;
}

int bf_scene_has_key(const bf_scene *sc, const char *section, const char *key)
{
    for (size_t k = 0; k < sc->nres; k++)
        if (!strcmp(sc->res[k].section, section) && !strcmp(sc->res[k].key, key))
            return 1;
    return 0;
}

int bf_scene_count(const bf_scene *sc, const char *base)
{
    int n = 0;
    char name[256];
    for (;;) {
        snprintf(name, sizeof name, "%s.%d", base, n + 1);
        if (!find_sect(sc, name))
            return n;
        n++;
    }
}

const char *bf_scene_text(const bf_scene *sc) { return sc->text; }
const char *bf_scene_path(const bf_scene *sc) { return sc->path; }

bf_status bf_scene_fail(const bf_scene *sc, bf_err *err, const char *section,
                        const char *key, const char *fmt, ...)
{
    char body[BF_ERR_MSG];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(body, sizeof body, fmt, ap);
    va_end(ap);
    const entry *r = key ? find_raw(sc, section, key) : NULL;
    if (r)
        return fail_at(err, r->origin, r->line, "[%s] %s: %s", section, key,
                       body);
    const sect *se = find_sect(sc, section);
    if (key)
        return fail_at(err, sc->path, se ? se->line : 0, "[%s] %s (default): %s",
                       section, key, body);
    return fail_at(err, sc->path, se ? se->line : 0, "[%s]: %s", section, body);
}

int bf_scene_visit(const bf_scene *sc, bf_scene_visit_fn fn, void *ctx)
{
    char name[512];
    for (size_t k = 0; k < sc->nres; k++) {
        const entry *e = &sc->res[k];
        snprintf(name, sizeof name, "%s.%s", e->section, e->key);
        int rc = fn(ctx, name, e->text, e->param->unit ? e->param->unit : "",
                    !e->given);
        if (rc)
            return rc;
    }
    return 0;
}

/* ------------------------------------------------------------------ help */

void bf_scene_print_specs(FILE *f, const bf_section_spec *const *specs, size_t n)
{
    for (size_t j = 0; j < n; j++) {
        const bf_section_spec *s = specs[j];
        fprintf(f, "\n[%s]  %s\n", s->name, s->doc ? s->doc : "");
        for (const bf_param *p = s->params; p && p->key; p++) {
            if (p->flags & BF_HIDDEN)
                continue;
            char range[96] = "";
            if (p->flags & BF_POS)
                snprintf(range, sizeof range, ", > 0");
            else if (p->flags & BF_NONNEG)
                snprintf(range, sizeof range, ", >= 0");
            if ((p->flags & BF_MIN) && (p->flags & BF_MAX))
                snprintf(range, sizeof range, ", in [%g, %g]", p->lo, p->hi);
            else if (p->flags & BF_MIN)
                snprintf(range, sizeof range, ", >= %g", p->lo);
            else if (p->flags & BF_MAX)
                snprintf(range, sizeof range, ", <= %g", p->hi);
            fprintf(f, "  %-16s %s\n", p->key, p->doc ? p->doc : "");
            fprintf(f, "  %-16s   [%s%s%s%s; unit %s; default %s]\n", "",
                    type_name(p->type), p->choices ? ": " : "",
                    p->choices ? p->choices : "", range,
                    p->unit && *p->unit ? p->unit : "-",
                    p->def ? (*p->def ? p->def : "\"\"") : "required");
        }
    }
}
