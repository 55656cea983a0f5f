/* cmd_xdmf.c: `ballfilm xdmf OUT.h5 [-o OUT.xmf] [--all | --max-steps N]`,
 * the XDMF sidecar that lets ParaView and VisIt open a run (io/xdmf.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/params.h"
#include "cli.h"
#include "io/xdmf.h"

static void xdmf_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm xdmf OUT.h5 [-o OUT.xmf] [--all | --max-steps N]\n"
            "\n"
            "Write the XDMF sidecar of a run's HDF5 file (ballfilm run writes "
            "it at the\n"
            "end of every run): open OUT.xmf in ParaView or VisIt.  It points "
            "at the\n"
            "datasets of OUT.h5 (named relative to OUT.xmf; keep the two "
            "together).\n"
            "\n"
            "  -o, --output OUT.xmf\n"
            "                   sidecar file (default: OUT.h5 with .xmf)\n"
            "  --max-steps N    at most N time steps per collection; longer "
            "series are\n"
            "                   thinned to every k-th row (default %d)\n"
            "  --all            one time step per output row\n",
            BF_XDMF_MAX_STEPS);
}

int bf_cmd_xdmf(int argc, char **argv)
{
    const char *h5 = NULL, *xmf = NULL;
    long max_steps = BF_XDMF_MAX_STEPS;
    enum { ALL = BF_CLI_LONG, MAX_STEPS };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"output", required_argument, NULL, 'o'},
        {"all", no_argument, NULL, ALL},
        {"max-steps", required_argument, NULL, MAX_STEPS},
        {NULL, 0, NULL, 0},
    };
    const bf_cli_cmd cmd = {"xdmf", ":ho:", longopts, xdmf_usage};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        switch (c) {
        case BF_CLI_HELP:
            return 0;
        case BF_CLI_BAD:
            return BF_EINPUT;
        case 'o':
            xmf = optarg;
            break;
        case ALL:
            max_steps = 0;
            break;
        case MAX_STEPS:
            if (!bf_parse_long(optarg, &max_steps) || max_steps < 2) {
                bf_cli_error(&cmd, "--max-steps needs a number >= 2");
                return BF_EINPUT;
            }
            break;
        }
    }
    if (optind + 1 < argc) {
        bf_cli_error(&cmd, "unexpected argument '%s'", argv[optind + 1]);
        return BF_EINPUT;
    }
    if (optind >= argc) {
        xdmf_usage(stderr);
        return BF_EINPUT;
    }
    h5 = argv[optind];
    if (bf_cli_no_such_file(h5))
        return BF_EINPUT;
    char *def = xmf ? NULL : bf_xdmf_default_path(h5);
    if (!xmf && !def)
        return BF_EINTERNAL;
    bf_err err = {0};
    bf_status st = bf_xdmf_write_n(h5, xmf ? xmf : def, (size_t)max_steps,
                                   &bf_cli_stop, &err);
    if (st)
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
    else
        printf("wrote %s\n", xmf ? xmf : def);
    free(def);
    return (int)st;
}

int bf_cli_write_xdmf(const char *h5_path)
{
    char *xmf = bf_xdmf_default_path(h5_path);
    bf_err err = {0};
    bf_status st = xmf ? bf_xdmf_write_n(h5_path, xmf, BF_XDMF_MAX_STEPS,
                                         &bf_cli_stop, &err)
                       : BF_EINTERNAL;
    if (st == BF_INTERRUPTED)
        fprintf(stderr, "ballfilm: interrupted: no XDMF sidecar (`ballfilm "
                        "xdmf %s` writes it)\n", h5_path);
    else if (st)
        fprintf(stderr, "ballfilm: warning: no XDMF sidecar: %s\n",
                xmf ? err.msg : "out of memory");
    free(xmf);
    return (int)st;
}
