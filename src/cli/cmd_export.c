/* cmd_export.c: `ballfilm export OUT.h5 --format h5md|extxyz [-o FILE]
 * [--mdanalysis]`, a run's particles for other programs (io/export.h). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "io/export.h"

static void export_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm export OUT.h5 --format h5md|extxyz [-o FILE] "
            "[--mdanalysis]\n"
            "\n"
            "Write the particles of a run -- the balls of a balls or coupled "
            "run, the\n"
            "particles of greenspan72 and greenspan73, the markers of mac -- "
            "in a format\n"
            "other programs read:\n"
            "  h5md     H5MD 1.1 (MDAnalysis, VMD's H5MD plugin, h5py): "
            "positions,\n"
            "           velocities, species, masses, energies, with units\n"
            "  extxyz   extended XYZ (OVITO, ASE): one frame per output "
            "row\n"
            "\n"
            "  -f, --format F    h5md or extxyz\n"
            "  -o, --output FILE the file written (default: OUT with .h5md "
            "or .xyz)\n"
            "      --mdanalysis  H5MD that MDAnalysis 2.4 reads: dimension 3 "
            "(missing\n"
            "                    coordinates 0), positions in nm, velocities "
            "in m s-1\n"
            "\n"
            "The file is written as FILE.tmp and renamed at the end: an "
            "interrupted or\n"
            "failed export leaves nothing.  Exit status: 0 ok, 2 bad input "
            "(no such file,\n"
            "no particles, FILE the input itself), 5 I/O error (also a "
            "symbolic link at\n"
            "FILE), 6 interrupted.\n");
}

/* OUT.h5 -> OUT.h5md or OUT.xyz (malloc'd). */
static char *default_out(const char *in, bf_export_format format)
{
    size_t n = strlen(in);
    if (n > 3 && !strcmp(in + n - 3, ".h5"))
        n -= 3;
    const char *ext = format == BF_EXPORT_H5MD ? ".h5md" : ".xyz";
    char *p = malloc(n + strlen(ext) + 1);
    if (p)
        snprintf(p, n + strlen(ext) + 1, "%.*s%s", (int)n, in, ext);
    return p;
}

int bf_cmd_export(int argc, char **argv)
{
    static const struct option longopts[] = {
        {"format", required_argument, NULL, 'f'},
        {"output", required_argument, NULL, 'o'},
        {"mdanalysis", no_argument, NULL, 'm'},
        {"help", no_argument, NULL, 'h'},
        {NULL, 0, NULL, 0}};
    bf_export_opts o = {BF_EXPORT_H5MD, 0};
    const char *out = NULL, *format = NULL;
    const bf_cli_cmd cmd = {"export", ":f:o:h", longopts, export_usage};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        if (c == BF_CLI_HELP || c == BF_CLI_BAD)
            return c == BF_CLI_HELP ? 0 : BF_EINPUT;
        if (c == 'f')
            format = optarg;
        else if (c == 'o')
            out = optarg;
        else if (c == 'm')
            o.mdanalysis = 1;
    }
    if (optind != argc - 1 || !format) {
        bf_cli_error(&cmd, "export needs one run's file and --format");
        return BF_EINPUT;
    }
    if (bf_cli_no_such_file(argv[optind]))
        return BF_EINPUT;
    if (!strcmp(format, "extxyz"))
        o.format = BF_EXPORT_EXTXYZ;
    else if (strcmp(format, "h5md")) {
        fprintf(stderr, "ballfilm: error: --format '%s': h5md or extxyz\n",
                format);
        return BF_EINPUT;
    }
    if (o.mdanalysis && o.format != BF_EXPORT_H5MD) {
        fprintf(stderr, "ballfilm: error: --mdanalysis is for --format "
                        "h5md\n");
        return BF_EINPUT;
    }
    const char *in = argv[optind];
    char *def = out ? NULL : default_out(in, o.format);
    if (!out && !def)
        return BF_EINTERNAL;
    bf_err err = {0};
    bf_status st = bf_export(in, out ? out : def, &o, &bf_cli_stop, &err);
    if (st == BF_INTERRUPTED)
        fprintf(stderr, "ballfilm: interrupted: nothing written\n");
    else if (st)
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
    else
        printf("wrote %s\n", out ? out : def);
    free(def);
    if (st == BF_EIO) {
        /* After a failed write HDF5 (1.10.8) keeps the file open
         * internally and its exit handler crashes closing it again; the
         * message is out and OUT.tmp removed: leave without exit
         * handlers, as `ballfilm run` does. */
        fflush(stdout);
        fflush(stderr);
        _exit((int)st);
    }
    return (int)st;
}
