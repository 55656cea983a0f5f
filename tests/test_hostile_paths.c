/* test_hostile_paths.c: the files a run creates, in directories shared
 * with people it does not trust (src/io/outpath.h).
 *
 * A link or a file planted at a name the program writes is refused and
 * its target left as it was; an output that is an input (through a link)
 * is refused; an output that cannot be replaced is refused before the
 * first step; a finished result survives an extension that is stopped or
 * killed; checkpoint targets of the C API are checked as outputs are. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "ballfilm/h5out.h"
#include "ballfilm/run.h"
#include "ballfilm/sim.h"
#include "io/outpath.h"
#include "testutil.h"

#define VICTIM "a file that belongs to someone else\n"

static int exists(const char *path)
{
    struct stat sb;
    return !lstat(path, &sb);
}

/* The file's text (malloc'd; "" when it cannot be read). */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *s = calloc(1, 1 << 16);
    ck_assert(s);
    if (f) {
        size_t n = fread(s, 1, (1 << 16) - 1, f);
        s[n] = '\0';
        fclose(f);
    }
    return s;
}

static void assert_victim_intact(const char *path)
{
    char *text = slurp(path);
    ck_assert_msg(!strcmp(text, VICTIM), "%s was written through a link",
                  path);
    free(text);
}

/* A victim file and a symbolic link to it at `at`. */
static const char *plant_link(const char *victim_name, const char *at)
{
    const char *victim = tu_write(victim_name, VICTIM);
    unlink(at);
    ck_assert_int_eq(symlink(victim, at), 0);
    return victim;
}

static void copy_file(const char *from, const char *to)
{
    int in = open(from, O_RDONLY), out = open(to, O_WRONLY | O_CREAT |
                                              O_TRUNC, 0644);
    ck_assert(in >= 0 && out >= 0);
    char buf[65536];
    ssize_t n;
    while ((n = read(in, buf, sizeof buf)) > 0)
        ck_assert(write(out, buf, (size_t)n) == n);
    close(in);
    close(out);
}

static const char *bin(void)
{
    const char *b = getenv("BALLFILM_BIN");
    return b && *b ? b : "bin/ballfilm";
}

/* bin/ballfilm with argv in the background, stdout and stderr dropped. */
static pid_t start(const char *const *argv)
{
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        dup2(fd, 1);
        dup2(fd, 2);
        size_t n = 0;
        while (argv[n])
            n++;
        char **a = calloc(n + 2, sizeof *a);
        a[0] = (char *)bin();
        for (size_t k = 0; k < n; k++)
            a[k + 1] = (char *)argv[k];
        execv(bin(), a);
        _exit(127);
    }
    return pid;
}

static off_t file_size(const char *path)
{
    struct stat sb;
    ck_assert(!stat(path, &sb));
    return sb.st_size;
}

/* ------------------------------------------------- links and planted files */

/* A link planted at OUT.h5.part (today's name of the file a run writes)
 * is refused, its target untouched. */
START_TEST(link_at_part_refused)
{
    char out[600], part[700];
    snprintf(out, sizeof out, "%s", tu_tmp("lpart.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    const char *victim = plant_link("lpart_victim", part);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    out, "-q", NULL);
    ck_assert_msg(rc == 5, "status %d: %s", rc, err);
    ck_assert_msg(strstr(err, part) && strstr(err, "symbolic link"), "%s",
                  err);
    assert_victim_intact(victim);
    ck_assert(!exists(out));
    free(err);
}
END_TEST

/* A hard link, or another user's file, at OUT.h5.part: refused as well
 * (writing it would change the file under its other name). */
START_TEST(planted_file_at_part_refused)
{
    char out[600], part[700];
    snprintf(out, sizeof out, "%s", tu_tmp("hpart.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    const char *victim = tu_write("hpart_victim", VICTIM);
    ck_assert_int_eq(link(victim, part), 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    out, "-q", NULL);
    ck_assert_msg(rc == 5 && strstr(err, "hard link"), "status %d: %s", rc,
                  err);
    assert_victim_intact(victim);
    free(err);
    if (geteuid() != 0)
        return; /* only root can give a file away */
    unlink(part);
    copy_file(victim, part);
    ck_assert_int_eq(chown(part, 65534, 65534), 0);
    rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o", out,
                "-q", NULL);
    ck_assert_msg(rc == 5 && strstr(err, "another user"), "status %d: %s",
                  rc, err);
    assert_victim_intact(part);
    free(err);
}
END_TEST

/* A link at the checkpoint's temporary OUT.h5.ckpt.tmp is refused, at
 * the start, the target untouched. */
START_TEST(link_at_checkpoint_tmp_refused)
{
    char out[600], tmp[700];
    snprintf(out, sizeof out, "%s", tu_tmp("lckpt.h5"));
    snprintf(tmp, sizeof tmp, "%s.ckpt.tmp", out);
    const char *victim = plant_link("lckpt_victim", tmp);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    out, "-q", "--set", "scene.checkpoint_every=100", NULL);
    ck_assert_msg(rc == 5 && strstr(err, "symbolic link"), "status %d: %s",
                  rc, err);
    ck_assert_msg(!exists(out) && !strstr(err, "step"),
                  "refused only once the run had begun: %s", err);
    assert_victim_intact(victim);
    free(err);
}
END_TEST

/* The files of a sweep (its summary, a case's record) are never written
 * through a link either. */
START_TEST(sweep_files_not_written_through_links)
{
    char dir[600], summary[700], done[700];
    snprintf(dir, sizeof dir, "%s", tu_tmp("lsweep"));
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    snprintf(summary, sizeof summary, "%s/summary.csv", dir);
    snprintf(done, sizeof done, "%s/case_00001.done.tmp", dir);
    const char *v1 = plant_link("lsweep_victim1", summary);
    const char *v2 = plant_link("lsweep_victim2", done);
    int rc = tu_run(NULL, NULL, "sweep", tu_repo("runs/harmonic.ini"),
                    "--vary", "spring.stiffness=1:2:2", "-o", dir, NULL);
    ck_assert_int_ne(rc, 0);
    assert_victim_intact(v1);
    assert_victim_intact(v2);
}
END_TEST

/* A sweep's directory planted as a link to another directory of the same
 * user (whose files the sweep would write over) is refused, and nothing
 * is written into the link's target. */
START_TEST(sweep_directory_link_refused)
{
    char target[600], dir[600], summary[700];
    snprintf(target, sizeof target, "%s", tu_tmp("lsweepdir_target"));
    snprintf(dir, sizeof dir, "%s", tu_tmp("lsweepdir"));
    ck_assert_int_eq(mkdir(target, 0777), 0);
    ck_assert_int_eq(symlink(target, dir), 0);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "sweep", tu_repo("runs/harmonic.ini"),
                    "--vary", "spring.stiffness=1:2:2", "-o", dir, NULL);
    ck_assert_msg(rc == 5, "status %d: %s", rc, err);
    ck_assert_msg(err && strstr(err, "symbolic link"), "%s", err);
    snprintf(summary, sizeof summary, "%s/sweep.txt", target);
    struct stat sb;
    ck_assert_msg(lstat(summary, &sb) != 0, "wrote %s", summary);
    free(err);
}
END_TEST

/* The movie of `animate` replaces a link at its name instead of writing
 * through it. */
START_TEST(movie_not_written_through_a_link)
{
    if (system("/usr/bin/python3 -c 'import matplotlib, h5py' 2>/dev/null")) {
        fprintf(stderr, "movie_not_written_through_a_link: no matplotlib, "
                        "not checked\n");
        return;
    }
    char out[600], movie[700];
    snprintf(out, sizeof out, "%s", tu_tmp("lmovie.h5"));
    snprintf(movie, sizeof movie, "%s", tu_tmp("lmovie.gif"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", NULL),
                     0);
    const char *victim = plant_link("lmovie_victim", movie);
    char *err = NULL;
    int rc = tu_run(NULL, &err, "animate", out, "-o", movie, "-q",
                    "--frames", "2", "--size", "64x48", NULL);
    ck_assert_msg(rc == 0, "status %d: %s", rc, err);
    assert_victim_intact(victim);
    struct stat sb;
    ck_assert(!lstat(movie, &sb) && S_ISREG(sb.st_mode) && sb.st_size > 0);
    free(err);
}
END_TEST

/* ------------------------------------------------------ the result's name */

/* -o a link to the scene file, or a second (hard) name of it, is the
 * scene: refused with status 2. */
START_TEST(output_linked_to_the_scene_refused)
{
    const char *scene = tu_write("lscene.ini", "");
    copy_file(tu_repo("runs/harmonic.ini"), scene);
    char *before = slurp(scene);
    char sym[600], hard[600];
    snprintf(sym, sizeof sym, "%s", tu_tmp("lscene_sym.h5"));
    snprintf(hard, sizeof hard, "%s", tu_tmp("lscene_hard.h5"));
    ck_assert_int_eq(symlink(scene, sym), 0);
    ck_assert_int_eq(link(scene, hard), 0);
    const char *outs[2] = {sym, hard};
    for (int k = 0; k < 2; k++) {
        char *err = NULL;
        int rc = tu_run(NULL, &err, "run", scene, "-o", outs[k], "-q", NULL);
        ck_assert_msg(rc == 2 && strstr(err, "the scene file"),
                      "-o %s: status %d: %s", outs[k], rc, err);
        free(err);
    }
    char *after = slurp(scene);
    ck_assert_str_eq(before, after);
    free(before);
    free(after);
}
END_TEST

/* -o an existing directory: refused at the start with status 2, nothing
 * created (the rename at the end could only fail). */
START_TEST(output_directory_refused_at_the_start)
{
    char dir[600], part[700];
    snprintf(dir, sizeof dir, "%s", tu_tmp("odir.h5"));
    snprintf(part, sizeof part, "%s.part", dir);
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    char *out = NULL, *err = NULL;
    int rc = tu_run(&out, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    dir, "-q", NULL);
    ck_assert_msg(rc == 2 && strstr(err, dir) && strstr(err, "directory"),
                  "status %d: %s", rc, err);
    ck_assert_msg(!exists(part), "%s was created", part);
    ck_assert_msg(!strstr(out, "steps:"), "the run ran: %s", out);
    free(out);
    free(err);
}
END_TEST

/* Another user's file in a sticky directory cannot be replaced: refused
 * at the start with status 5, no .part left.  The run is made as user
 * nobody (a forked child drops root's privileges with setuid) against a
 * file of root's in a directory of mode 1777. */
START_TEST(other_users_file_in_a_sticky_directory_refused)
{
    if (geteuid() != 0) {
        fprintf(stderr, "other_users_file_in_a_sticky_directory_refused: "
                        "needs root to make a second user's run; the "
                        "decision is checked by replace_decision\n");
        return;
    }
    char dir[] = "/tmp/bf_sticky_XXXXXX";
    ck_assert(mkdtemp(dir));
    ck_assert_int_eq(chmod(dir, 01777), 0);
    char scene[600], res[600], part[700], errf[600];
    snprintf(scene, sizeof scene, "%s/s.ini", dir);
    snprintf(res, sizeof res, "%s/res.h5", dir);
    snprintf(part, sizeof part, "%s.part", res);
    snprintf(errf, sizeof errf, "%s/err.txt", dir);
    copy_file(tu_repo("runs/harmonic.ini"), scene);
    copy_file(scene, res); /* root's file */
    int fe = open(errf, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ck_assert(fe >= 0);
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        int fo = open("/dev/null", O_WRONLY);
        dup2(fo, 1);
        dup2(fe, 2);
        if (setgid(65534) || setuid(65534))
            _exit(126);
        execl(bin(), bin(), "run", scene, "-o", res, "-q", (char *)NULL);
        _exit(127);
    }
    close(fe);
    int status;
    ck_assert(waitpid(pid, &status, 0) == pid);
    char *err = slurp(errf);
    int rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const int had_part = exists(part);
    unlink(part);
    unlink(res);
    unlink(scene);
    unlink(errf);
    rmdir(dir);
    ck_assert_msg(rc == 5 && strstr(err, "res.h5") &&
                      strstr(err, "another user"),
                  "status %d: %s", rc, err);
    ck_assert_msg(!had_part, "the run created its .part and ran");
    free(err);
}
END_TEST

/* The decision itself, on crafted file states: what root may replace, a
 * user's own file, another's file in a sticky or a plain directory, an
 * unwritable directory, a directory named as the output. */
START_TEST(replace_decision)
{
    struct stat dir = {0}, file = {0}, sub = {0};
    dir.st_mode = S_IFDIR | 01777;
    dir.st_uid = 0;
    file.st_mode = S_IFREG | 0644;
    file.st_uid = 1000;
    file.st_nlink = 1;
    sub.st_mode = S_IFDIR | 0755;
    bf_status st;
    ck_assert(bf_path_replace_refusal(&file, &dir, 1001, 1, &st));
    ck_assert_int_eq(st, BF_EIO);
    ck_assert(!bf_path_replace_refusal(&file, &dir, 1000, 1, &st));
    ck_assert(!bf_path_replace_refusal(&file, &dir, 0, 1, &st));
    ck_assert(!bf_path_replace_refusal(NULL, &dir, 1001, 1, &st));
    dir.st_uid = 1001; /* the directory's owner may */
    ck_assert(!bf_path_replace_refusal(&file, &dir, 1001, 1, &st));
    dir.st_uid = 0;
    dir.st_mode = S_IFDIR | 0777; /* not sticky: anyone who may write */
    ck_assert(!bf_path_replace_refusal(&file, &dir, 1001, 1, &st));
    ck_assert(bf_path_replace_refusal(&file, &dir, 1001, 0, &st));
    ck_assert_int_eq(st, BF_EIO);
    ck_assert(bf_path_replace_refusal(&sub, &dir, 1000, 1, &st));
    ck_assert_int_eq(st, BF_EINPUT);
    /* files written in place */
    ck_assert(!bf_path_own_refusal(&file, 1000));
    ck_assert(bf_path_own_refusal(&file, 1001));
    file.st_nlink = 2;
    ck_assert(bf_path_own_refusal(&file, 1000));
}
END_TEST

/* --------------------------------------------------------------- extension */

static const char *attr_status(const char *file)
{
    static char buf[1100];
    char *v = NULL;
    bf_err e = {0};
    if (bf_h5_read_attr_str(file, "/", "status", &v, &e))
        snprintf(buf, sizeof buf, "(unreadable: %s)", e.msg);
    else
        snprintf(buf, sizeof buf, "%s", v);
    free(v);
    return buf;
}

/* A finished run extended (--restart --set scene.t_end=...) and stopped
 * in the middle keeps OUT.h5 as the finished result; continued, the
 * extension ends with the datasets and counters of a run made at once. */
START_TEST(stopped_extension_keeps_the_result)
{
    char out[600], ref[600], full[600];
    snprintf(out, sizeof out, "%s", tu_tmp("ext.h5"));
    snprintf(ref, sizeof ref, "%s", tu_tmp("ext_ref.h5"));
    snprintf(full, sizeof full, "%s", tu_tmp("ext_full.h5"));
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", "--set",
                            "scene.checkpoint_every=100", "--keep-checkpoint",
                            NULL),
                     0);
    copy_file(out, ref);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", out, "-q",
                            "--set", "scene.t_end=20", "--stop-after", "300",
                            NULL),
                     6);
    ck_assert_msg(exists(out), "%s is gone", out);
    ck_assert_str_eq(attr_status(out), "ok");
    tu_same_datasets(ref, out);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", "--restart", out, "-q",
                            "--set", "scene.t_end=20", NULL),
                     0);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", full, "-q", "--set",
                            "scene.checkpoint_every=100", "--set",
                            "scene.t_end=20", NULL),
                     0);
    tu_same_datasets(full, out);
    tu_same_counters(full, out);
}
END_TEST

/* The same extension killed with SIGKILL while it writes: OUT.h5 is still
 * the finished result. */
START_TEST(killed_extension_keeps_the_result)
{
    char out[600], ref[600], part[700];
    snprintf(out, sizeof out, "%s", tu_tmp("kext.h5"));
    snprintf(ref, sizeof ref, "%s", tu_tmp("kext_ref.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    ck_assert_int_eq(tu_run(NULL, NULL, "run", tu_repo("runs/harmonic.ini"),
                            "-o", out, "-q", "--set",
                            "scene.checkpoint_every=100", "--keep-checkpoint",
                            NULL),
                     0);
    copy_file(out, ref);
    const char *argv[] = {"run", "--restart", out, "-q", "--set",
                          "scene.t_end=1e7", "--set",
                          "scene.flush_seconds=0.01", NULL};
    pid_t pid = start(argv);
    tu_wait_for_file(part, (long)file_size(ref) + 4096);
    kill(pid, SIGKILL);
    int status;
    ck_assert(waitpid(pid, &status, 0) == pid);
    ck_assert(WIFSIGNALED(status));
    ck_assert_msg(exists(out), "%s is gone", out);
    ck_assert_str_eq(attr_status(out), "ok");
    tu_same_datasets(ref, out);
}
END_TEST

/* --keep-checkpoint without checkpoint_every would keep nothing: refused,
 * naming both, before anything is written. */
START_TEST(keep_checkpoint_without_interval_refused)
{
    char out[600];
    snprintf(out, sizeof out, "%s", tu_tmp("keep.h5"));
    char *err = NULL;
    int rc = tu_run(NULL, &err, "run", tu_repo("runs/harmonic.ini"), "-o",
                    out, "-q", "--keep-checkpoint", NULL);
    ck_assert_msg(rc == 2 && strstr(err, "--keep-checkpoint") &&
                      strstr(err, "checkpoint_every"),
                  "status %d: %s", rc, err);
    ck_assert(!exists(out));
    free(err);
}
END_TEST

/* ------------------------------------------------------------------ C API */

/* A run of scene (a file) writing out, for the checkpoint targets. */
static bf_run *api_run(const char *scene, const char *out)
{
    bf_sim_opts opts = {0};
    bf_err err = {0};
    bf_run *run = NULL;
    ck_assert_msg(!bf_run_load(&run, bf_catalog_builtin(), scene, NULL, 0,
                               &opts, &err),
                  "%s", err.msg);
    ck_assert_msg(!bf_run_open_output(run, out, &err), "%s", err.msg);
    return run;
}

/* bf_sim_checkpoint_write onto the run's own .part, its output or its
 * scene file is refused (BF_EINPUT, a message), and the run's file is
 * still its result. */
START_TEST(checkpoint_onto_the_runs_own_files_refused)
{
    const char *scene = tu_write("api_scene.ini", "");
    copy_file(tu_repo("runs/harmonic.ini"), scene);
    char *before = slurp(scene);
    char out[600], part[700];
    snprintf(out, sizeof out, "%s", tu_tmp("api.h5"));
    snprintf(part, sizeof part, "%s.part", out);
    bf_run *run = api_run(scene, out);
    bf_sim *sim = bf_run_sim(run);
    const char *targets[3] = {part, scene, out};
    for (int k = 0; k < 3; k++) {
        bf_err err = {0};
        bf_status st = bf_sim_checkpoint_write(sim, targets[k], &err);
        ck_assert_msg(st == BF_EINPUT && err.msg[0],
                      "checkpoint onto %s: status %d (%s)", targets[k], st,
                      err.msg);
    }
    bf_err err = {0};
    ck_assert_msg(!bf_sim_run(sim, &err), "%s", err.msg);
    bf_err cerr = {0};
    ck_assert_msg(!bf_sim_close_output(sim, BF_OK, &err, &cerr), "%s",
                  cerr.msg);
    bf_run_free(run);
    ck_assert_str_eq(attr_status(out), "ok");
    char *after = slurp(scene);
    ck_assert_str_eq(before, after);
    free(before);
    free(after);
}
END_TEST

Suite *suite_hostile_paths(void)
{
    Suite *s = suite_create("hostile_paths");
    TCase *tc = tu_tcase("links");
    tcase_add_test(tc, link_at_part_refused);
    tcase_add_test(tc, planted_file_at_part_refused);
    tcase_add_test(tc, link_at_checkpoint_tmp_refused);
    tcase_add_test(tc, sweep_files_not_written_through_links);
    tcase_add_test(tc, sweep_directory_link_refused);
    tcase_add_test(tc, movie_not_written_through_a_link);
    suite_add_tcase(s, tc);
    tc = tu_tcase("result_name");
    tcase_add_test(tc, output_linked_to_the_scene_refused);
    tcase_add_test(tc, output_directory_refused_at_the_start);
    tcase_add_test(tc, other_users_file_in_a_sticky_directory_refused);
    tcase_add_test(tc, replace_decision);
    suite_add_tcase(s, tc);
    tc = tu_tcase("extension");
    tcase_add_test(tc, stopped_extension_keeps_the_result);
    tcase_add_test(tc, killed_extension_keeps_the_result);
    tcase_add_test(tc, keep_checkpoint_without_interval_refused);
    suite_add_tcase(s, tc);
    tc = tu_tcase("c_api");
    tcase_add_test(tc, checkpoint_onto_the_runs_own_files_refused);
    suite_add_tcase(s, tc);
    return s;
}
