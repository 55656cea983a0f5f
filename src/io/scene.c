/* scene.c: reading, overriding and validating scene files (see scene.h).
 *
 * inih does the INI syntax.  We feed it through our own line reader so that
 * we know the line number of every key (the Debian build of inih does not
 * pass it to the handler), can tell a continuation line from a duplicate key,
 * and can refuse over-long lines instead of letting inih split them: inih
 * reads a line into a buffer of INI_MAX_LINE bytes, which it passes to the
 * reader (Debian's build: 200, so 198 characters and the newline).  A
 * longer comment line is skipped; a longer key line is refused at its
 * line, with the limit and the way round it (continuation lines).  A
 * scene is text: a NUL byte or invalid UTF-8 is refused at its line (so
 * that the scene's text in an output is valid UTF-8, as its attributes
 * are tagged).
 */
#include "ballfilm/scene.h"
#include "base/utf8.h"
#include "base/xalloc.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAX_SPECS 64

typedef struct entry {
    char *section, *key, *text;
    char *origin; /* file path or "--set" */
    int line;     /* 0: no line (default or command line) */
    int given;    /* 1: from the file or an override, 0: default */
    const bf_param *param;
    bf_value v; /* parsed (resolved entries) */
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

static void entry_free(entry *e)
{
    free(e->section);
    free(e->key);
    free(e->text);
    free(e->origin);
    bf_value_free(&e->v);
}

static entry *push_entry(entry **arr, size_t *n, size_t *cap)
{
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 32;
        *arr = bf_xrealloc(*arr, *cap * sizeof **arr);
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
        sc->sects = bf_xrealloc(sc->sects, sc->capsects * sizeof *sc->sects);
    }
    sc->sects[sc->nsects].name = bf_xstrdup(name);
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
    int too_long;       /* first over-long key line, or 0 */
    int max_len;        /* the longest line inih takes, characters */
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
    r->max_len = num - 2;
    if (len >= (size_t)num) {
        const char *q = r->p;
        while (*q == ' ' || *q == '\t')
            q++;
        /* a comment says nothing: skip it whatever its length */
        if (!r->too_long && *q != ';' && *q != '#')
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
        old->text = bf_xrealloc(old->text, a + b + 2);
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
    e->section = bf_xstrdup(section);
    e->key = bf_xstrdup(name);
    e->text = bf_xstrdup(value);
    e->origin = bf_xstrdup(sc->path);
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
    sc->path = bf_xstrdup(name);
    sc->text = bf_xstrdup(text);
    size_t len = strlen(text), bad = bf_utf8_invalid(text, len);
    if (bad < len) {
        int line = 1;
        const char *bol = text;
        for (const char *q = text; q < text + bad; q++)
            if (*q == '\n') {
                line++;
                bol = q + 1;
            }
        bf_scene_free(sc);
        return fail_at(err, name, line,
                       "not UTF-8 text (byte 0x%02x at column %d); save the "
                       "scene as UTF-8",
                       (unsigned char)text[bad], (int)(text + bad - bol) + 1);
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
                       "line too long (the INI reader takes at most %d "
                       "characters); split the value over continuation "
                       "lines (indented lines continue a value)",
                       r.max_len);
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
    size_t n;
    int too_long;
    char *buf = bf_xread_all(f, 64u << 20, &n, &too_long);
    fclose(f);
    if (too_long)
        return bf_fail(err, BF_EINPUT,
                       "%s: error: scene file larger than 64 MiB", path);
    if (!buf)
        return bf_fail(err, BF_EINPUT, "%s: error: cannot read scene file",
                       path);
    const char *nul = memchr(buf, '\0', n);
    if (nul) {
        int line = 1;
        for (const char *q = buf; q < nul; q++)
            line += *q == '\n';
        free(buf);
        return fail_at(err, path, line,
                       "a NUL byte: the scene file is not text");
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
    c->path = bf_xstrdup(sc->path);
    c->text = bf_xstrdup(sc->text);
    for (size_t k = 0; k < sc->nraw; k++) {
        entry *e = push_entry(&c->raw, &c->nraw, &c->capraw);
        e->section = bf_xstrdup(sc->raw[k].section);
        e->key = bf_xstrdup(sc->raw[k].key);
        e->text = bf_xstrdup(sc->raw[k].text);
        e->origin = bf_xstrdup(sc->raw[k].origin);
        e->line = sc->raw[k].line;
        e->given = 1;
    }
    for (size_t k = 0; k < sc->nsects; k++)
        add_sect(c, sc->sects[k].name, sc->sects[k].line);
    for (size_t k = 0; k < sc->nsets; k++) {
        c->sets = bf_xrealloc(c->sets, (c->nsets + 1) * sizeof *c->sets);
        c->sets[c->nsets++] = bf_xstrdup(sc->sets[k]);
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
    if (bf_utf8_invalid(v, strlen(v)) < strlen(v))
        return bf_fail(err, BF_EINPUT, "%s: error: %s.%s: the value is not "
                       "UTF-8 text", origin, section, key);
    while (*v == ' ' || *v == '\t')
        v++;
    char *val = bf_xstrdup(v);
    for (size_t n = strlen(val); n && (val[n - 1] == ' ' || val[n - 1] == '\t');)
        val[--n] = '\0';
    entry *e = find_raw(sc, section, key);
    if (!e) {
        e = push_entry(&sc->raw, &sc->nraw, &sc->capraw);
        e->section = bf_xstrdup(section);
        e->key = bf_xstrdup(key);
    } else {
        free(e->text);
        free(e->origin);
    }
    e->text = val;
    e->origin = bf_xstrdup(origin);
    e->line = 0;
    e->given = 1;
    add_sect(sc, section, 0);
    sc->sets = bf_xrealloc(sc->sets, (sc->nsets + 1) * sizeof *sc->sets);
    sc->sets[sc->nsets++] = bf_xstrdup(assignment);
    free_resolved(sc);
    return BF_OK;
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
    char why[256];
    bf_value_free(&e->v);
    if (!bf_param_parse(e->param, e->text, &e->v, why, sizeof why))
        return where_fail(err, e, "%s", why);
    return BF_OK;
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
            bf_params_list_keys(s, keys, sizeof keys);
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
                e->section = bf_xstrdup(secname);
                e->key = bf_xstrdup(p->key);
                e->param = p;
                const entry *r = find_raw(sc, secname, p->key);
                if (r) {
                    e->text = bf_xstrdup(r->text);
                    e->origin = bf_xstrdup(r->origin);
                    e->line = r->line;
                    e->given = 1;
                } else if (p->def) {
                    e->text = bf_xstrdup(p->def);
                    e->origin = bf_xstrdup(sc->path);
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
    st = prov->select(sc, more, MAX_SPECS - 1, &n, prov->ctx, err);
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
                        section, key, bf_ptype_name(want), bf_ptype_name(e->param->type));
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
    return get(sc, s, k, BF_REAL)->v.r;
}

long bf_scene_int(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_INT)->v.i;
}

int bf_scene_bool(const bf_scene *sc, const char *s, const char *k)
{
    return get(sc, s, k, BF_BOOL)->v.b;
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
    return get(sc, s, k, BF_ENUM)->v.e;
}

const double *bf_scene_reals(const bf_scene *sc, const char *s, const char *k,
                             size_t *n)
{
    const entry *e = get(sc, s, k, BF_REALS);
    *n = e->v.nreals;
    return e->v.reals;
}

const char *const *bf_scene_names(const bf_scene *sc, const char *s,
                                  const char *k, size_t *n)
{
    const entry *e = get(sc, s, k, BF_NAMES);
    *n = e->v.nnames;
    return (const char *const *)e->v.names;
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
    return get(sc, s, k, BF_INTERVAL)->v.iv;
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

void bf_scene_fill(const bf_scene *sc, const char *section,
                   const bf_section_spec *spec, void *dst)
{
    memset(dst, 0, spec->size);
    for (const bf_param *p = spec->params; p && p->key; p++) {
        const entry *e = get(sc, section, p->key, p->type);
        bf_param_store(p, &e->v, e->text, dst);
    }
}

void bf_scene_locate(const bf_scene *sc, bf_err *err)
{
    if (!err || !err->section[0])
        return;
    char section[sizeof err->section], key[sizeof err->key];
    char msg[BF_ERR_MSG];
    memcpy(section, err->section, sizeof section);
    memcpy(key, err->key, sizeof key);
    memcpy(msg, err->msg, sizeof msg);
    bf_status st = err->status;
    bf_scene_fail(sc, err, section, key[0] ? key : NULL, "%s", msg);
    err->status = st;
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

