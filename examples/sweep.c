/* sweep.c: a parameter sweep from C (sweep.h): the harmonic oscillator
 * x'' = -x (built-in spring, omega = 1) under velocity Verlet for the
 * steps dt = 0.2, 0.1, 0.05, 0.025 s, one case each, every case in its own
 * HDF5 file under sweep_out/ and a summary table (summary.h5,
 * summary.csv).  Run it again and the finished cases are skipped (their
 * rows are read back from sweep_out/case_NNNNN.done).
 *
 * Trust numbers against the analytic bound.  Velocity Verlet conserves
 * exactly the modified energy p^2/2 + (1 - dt^2/4) x^2/2 on the
 * oscillator, so from x = 1, v = 0 the relative energy error at a step
 * is (dt^2/4)(1 - x^2): at most dt^2/4, reached where the orbit crosses
 * x = 0.  The sweep's largest relative energy error (checked every step)
 * must therefore lie just below dt^2/4 for every case: the ratio within
 * (1 - dt^2/4, 1], and the observed order 2.
 *
 * Build and run: make -C examples sweep && examples/sweep
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <ballfilm/sweep.h>

static const char *const scene_text =
    "[scene]\n"
    "title        = harmonic oscillator, velocity Verlet\n"
    "integrator   = verlet\n"
    "effects      = spring\n"
    "dt           = 0.1\n"
    "t_end        = 20\n"
    "output_every = 10\n"
    "energy_every = 1\n"
    "[spring]\n"
    "stiffness    = 1\n"
    "[ball.1]\n"
    "position     = 1\n";

int main(void)
{
    /* a sweep reads its scene from a file (it records the file's hash so
     * that a rerun against an edited scene is refused) */
    FILE *f = fopen("sweep_oscillator.ini", "w");
    if (!f || fputs(scene_text, f) < 0 || fclose(f)) {
        perror("sweep: sweep_oscillator.ini");
        return 1;
    }
    const char *vary[] = {"scene.dt=0.2,0.1,0.05,0.025"};
    bf_sweep sw;
    bf_err err = {0};
    if (bf_sweep_init(&sw, "sweep_oscillator.ini", NULL, 0, vary, 1,
                      "sweep_out", &err)) {
        fprintf(stderr, "sweep: %s\n", err.msg);
        return 1;
    }
    bf_sweep_row *rows = calloc(sw.ncases, sizeof *rows);
    int bad = !rows;
    for (long k = 0; !bad && k < (long)sw.ncases; k++) {
        if (bf_sweep_case_done(&sw, k, &rows[k]))
            continue; /* from an earlier run of this program */
        if (bf_sweep_run_case(&sw, k, &rows[k], &err)) {
            fprintf(stderr, "sweep: case %ld: %s\n", k, err.msg);
            bad = 1;
        }
    }
    if (!bad && bf_sweep_write_summary(&sw, rows, &err)) {
        fprintf(stderr, "sweep: %s\n", err.msg);
        bad = 1;
    }
    printf("%8s %14s %14s %8s %7s\n", "dt (s)", "max |dE/E|", "dt^2/4",
           "ratio", "order");
    double worst = 0.0;
    for (size_t k = 0; !bad && k < sw.ncases; k++) {
        const double dt = rows[k].values[0], e = rows[k].energy_error;
        const double bound = dt * dt / 4.0, ratio = e / bound;
        if (rows[k].status || !(ratio <= 1.0 + 1e-12 && ratio > 1.0 - bound))
            bad = 1;
        worst = fmax(worst, fabs(1.0 - ratio));
        printf("%8g %14.6e %14.6e %8.5f", dt, e, bound, ratio);
        if (k)
            printf(" %7.3f\n",
                   log(rows[k - 1].energy_error / e) / log(rows[k - 1].values[0] / dt));
        else
            printf("\n");
    }
    printf("%zu cases in sweep_out/ (summary.h5, summary.csv); the energy "
           "error is within %.2e of the bound dt^2/4 in every case\n",
           sw.ncases, worst);
    free(rows);
    bf_sweep_free(&sw);
    return bad;
}
