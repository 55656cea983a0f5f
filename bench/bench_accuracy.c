/* bench_accuracy.c: what a given accuracy costs on the bouncing ball
 * (runs/bouncing_ball.ini, k = 1e7, about 35 bounces) and on two balls
 * (runs/two_balls_B.ini), both to T = 1 s: our best fixed-step method
 * against ARKODE's best adaptive method (issue 19).
 *
 * The study is `ballfilm converge` (converge.h) with many step sizes and
 * tolerances: our fixed-step methods (verlet, mv2m, rk4, rkn6), each
 * with and without event splitting ([integrator] events = yes), at
 * dt = 3e-4 s * 2^(-k/4), k = 0..28; ARKODE's adaptive ERK with five
 * Butcher tables, each with and without its rootfinding at the contacts
 * (restarting there), at rtol = 10^(-k/2), k = 6..26 (atol = rtol/100,
 * largest step 10 dt of the scene); all against the VERNER_8_5_6
 * reference with rootfinding at the contacts, at rtol 1e-14 and 1e-15
 * (its estimated error is their difference).  Because the Hertz contact
 * is only C^1, the error is not monotone in dt or rtol; a method
 * "reaches" an accuracy at the cheapest run from which every more
 * expensive run of the same method is at least as accurate (within a
 * method: the reliable run with the fewest evaluations; between methods:
 * the smallest wall time).
 * Cost is the wall time of the stepping loop (minimum of 3 repeats), the
 * measure of the issue: our steps are specialised (inline force kernels)
 * and ARKODE's are not, so evaluations alone would hide what a step
 * costs; the evaluations are printed too.  Wall times on a shared machine
 * vary by tens of percent between invocations.  Printed for the
 * accuracies 1e-3 ... 1e-10 cm of the final position: the best of ours,
 * the best of ARKODE's, and the ratio ours/ARKODE of their wall times and
 * evaluations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ballfilm/converge.h"
#include "ballfilm/scene.h"

typedef struct best {
    const char *label;
    int method;
    double wall, err, dt;
    unsigned long long evals;
} best;

/* cheapest run of method m reliably below `target` */
static int reach(const bf_converge_result *r, int m, double target, best *b)
{
    int found = 0;
    for (size_t k = 0; k < r->nrows; k++) {
        const bf_converge_row *w = &r->rows[k];
        if (w->method != m || w->status || !(w->err_x <= target))
            continue;
        int ok = 1; /* every costlier run of m is accurate enough */
        for (size_t j = 0; j < r->nrows && ok; j++) {
            const bf_converge_row *u = &r->rows[j];
            if (u->method == m && u->count.evals > w->count.evals &&
                (u->status || !(u->err_x <= target)))
                ok = 0;
        }
        /* within a method the cheapest is the one with the fewest
         * evaluations (deterministic; wall times carry noise) */
        if (ok && (!found || w->count.evals < b->evals)) {
            b->label = w->label;
            b->method = m;
            b->wall = w->wall;
            b->err = w->err_x;
            b->dt = w->adaptive ? w->tol : w->dt;
            b->evals = w->count.evals;
            found = 1;
        }
    }
    return found;
}

static int study(const char *root, const char *scene, const char *title)
{
    char path[600];
    snprintf(path, sizeof path, "%s/runs/%s", root, scene);
    bf_err err = {0};
    bf_scene *sc;
    if (bf_scene_load(&sc, path, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    const char *ours[] = {"verlet", "mv2m", "rk4", "rkn6",
                          "verlet:events=yes", "mv2m:events=yes",
                          "rk4:events=yes", "rkn6:events=yes"};
    const char *tabs[] = {"DORMAND_PRINCE_7_4_5", "CASH_KARP_6_4_5",
                          "FEHLBERG_6_4_5", "BOGACKI_SHAMPINE_4_2_3",
                          "ZONNEVELD_5_3_4"};
    enum { NO = 8, NT = 5, NA = 2 * NT, ND = 29, NTOL = 21 };
    char ark[NA][96];
    const char *methods[NO + NA];
    for (size_t k = 0; k < NO; k++)
        methods[k] = ours[k];
    for (size_t k = 0; k < NA; k++) {
        snprintf(ark[k], sizeof ark[k], "arkode:table=ARKODE_%s%s",
                 tabs[k % NT], k >= NT ? ":events=yes" : "");
        methods[NO + k] = ark[k];
    }
    double dts[ND], tols[NTOL];
    for (int k = 0; k < ND; k++)
        dts[k] = 3e-4 * pow(2.0, -k / 4.0);
    for (int k = 0; k < NTOL; k++)
        tols[k] = pow(10.0, -(k + 6) / 2.0);
    bf_converge_opts o = {.methods = methods,
                          .nmethods = NO + NA,
                          .dts = dts,
                          .ndts = ND,
                          .tols = tols,
                          .ntols = NTOL,
                          .t_end = 1.0,
                          .repeats = 3,
                          .ref_rtol = 1e-14,
                          .ref_table = "ARKODE_VERNER_8_5_6"};
    bf_converge_result *r;
    if (bf_converge_run(sc, &o, &r, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    printf("\n%s to T = 1 s; reference %s with rootfinding at the "
           "contacts,\n  its estimated error %.1e cm (rtol 1e-14 against "
           "1e-15)\n",
           title, r->ref_label, r->ref_err_x);
    printf("%-9s  %-26s %9s %9s  %-40s %9s %9s  %8s %8s\n", "accuracy",
           "ours: best (dt [s])", "wall [s]", "evals",
           "ARKODE: best (rtol)", "wall [s]", "evals", "wall", "evals");
    printf("%-9s  %-26s %9s %9s  %-40s %9s %9s  %8s %8s\n", "[cm]", "", "",
           "", "", "", "", "ours/ARK", "ours/ARK");
    int worst = 0;
    for (int t = 0; t < 8; t++) {
        const double target = pow(10.0, -3 - t);
        best bo = {0}, ba = {0}, c;
        int fo = 0, fa = 0;
        for (size_t m = 0; m < NO + NA; m++) {
            if (!reach(r, (int)m, target, &c))
                continue;
            if (m < NO && (!fo || c.wall < bo.wall)) {
                bo = c;
                fo = 1;
            }
            if (m >= NO && (!fa || c.wall < ba.wall)) {
                ba = c;
                fa = 1;
            }
        }
        char lo[80] = "not reached", la[80] = "not reached";
        if (fo)
            snprintf(lo, sizeof lo, "%s%s (%.3g)", bo.label,
                     strstr(methods[bo.method], "events") ? "+ev" : "",
                     bo.dt);
        if (fa) {
            char tab[64] = "";
            sscanf(ba.label, "arkode %63s", tab);
            snprintf(la, sizeof la, "%s%s (%.3g)", tab,
                     strstr(methods[ba.method], "events") ? "+roots" : "",
                     ba.dt);
        }
        printf("%-9.0e  %-26s %9.5f %9llu  %-40s %9.5f %9llu  ", target, lo,
               fo ? bo.wall : NAN, fo ? bo.evals : 0ULL, la,
               fa ? ba.wall : NAN, fa ? ba.evals : 0ULL);
        if (fo && fa) {
            printf("%8.3f %8.2f\n", bo.wall / ba.wall,
                   (double)bo.evals / (double)ba.evals);
            worst |= !(bo.wall < ba.wall);
        } else {
            printf("%8s %8s\n", "-", "-");
            worst = 1;
        }
    }
    if (worst)
        printf("NOTE: at some accuracy ours is not cheaper than ARKODE's "
               "best (ratio >= 1 or not reached)\n");
    bf_converge_free(r);
    bf_scene_free(sc);
    return 0;
}

int main(void)
{
    const char *root = getenv("BALLFILM_ROOT");
    char model[256] = "unknown";
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10)) {
            const char *c = strchr(line, ':');
            snprintf(model, sizeof model, "%.200s", c ? c + 2 : line);
            model[strcspn(model, "\n")] = '\0';
            break;
        }
    if (f)
        fclose(f);
    printf("machine: %s (wall times are of this machine)\n", model);
    if (study(root ? root : ".", "bouncing_ball.ini", "bouncing ball"))
        return 1;
    return study(root ? root : ".", "two_balls_B.ini",
                 "two balls (runs/two_balls_B.ini)");
}
