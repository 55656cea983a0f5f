/* registry.c: the list of ball effects.  One line per effect. */
#include <string.h>

#include "ballfilm/effects.h"

extern const bf_effect_type bf_effect_gravity;
extern const bf_effect_type bf_effect_floor;
extern const bf_effect_type bf_effect_contact;
extern const bf_effect_type bf_effect_spring;
extern const bf_effect_type bf_effect_coupling;

static const bf_effect_type *const all[] = {
    &bf_effect_gravity,
    &bf_effect_floor,
    &bf_effect_contact,
    &bf_effect_spring,
    &bf_effect_coupling,
};

const bf_effect_type *const *bf_effect_types(size_t *n)
{
    *n = sizeof all / sizeof all[0];
    return all;
}

const bf_effect_type *bf_effect_find(const char *name)
{
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (!strcmp(all[k]->name, name))
            return all[k];
    return NULL;
}
