/* cmd_animate.c: `ballfilm animate OUT.h5 [-o MOVIE.mp4] [--fps N]
 * [--t0 T] [--t1 T] ...` runs plots/animate.py with Debian's Python
 * (matplotlib, h5py; ffmpeg for MP4, else a GIF through Pillow).
 *
 * The repository is $BALLFILM_ROOT, else the parent of the program's
 * directory (bin/ballfilm -> .).  The interpreter is $BALLFILM_PYTHON,
 * else /usr/bin/python3. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/error.h"
#include "cli.h"

/* The repository root (malloc'd), or NULL. */
static char *repo_root(void)
{
    const char *env = getenv("BALLFILM_ROOT");
    if (env && *env)
        return strdup(env);
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return NULL;
    exe[n] = '\0';
    for (int up = 0; up < 2; up++) {
        char *slash = strrchr(exe, '/');
        if (!slash)
            return NULL;
        *(slash == exe ? slash + 1 : slash) = '\0';
    }
    return strdup(exe);
}

int bf_cmd_animate(int argc, char **argv)
{
    char *root = repo_root();
    if (!root) {
        fprintf(stderr, "ballfilm: error: cannot find the repository (set "
                        "BALLFILM_ROOT to the folder that holds plots/)\n");
        return BF_EIO;
    }
    size_t len = strlen(root) + 32;
    char *script = malloc(len);
    const char **args = calloc((size_t)argc + 3, sizeof *args);
    if (!script || !args) {
        free(root);
        free(script);
        free(args);
        return BF_EINTERNAL;
    }
    snprintf(script, len, "%s/plots/animate.py", root);
    free(root);
    const char *py = getenv("BALLFILM_PYTHON");
    if (!py || !*py)
        py = "/usr/bin/python3";
    if (access(script, R_OK)) {
        fprintf(stderr, "ballfilm: error: %s: %s (set BALLFILM_ROOT to the "
                        "repository)\n", script, strerror(errno));
        free(script);
        free(args);
        return BF_EIO;
    }
    if (access(py, X_OK)) {
        fprintf(stderr, "ballfilm: error: animate needs %s with Debian's "
                        "numpy, matplotlib and h5py: sudo apt-get install -y "
                        "python3 python3-numpy python3-matplotlib python3-h5py "
                        "(and ffmpeg for MP4)\n", py);
        free(script);
        free(args);
        return BF_EINPUT;
    }
    args[0] = py;
    args[1] = script;
    for (int k = 1; k < argc; k++)
        args[k + 1] = argv[k];
    args[argc + 1] = NULL;
    fflush(stdout);
    execv(py, (char *const *)args);
    fprintf(stderr, "ballfilm: error: cannot run %s: %s\n", py,
            strerror(errno));
    free(script);
    free(args);
    return BF_EIO;
}
