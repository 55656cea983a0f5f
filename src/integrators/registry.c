/* registry.c: the list of integrators.  One line per integrator. */
#include <string.h>

#include "ballfilm/integrator.h"

extern const bf_integrator_type bf_integrator_verlet;
extern const bf_integrator_type bf_integrator_mv2m;
extern const bf_integrator_type bf_integrator_alpha;
extern const bf_integrator_type bf_integrator_rk3;
extern const bf_integrator_type bf_integrator_rk4;
extern const bf_integrator_type bf_integrator_impmid;
extern const bf_integrator_type bf_integrator_arkode;
extern const bf_integrator_type bf_integrator_arkode_fixed;

static const bf_integrator_type *const all[] = {
    &bf_integrator_verlet,
    &bf_integrator_mv2m,
    &bf_integrator_alpha,
    &bf_integrator_rk3,
    &bf_integrator_rk4,
    &bf_integrator_impmid,
    &bf_integrator_arkode,
    &bf_integrator_arkode_fixed,
};

const bf_integrator_type *const *bf_integrator_types(size_t *n)
{
    *n = sizeof all / sizeof all[0];
    return all;
}

const bf_integrator_type *bf_integrator_find(const char *name)
{
    for (size_t k = 0; k < sizeof all / sizeof all[0]; k++)
        if (!strcmp(all[k]->name, name))
            return all[k];
    return NULL;
}
