/* params.h: typed parameters.  Every key a scene may contain is declared
 * once, in a bf_section_spec owned by the module that uses it, together
 * with the place of its value in that module's parameter struct.
 *
 * One source of truth: the scene layer validates a scene against these
 * tables, fills in defaults and writes the values into the structs
 * (bf_scene_fill); `ballfilm help` prints the same tables; the modules
 * receive filled structs and never look a key up by name.  A key that no
 * table declares is an error, so a typo never passes silently.
 *
 * Declaring a key (the member's C type is checked at compile time):
 *
 *   typedef struct film_keys { double dx; int initial; } film_keys;
 *   static const bf_param film_params[] = {
 *       {"dx", BF_AT(film_keys, dx, BF_REAL), "cm", "0.1",
 *        "node spacing", BF_POS, 0, 0, NULL},
 *       {"initial", BF_AT(film_keys, initial, BF_ENUM), "", "kink",
 *        "initial state", 0, 0, 0, "kink|uniform|file"},
 *       {0},
 *   };
 *   const bf_section_spec film_spec = BF_SECTION("film", "the film",
 *                                                film_params, film_keys);
 *
 * The C type of each kind of value:
 *   BF_REAL     double           BF_ENUM      int (index in `choices`)
 *   BF_INT      long             BF_NAMES     bf_names
 *   BF_BOOL     int (0 or 1)     BF_REALS     bf_reals
 *   BF_STR      const char *     BF_INTERVAL  bf_interval
 * Strings and lists point into the scene that filled the struct and live
 * as long as it does.
 *
 * Sections named "NAME.N" ("ball.N") are indexed: a scene may contain
 * [ball.1], [ball.2], ... with consecutive indices, each filling one
 * struct.
 */
#ifndef BALLFILM_PARAMS_H
#define BALLFILM_PARAMS_H

#include <stddef.h>
#include <stdio.h>

#include "ballfilm/error.h"

typedef enum bf_ptype {
    BF_REAL,    /* a finite real number */
    BF_INT,     /* an integer (long) */
    BF_BOOL,    /* true/false, yes/no, on/off, 1/0 */
    BF_STR,     /* free text (file names) */
    BF_ENUM,    /* one word from `choices` ("a|b|c") */
    BF_NAMES,   /* a list of words (from `choices` if given), comma or blank
                   separated */
    BF_REALS,   /* a list of real numbers, comma or blank separated */
    BF_INTERVAL /* "N" steps, or "T s" simulated seconds */
} bf_ptype;

/* Constraint flags for BF_REAL / BF_INT / BF_REALS (each element). */
enum {
    BF_POS = 1u << 0,    /* value > 0 */
    BF_NONNEG = 1u << 1, /* value >= 0 */
    BF_MIN = 1u << 2,    /* value >= lo */
    BF_MAX = 1u << 3,    /* value <= hi */
    BF_HIDDEN = 1u << 4  /* not listed by help (internal/test keys) */
};

typedef struct bf_interval {
    int in_time; /* 0: `steps` is set; 1: `time` is set (seconds) */
    long steps;
    double time;
} bf_interval;

typedef struct bf_reals {
    size_t n;
    const double *v;
} bf_reals;

typedef struct bf_names {
    size_t n;
    const char *const *v;
} bf_names;

typedef struct bf_param {
    const char *key;
    bf_ptype type;
    size_t offset;       /* of the value in the section's struct */
    const char *unit;    /* CGS unit ("cm", "g", "s", "1" = dimensionless) */
    const char *def;     /* default as text; NULL: the key is required */
    const char *doc;     /* one line, shown by help */
    unsigned flags;
    double lo, hi;
    const char *choices; /* BF_ENUM, BF_NAMES: "a|b|c" */
} bf_param;

typedef struct bf_section_spec {
    const char *name;       /* "scene", "film", "ball.N" */
    const char *doc;
    const bf_param *params; /* terminated by an entry with key == NULL */
    size_t size;            /* of the struct the values are written to */
} bf_section_spec;

#define BF_SECTION(name, doc, params, type) {name, doc, params, sizeof(type)}

/* The C type of each kind of value (used by BF_AT). */
#define BF_CTYPE_BF_REAL double
#define BF_CTYPE_BF_INT long
#define BF_CTYPE_BF_BOOL int
#define BF_CTYPE_BF_STR const char *
#define BF_CTYPE_BF_ENUM int
#define BF_CTYPE_BF_NAMES bf_names
#define BF_CTYPE_BF_REALS bf_reals
#define BF_CTYPE_BF_INTERVAL bf_interval

/* "kind, offset" of member m of struct T; a member of another C type than
 * the kind needs is a compile-time error (comparison of distinct pointer
 * types). */
#define BF_AT(T, m, KIND)                                                      \
    KIND, (offsetof(T, m) + 0 * sizeof(&((T *)0)->m == (BF_CTYPE_##KIND *)0))

/* A parsed value (what a scene stores for one key). */
typedef struct bf_value {
    double r;
    long i;
    int b, e;
    bf_interval iv;
    double *reals; /* malloc'd (BF_REALS) */
    size_t nreals;
    char **names;  /* malloc'd strings (BF_NAMES) */
    size_t nnames;
} bf_value;

/* Parse `text` as the value of p (type, range, choices).  Returns 1 on
 * success; otherwise 0 with the reason in `why` (for example "must be
 * > 0", "is not a finite real number"), and v holds nothing to free. */
int bf_param_parse(const bf_param *p, const char *text, bf_value *v,
                   char *why, size_t cap);
void bf_value_free(bf_value *v);
/* Write a parsed value into the struct at p->offset (text: the value as
 * written, kept by pointer for BF_STR). */
void bf_param_store(const bf_param *p, const bf_value *v, const char *text,
                    void *dst);

/* Fill a struct with the defaults of every key of a section (the struct
 * is zeroed first).  Keys without a default, and lists with a non-empty
 * default, are an error (BF_EINTERNAL): they need a scene. */
bf_status bf_params_defaults(const bf_section_spec *spec, void *dst,
                             bf_err *err);

/* An interval in whole steps of dt: steps as given, times rounded to the
 * nearest step (a positive time shorter than half a step is one step; a
 * time longer than any run, 9e15 steps). */
long bf_interval_steps(bf_interval iv, double dt);

/* Number parsing shared by the scene and the command line: a finite real
 * (strtod syntax, blanks after it allowed) and an integer (also integral
 * reals such as 1e5).  Return 1 on success. */
int bf_parse_real(const char *text, double *out);
int bf_parse_long(const char *text, long *out);

/* Name of a kind of value ("real", "list of names", ...). */
const char *bf_ptype_name(bf_ptype t);

/* Print the documentation of sections (for help). */
void bf_params_print(FILE *f, const bf_section_spec *const *specs, size_t n);
/* The keys of a section for messages: "a, b, c" (hidden keys left out). */
void bf_params_list_keys(const bf_section_spec *s, char *buf, size_t cap);

#endif
