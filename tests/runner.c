/* runner.c: runs every suite listed in the generated suites.inc (one per
 * tests/test_NAME.c) and prints Check's summary line. */
#include <check.h>
#include <stdlib.h>

#define BF_SUITE(name) Suite *suite_##name(void);
#include "suites.inc"
#undef BF_SUITE

int main(void)
{
    SRunner *sr = srunner_create(NULL);
#define BF_SUITE(name) srunner_add_suite(sr, suite_##name());
#include "suites.inc"
#undef BF_SUITE
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
