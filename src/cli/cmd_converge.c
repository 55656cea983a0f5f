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
            "  -o OUT.h5        write the table (default "
            "out/converge_<scene>.h5)\n"
            "  -q               no progress lines\n");
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
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        const char *val = k + 1 < argc ? argv[k + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            converge_usage(stdout);
            free(sets);
            return 0;
        } else if (!strcmp(a, "--methods") && val) {
            methods = val;
            k++;
        } else if (!strcmp(a, "--dt") && val) {
            if ((ndt = parse_reals(val, dts, 64)) < 1) {
                fprintf(stderr, "ballfilm: error: --dt needs positive numbers "
                                "separated by commas\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--tol") && val) {
            if ((ntol = parse_reals(val, tols, 64)) < 1) {
                fprintf(stderr, "ballfilm: error: --tol needs positive numbers "
                                "separated by commas\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--t-end") && val) {
            if (!bf_parse_real(val, &o.t_end) || !(o.t_end > 0)) {
                fprintf(stderr, "ballfilm: error: --t-end needs a time > 0\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--rows") && val) {
            if (!bf_parse_long(val, &o.rows) || o.rows < 1 ||
                o.rows > 100000) {
                fprintf(stderr, "ballfilm: error: --rows needs 1..100000\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--repeats") && val) {
            long r;
            if (!bf_parse_long(val, &r) || r < 1 || r > 100) {
                fprintf(stderr, "ballfilm: error: --repeats needs 1..100\n");
                goto done;
            }
            o.repeats = (int)r;
            k++;
        } else if (!strcmp(a, "--ref-rtol") && val) {
            if (!bf_parse_real(val, &o.ref_rtol) || !(o.ref_rtol > 0)) {
                fprintf(stderr, "ballfilm: error: --ref-rtol needs a number "
                                "> 0\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--max-step") && val) {
            if (!strcmp(val, "none"))
                o.max_step = -1;
            else if (!bf_parse_real(val, &o.max_step) || !(o.max_step > 0)) {
                fprintf(stderr, "ballfilm: error: --max-step needs a time > 0 "
                                "or 'none'\n");
                goto done;
            }
            k++;
        } else if (!strcmp(a, "--ref-table") && val) {
            o.ref_table = val;
            k++;
        } else if (!strcmp(a, "--set") && val) {
            sets[nset++] = val;
            k++;
        } else if ((!strcmp(a, "-o") || !strcmp(a, "--output")) && val) {
            out_path = val;
            k++;
        } else if (!strcmp(a, "-q") || !strcmp(a, "--quiet")) {
            quiet = 1;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "ballfilm: error: unknown option '%s' (or it "
                            "lacks its value)\n", a);
            converge_usage(stderr);
            goto done;
        } else if (!scene_path) {
            scene_path = a;
        } else {
            fprintf(stderr, "ballfilm: error: more than one scene file\n");
            goto done;
        }
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
