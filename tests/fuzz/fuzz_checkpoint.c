/* fuzz_checkpoint.c: libFuzzer entry point for checkpoints (see
 * tests/fuzz_ckpt.h): byte 0 picks the model, the rest damages or edits
 * a real checkpoint of it, and the restart must refuse it cleanly or
 * continue to a status with a message.  Built and run by `make fuzz` with
 * clang -fsanitize=fuzzer,address,undefined; BALLFILM_ROOT names the
 * repository (runs/). */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_ckpt.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_MODELS = 16 };
static bf_fuzz_ckpt *model[MAX_MODELS];
static const char *name[MAX_MODELS];
static long steps[MAX_MODELS];
static size_t nmodels;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    static char dir[] = "/tmp/ballfilm-fuzz-ckpt-XXXXXX";
    const char *root = getenv("BALLFILM_ROOT");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        abort();
    }
    nmodels = bf_fuzz_ckpt_nmodels();
    if (nmodels > MAX_MODELS)
        nmodels = MAX_MODELS;
    for (size_t k = 0; k < nmodels; k++) {
        char why[2048];
        model[k] = bf_fuzz_ckpt_model(root ? root : ".", dir, k, &name[k],
                                      &steps[k], why, sizeof why);
        if (!model[k]) {
            fprintf(stderr, "fuzz_checkpoint: %s\n", why);
            abort();
        }
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    size_t k = data[0] % nmodels;
    bf_fuzz_outcome o;
    char why[2048];
    if (!bf_fuzz_ckpt_input(model[k], data + 1, size - 1, steps[k], &o, why,
                            sizeof why)) {
        fprintf(stderr, "fuzz_checkpoint (%s): %s\n", name[k], why);
        abort();
    }
    return 0;
}
