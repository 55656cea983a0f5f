/* checkpoint.h: named arrays that capture the complete state of a run, and
 * their atomic storage in an HDF5 file.
 *
 * Each model saves what it needs to continue bit for bit (positions,
 * velocities, fields, integrator counters and history, RNG state, events
 * collected so far) under names of its choice; the time loop adds its own
 * (step counter, energy bookkeeping, output row counts) and the scene.
 * bf_ckpt_write() writes to "PATH.tmp", flushes it to disk and renames it
 * over PATH, so a checkpoint file is always either the old or the new one.
 */
#ifndef BALLFILM_CHECKPOINT_H
#define BALLFILM_CHECKPOINT_H

#include <stddef.h>
#include <stdint.h>

#include "ballfilm/error.h"

typedef struct bf_ckpt bf_ckpt;

bf_ckpt *bf_ckpt_new(void);
void bf_ckpt_free(bf_ckpt *ck);

/* Store a copy (a name may be stored once). */
bf_status bf_ckpt_put(bf_ckpt *ck, const char *name, const double *v, size_t n,
                      bf_err *err);
bf_status bf_ckpt_put_i64(bf_ckpt *ck, const char *name, const int64_t *v,
                          size_t n, bf_err *err);
bf_status bf_ckpt_put_bytes(bf_ckpt *ck, const char *name, const void *p,
                            size_t n, bf_err *err);
bf_status bf_ckpt_put_real(bf_ckpt *ck, const char *name, double v,
                           bf_err *err);
bf_status bf_ckpt_put_int(bf_ckpt *ck, const char *name, int64_t v,
                          bf_err *err);
bf_status bf_ckpt_put_str(bf_ckpt *ck, const char *name, const char *s,
                          bf_err *err);

/* Copy out exactly n elements; a missing name or another length is an
 * error naming the entry. */
bf_status bf_ckpt_get(const bf_ckpt *ck, const char *name, double *v, size_t n,
                      bf_err *err);
bf_status bf_ckpt_get_i64(const bf_ckpt *ck, const char *name, int64_t *v,
                          size_t n, bf_err *err);
bf_status bf_ckpt_get_bytes(const bf_ckpt *ck, const char *name, void *p,
                            size_t n, bf_err *err);
bf_status bf_ckpt_get_real(const bf_ckpt *ck, const char *name, double *v,
                           bf_err *err);
bf_status bf_ckpt_get_int(const bf_ckpt *ck, const char *name, int64_t *v,
                          bf_err *err);
/* Variable-length entries: the stored data and its length in elements
 * (bytes for byte entries), or NULL if absent. */
const double *bf_ckpt_data(const bf_ckpt *ck, const char *name, size_t *n);
const int64_t *bf_ckpt_data_i64(const bf_ckpt *ck, const char *name,
                                size_t *n);
const char *bf_ckpt_str(const bf_ckpt *ck, const char *name); /* or NULL */
int bf_ckpt_has(const bf_ckpt *ck, const char *name);

/* Atomic write (PATH.tmp + fsync + rename) and read. */
bf_status bf_ckpt_write(const bf_ckpt *ck, const char *path, bf_err *err);
bf_status bf_ckpt_read(bf_ckpt **out, const char *path, bf_err *err);

#endif
