/* registry.c: the list of models.  One line per model. */
#include <string.h>

#include "ballfilm/model.h"

extern const bf_model_type bf_model_balls;
extern const bf_model_type bf_model_mac;
extern const bf_model_type bf_model_film;
extern const bf_model_type bf_model_coupled;
extern const bf_model_type bf_model_greenspan72;
extern const bf_model_type bf_model_greenspan73;

static const bf_model_type *const all[] = {
    &bf_model_balls,
    &bf_model_film,
    &bf_model_coupled,
    &bf_model_greenspan72,
    &bf_model_greenspan73,
    &bf_model_mac,
};

const bf_model_type *const *bf_model_types(size_t *n)
{
    *n = sizeof all / sizeof all[0];
    return all;
}

const bf_model_type *bf_model_find(const char *name)
{
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (!strcmp(all[k]->name, name))
            return all[k];
    return NULL;
}
