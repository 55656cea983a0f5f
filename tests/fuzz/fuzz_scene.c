/* fuzz_scene.c: libFuzzer entry point for the scene parser and the
 * validation behind it (see tests/fuzz_one.c).  Built and run by
 * `make fuzz` with clang -fsanitize=fuzzer,address,undefined. */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_one.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return bf_fuzz_one(data, size);
}
