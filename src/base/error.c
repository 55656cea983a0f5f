/* error.c: formatting of error messages (see error.h). */
#include "ballfilm/error.h"

#include <stdio.h>
#include <string.h>

bf_status bf_vfail(bf_err *err, bf_status status, const char *fmt, va_list ap)
{
    if (err) {
        err->status = status;
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        err->section[0] = err->key[0] = '\0';
    }
    return status;
}

bf_status bf_fail(bf_err *err, bf_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    bf_vfail(err, status, fmt, ap);
    va_end(ap);
    return status;
}

void bf_err_set_key(bf_err *err, const char *section, const char *key)
{
    if (!err)
        return;
    snprintf(err->section, sizeof err->section, "%s", section ? section : "");
    snprintf(err->key, sizeof err->key, "%s", section && key ? key : "");
}

bf_status bf_fail_key(bf_err *err, bf_status status, const char *section,
                      const char *key, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    bf_vfail(err, status, fmt, ap);
    va_end(ap);
    bf_err_set_key(err, section, key);
    return status;
}

void bf_err_prefix(bf_err *err, const char *fmt, ...)
{
    if (!err)
        return;
    char pre[BF_ERR_MSG], old[BF_ERR_MSG];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pre, sizeof pre, fmt, ap);
    va_end(ap);
    memcpy(old, err->msg, sizeof old);
    /* truncation of an over-long message is acceptable */
    if (snprintf(err->msg, sizeof err->msg, "%s: %s", pre, old) < 0)
        err->msg[0] = '\0';
}

void bf_err_clear(bf_err *err)
{
    if (err) {
        err->status = BF_OK;
        err->msg[0] = err->section[0] = err->key[0] = '\0';
    }
}

const char *bf_status_name(bf_status s)
{
    switch (s) {
    case BF_OK: return "ok";
    case BF_EINTERNAL: return "internal error";
    case BF_EINPUT: return "bad input";
    case BF_EUNSTABLE: return "unstable";
    case BF_ENOCONV: return "no convergence";
    case BF_EIO: return "I/O error";
    case BF_INTERRUPTED: return "interrupted";
    }
    return "unknown";
}
