/* fuzz_one.c: one fuzz case — a scene text goes through everything that
 * validates input: INI parsing, "#set section.key=value" lines applied as
 * command-line overrides, resolution against the parameter tables, model
 * creation (physical validation) and a few steps without output.  Used by
 * the libFuzzer target (tests/fuzz/fuzz_scene.c, `make fuzz`) and by the
 * regression test over tests/fuzz/regress/ (tests/test_fuzz.c). */
#include "fuzz_one.h"

#include <stdlib.h>
#include <string.h>

#include "ballfilm/scene.h"
#include "ballfilm/sim.h"
#include "ballfilm/run.h"

int bf_fuzz_one(const unsigned char *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    bf_scene *sc = NULL;
    bf_err err = {0};
    if (bf_scene_load_string(&sc, "fuzz.ini", text, &err) == BF_OK) {
        int ok = 1;
        for (char *line = text; ok && line && *line;) {
            char *nl = strchr(line, '\n');
            if (nl)
                *nl = '\0';
            if (!strncmp(line, "#set ", 5))
                ok = bf_scene_set(sc, line + 5, "--set", &err) == BF_OK;
            line = nl ? nl + 1 : NULL;
        }
        if (ok && bf_catalog_resolve(bf_catalog_builtin(), sc, &err) == BF_OK) {
            bf_sim *sim = NULL;
            bf_sim_opts opts = {.progress = 0, .stop_flag = NULL,
                                .stop_after = 5};
            if (bf_sim_from_scene(&sim, bf_catalog_builtin(), sc, &opts, &err) == BF_OK) {
                bf_sim_run(sim, &err);
                bf_sim_free(sim);
            }
        }
        bf_scene_free(sc);
    }
    free(text);
    return 0;
}
