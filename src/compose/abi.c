/* abi.c: the sizes of the public structs by name (run.h, bf_sizeof), so
 * that a foreign-function interface (the Python package's ctypes
 * mirrors) can check its layout against the library it loaded. */
#include <string.h>

#include "ballfilm/converge.h"
#include "ballfilm/run.h"
#include "ballfilm/sweep.h"

#define SIZE(T) {#T, sizeof(T)}

static const struct {
    const char *name;
    size_t size;
} sizes[] = {
    SIZE(bf_err),          SIZE(bf_sim_opts),      SIZE(bf_state_var),
    SIZE(bf_counters),     SIZE(bf_results),       SIZE(bf_sweep),
    SIZE(bf_sweep_axis),   SIZE(bf_sweep_row),     SIZE(bf_converge_opts),
    SIZE(bf_converge_row), SIZE(bf_converge_result), SIZE(bf_h5_dataset),
    SIZE(bf_effect_type),  SIZE(bf_integrator_type), SIZE(bf_balls),
    SIZE(bf_converge_group),
};

size_t bf_sizeof(const char *name)
{
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++)
        if (!strcmp(sizes[k].name, name))
            return sizes[k].size;
    return 0;
}
