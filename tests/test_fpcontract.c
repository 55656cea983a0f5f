/* test_fpcontract.c: the build must not let the compiler fuse multiply-adds
 * (-ffp-contract=off), or results would depend on the compiler and the CPU.
 * We compile tests/fpcontract/probe.c with the project's own flags plus
 * -mfma (so fusing is possible) and check that a*b + c is evaluated as
 * written; a second build with -ffp-contract=fast must give the fused
 * result, which shows the probe can tell the two apart. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

static void probe(const char *extra, char *out, size_t cap)
{
    const char *cc = getenv("BALLFILM_CC"), *fl = getenv("BALLFILM_CFLAGS");
    ck_assert_msg(cc && fl, "BALLFILM_CC/BALLFILM_CFLAGS not set (run via make)");
    char exe[512], cmd[2048];
    snprintf(exe, sizeof exe, "%s", tu_tmp("probe"));
    snprintf(cmd, sizeof cmd, "%s %s -mfma %s -o '%s' '%s' && '%s'", cc, fl,
             extra, exe, tu_repo("tests/fpcontract/probe.c"), exe);
    FILE *p = popen(cmd, "r");
    ck_assert(p != NULL);
    out[0] = '\0';
    ck_assert_msg(fgets(out, (int)cap, p) != NULL, "probe failed: %s", cmd);
    ck_assert_int_eq(pclose(p), 0);
    out[strcspn(out, "\n")] = '\0';
}

START_TEST(no_fused_multiply_add)
{
    const char *fl = getenv("BALLFILM_CFLAGS");
    ck_assert_msg(fl && strstr(fl, "-ffp-contract=off"),
                  "project flags lack -ffp-contract=off: %s", fl ? fl : "");
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("fma")) {
        fprintf(stderr, "note: CPU without FMA; only the flags were checked\n");
        return;
    }
    char ours[64], fused[64];
    probe("", ours, sizeof ours);
    probe("-ffp-contract=fast", fused, sizeof fused);
    ck_assert_msg(!strcmp(fused, "-0x1p-60"),
                  "the probe cannot detect fusion (got %s)", fused);
    ck_assert_msg(!strcmp(ours, "0x0p+0"),
                  "project flags fused a*b+c (got %s)", ours);
}
END_TEST

Suite *suite_fpcontract(void)
{
    Suite *s = suite_create("fpcontract");
    TCase *tc = tu_tcase("flags");
    tcase_add_test(tc, no_fused_multiply_add);
    suite_add_tcase(s, tc);
    return s;
}
