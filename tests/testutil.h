/* testutil.h: helpers shared by the test files (Check framework).
 *
 * Each tests/test_NAME.c defines `Suite *suite_NAME(void)`; runner.c runs
 * them all and Check prints the summary line.  Tests that run the program
 * find it through $BALLFILM_BIN and the repository through $BALLFILM_ROOT
 * (set by the Makefile). */
#ifndef BALLFILM_TESTUTIL_H
#define BALLFILM_TESTUTIL_H

#include <check.h>
#include <stddef.h>

#include "models/ballsys.h"
#include "ballfilm/film.h"
#include "ballfilm/integrator.h"
#include "ballfilm/scene.h"
#include "ballfilm/sim.h"

/* A fresh temporary directory (removed at exit of the test process). */
const char *tu_tmpdir(void);
/* Path inside the temporary directory (static buffer rotation of 8). */
const char *tu_tmp(const char *name);
/* Write text to a file; returns its path. */
const char *tu_write(const char *name, const char *text);
/* Path of a repository file ("runs/harmonic.ini"). */
const char *tu_repo(const char *rel);

/* Run bin/ballfilm with arguments (NULL-terminated); stdout and stderr are
 * captured into *out and *errout (malloc'd, may be NULL).  Returns the exit
 * status, or -signal if killed. */
int tu_run(char **out, char **errout, const char *arg0, ...);
/* The same with an argv array. */
int tu_runv(char **out, char **errout, const char *const *argv);
/* Run the program of tu_run/tu_runv under an address-space limit
 * (setrlimit RLIMIT_AS, as `ulimit -v`) of `bytes` from now on (0: none).
 * Not under the sanitizers, whose shadow memory needs terabytes of
 * address space. */
void tu_run_limit_as(long long bytes);

/* Build and resolve a scene from text; fails the test on error. */
bf_scene *tu_scene(const char *text);
/* Resolve a scene from text and return the error status and message. */
bf_status tu_scene_error(const char *text, char *msg, size_t cap);

/* Run a scene (text plus optional "section.key=value" overrides, NULL-
 * terminated) to the end without output.  Returns the sim (free it). */
bf_sim *tu_run_scene(const char *text, ...);

/* Names of every dataset in an HDF5 file (NULL-terminated, malloc'd; free
 * with tu_free_list). */
char **tu_h5_datasets(const char *file);
void tu_free_list(char **list);
/* The file a run wrote for output PATH: PATH once the run ended, PATH.part
 * while it may still be continued (interrupted, killed, disk full). */
const char *tu_result(const char *path);
/* Wait (polling, at most a minute; the test fails otherwise) until `path`
 * exists with more than `bytes` bytes: the marker that a background run is
 * under way, instead of a fixed wait. */
void tu_wait_for_file(const char *path, long bytes);
/* Assert that two files hold the same datasets with the same bits (each
 * looked up with tu_result). */
void tu_same_datasets(const char *a, const char *b);

/* Assert that two runs' counters agree (root attributes steps_done,
 * force_evaluations, rejected_steps, iterations,
 * max_relative_energy_error; each present in both or in neither). */
void tu_same_counters(const char *a, const char *b);

/* Run `run SCENE -o PART -q ARGS... --stop-after STOP` (it must stop:
 * exit 6), continue it with `run --restart PART -q` (it must finish), and
 * assert that PART holds FULL's datasets bit for bit and its counters
 * (tu_same_counters).  args is
 * NULL-terminated (at most 16). */
void tu_stop_restart_same(const char *scene, const char *full,
                          const char *part, const char *stop,
                          const char *const *args);

double tu_max(const double *v, size_t n);
double tu_absmax(const double *v, size_t n);

/* An integrator of n unknowns with [integrator] keys given as
 * "key=value;key=value" (NULL: defaults); fails the test on error. */
bf_integrator *tu_integrator(const char *name, const char *keys, size_t n);

/* A ball system (balls, effects, integrator) from scene text; fails the
 * test on error.  Free it with bf_ballsys_free. */
bf_ballsys *tu_ballsys(const char *text);
/* A film of length L (cm) and cell dx (cm) with the Yasuda sec. 3.5
 * parameters (rho 1, nu 0.01, g 980, a = b = gamma = 1) at rest, with
 * h = h_of(x) and psi = psi_of(x) at its nodes. */
bf_film *tu_film(double L, double dx, double (*h_of)(double),
                 double (*psi_of)(double));

/* x'' = -x for one unknown (a bf_accel_fn; ctx, t and v unused). */
int tu_accel_harmonic(void *ctx, double t, const double *x, const double *v,
                      double *a);

/* Standard test case with a generous timeout. */
TCase *tu_tcase(const char *name);

/* 1 if no process holds the writer's lock (outpath.c, bf_path_lock) on the
 * open file fd. */
int tu_part_unlocked(int fd);

/* Golden lines (Basilisk's .ref habit).  Format a line, print it on
 * stderr and compare it with the line of tests/ref/NAME.ref that has the
 * same text once every number is masked: the numbers must agree within the
 * file's tolerance, stated on its first line as
 *   # tolerance: rtol=R atol=A     (|a - b| <= R max(|a|, |b|) + A)
 * with the reason.  A line missing from the file fails the test; with
 * BALLFILM_REF_UPDATE=1 in the environment it is appended to
 * tests/ref/NAME.ref.new instead, for review. */
void tu_ref(const char *name, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Wait (up to a minute) until the HDF5 file at path, while a run writes
 * it, holds more than `rows` rows of dataset `dset`; fails the test
 * otherwise.  Returns the rows seen.  (A read in the middle of a flush may
 * fail; it is retried.) */
size_t tu_wait_for_rows(const char *path, const char *dset, size_t rows);

#endif
