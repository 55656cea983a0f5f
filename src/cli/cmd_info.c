/* cmd_info.c: `ballfilm info OUT.h5`: what a run's file holds, without
 * h5dump: its scene's title, model and integrator, the program's version,
 * the run's status and counters, the energy error, and every dataset with
 * its shape and unit.  A run still being written (or interrupted) is in
 * OUT.h5.part; given OUT.h5, that file is shown when OUT.h5 is absent. */
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
               "energy error, and every dataset with its shape, unit and "
               "description.\n"
               "Works on a running or interrupted run's OUT.h5.part too, and "
               "on the files\n"
               "of ballfilm sweep and converge.\n");
}

/* A root attribute as text ("" if absent). */
static void text_attr(const char *file, const char *name, char *buf,
                      size_t cap)
{
    char *v = NULL;
    bf_err err = {0};
    buf[0] = '\0';
    if (!bf_h5_read_attr_str(file, "/", name, &v, &err))
        snprintf(buf, cap, "%s", v);
    free(v);
}

/* A numeric root attribute; 0 if absent. */
static int real_attr(const char *file, const char *name, double *v)
{
    bf_err err = {0};
    return !bf_h5_read_attr_real(file, "/", name, v, &err);
}

static void line(const char *label, const char *value)
{
    if (value[0])
        printf("%-26s %s\n", label, value);
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

int bf_cmd_info(int argc, char **argv)
{
    if (argc == 2 && (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help"))) {
        info_usage(stdout);
        return 0;
    }
    if (argc != 2 || argv[1][0] == '-') {
        info_usage(stderr);
        return BF_EINPUT;
    }
    char file[4096], buf[1024];
    snprintf(file, sizeof file, "%s", argv[1]);
    const char *note = "";
    if (access(file, F_OK) && strlen(argv[1]) + 6 < sizeof file) {
        snprintf(file, sizeof file, "%s.part", argv[1]);
        if (!access(file, F_OK))
            note = " (not finished: the run is going on or was interrupted)";
        else
            snprintf(file, sizeof file, "%s", argv[1]);
    }
    bf_h5_dataset *list;
    size_t n;
    bf_err err = {0};
    if (bf_h5_list(file, &list, &n, &err)) {
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
        return err.status;
    }
    printf("%-26s %s%s\n", "file:", file, note);
    static const char *const texts[][2] = {
        {"title:", "scene.title"},     {"model:", "scene.model"},
        {"integrator:", "scene.integrator"}, {"effects:", "scene.effects"},
        {"written by:", "version"},    {"scene file:", "scene_file"},
        {"status:", "status"},         {"message:", "message"},
    };
    for (size_t k = 0; k < sizeof texts / sizeof *texts; k++) {
        text_attr(file, texts[k][1], buf, sizeof buf);
        line(texts[k][0], buf);
    }
    double steps, t, v;
    if (real_attr(file, "steps_done", &steps) &&
        real_attr(file, "t_final", &t)) {
        snprintf(buf, sizeof buf, "%.0f (t = %.9g s)", steps, t);
        line("steps:", buf);
    }
    static const char *const counts[][2] = {
        {"force evaluations:", "force_evaluations"},
        {"rejected steps:", "rejected_steps"},
        {"iterations:", "iterations"},
    };
    for (size_t k = 0; k < sizeof counts / sizeof *counts; k++)
        if (real_attr(file, counts[k][1], &v)) {
            snprintf(buf, sizeof buf, "%.0f", v);
            line(counts[k][0], buf);
        }
    if (real_attr(file, "max_relative_energy_error", &v)) {
        snprintf(buf, sizeof buf, "%.6e", v);
        line("max relative energy error:", buf);
    }
    size_t wpath = 8;
    for (size_t k = 0; k < n; k++)
        if (strlen(list[k].path) > wpath)
            wpath = strlen(list[k].path);
    printf("datasets: %zu\n", n);
    for (size_t k = 0; k < n; k++) {
        char sh[64];
        shape(&list[k], sh, sizeof sh);
        printf("  %-*s  %-16s %-7s %s\n", (int)wpath, list[k].path, sh,
               list[k].unit[0] ? list[k].unit : "-", list[k].description);
    }
    free(list);
    return 0;
}
