/* cmd_animate.c: `ballfilm animate OUT.h5 [-o MOVIE.mp4] [--fps N]
 * [--t0 T] [--t1 T] ...` runs plots/animate.py with Debian's Python
 * (matplotlib, h5py; ffmpeg for MP4, else a GIF through Pillow).
 *
 * The script is looked for, first found wins, in $BALLFILM_ROOT/plots,
 * then beside the program: PREFIX/share/ballfilm/plots for an installed
 * PREFIX/bin/ballfilm (make install), and the repository's plots/ for
 * its bin/ballfilm.  The interpreter is $BALLFILM_PYTHON, else
 * /usr/bin/python3. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/error.h"
#include "cli.h"

#define ANIMATE_PY "animate.py"

/* Tries BASE + SUFFIX + "/animate.py": 0 when readable (in out), else
 * -1 with the path appended to tried. */
static int try_script(char *out, size_t n, const char *base,
                      const char *suffix, char *tried, size_t tn)
{
    int w = snprintf(out, n, "%s%s/" ANIMATE_PY, base, suffix);
    if (w > 0 && (size_t)w < n && access(out, R_OK) == 0)
        return 0;
    size_t used = strlen(tried);
    if (snprintf(tried + used, tn - used, "%s%s", used ? ", " : "", out) < 0)
        tried[used] = '\0';
    return -1;
}

/* The readable animate.py into out (size n): 0, or -1 with the paths
 * tried in tried (size tn). */
static int find_script(char *out, size_t n, char *tried, size_t tn)
{
    tried[0] = '\0';
    const char *env = getenv("BALLFILM_ROOT");
    if (env && *env && !try_script(out, n, env, "/plots", tried, tn))
        return 0;
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len <= 0)
        return -1;
    exe[len] = '\0';
    for (int up = 0; up < 2; up++) {   /* PREFIX/bin/ballfilm -> PREFIX */
        char *slash = strrchr(exe, '/');
        if (!slash)
            return -1;
        *slash = '\0';
    }
    if (!try_script(out, n, exe, "/share/ballfilm/plots", tried, tn) ||
        !try_script(out, n, exe, "/plots", tried, tn))
        return 0;
    return -1;
}

int bf_cmd_animate(int argc, char **argv)
{
    char script[PATH_MAX + 32], tried[3 * (PATH_MAX + 32)];
    if (find_script(script, sizeof script, tried, sizeof tried)) {
        fprintf(stderr, "ballfilm: error: cannot find the plot script "
                        ANIMATE_PY " (tried %s; set BALLFILM_ROOT to the "
                        "folder that holds plots/)\n", tried);
        return BF_EIO;
    }
    const char **args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return BF_EINTERNAL;
    const char *py = getenv("BALLFILM_PYTHON");
    if (!py || !*py)
        py = "/usr/bin/python3";
    if (access(py, X_OK)) {
        fprintf(stderr, "ballfilm: error: animate needs %s with Debian's "
                        "numpy, matplotlib and h5py: sudo apt-get install -y "
                        "python3 python3-numpy python3-matplotlib python3-h5py "
                        "(and ffmpeg for MP4)\n", py);
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
    free(args);
    return BF_EIO;
}
