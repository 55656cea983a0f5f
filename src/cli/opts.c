/* opts.c: what every command's option parsing shares.  glibc's
 * getopt_long gives the conventions (--name=VALUE and --name VALUE,
 * bundled short options, unique prefixes of long names, `--` ends the
 * options, options anywhere among the operands); this file adds --help
 * and the one error line every command prints. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

/* The long option whose code is `val` (NULL if none). */
static const struct option *long_of(const bf_cli_cmd *c, int val)
{
    for (const struct option *o = c->longopts; o && o->name; o++)
        if (o->val == val)
            return o;
    return NULL;
}

/* "-o/--output", "--set" or "-q": how the option of code val is written. */
static void name_of(const bf_cli_cmd *c, int val, char *buf, size_t cap)
{
    const struct option *o = long_of(c, val);
    const char *s = val > 0 && val < 128 ? strchr(c->shortopts, val) : NULL;
    if (s && val != ':' && o)
        snprintf(buf, cap, "-%c/--%s", val, o->name);
    else if (o)
        snprintf(buf, cap, "--%s", o->name);
    else
        snprintf(buf, cap, "-%c", val);
}

void bf_cli_error(const bf_cli_cmd *c, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "ballfilm: error: %s; see 'ballfilm %s%s--help'\n", msg,
            c->name ? c->name : "", c->name ? " " : "");
}

/* The long options that `arg` ("--na" or "--na=v") is a prefix of:
 * how many, and their names into buf. */
static int candidates(const bf_cli_cmd *c, const char *arg, char *buf,
                      size_t cap)
{
    size_t len = strcspn(arg + 2, "=");
    int n = 0;
    buf[0] = '\0';
    for (const struct option *o = c->longopts; o && o->name; o++)
        if (!strncmp(o->name, arg + 2, len)) {
            size_t used = strlen(buf);
            snprintf(buf + used, cap - used, "%s--%s", n ? ", " : "",
                     o->name);
            n++;
        }
    return n;
}

/* The error line of getopt_long's '?' (opterr is 0): an unknown short
 * option (optopt that is no option of the command), an unknown or
 * ambiguous long one (optopt 0: the element is argv[optind - 1]), or an
 * option given a value it does not take (optopt its code). */
static void unknown(const bf_cli_cmd *c, char **argv)
{
    char name[96];
    if (optopt && !(optopt < 128 && strchr(c->shortopts, optopt)) &&
        !long_of(c, optopt)) {
        bf_cli_error(c, "unknown option '-%c'", optopt);
    } else if (optopt) {
        name_of(c, optopt, name, sizeof name);
        bf_cli_error(c, "option '%s' takes no value", name);
    } else {
        const char *arg = argv[optind - 1];
        char list[512];
        int len = (int)strcspn(arg, "=");
        if (!strncmp(arg, "--", 2) && candidates(c, arg, list, sizeof list) > 1)
            bf_cli_error(c, "ambiguous option '%.*s' (%s)", len, arg, list);
        else
            bf_cli_error(c, "unknown option '%.*s'", len, arg);
    }
}

int bf_cli_getopt(const bf_cli_cmd *c, int argc, char **argv)
{
    opterr = 0; /* the messages are ours */
    int r = getopt_long(argc, argv, c->shortopts, c->longopts, NULL);
    if (r == 'h' && c->usage) {
        c->usage(stdout);
        return BF_CLI_HELP;
    }
    if (r == ':') {
        char name[96];
        name_of(c, optopt, name, sizeof name);
        bf_cli_error(c, "option '%s' needs a value", name);
        return BF_CLI_BAD;
    }
    if (r == '?') {
        unknown(c, argv);
        return BF_CLI_BAD;
    }
    return r;
}

int bf_cli_no_such_file(const char *path)
{
    struct stat st;
    if (!stat(path, &st) || (errno != ENOENT && errno != ENOTDIR))
        return 0; /* there, or not ours to judge: the reader says why */
    fprintf(stderr, "ballfilm: error: %s: no such file\n", path);
    return 1;
}
