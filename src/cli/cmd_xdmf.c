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
            "  -o OUT.xmf       sidecar file (default: OUT.h5 with .xmf)\n"
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
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            xdmf_usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o") && k + 1 < argc) {
            xmf = argv[++k];
        } else if (!strcmp(a, "--all")) {
            max_steps = 0;
        } else if (!strcmp(a, "--max-steps")) {
            if (++k >= argc || !bf_parse_long(argv[k], &max_steps) ||
                max_steps < 2) {
                fprintf(stderr, "ballfilm: error: --max-steps needs a number "
                                ">= 2\n");
                return BF_EINPUT;
            }
        } else if (a[0] == '-' || h5) {
            fprintf(stderr, "ballfilm: error: unexpected argument '%s'\n", a);
            xdmf_usage(stderr);
            return BF_EINPUT;
        } else {
            h5 = a;
        }
    }
    if (!h5) {
        xdmf_usage(stderr);
        return BF_EINPUT;
    }
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
