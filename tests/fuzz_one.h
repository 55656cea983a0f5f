/* fuzz_one.h: the fuzz case shared by `make fuzz` and the test suite. */
#ifndef BALLFILM_FUZZ_ONE_H
#define BALLFILM_FUZZ_ONE_H

#include <stddef.h>

int bf_fuzz_one(const unsigned char *data, size_t size);

#endif
