/* fuzz_h5.h: hostile HDF5 files for the readers' tests and fuzzer: real
 * outputs of every model, mutated at the level of HDF5 objects, given to
 * the program's readers (info, xdmf, run --restart, [film] initial =
 * file) in child processes under CPU and file-size limits. */
#ifndef BALLFILM_TESTS_FUZZ_H5_H
#define BALLFILM_TESTS_FUZZ_H5_H

#include <stddef.h>

/* Make the corpus file `name` in directory dir unless it is there (a
 * short run of bin/ballfilm, $BALLFILM_BIN): balls film mac coupled g72
 * g73 (NAME.h5), part or ckpt (part.h5.part with part.h5.ckpt, a run
 * stopped after a few steps).  Returns 0, or -1 (with a line on
 * stderr). */
int fh5_make_corpus(const char *dir, const char *name);

/* The word that joins the mutations of one recipe line. */
#define FH5_AND "+"

/* Apply the mutations (words of a recipe line after EXPECT CORPUS
 * COMMAND, NULL-terminated; several joined by FH5_AND) to the HDF5 file
 * `file`.  0, or -1 when the recipe is malformed or HDF5 refused a
 * change. */
int fh5_mutate(const char *file, const char *const *op);

/* Run the program on a copy of the corpus made in `work` (a directory):
 * CORPUS and COMMAND as in tests/fuzz/h5_regress/fixed.recipes.  Returns
 * the exit status, or -signal; *errout (malloc'd) holds its stderr, and
 * *target the file given to it (static). */
int fh5_run(const char *corpus_dir, const char *work, const char *corpus,
            const char *command, const char *const *op, char **errout,
            const char **target);

/* Run bin/ballfilm with argv (NULL-terminated, without the program) under
 * RLIMIT_CPU of cpu seconds and RLIMIT_FSIZE of fsize bytes, stdout to
 * /dev/null, stderr into *errout (malloc'd; may be NULL).  With
 * pending_term, SIGTERM is pending when the program starts (it arrived
 * as it started).  The exit status, or -signal. */
int fh5_exec(const char *const *argv, int cpu, long long fsize,
             int pending_term, char **errout);

/* What is wrong with a run of fh5_run (its status rc, stderr err, the
 * file given it): a signal (a CPU, file-size or wall-clock limit among
 * them), an exit status outside 0-6, a sanitizer report, a failure
 * (status 1, 2 or 5) whose message does not name the file (for OUT.part
 * and OUT.ckpt: OUT); NULL when none of these, or when the case could not
 * be made (rc <= -1000). */
const char *fh5_verdict(int rc, const char *err, const char *target);

#endif
