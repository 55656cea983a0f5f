/* test_scenes.c: every scene in runs/ — whatever its model — starts, is
 * deterministic (two runs give the same bits), and survives interruption
 * (stopped at an odd step and continued with --restart, it gives the same
 * bits and counters as the uninterrupted run).  Each scene runs 40 steps with a row every
 * 10 steps, so the suite stays short while new scenes are covered
 * automatically. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

/* exit status of a run stopped by --stop-after (6), or 0 if it finished */
static void expect_ok_or_stopped(int rc, const char *what, const char *scene,
                                 char *err)
{
    ck_assert_msg(rc == 0 || rc == 6, "%s %s: exit %d\n%s", what, scene, rc,
                  err ? err : "");
}

static void check_scene(const char *name)
{
    char scene[512], a[512], c[512], b[512], tag[300];
    snprintf(scene, sizeof scene, "%s", tu_repo("runs"));
    strncat(scene, "/", sizeof scene - strlen(scene) - 1);
    strncat(scene, name, sizeof scene - strlen(scene) - 1);
    snprintf(tag, sizeof tag, "%.200s", name);
    snprintf(a, sizeof a, "%s.A.h5", tu_tmp(tag));
    snprintf(c, sizeof c, "%s.C.h5", tu_tmp(tag));
    snprintf(b, sizeof b, "%s.B.h5", tu_tmp(tag));
    const char *common[] = {"-q", "--set", "scene.output_every=10", NULL};
    char *err = NULL;
    int rc;
#define RUN(out, stop)                                                         \
    rc = tu_run(NULL, &err, "run", scene, "-o", out, common[0], common[1],     \
                common[2], "--stop-after", stop, NULL)
    RUN(a, "40");
    expect_ok_or_stopped(rc, "first run of", name, err);
    free(err);
    RUN(c, "40");
    expect_ok_or_stopped(rc, "second run of", name, err);
    free(err);
    tu_same_datasets(a, c);
    RUN(b, "17");
    expect_ok_or_stopped(rc, "interrupted run of", name, err);
    free(err);
#undef RUN
    if (rc == 6) {
        rc = tu_run(NULL, &err, "run", "--restart", b, "-q", "--stop-after",
                    "23", NULL);
        expect_ok_or_stopped(rc, "restart of", name, err);
        free(err);
    }
    tu_same_datasets(a, b);
    /* a restart recomputes what it does not store: never counted twice */
    tu_same_counters(a, b);
}

START_TEST(every_scene_deterministic_and_restartable)
{
    DIR *d = opendir(tu_repo("runs"));
    ck_assert(d != NULL);
    struct dirent *e;
    int n = 0;
    char names[256][256];
    while ((e = readdir(d)) && n < 256) {
        size_t len = strlen(e->d_name);
        if (len > 4 && !strcmp(e->d_name + len - 4, ".ini"))
            snprintf(names[n++], 256, "%s", e->d_name);
    }
    closedir(d);
    ck_assert_msg(n >= 4, "only %d scenes in runs/", n);
    for (int k = 0; k < n; k++)
        check_scene(names[k]);
}
END_TEST

Suite *suite_scenes(void)
{
    Suite *s = suite_create("scenes");
    TCase *tc = tu_tcase("runs");
    tcase_add_test(tc, every_scene_deterministic_and_restartable);
    suite_add_tcase(s, tc);
    return s;
}
