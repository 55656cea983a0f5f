/* xalloc.h: allocation that cannot fail quietly, for the scene parser,
 * the parameter tables and a sweep's manifest (private to the library).
 * All hold small texts read once at start-up; running out of memory there
 * leaves nothing to recover, so these report it and abort instead of
 * threading an error through every string operation. */
#ifndef BALLFILM_BASE_XALLOC_H
#define BALLFILM_BASE_XALLOC_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static inline void bf_out_of_memory(void)
{
    fprintf(stderr, "ballfilm: out of memory\n");
    abort();
}

/* realloc(p, n), never NULL (n = 0 allocates one byte) */
static inline void *bf_xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q)
        bf_out_of_memory();
    return q;
}

/* a copy of s ("" for NULL), never NULL */
static inline char *bf_xstrdup(const char *s)
{
    const size_t n = strlen(s ? s : "") + 1;
    char *d = bf_xrealloc(NULL, n);
    memcpy(d, s ? s : "", n);
    return d;
}

/* The rest of stream f as a string of *len bytes and a terminating NUL
 * (the bytes read may hold NULs of their own), never NULL for want of
 * memory; NULL if reading fails, or (*too_long set) if the buffer grew
 * past max bytes, so that a file that never ends is not read forever. */
static inline char *bf_xread_all(FILE *f, size_t max, size_t *len,
                                 int *too_long)
{
    size_t cap = 4096, n = 0, got;
    char *buf = bf_xrealloc(NULL, cap);
    *too_long = 0;
    while ((got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (n + 1 == cap) {
            if (cap > max) {
                free(buf);
                *too_long = 1;
                return NULL;
            }
            cap *= 2;
            buf = bf_xrealloc(buf, cap);
        }
    }
    if (ferror(f)) {
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

#endif
