/* params.c: parsing and storing typed parameter values (see params.h). */
#include "ballfilm/params.h"
#include "base/xalloc.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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

long bf_interval_steps(bf_interval iv, double dt)
{
    if (!iv.in_time)
        return iv.steps;
    double k = floor(iv.time / dt + 0.5);
    if (!(k < 9e15)) /* longer than any run: never (the final row is kept) */
        return (long)9e15;
    return iv.time > 0 && k < 1 ? 1 : (long)k;
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

/* Split on commas and blanks.  Returns the number of tokens; *toks is a
 * malloc'd array of malloc'd strings. */
static size_t split_list(const char *text, char ***toks)
{
    size_t n = 0, cap = 8;
    char **t = bf_xrealloc(NULL, cap * sizeof *t);
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
            t = bf_xrealloc(t, cap * sizeof *t);
        }
        t[n] = bf_xrealloc(NULL, (size_t)(q - p) + 1);
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

const char *bf_ptype_name(bf_ptype t)
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

void bf_value_free(bf_value *v)
{
    free(v->reals);
    v->reals = NULL;
    v->nreals = 0;
    for (size_t k = 0; k < v->nnames; k++)
        free(v->names[k]);
    free(v->names);
    v->names = NULL;
    v->nnames = 0;
}

static int parse_names(const bf_param *p, const char *text, bf_value *v,
                       char *why, size_t cap)
{
    char **t;
    size_t n = split_list(text, &t);
    for (size_t k = 0; k < n; k++) {
        if (p->choices && choice_index(p->choices, t[k]) < 0) {
            snprintf(why, cap, "contains '%s', not one of %s", t[k],
                     p->choices);
            free_toks(t, n);
            return 0;
        }
        for (size_t j = 0; j < k; j++)
            if (!strcmp(t[j], t[k])) {
                snprintf(why, cap, "names '%s' twice", t[k]);
                free_toks(t, n);
                return 0;
            }
    }
    v->names = t;
    v->nnames = n;
    return 1;
}

static int parse_reals(const bf_param *p, const char *text, bf_value *v,
                       char *why, size_t cap)
{
    char **t;
    size_t n = split_list(text, &t);
    v->reals = bf_xrealloc(NULL, (n ? n : 1) * sizeof *v->reals);
    v->nreals = n;
    char range[128];
    for (size_t k = 0; k < n; k++) {
        int ok = bf_parse_real(t[k], &v->reals[k]);
        if (!ok)
            snprintf(why, cap, "element %zu '%s' is not a finite real number",
                     k + 1, t[k]);
        else if (!(ok = in_range(p, v->reals[k], range, sizeof range)))
            snprintf(why, cap, "element %zu %s", k + 1, range);
        if (!ok) {
            free_toks(t, n);
            bf_value_free(v);
            return 0;
        }
    }
    free_toks(t, n);
    return 1;
}

static int parse_interval(const char *text, bf_value *v, char *why, size_t cap)
{
    char **t;
    size_t n = split_list(text, &t);
    int ok = 1;
    memset(&v->iv, 0, sizeof v->iv);
    if (n == 1 || (n == 2 && !strcmp(t[1], "steps"))) {
        if (!bf_parse_long(t[0], &v->iv.steps) || v->iv.steps < 0) {
            snprintf(why, cap, "is not a number of steps >= 0 (write 'T s' "
                               "for simulated seconds)");
            ok = 0;
        }
    } else if (n == 2 && !strcmp(t[1], "s")) {
        v->iv.in_time = 1;
        if (!bf_parse_real(t[0], &v->iv.time) || !(v->iv.time >= 0)) {
            snprintf(why, cap, "is not a time >= 0 in seconds");
            ok = 0;
        }
    } else {
        snprintf(why, cap, "expected 'N' (steps), 'N steps' or 'T s' "
                           "(simulated seconds)");
        ok = 0;
    }
    free_toks(t, n);
    return ok;
}

int bf_param_parse(const bf_param *p, const char *text, bf_value *v,
                   char *why, size_t cap)
{
    memset(v, 0, sizeof *v);
    switch (p->type) {
    case BF_REAL:
        if (!bf_parse_real(text, &v->r)) {
            snprintf(why, cap, "is not a finite real number");
            return 0;
        }
        return in_range(p, v->r, why, cap);
    case BF_INT:
        if (!bf_parse_long(text, &v->i)) {
            snprintf(why, cap, "is not an integer");
            return 0;
        }
        return in_range(p, (double)v->i, why, cap);
    case BF_BOOL:
        if (!parse_bool(text, &v->b)) {
            snprintf(why, cap, "is not true/false (yes/no, on/off, 1/0)");
            return 0;
        }
        return 1;
    case BF_STR:
        return 1;
    case BF_ENUM:
        v->e = choice_index(p->choices, text);
        if (v->e < 0) {
            snprintf(why, cap, "is not one of %s", p->choices);
            return 0;
        }
        return 1;
    case BF_NAMES:
        return parse_names(p, text, v, why, cap);
    case BF_REALS:
        return parse_reals(p, text, v, why, cap);
    case BF_INTERVAL:
        return parse_interval(text, v, why, cap);
    }
    snprintf(why, cap, "has an unknown type");
    return 0;
}

void bf_param_store(const bf_param *p, const bf_value *v, const char *text,
                    void *dst)
{
    char *at = (char *)dst + p->offset;
    switch (p->type) {
    case BF_REAL:
        memcpy(at, &v->r, sizeof v->r);
        break;
    case BF_INT:
        memcpy(at, &v->i, sizeof v->i);
        break;
    case BF_BOOL:
        memcpy(at, &v->b, sizeof v->b);
        break;
    case BF_STR:
        memcpy(at, &text, sizeof text);
        break;
    case BF_ENUM:
        memcpy(at, &v->e, sizeof v->e);
        break;
    case BF_NAMES: {
        bf_names l = {v->nnames, (const char *const *)v->names};
        memcpy(at, &l, sizeof l);
        break;
    }
    case BF_REALS: {
        bf_reals l = {v->nreals, v->reals};
        memcpy(at, &l, sizeof l);
        break;
    }
    case BF_INTERVAL:
        memcpy(at, &v->iv, sizeof v->iv);
        break;
    }
}

bf_status bf_params_defaults(const bf_section_spec *spec, void *dst,
                             bf_err *err)
{
    memset(dst, 0, spec->size);
    char why[256];
    for (const bf_param *p = spec->params; p && p->key; p++) {
        bf_value v;
        if (!p->def)
            return bf_fail(err, BF_EINTERNAL, "[%s] %s has no default",
                           spec->name, p->key);
        if ((p->type == BF_REALS || p->type == BF_NAMES) && *p->def)
            return bf_fail(err, BF_EINTERNAL, "[%s] %s: a list default needs "
                           "a scene", spec->name, p->key);
        if (!bf_param_parse(p, p->def, &v, why, sizeof why))
            return bf_fail(err, BF_EINTERNAL, "[%s] %s: default '%s' %s",
                           spec->name, p->key, p->def, why);
        bf_param_store(p, &v, p->def, dst);
    }
    return BF_OK;
}

void bf_params_list_keys(const bf_section_spec *s, char *buf, size_t n)
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

void bf_params_print(FILE *f, const bf_section_spec *const *specs, size_t n)
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
                    bf_ptype_name(p->type), p->choices ? ": " : "",
                    p->choices ? p->choices : "", range,
                    p->unit && *p->unit ? p->unit : "-",
                    p->def ? (*p->def ? p->def : "\"\"") : "required");
        }
    }
}
