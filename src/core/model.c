/* model.c: helpers of the model interface (see model.h). */
#include "ballfilm/model.h"

const void *bf_setup_get(const bf_model_setup *s, const bf_section_spec *spec,
                         size_t *count)
{
    for (size_t k = 0; k < s->nsections; k++)
        if (s->sections[k].spec == spec) {
            if (count)
                *count = s->sections[k].count;
            return s->sections[k].values;
        }
    if (count)
        *count = 0;
    return NULL;
}
