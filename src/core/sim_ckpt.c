/* sim_ckpt.c: checkpoints of the time loop and the restart from one (see
 * sim.h).  A checkpoint holds the loop's own state (loop_state), the row
 * counts of every series, the model's and the observers' entries, the
 * scene, and what ties it to its output: the run's identifier and the
 * scene's hash, which a restart compares with the output's before it
 * touches anything. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/version.h"
#include "core/sim_impl.h"
#include "io/h5lock.h"
#include "io/outpath.h"


int bf_sim_can_checkpoint(const bf_sim *s)
{
    return s->mt->checkpoint_save && s->mt->checkpoint_load;
}

const char *bf_sim_checkpoint_path(const bf_sim *s) { return s->ckpt_path; }

/* What a checkpoint keeps of the loop itself. */
static const bf_field loop_state[] = {
    BF_FIELD(bf_sim, n, BF_F_LONG, "1"),
    BF_FIELD(bf_sim, last_row, BF_F_LONG, "1"),
    BF_FIELD(bf_sim, en.e0, BF_F_DOUBLE, "erg"),
    BF_FIELD(bf_sim, en.max_rel, BF_F_DOUBLE, "1"),
    BF_FIELD(bf_sim, wall, BF_F_DOUBLE, "s"),
};

/* The rows of every series and their paths (one per line). */
static bf_status put_rows(const bf_sim *s, bf_ckpt *ck, bf_err *err)
{
    size_t ns = bf_out_nseries(s->out), plen = 1;
    int64_t *rows = malloc((ns ? ns : 1) * sizeof *rows);
    for (size_t k = 0; k < ns; k++)
        plen += strlen(bf_series_path(bf_out_series_at(s->out, k))) + 1;
    char *paths = malloc(plen);
    bf_status st = BF_OK;
    if (!rows || !paths) {
        st = bf_fail(err, BF_EINTERNAL, "out of memory");
    } else {
        paths[0] = '\0';
        for (size_t k = 0; k < ns; k++) {
            bf_series *se = bf_out_series_at(s->out, k);
            rows[k] = (int64_t)bf_series_rows(se);
            strcat(paths, bf_series_path(se));
            strcat(paths, "\n");
        }
        st = bf_ckpt_put_i64(ck, "out.rows", rows, ns, err);
        if (!st)
            st = bf_ckpt_put_str(ck, "out.paths", paths, err);
    }
    free(rows);
    free(paths);
    return st;
}

/* A checkpoint replaces the file at path (a rename): refused when that is
 * a file of the run itself (its scene, its output or the output's .part,
 * by identity: outpath.h) or a name that cannot be replaced, as an output
 * path would be. */
static bf_status check_target(const bf_sim *s, const char *path, bf_err *err)
{
    if (!path || !*path)
        return bf_fail(err, BF_EINPUT, "a checkpoint needs a file name");
    if (bf_path_same_file(path, s->scene_path))
        return bf_fail(err, BF_EINPUT, "checkpoint %s: that is %s, the scene "
                       "file of this run; the checkpoint would overwrite it",
                       path, s->scene_path);
    const char *out = s->out ? bf_out_path(s->out) : NULL;
    if (out) {
        size_t len = strlen(out) + 6;
        char *part = malloc(len);
        if (!part)
            return bf_fail(err, BF_EINTERNAL, "out of memory");
        snprintf(part, len, "%s.part", out);
        const int own = !strcmp(path, out) || !strcmp(path, part) ||
                        bf_path_same_file(path, out) ||
                        bf_path_same_file(path, part);
        free(part);
        if (own)
            return bf_fail(err, BF_EINPUT, "checkpoint %s: that is the "
                           "output of this run (%s or its .part); the "
                           "checkpoint would overwrite it", path, out);
    }
    if (bf_path_check_replaceable(path, err)) {
        bf_err_prefix(err, "checkpoint");
        if (err)
            err->status = BF_EINPUT;
        return BF_EINPUT;
    }
    return BF_OK;
}

static bf_status checkpoint_write(bf_sim *s, const char *path, bf_err *err)
{
    if (!bf_sim_can_checkpoint(s))
        return bf_fail(err, BF_EINPUT, "model '%s' cannot write checkpoints",
                       s->mt->name);
    /* a follower's part: the model's, with no file (bf_sim_opts) */
    if (!s->out && bf_sim_follower_(s))
        return s->mt->checkpoint_save(s->model, NULL, err);
    bf_status st = check_target(s, path, err);
    if (st)
        return st;
    /* rows on disk must cover what the checkpoint claims */
    if (s->out && (st = bf_out_flush(s->out, err)))
        return st;
    bf_ckpt *ck = bf_ckpt_new();
    if (!ck)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    if (!st) st = bf_ckpt_put_str(ck, "version", bf_version_string(), err);
    if (!st) st = bf_ckpt_put_str(ck, "scene.path", s->scene_path, err);
    if (!st) st = bf_ckpt_put_str(ck, "scene.text", s->scene_text, err);
    if (!st) st = bf_ckpt_put_str(ck, "scene.sets", s->scene_sets, err);
    if (!st) st = bf_ckpt_put_str(ck, "run.id", s->run_id, err);
    if (!st) st = bf_ckpt_put_str(ck, "run.scene_hash", s->scene_hash, err);
    if (!st)
        st = bf_ckpt_put_fields(ck, "sim", loop_state, BF_NFIELDS(loop_state),
                                s, err);
    if (!st && s->out)
        st = put_rows(s, ck, err);
    if (!st)
        st = s->mt->checkpoint_save(s->model, ck, err);
    EACH_OBSERVER(s, st, save, ck, err);
    if (!st)
        st = bf_ckpt_write(ck, path, err);
    bf_ckpt_free(ck);
    return st;
}

bf_status bf_sim_checkpoint_write(bf_sim *s, const char *path, bf_err *err)
{
    H5_LOCKED(checkpoint_write(s, path, err));
}

/* An identifier of 16 hex digits (as bf_sim_new_run_id_ and
 * bf_sim_scene_hash_ make them). */
static int is_id(const char *v)
{
    if (!v || strlen(v) != 16)
        return 0;
    for (const char *p = v; *p; p++)
        if (!((*p >= '0' && *p <= '9') || (*p >= 'a' && *p <= 'f')))
            return 0;
    return 1;
}

/* The checkpoint continues the output it is next to: the same run (its
 * identifier) of the same scene (its hash), read from the file the run
 * writes (OUT.part, or OUT when it had ended) before it is touched. */
static bf_status same_run(bf_sim *s, const bf_ckpt *ck, const char *out_path,
                          bf_err *err)
{
    const char *cid = bf_ckpt_str(ck, "run.id");
    const char *chash = bf_ckpt_str(ck, "run.scene_hash");
    if (!is_id(cid) || !is_id(chash))
        return bf_fail(err, BF_EINPUT, "%s.ckpt: the checkpoint names no run "
                       "(written by another version?); it cannot continue %s",
                       out_path, out_path);
    size_t len = strlen(out_path) + 6;
    char *part = malloc(len);
    if (!part)
        return bf_fail(err, BF_EINTERNAL, "out of memory");
    snprintf(part, len, "%s.part", out_path);
    const char *file = access(part, F_OK) ? out_path : part;
    char *oid = NULL, *ohash = NULL;
    bf_err e = {0};
    bf_status st = BF_OK;
    if (bf_h5_read_attr_str(file, "/", "run_id", &oid, &e) ||
        bf_h5_read_attr_str(file, "/", "scene_hash", &ohash, &e))
        st = bf_fail(err, BF_EINPUT, "%s: %s names no run (%s); the "
                     "checkpoint %s.ckpt cannot continue it",
                     out_path, file, e.msg, out_path);
    else if (strcmp(oid, cid) || strcmp(ohash, chash))
        st = bf_fail(err, BF_EINPUT, "%s.ckpt is the checkpoint of another "
                     "run (run %s of scene %s) than %s (run %s of scene %s); "
                     "it cannot continue it: restart the run that wrote it, "
                     "or start %s again",
                     out_path, cid, chash, file, oid, ohash, out_path);
    free(oid);
    free(ohash);
    free(part);
    if (!st) {
        snprintf(s->run_id, sizeof s->run_id, "%s", cid);
        snprintf(s->scene_hash, sizeof s->scene_hash, "%s", chash);
    }
    return st;
}

/* The loop's, the model's and the observers' state from ck. */
static bf_status resume_state(bf_sim *s, const bf_ckpt *ck,
                              const char *out_path, bf_err *err)
{
    if (!bf_sim_can_checkpoint(s))
        return bf_fail(err, BF_EINPUT, "model '%s' cannot restart",
                       s->mt->name);
    bf_status st = bf_ckpt_get_fields(ck, "sim", loop_state,
                                      BF_NFIELDS(loop_state), s, err);
    if (!st)
        st = s->mt->checkpoint_load(s->model, ck, err);
    EACH_OBSERVER(s, st, load, ck, err);
    if (st)
        return st;
    if (s->n > s->nsteps)
        return bf_fail(err, BF_EINPUT, "%s.ckpt: the checkpoint is at step "
                       "%ld, beyond t_end (%ld steps)", out_path, s->n,
                       s->nsteps);
    if (s->n < 0 || s->last_row < -1 || s->last_row > s->n ||
        !(s->wall >= 0) || !isfinite(s->en.e0) || !(s->en.max_rel >= 0))
        return bf_fail(err, BF_EINPUT, "%s.ckpt: the loop's state is out of "
                       "range (step %ld, last row %ld)", out_path, s->n,
                       s->last_row);
    return BF_OK;
}

static bf_status resume(bf_sim *s, const bf_ckpt *ck, const char *out_path,
                        bf_err *err)
{
    bf_status st;
    if (!bf_sim_can_checkpoint(s))
        return bf_fail(err, BF_EINPUT, "model '%s' cannot restart",
                       s->mt->name);
    if ((st = same_run(s, ck, out_path, err)) ||
        (st = resume_state(s, ck, out_path, err)))
        return st;
    /* reopen the output and drop rows written after the checkpoint */
    if ((st = bf_sim_set_ckpt_path_(s, out_path, err)) ||
        (st = bf_out_open_append(&s->out, out_path, err)) ||
        (st = bf_sim_open_series_(s, err)))
        return st;
    size_t nrows;
    const int64_t *rows = bf_ckpt_data_i64(ck, "out.rows", &nrows);
    if (!rows || nrows != bf_out_nseries(s->out))
        return bf_fail(err, BF_EINPUT, "%s.ckpt: the checkpoint does not "
                       "match the datasets of %s", out_path, out_path);
    for (size_t k = 0; k < nrows; k++) {
        bf_series *se = bf_out_series_at(s->out, k);
        if (rows[k] < 0 || (uint64_t)rows[k] > bf_series_rows(se))
            return bf_fail(err, BF_EINPUT, "%s.ckpt: the checkpoint counts "
                           "%lld rows of %s, the output has %zu (a checkpoint "
                           "of another state of this run?)",
                           out_path, (long long)rows[k], bf_series_path(se),
                           bf_series_rows(se));
        if ((st = bf_series_truncate(se,
                                     (size_t)rows[k], err)))
            return st;
    }
    if ((st = bf_out_attr_str(s->out, "/", "status", "running", err)))
        return st;
    return bf_out_start_appending(s->out, err);
}

bf_status bf_sim_resume(bf_sim *s, const bf_ckpt *ck, const char *out_path,
                        bf_err *err)
{
    H5_LOCKED(resume(s, ck, out_path, err));
}

bf_status bf_sim_resume_state(bf_sim *s, const bf_ckpt *ck,
                              const char *out_path, bf_err *err)
{
    H5_LOCKED(resume_state(s, ck, out_path, err));
}
