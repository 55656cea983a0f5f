/* test_fuzz.c: every input the fuzzer ever found troublesome (and the seed
 * corpus) goes through the fuzz case again: no crash, no hang, no sanitizer
 * report (under `make check`). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_one.h"
#include "testutil.h"

static int run_dir(const char *rel)
{
    DIR *d = opendir(tu_repo(rel));
    if (!d)
        return 0;
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", tu_repo(rel), e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        unsigned char buf[1 << 16];
        size_t len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        bf_fuzz_one(buf, len);
        n++;
    }
    closedir(d);
    return n;
}

START_TEST(regressions_and_corpus)
{
    int n = run_dir("tests/fuzz/regress");
    n += run_dir("tests/fuzz/corpus");
    ck_assert_msg(n > 0, "no fuzz inputs found");
}
END_TEST

Suite *suite_fuzz(void)
{
    Suite *s = suite_create("fuzz");
    TCase *tc = tu_tcase("inputs");
    tcase_add_test(tc, regressions_and_corpus);
    suite_add_tcase(s, tc);
    return s;
}
