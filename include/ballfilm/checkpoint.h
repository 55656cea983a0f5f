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
/* The entries in the order stored, for tools that list or edit a
 * checkpoint: how many, and entry k's name (NULL past the end), kind
 * ("real", "int", "bytes", "str"), length in elements and data (doubles,
 * int64s, bytes, a NUL-terminated string). */
size_t bf_ckpt_count(const bf_ckpt *ck);
const char *bf_ckpt_entry(const bf_ckpt *ck, size_t k, const char **kind,
                          size_t *n, const void **data);

/* ---- state described by data ----
 * A model (or a component) describes its state by a table of fields:
 * name, C type, offset in its struct, how many elements, unit.  One call
 * saves or loads them all, so a new field is one line of the table, and
 * the counts are checked on load (an entry of another length is refused,
 * naming it).  Each field is stored as the entry prefix.name (integers as
 * int64, doubles as they are).
 *
 *   static const bf_field g72_state[] = {
 *       BF_FIELD(g72, steps, BF_F_ULL, "1"),
 *       BF_FIELD_ARRAY(g72, kind_total, BF_F_ULL, "particle-steps"),
 *       BF_FIELD_PTR(g72, ax, BF_F_DOUBLE, n, "cm/s^2"),
 *   };
 *   bf_ckpt_put_fields(ck, "g72", g72_state, BF_NFIELDS(g72_state), m, err);
 */
typedef enum bf_ftype {
    BF_F_DOUBLE, /* double */
    BF_F_INT,    /* int */
    BF_F_LONG,   /* long */
    BF_F_ULONG,  /* unsigned long */
    BF_F_ULL,    /* unsigned long long */
    BF_F_SIZE,   /* size_t */
    BF_F_I64,    /* int64_t */
    BF_F_I32,    /* int32_t */
    BF_F_U32,    /* uint32_t */
    BF_F_U8      /* uint8_t */
} bf_ftype;

typedef struct bf_field {
    const char *name;
    bf_ftype type;
    size_t offset;   /* of the member */
    size_t count;    /* elements of a scalar or array member; 0: pointer */
    size_t count_of; /* pointer members: offset of the size_t member that
                        holds the number of elements */
    const char *unit;
} bf_field;

#define BF_FTYPE_BF_F_DOUBLE double
#define BF_FTYPE_BF_F_INT int
#define BF_FTYPE_BF_F_LONG long
#define BF_FTYPE_BF_F_ULONG unsigned long
#define BF_FTYPE_BF_F_ULL unsigned long long
#define BF_FTYPE_BF_F_SIZE size_t
#define BF_FTYPE_BF_F_I64 int64_t
#define BF_FTYPE_BF_F_I32 int32_t
#define BF_FTYPE_BF_F_U32 uint32_t
#define BF_FTYPE_BF_F_U8 uint8_t
/* The members' C types are checked at compile time (as params.h's BF_AT). */
#define BF_FIELD_CHECK_(ptr, TYPE) (0 * sizeof((ptr) == (BF_FTYPE_##TYPE *)0))
/* a scalar member */
#define BF_FIELD(T, m, TYPE, unit)                                             \
    {#m, TYPE, offsetof(T, m) + BF_FIELD_CHECK_(&((T *)0)->m, TYPE), 1, 0,     \
     unit}
/* an array member (its whole length) */
#define BF_FIELD_ARRAY(T, m, TYPE, unit)                                       \
    {#m, TYPE, offsetof(T, m) + BF_FIELD_CHECK_(&((T *)0)->m[0], TYPE),        \
     sizeof(((T *)0)->m) / sizeof(((T *)0)->m[0]), 0, unit}
/* a pointer member to n elements, n in the size_t member `cnt` */
#define BF_FIELD_PTR(T, m, TYPE, cnt, unit)                                    \
    {#m, TYPE, offsetof(T, m) + BF_FIELD_CHECK_(((T *)0)->m, TYPE), 0,         \
     offsetof(T, cnt) + 0 * sizeof(&((T *)0)->cnt == (size_t *)0), unit}
#define BF_NFIELDS(table) (sizeof(table) / sizeof((table)[0]))

bf_status bf_ckpt_put_fields(bf_ckpt *ck, const char *prefix,
                             const bf_field *f, size_t nf, const void *obj,
                             bf_err *err);
bf_status bf_ckpt_get_fields(const bf_ckpt *ck, const char *prefix,
                             const bf_field *f, size_t nf, void *obj,
                             bf_err *err);

/* Atomic write (PATH.tmp + fsync + rename) and read.  The file is sealed
 * (its length and a hash of its bytes, checked before HDF5 reads it) and
 * every entry is covered by a checksum: a damaged or edited file is
 * refused (BF_EINPUT) with a message, never half-read. */
bf_status bf_ckpt_write(const bf_ckpt *ck, const char *path, bf_err *err);
bf_status bf_ckpt_read(bf_ckpt **out, const char *path, bf_err *err);

#endif
