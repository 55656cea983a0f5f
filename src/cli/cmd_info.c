/* cmd_info.c: `ballfilm info OUT.h5`: what a run's file holds, without
 * h5dump: its scene's title, model and integrator, the program's version,
 * the run's status and counters, the energy error, and every dataset with
 * its shape, its kind and role (series.h, from the attributes its series
 * spec wrote), unit and description.  A run still being written (or
 * interrupted) is in OUT.h5.part; given OUT.h5, that file is shown when
 * OUT.h5 is absent.  The file is opened once for the listing and once for
 * the root attributes; an attribute that is there but cannot be read is
 * an error naming it, never shown as absent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "cli.h"

static void info_usage(FILE *f)
{
    fprintf(f, "usage: ballfilm info OUT.h5\n"
               "\n"
               "What a ballfilm output file holds: the scene's title, model "
               "and integrator,\n"
               "the version that wrote it, the run's status and counters, "
               "the relative\n"
               "energy error, and every dataset with its shape, kind/role "
               "(rows, snapshot,\n"
               "events or static; time, position, field, ...), unit and "
               "description.\n"
               "Works on a running or interrupted run's OUT.h5.part too, and "
               "on the files\n"
               "of ballfilm sweep and converge.\n");
}

/* A root attribute as text into buf ("" if absent).  One that is there
 * but is not one bounded string, or cannot be read, is an error (in
 * err). */
static bf_status text_attr(bf_h5_reader *r, const char *name, char *buf,
                           size_t cap, bf_err *err)
{
    buf[0] = '\0';
    int has = bf_h5_reader_has_attr(r, "/", name, err);
    if (has <= 0)
        return has < 0 ? err->status : BF_OK; /* absent: nothing to show */
    char *v = NULL;
    bf_status st = bf_h5_reader_attr_str(r, "/", name, &v, err);
    if (!st)
        snprintf(buf, cap, "%s", v);
    free(v);
    return st;
}

/* A numeric root attribute: 1 if there, 0 if absent, -1 (err set) if it
 * is not one number or cannot be read. */
static int real_attr(bf_h5_reader *r, const char *name, double *v,
                     bf_err *err)
{
    int has = bf_h5_reader_has_attr(r, "/", name, err);
    if (has <= 0)
        return has;
    return bf_h5_reader_attr_real(r, "/", name, v, err) ? -1 : 1;
}

/* One character of text from a file, shown so that it cannot drive the
 * terminal: control characters (C0, DEL, and C1 as UTF-8 or as raw bytes)
 * and bytes that are not UTF-8 as \xNN or \u00NN escapes, newlines as
 * `newline`; tabs and printable text as they are.  Returns the bytes of
 * s taken. */
static size_t put_char(const unsigned char *s, const char *newline)
{
    if (*s == '\n') {
        fputs(newline, stdout);
        return 1;
    }
    if (*s == '\t' || (*s >= 0x20 && *s < 0x7f)) {
        putchar(*s);
        return 1;
    }
    size_t len = *s >= 0xc2 && *s <= 0xdf   ? 2
                 : *s >= 0xe0 && *s <= 0xef ? 3
                 : *s >= 0xf0 && *s <= 0xf4 ? 4
                                            : 0;
    for (size_t k = 1; k < len; k++)
        if ((s[k] & 0xc0) != 0x80)
            len = 0;
    if (!len) {
        printf("\\x%02x", *s);
        return 1;
    }
    if (s[0] == 0xc2 && s[1] < 0xa0)
        printf("\\u%04x", s[1]);
    else
        fwrite(s, 1, len, stdout);
    return len;
}

static void put_text(const char *s, const char *newline)
{
    const unsigned char *p = (const unsigned char *)s;
    while (*p)
        p += put_char(p, newline);
}

/* A labelled value; the lines of a text of several go on below it. */
static void line(const char *label, const char *value)
{
    if (!value[0])
        return;
    printf("%-26s ", label);
    put_text(value, "\n                           ");
    putchar('\n');
}

static void shape(const bf_h5_dataset *d, char *buf, size_t cap)
{
    if (d->rank == 0)
        snprintf(buf, cap, "scalar");
    else if (d->rank == 1)
        snprintf(buf, cap, "[%zu]", d->dims[0]);
    else
        snprintf(buf, cap, "[%zu x %zu]", d->dims[0], d->dims[1]);
}

/* Everything about the file but its datasets' list, from its root
 * attributes (r); 0, or a status with err set. */
static int header(bf_h5_reader *r, const char *file, const char *note,
                  bf_err *err)
{
    char buf[1024];
    printf("%-26s ", "file:");
    put_text(file, "\\n");
    printf("%s\n", note);
    static const char *const texts[][2] = {
        {"title:", "scene.title"},     {"model:", "scene.model"},
        {"integrator:", "scene.integrator"}, {"effects:", "scene.effects"},
        {"written by:", "version"},    {"scene file:", "scene_file"},
        {"status:", "status"},         {"message:", "message"},
    };
    for (size_t k = 0; k < sizeof texts / sizeof *texts; k++) {
        if (bf_cli_stop)
            return bf_fail(err, BF_INTERRUPTED, "%s: interrupted", file);
        if (text_attr(r, texts[k][1], buf, sizeof buf, err))
            return err->status;
        line(texts[k][0], buf);
    }
    double steps, t, v;
    int hs = real_attr(r, "steps_done", &steps, err);
    int ht = hs < 0 ? 0 : real_attr(r, "t_final", &t, err);
    if (hs < 0 || ht < 0)
        return err->status;
    if (hs && ht) {
        snprintf(buf, sizeof buf, "%.0f (t = %.9g s)", steps, t);
        line("steps:", buf);
    }
    static const char *const counts[][3] = {
        {"force evaluations:", "force_evaluations", "%.0f"},
        {"rejected steps:", "rejected_steps", "%.0f"},
        {"iterations:", "iterations", "%.0f"},
        {"max relative energy error:", "max_relative_energy_error", "%.6e"},
    };
    for (size_t k = 0; k < sizeof counts / sizeof *counts; k++) {
        int h = real_attr(r, counts[k][1], &v, err);
        if (h < 0)
            return err->status;
        if (h) {
            snprintf(buf, sizeof buf, counts[k][2], v);
            line(counts[k][0], buf);
        }
    }
    /* the energy error of a scene with non-conservative forces is that of
     * the balance (attribute energy_balance) */
    char bal[128];
    if (text_attr(r, "energy_balance", bal, sizeof bal, err))
        return err->status;
    if (bal[0])
        line("energy error of:", bal);
    return bf_cli_stop ? bf_fail(err, BF_INTERRUPTED, "%s: interrupted",
                                 file)
                       : 0;
}

/* A dataset's kind and role ("rows/time"; "-" without them). */
static void kind_role(const bf_h5_dataset *d, char *buf, size_t cap)
{
    if (!d->series_kind[0] && !d->role[0])
        snprintf(buf, cap, "-");
    else
        snprintf(buf, cap, "%s/%s", d->series_kind[0] ? d->series_kind : "-",
                 d->role[0] ? d->role : "-");
}

static int show(bf_h5_reader *r, const char *file, const char *note,
                const bf_h5_dataset *list, size_t n, bf_err *err)
{
    int st = header(r, file, note, err);
    if (st)
        return st;
    size_t wpath = 8, wkr = 9;
    char kr[64];
    for (size_t k = 0; k < n; k++) {
        kind_role(&list[k], kr, sizeof kr);
        if (strlen(list[k].path) > wpath)
            wpath = strlen(list[k].path);
        if (strlen(kr) > wkr)
            wkr = strlen(kr);
    }
    printf("datasets: %zu\n", n);
    for (size_t k = 0; k < n; k++) {
        char sh[64];
        shape(&list[k], sh, sizeof sh);
        kind_role(&list[k], kr, sizeof kr);
        size_t w = strlen(list[k].path), wu = strlen(list[k].unit);
        fputs("  ", stdout);
        put_text(list[k].path, "\\n");
        printf("%*s  %-16s ", (int)(wpath - w), "", sh);
        /* kind and role are shown as text from the file: escaped */
        put_text(kr, "\\n");
        printf("%*s ", (int)(wkr - strlen(kr)), "");
        put_text(list[k].unit[0] ? list[k].unit : "-", "\\n");
        printf("%*s ", wu < 7 ? (int)(7 - (wu ? wu : 1)) : 0, "");
        put_text(list[k].description, "\\n");
        putchar('\n');
    }
    return 0;
}

int bf_cmd_info(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0},
    };
    const bf_cli_cmd cmd = {"info", ":h", longopts, info_usage};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;)
        if (c == BF_CLI_HELP || c == BF_CLI_BAD)
            return c == BF_CLI_HELP ? 0 : BF_EINPUT;
    if (optind + 1 != argc) {
        info_usage(stderr);
        return BF_EINPUT;
    }
    const char *given = argv[optind];
    char file[4096];
    snprintf(file, sizeof file, "%s", given);
    const char *note = "";
    if (access(file, F_OK) && strlen(given) + 6 < sizeof file) {
        snprintf(file, sizeof file, "%s.part", given);
        if (!access(file, F_OK))
            note = " (not finished: the run is going on or was interrupted)";
        else if (bf_cli_no_such_file(given))
            return BF_EINPUT;
        else
            snprintf(file, sizeof file, "%s", given);
    }
    bf_h5_dataset *list;
    size_t n;
    bf_err err = {0};
    if (bf_h5_list_until(file, &list, &n, &bf_cli_stop, &err)) {
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
        return err.status;
    }
    /* one open for every root attribute */
    bf_h5_reader *rd = NULL;
    int st = bf_h5_reader_open(&rd, file, &err);
    if (!st)
        st = show(rd, file, note, list, n, &err);
    bf_h5_reader_close(rd);
    free(list);
    if (st) {
        fflush(stdout);
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
    }
    return st;
}
