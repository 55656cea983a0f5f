/* cmd_converge.c: `ballfilm converge SCENE.ini --methods a,b,... [--dt ...]
 * [--tol ...] [--t-end T] [-o OUT.h5] ...`: the convergence and
 * work-precision study of converge.h, printed and written to HDF5. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/converge.h"
#include "cli.h"

static void converge_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm converge SCENE.ini --methods M1,M2,... [options]\n"
            "\n"
            "Runs each time integrator on the scene's model from 0 to T and "
            "compares the state\n"
            "at the output rows with an ARKODE reference (a Butcher table no "
            "compared method\n"
            "uses); prints errors, observed orders, the energy (or conserved "
            "totals), the cost.\n"
            "\n"
            "  --methods LIST   time integrators, each 'name' or "
            "'name:key=value:...':\n"
            "                   balls: [scene] integrator with [integrator] "
            "keys, e.g.\n"
            "                     verlet,mv2m,rk4,mv2m:events=yes,"
            "arkode:table=ARKODE_CASH_KARP_6_4_5\n"
            "                   film: [film] scheme invariant, arkode, "
            "arkode-imex (keys of [film])\n"
            "                   coupled: a ball integrator (the split "
            "scheme, [coupled] keys:\n"
            "                     mv2m,rk4,mv2m:film_every=10), arkode "
            "(whole system), mri\n"
            "                   greenspan73: [greenspan73] integrator "
            "greenspan73, leapfrog, arkode\n"
            "                   greenspan72: [greenspan72] integrator "
            "leapfrog, arkode\n"
            "                   mac: [mac] update printed, consistent, "
            "original (one at a time:\n"
            "                     self-convergence, the reference is the "
            "method at [scene] dt / 64)\n"
            "                   a key written section.key goes to that "
            "section (mv2m:coupled.film_every=10)\n"
            "  --dt LIST        step sizes of fixed-step methods, s "
            "(default: the scene's dt x 4,2,1,1/2)\n"
            "  --tol LIST       tolerances (rtol; atol = rtol/100) of "
            "adaptive methods\n"
            "                   (default 1e-4,1e-6,1e-8,1e-10)\n"
            "  --t-end T        final time, s (default: [scene] t_end)\n"
            "  --rows N         output rows compared (default 10; max and RMS "
            "errors over them)\n"
            "  --repeats N      timing repeats, minimum taken (default 3)\n"
            "  --ref-rtol R     reference tolerance (default: the model's, "
            "1e-12 for balls,\n"
            "                   Greenspan's particles and the coupled model, "
            "1e-10 for the film;\n"
            "                   docs/accuracy.md)\n"
            "  --ref-table NAME reference Butcher table (default "
            "ARKODE_VERNER_8_5_6,\n"
            "                   or DORMAND_PRINCE_7_4_5 / CASH_KARP_6_4_5 when "
            "it is compared)\n"
            "  --max-step H     largest internal step of adaptive methods and "
            "the reference, s\n"
            "                   (default for balls with Hertz contacts: 10 x "
            "the scene's dt, else none;\n"
            "                   'none': no limit)\n"
            "  --set s.k=v      override a scene key (repeatable)\n"
            "  -o, --output OUT.h5\n"
            "                   write the table (default "
            "out/converge_<scene>.h5)\n"
            "  -q, --quiet      no progress lines\n");
}

/* "a,b,c" -> reals; returns the count or -1 */
static int parse_reals(const char *s, double *out, int cap)
{
    int n = 0;
    char buf[64];
    while (*s) {
        const char *c = strchr(s, ',');
        size_t l = c ? (size_t)(c - s) : strlen(s);
        if (l == 0 || l >= sizeof buf || n == cap)
            return -1;
        memcpy(buf, s, l);
        buf[l] = '\0';
        if (!bf_parse_real(buf, &out[n]) || !(out[n] > 0))
            return -1;
        n++;
        s += l + (c ? 1 : 0);
    }
    return n;
}

int bf_cmd_converge(int argc, char **argv)
{
    const char *scene_path = NULL, *out_path = NULL, *methods = NULL;
    double dts[64], tols[64];
    int ndt = 0, ntol = 0, quiet = 0;
    bf_converge_opts o = {0};
    const char **sets = calloc((size_t)argc, sizeof *sets);
    char *mcopy = NULL;
    const char *mlist[64];
    size_t nm = 0;
    int nset = 0, rc = BF_EINPUT;
    if (!sets)
        return BF_EINTERNAL;
    enum { METHODS = BF_CLI_LONG, DT, TOL, T_END, ROWS, REPEATS, REF_RTOL,
           MAX_STEP, REF_TABLE, SET };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"output", required_argument, NULL, 'o'},
        {"quiet", no_argument, NULL, 'q'},
        {"methods", required_argument, NULL, METHODS},
        {"dt", required_argument, NULL, DT},
        {"tol", required_argument, NULL, TOL},
        {"t-end", required_argument, NULL, T_END},
        {"rows", required_argument, NULL, ROWS},
        {"repeats", required_argument, NULL, REPEATS},
        {"ref-rtol", required_argument, NULL, REF_RTOL},
        {"max-step", required_argument, NULL, MAX_STEP},
        {"ref-table", required_argument, NULL, REF_TABLE},
        {"set", required_argument, NULL, SET},
        {NULL, 0, NULL, 0},
    };
    const bf_cli_cmd cmd = {"converge", ":ho:q", longopts, converge_usage};
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        const char *val = optarg;
        long r;
        switch (c) {
        case BF_CLI_HELP:
            rc = 0;
            goto done;
        case BF_CLI_BAD:
            goto done;
        case METHODS:
            methods = val;
            break;
        case DT:
            if ((ndt = parse_reals(val, dts, 64)) < 1) {
                bf_cli_error(&cmd, "--dt needs positive numbers separated "
                                   "by commas");
                goto done;
            }
            break;
        case TOL:
            if ((ntol = parse_reals(val, tols, 64)) < 1) {
                bf_cli_error(&cmd, "--tol needs positive numbers separated "
                                   "by commas");
                goto done;
            }
            break;
        case T_END:
            if (!bf_parse_real(val, &o.t_end) || !(o.t_end > 0)) {
                bf_cli_error(&cmd, "--t-end needs a time > 0");
                goto done;
            }
            break;
        case ROWS:
            if (!bf_parse_long(val, &o.rows) || o.rows < 1 ||
                o.rows > 100000) {
                bf_cli_error(&cmd, "--rows needs 1..100000");
                goto done;
            }
            break;
        case REPEATS:
            if (!bf_parse_long(val, &r) || r < 1 || r > 100) {
                bf_cli_error(&cmd, "--repeats needs 1..100");
                goto done;
            }
            o.repeats = (int)r;
            break;
        case REF_RTOL:
            if (!bf_parse_real(val, &o.ref_rtol) || !(o.ref_rtol > 0)) {
                bf_cli_error(&cmd, "--ref-rtol needs a number > 0");
                goto done;
            }
            break;
        case MAX_STEP:
            if (!strcmp(val, "none"))
                o.max_step = -1;
            else if (!bf_parse_real(val, &o.max_step) || !(o.max_step > 0)) {
                bf_cli_error(&cmd, "--max-step needs a time > 0 or 'none'");
                goto done;
            }
            break;
        case REF_TABLE:
            o.ref_table = val;
            break;
        case SET:
            sets[nset++] = val;
            break;
        case 'o':
            out_path = val;
            break;
        case 'q':
            quiet = 1;
            break;
        }
    }
    for (int k = optind; k < argc; k++) {
        if (scene_path) {
            fprintf(stderr, "ballfilm: error: more than one scene file\n");
            goto done;
        }
        scene_path = argv[k];
    }
    if (!scene_path || !methods) {
        converge_usage(stderr);
        goto done;
    }
    mcopy = strdup(methods);
    for (char *p = strtok(mcopy, ","); p && nm < 64; p = strtok(NULL, ","))
        mlist[nm++] = p;
    o.methods = mlist;
    o.nmethods = nm;
    if (ndt) {
        o.dts = dts;
        o.ndts = (size_t)ndt;
    }
    if (ntol) {
        o.tols = tols;
        o.ntols = (size_t)ntol;
    }
    o.progress = quiet ? NULL : stderr;
    o.stop_flag = &bf_cli_stop;

    bf_err err = {0};
    bf_converge_result *res = NULL;
    bf_status st = bf_converge_file(scene_path, sets, (size_t)nset, &o, &res,
                                    &err);
    if (st) {
        fprintf(stderr, "ballfilm: %s: %s\n",
                st == BF_INTERRUPTED ? "interrupted" : "error", err.msg);
        rc = (int)st;
        goto done;
    }
    if (bf_cli_stop) {
        /* the study ended as the signal came: no table of it either */
        bf_converge_free(res);
        fprintf(stderr, "ballfilm: interrupted: the convergence study was "
                        "interrupted; nothing was written\n");
        rc = BF_INTERRUPTED;
        goto done;
    }
    bf_converge_print(res, stdout);
    char defout[600];
    if (!out_path) {
        const char *base = strrchr(scene_path, '/');
        base = base ? base + 1 : scene_path;
        size_t len = strlen(base);
        if (len > 4 && !strcmp(base + len - 4, ".ini"))
            len -= 4;
        snprintf(defout, sizeof defout, "out/converge_%.*s.h5", (int)len, base);
        if (bf_cli_mkdir_out())
            fprintf(stderr, "ballfilm: warning: cannot create out/\n");
        out_path = defout;
    }
    st = bf_converge_write(res, out_path, &err);
    bf_converge_free(res);
    if (st) {
        fprintf(stderr, "ballfilm: error: %s\n", err.msg);
        rc = (int)st;
        goto done;
    }
    printf("wrote %s\n", out_path);
    rc = 0;
done:
    free(mcopy);
    free(sets);
    return rc;
}
