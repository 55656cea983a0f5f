/* fuzz_ckpt.h: the checkpoint fuzz case, shared by `make fuzz`
 * (tests/fuzz/fuzz_checkpoint.c, libFuzzer) and the test suite
 * (tests/test_fuzz.c).
 *
 * A real run is stopped after a few steps, leaving its output OUT.part and
 * its checkpoint OUT.ckpt, and the same run is made uninterrupted.  A case
 * is a checkpoint file (the real one damaged: bits flipped, cut short; or
 * edited entry by entry and sealed again, as a bug or a hand might): the
 * run is continued from it in this process with the real OUT.part, and the
 * outcome must be one of: refused with a message (BF_EINPUT), or a run
 * that ends with a status and a message (stopped unstable, interrupted at
 * the step bound) or ends well.  Never a crash, a hang, an allocation a
 * stored count asked for (an "out of memory"), an I/O error.  The real
 * checkpoint itself must give the uninterrupted run's datasets. */
#ifndef BALLFILM_FUZZ_CKPT_H
#define BALLFILM_FUZZ_CKPT_H

#include <stddef.h>

#include "ballfilm/error.h"

typedef struct bf_fuzz_ckpt bf_fuzz_ckpt;

/* The stopped and the uninterrupted run of `scene` (path) with overrides
 * `sets` (NULL-terminated), stopped after `stop` steps, in directory dir
 * under the name `name`.  NULL with the reason in why. */
bf_fuzz_ckpt *bf_fuzz_ckpt_new(const char *dir, const char *name,
                               const char *scene, const char *const *sets,
                               long stop, char *why, size_t cap);
void bf_fuzz_ckpt_free(bf_fuzz_ckpt *fc);

/* The real checkpoint file's bytes. */
const unsigned char *bf_fuzz_ckpt_file(const bf_fuzz_ckpt *fc, size_t *n);

typedef struct bf_fuzz_outcome {
    bf_status status; /* of the restart, or of the continued run */
    int restarted;    /* 1: the checkpoint was accepted */
    int same;         /* restarted and ended with the uninterrupted
                         run's datasets */
    char msg[BF_ERR_MSG];
} bf_fuzz_outcome;

/* Continue the run from the checkpoint file `data` (at most `max_steps`
 * steps of the continued run). */
void bf_fuzz_ckpt_run(bf_fuzz_ckpt *fc, const unsigned char *data, size_t n,
                      long max_steps, bf_fuzz_outcome *out);

/* 1 if the outcome is one of those allowed (see above); why says what
 * was not. */
int bf_fuzz_ckpt_allowed(const bf_fuzz_outcome *o, char *why, size_t cap);

/* The real checkpoint edited by `prog` and sealed again: each 6 bytes of
 * prog are one edit (entry, element, operation: a special integer or real
 * value, a dropped entry, a length one shorter or longer, a changed
 * kind, a changed string byte).  malloc'd file bytes in *out (NULL if the
 * edits could not be written). */
void bf_fuzz_ckpt_edit(const bf_fuzz_ckpt *fc, const unsigned char *prog,
                       size_t nprog, unsigned char **out, size_t *nout);

/* The real checkpoint damaged by `prog`: each 4 bytes are an offset (3
 * bytes, little-endian, modulo the file's size) and a byte XORed into the
 * file there, or 0: the file cut at that offset. */
void bf_fuzz_ckpt_damage(const bf_fuzz_ckpt *fc, const unsigned char *prog,
                         size_t nprog, unsigned char **out, size_t *nout);

/* The number of entries of the real checkpoint (for enumerating edits). */
size_t bf_fuzz_ckpt_entries(const bf_fuzz_ckpt *fc);

/* One fuzzer input: byte 0 odd, the rest an edit program
 * (bf_fuzz_ckpt_edit), even, a damage program (bf_fuzz_ckpt_damage).
 * Returns 1 if the outcome is allowed: refused with a message or a
 * finished run for an edit; refused, or the uninterrupted run's datasets,
 * for damage; the uninterrupted run's datasets for the real file.  0 with
 * the reason in why otherwise. */
int bf_fuzz_ckpt_input(bf_fuzz_ckpt *fc, const unsigned char *in, size_t n,
                       long max_steps, bf_fuzz_outcome *o, char *why,
                       size_t cap);

/* The models fuzzed: how many, and model k's case (a run of a scene of
 * runs/ under the repository `root`, made in `dir`): its name and the
 * steps a continued run may take. */
size_t bf_fuzz_ckpt_nmodels(void);
bf_fuzz_ckpt *bf_fuzz_ckpt_model(const char *root, const char *dir, size_t k,
                                 const char **name, long *steps, char *why,
                                 size_t cap);

#endif
