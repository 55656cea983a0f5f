/* xalloc.h: allocation that cannot fail quietly, for the scene parser and
 * the parameter tables (private to the library).  Both hold small texts
 * read once at start-up; running out of memory there leaves nothing to
 * recover, so these report it and abort instead of threading an error
 * through every string operation. */
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

#endif
