/* hash.h: a 64-bit FNV-1a hash of bytes, for telling scenes and
 * checkpoints apart (not for security: an edit that keeps the hash must be
 * made on purpose).  Private to the library. */
#ifndef BALLFILM_BASE_HASH_H
#define BALLFILM_BASE_HASH_H

#include <stddef.h>
#include <stdint.h>

#define BF_HASH_INIT 0xcbf29ce484222325ull

/* Continue hash h over n bytes at p (start with BF_HASH_INIT). */
static inline uint64_t bf_hash64(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t k = 0; k < n; k++) {
        h ^= b[k];
        h *= 0x100000001b3ull;
    }
    return h;
}

#endif
