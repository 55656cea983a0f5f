/* utf8.h: checking text for well-formed UTF-8 (RFC 3629: no overlong
 * forms, no surrogates U+D800..U+DFFF, nothing above U+10FFFF), so that no
 * attribute tagged UTF-8 in an output holds anything else (scene.c refuses
 * such scenes, h5out.c escapes such strings).  Private to the library. */
#ifndef BALLFILM_BASE_UTF8_H
#define BALLFILM_BASE_UTF8_H

#include <stddef.h>

/* The length (1-4) of the well-formed sequence at s[0..n), or 0. */
static inline size_t bf_utf8_seq(const unsigned char *s, size_t n)
{
    unsigned c = s[0];
    if (c < 0x80)
        return 1;
    size_t len = c >= 0xc2 && c <= 0xdf   ? 2
                 : c >= 0xe0 && c <= 0xef ? 3
                 : c >= 0xf0 && c <= 0xf4 ? 4
                                          : 0;
    if (!len || len > n)
        return 0;
    for (size_t k = 1; k < len; k++)
        if ((s[k] & 0xc0) != 0x80)
            return 0;
    /* the second byte's range that excludes overlongs, surrogates and
     * code points above U+10FFFF */
    unsigned d = s[1];
    if ((c == 0xe0 && d < 0xa0) || (c == 0xed && d > 0x9f) ||
        (c == 0xf0 && d < 0x90) || (c == 0xf4 && d > 0x8f))
        return 0;
    return len;
}

/* The offset of the first byte of s[0..n) that is not well-formed UTF-8,
 * or n if all is. */
static inline size_t bf_utf8_invalid(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t k = 0;
    while (k < n) {
        size_t len = bf_utf8_seq(u + k, n - k);
        if (!len)
            return k;
        k += len;
    }
    return n;
}

#endif
