/* test_fuzz.c: every input the fuzzers ever found troublesome (and the
 * seed corpora) goes through the fuzz cases again: no crash, no hang, no
 * sanitizer report (under `make check`).  The scene fuzz case is
 * tests/fuzz_one.c, the checkpoint one tests/fuzz_ckpt.c; here the
 * checkpoint case also runs a bounded, deterministic set of damages and
 * edits of a real checkpoint of every model (`make fuzz` runs it at
 * random, for longer). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_ckpt.h"
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

/* ---- checkpoints ---- */

static unsigned lcg(unsigned *s) { return *s = *s * 1103515245u + 12345u; }

/* One input, which must be allowed (fuzz_ckpt.h); 1 if it was refused. */
static int ck_case(bf_fuzz_ckpt *fc, const char *scene, long steps,
                   const unsigned char *in, size_t n, const char *what,
                   int *refused, int *continued)
{
    bf_fuzz_outcome o;
    char why[2048];
    int ok = bf_fuzz_ckpt_input(fc, in, n, steps, &o, why, sizeof why);
    ck_assert_msg(ok, "%s, %s: %s", scene, what, why);
    *refused += !o.restarted;
    *continued += o.restarted;
    return !o.restarted;
}

/* Damage (the file cut at 32 places, 32 bytes with a bit flipped): always
 * refused with a message (the seal covers every byte after its own block
 * of 512 bytes, whose unused padding alone may change and leave the run
 * as the uninterrupted one; without the seal a flip in HDF5's metadata
 * could pass unseen or crash the reader); edits of every entry, sealed
 * again: a special value in its first and in its last element (counts
 * and indices at their limits, off by one, non-finite reals), and one of
 * dropped, one shorter, one longer, another kind, empty (in turn from
 * entry to entry: each kind of edit meets every sort of entry, in a
 * third of the cases that all of them for every entry would take; `make
 * fuzz` tries them all at random): refused with a message or continued
 * to a status with a message, never a crash, a hang, an allocation by a
 * stored count or an I/O error.  Seconds per model. */
START_TEST(checkpoint_damage_and_edits)
{
    for (size_t m = 0; m < bf_fuzz_ckpt_nmodels(); m++) {
        char why[2048];
        long steps;
        const char *nm;
        bf_fuzz_ckpt *fc = bf_fuzz_ckpt_model(tu_repo(""), tu_tmpdir(), m,
                                              &nm, &steps, why, sizeof why);
        ck_assert_msg(fc != NULL, "%s", why);
        int refused = 0, continued = 0;
        unsigned char in[8] = {0};
        ck_case(fc, nm, steps, in, 1, "the real checkpoint", &refused,
                &continued);
        size_t size;
        bf_fuzz_ckpt_file(fc, &size);
        unsigned seed = 17;
        for (int j = 1; j <= 32; j++) {
            size_t at = (size_t)j * size / 33;
            unsigned char cut[5] = {0, (unsigned char)at,
                                    (unsigned char)(at >> 8),
                                    (unsigned char)(at >> 16), 0};
            ck_assert_msg(ck_case(fc, nm, steps, cut, 5, "cut short",
                                  &refused, &continued),
                          "%s: the file cut at byte %zu was accepted", nm, at);
            size_t flip = lcg(&seed) % size;
            unsigned char bit[5] = {0, (unsigned char)flip,
                                    (unsigned char)(flip >> 8),
                                    (unsigned char)(flip >> 16),
                                    (unsigned char)(1u << (lcg(&seed) % 8))};
            int no = ck_case(fc, nm, steps, bit, 5, "a bit flipped",
                             &refused, &continued);
            ck_assert_msg(no || flip < 512,
                          "%s: a bit flipped at byte %zu was accepted", nm,
                          flip);
        }
        size_t ne = bf_fuzz_ckpt_entries(fc);
        for (size_t k = 0; k < ne; k++) {
            /* {operation, element, special value} */
            const unsigned ops[][3] = {{0, 0, 0},
                                       {0, 0xffff, 5},
                                       {1 + (unsigned)k % 5, 0, 0}};
            for (size_t q = 0; q < sizeof ops / sizeof *ops; q++) {
                unsigned v = ops[q][2] + (unsigned)k;
                unsigned char e[7] = {1,
                                      (unsigned char)k,
                                      (unsigned char)(k >> 8),
                                      (unsigned char)ops[q][1],
                                      (unsigned char)(ops[q][1] >> 8),
                                      (unsigned char)ops[q][0],
                                      (unsigned char)v};
                char what[64];
                snprintf(what, sizeof what, "entry %zu, edit %u", k,
                         ops[q][0]);
                ck_case(fc, nm, steps, e, 7, what, &refused, &continued);
            }
        }
        fprintf(stderr, "checkpoint fuzz %s: %zu entries, %d cases refused, "
                        "%d continued\n",
                nm, ne, refused, continued);
        bf_fuzz_ckpt_free(fc);
    }
}
END_TEST

/* Every input kept under tests/fuzz/ckpt_regress/ (what `make fuzz` once
 * found) and the seed corpus tests/fuzz/ckpt_corpus/, in the fuzzer's
 * format (byte 0: the model, then bf_fuzz_ckpt_input's input). */
START_TEST(checkpoint_regressions_and_corpus)
{
    size_t nm = bf_fuzz_ckpt_nmodels();
    bf_fuzz_ckpt *fc[16] = {0};
    long steps[16];
    const char *names[16];
    int n = 0;
    static const char *const dirs[] = {"tests/fuzz/ckpt_regress",
                                       "tests/fuzz/ckpt_corpus"};
    for (int d = 0; d < 2; d++) {
        DIR *dir = opendir(tu_repo(dirs[d]));
        struct dirent *e;
        while (dir && (e = readdir(dir))) {
            if (e->d_name[0] == '.')
                continue;
            char path[1024], why[2048];
            snprintf(path, sizeof path, "%s/%s", tu_repo(dirs[d]), e->d_name);
            FILE *f = fopen(path, "rb");
            unsigned char buf[1 << 16];
            size_t len = f ? fread(buf, 1, sizeof buf, f) : 0;
            if (f)
                fclose(f);
            if (len < 2)
                continue;
            size_t m = buf[0] % nm;
            if (!fc[m])
                fc[m] = bf_fuzz_ckpt_model(tu_repo(""), tu_tmpdir(), m,
                                           &names[m], &steps[m], why,
                                           sizeof why);
            ck_assert_msg(fc[m] != NULL, "%s", why);
            bf_fuzz_outcome o;
            ck_assert_msg(bf_fuzz_ckpt_input(fc[m], buf + 1, len - 1, steps[m],
                                             &o, why, sizeof why),
                          "%s (%s): %s", path, names[m], why);
            n++;
        }
        if (dir)
            closedir(dir);
    }
    for (size_t m = 0; m < nm; m++)
        bf_fuzz_ckpt_free(fc[m]);
    ck_assert_msg(n > 0, "no checkpoint fuzz inputs found");
}
END_TEST

Suite *suite_fuzz(void)
{
    Suite *s = suite_create("fuzz");
    TCase *tc = tu_tcase("inputs");
    tcase_add_test(tc, regressions_and_corpus);
    tcase_add_test(tc, checkpoint_damage_and_edits);
    tcase_add_test(tc, checkpoint_regressions_and_corpus);
    suite_add_tcase(s, tc);
    return s;
}
