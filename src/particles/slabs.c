/* slabs.c: x-slabs of cell columns balanced by particle counts (see
 * slabs.h). */
#include "particles/slabs.h"

#include <stdlib.h>
#include <string.h>

bf_status bf_slabs_init(bf_slabs *s, int size, int nx, int hl, int hr,
                        bf_err *err)
{
    memset(s, 0, sizeof *s);
    if (size < 1 || nx < 1 || hl < 0 || hr < 0)
        return bf_fail(err, BF_EINTERNAL, "slabs: bad geometry");
    s->size = size;
    s->nx = nx;
    s->hl = hl;
    s->hr = hr;
    s->cut = calloc((size_t)size + 1, sizeof *s->cut);
    s->rank_of = calloc((size_t)nx, sizeof *s->rank_of);
    s->cnt = calloc((size_t)nx, sizeof *s->cnt);
    s->own = calloc((size_t)size, sizeof *s->own);
    if (!s->cut || !s->rank_of || !s->cnt || !s->own) {
        bf_slabs_free(s);
        return bf_fail(err, BF_EINTERNAL, "out of memory (slabs)");
    }
    return BF_OK;
}

void bf_slabs_free(bf_slabs *s)
{
    free(s->cut);
    free(s->rank_of);
    free(s->cnt);
    free(s->own);
    memset(s, 0, sizeof *s);
}

void bf_slabs_balance(bf_slabs *s, const int32_t *col, size_t n)
{
    memset(s->cnt, 0, (size_t)s->nx * sizeof *s->cnt);
    for (size_t i = 0; i < n; i++)
        s->cnt[col[i]]++;
    bf_slabs_cut(s, n);
}

void bf_slabs_cut(bf_slabs *s, size_t n)
{
    const int nx = s->nx, size = s->size;
    memset(s->own, 0, (size_t)size * sizeof *s->own);
    /* rank r starts at the first column before which at least r n / size
     * particles lie (integers: no rounding) */
    size_t before = 0;
    int r = 1;
    s->cut[0] = 0;
    for (int c = 0; c < nx && r < size; c++) {
        while (r < size && (unsigned long long)before * (unsigned long long)size >=
                               (unsigned long long)r * (unsigned long long)n)
            s->cut[r++] = c;
        before += s->cnt[c];
    }
    while (r <= size)
        s->cut[r++] = nx;
    for (int q = 0; q < size; q++)
        for (int c = s->cut[q]; c < s->cut[q + 1]; c++) {
            s->rank_of[c] = q;
            s->own[q] += s->cnt[c];
        }
}
