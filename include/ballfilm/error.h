/* error.h: status codes and error messages shared by every module.
 *
 * Errors are values (REBOUND style): a function that can fail returns a
 * bf_status and, on failure, writes a one-line message into a bf_err that the
 * caller owns.  Only the command-line front end turns a status into an exit
 * code, and the exit code *is* the status, so a shell script can tell a bad
 * scene (2) from a run that went unstable (3).
 */
#ifndef BALLFILM_ERROR_H
#define BALLFILM_ERROR_H

#include <stdarg.h>

typedef enum bf_status {
    BF_OK = 0,          /* success, run finished */
    BF_EINTERNAL = 1,   /* a bug or an out-of-memory condition */
    BF_EINPUT = 2,      /* bad scene file, bad --set, bad command line, a
                           run that needs more memory than there is */
    BF_EUNSTABLE = 3,   /* run stopped: non-finite or out-of-range state,
                           energy bound exceeded, CFL violated */
    BF_ENOCONV = 4,     /* an iteration (implicit step, pressure) did not
                           converge */
    BF_EIO = 5,         /* HDF5 or file-system failure */
    BF_INTERRUPTED = 6  /* SIGINT/SIGTERM: stopped cleanly, checkpoint written */
} bf_status;

#define BF_ERR_MSG 1024

/* section, key: the scene key a failure is about ("film", "dx";
 * "ball.2", "position"; key "" for the section as a whole), or "" when it
 * is about none.  A module that validates its parameters names the key
 * this way (bf_fail_key) without knowing the scene; the layer that built
 * the parameters from a scene turns it into "FILE:LINE: error: [film] dx:
 * ..." (bf_scene_locate). */
typedef struct bf_err {
    bf_status status;
    char msg[BF_ERR_MSG];
    char section[64];
    char key[64];
} bf_err;

/* Record a failure; returns `status` so callers can write
 * `return bf_fail(err, BF_EINPUT, "...")`.  A NULL err is allowed. */
bf_status bf_fail(bf_err *err, bf_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
bf_status bf_vfail(bf_err *err, bf_status status, const char *fmt, va_list ap);

/* The same, naming the scene key the failure is about. */
bf_status bf_fail_key(bf_err *err, bf_status status, const char *section,
                      const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* Name the key of a failure already recorded (section NULL: none). */
void bf_err_set_key(bf_err *err, const char *section, const char *key);

/* Prefix an existing message: "context: old message". */
void bf_err_prefix(bf_err *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

void bf_err_clear(bf_err *err);

/* Short name of a status ("input", "unstable", ...). */
const char *bf_status_name(bf_status s);

#endif
