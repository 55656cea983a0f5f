/* state_names.h: the lookup the models' state hooks share (model.h,
 * set_state; private to src/models). */
#ifndef BALLFILM_MODELS_STATE_NAMES_H
#define BALLFILM_MODELS_STATE_NAMES_H

#include <stddef.h>
#include <string.h>

/* The index of `name` in names[0 .. n-1], or n when it is not there. */
static inline size_t bf_state_index(const char *const *names, size_t n,
                                    const char *name)
{
    size_t k = 0;
    while (k < n && strcmp(names[k], name))
        k++;
    return k;
}

#endif
