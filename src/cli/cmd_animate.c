/* cmd_animate.c: `ballfilm animate OUT.h5 [-o MOVIE.mp4] [--fps N]
 * [--t0 T] [--t1 T] ...` runs plots/animate.py with Debian's Python
 * (matplotlib, h5py; ffmpeg for MP4, else a GIF through Pillow).
 *
 * The script is looked for, first found wins, in $BALLFILM_ROOT/plots,
 * then beside the program: PREFIX/share/ballfilm/plots for an installed
 * PREFIX/bin/ballfilm (make install), and the repository's plots/ for
 * its bin/ballfilm.  The interpreter is $BALLFILM_PYTHON, else
 * /usr/bin/python3.
 *
 * The script runs as a child in a process group of its own (with the
 * ffmpeg it starts), so that SIGINT and SIGTERM reach this process alone:
 * it ends the group and removes the movie the script had begun, then
 * exits with status 6 like every interrupted command. */
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
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

/* The movie files the script may write for its arguments: -o/--output
 * (or OUT.mp4 beside OUT.h5) and the GIF it falls back to without ffmpeg
 * (plots/animate.py, writer_for); NULL when not known. */
static void movie_paths(int argc, char **argv, char *mp4, char *gif,
                        size_t cap)
{
    const char *h5 = NULL, *out = NULL;
    for (int k = 1; k < argc; k++) {
        if ((!strcmp(argv[k], "-o") || !strcmp(argv[k], "--output")) &&
            k + 1 < argc)
            out = argv[++k];
        else if (!strncmp(argv[k], "--output=", 9))
            out = argv[k] + 9;
        else if (argv[k][0] != '-' && !h5)
            h5 = argv[k];
    }
    mp4[0] = gif[0] = '\0';
    if (out)
        snprintf(mp4, cap, "%s", out);
    else if (h5) {
        const char *dot = strrchr(h5, '.'), *slash = strrchr(h5, '/');
        int len = dot && (!slash || dot > slash) ? (int)(dot - h5)
                                                 : (int)strlen(h5);
        snprintf(mp4, cap, "%.*s.mp4", len, h5);
    }
    const char *dot = strrchr(mp4, '.'), *slash = strrchr(mp4, '/');
    int len = dot && (!slash || dot > slash) ? (int)(dot - mp4)
                                             : (int)strlen(mp4);
    if (mp4[0])
        snprintf(gif, cap, "%.*s.gif", len, mp4);
}

/* Identity and age of a file (st_ino 0: missing). */
static struct stat file_id(const char *path)
{
    struct stat st;
    if (!path[0] || lstat(path, &st))
        memset(&st, 0, sizeof st);
    return st;
}

/* A movie the interrupted script created or rewrote is not a movie. */
static void remove_begun(const char *path, const struct stat *before)
{
    struct stat now = file_id(path);
    if (!now.st_ino || !S_ISREG(now.st_mode))
        return;
    if (before->st_ino == now.st_ino && before->st_dev == now.st_dev &&
        before->st_mtim.tv_sec == now.st_mtim.tv_sec &&
        before->st_mtim.tv_nsec == now.st_mtim.tv_nsec &&
        before->st_size == now.st_size)
        return;
    unlink(path);
}

/* Run the script as a child until it ends, or until SIGINT/SIGTERM:
 * then its process group is ended (SIGTERM, SIGKILL a second later), the
 * movie it had begun removed, and the status is 6. */
static int run_script(const char *py, const char **args, int argc,
                      char **argv)
{
    char mp4[PATH_MAX], gif[PATH_MAX];
    movie_paths(argc, argv, mp4, gif, sizeof mp4);
    const struct stat mp4_0 = file_id(mp4), gif_0 = file_id(gif);
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "ballfilm: error: cannot start %s: %s\n", py,
                strerror(errno));
        return BF_EIO;
    }
    if (pid == 0) {
        setpgid(0, 0);
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        execv(py, (char *const *)args);
        fprintf(stderr, "ballfilm: error: cannot run %s: %s\n", py,
                strerror(errno));
        _exit(BF_EIO);
    }
    setpgid(pid, pid); /* also here: no window before the child's own */
    /* polled, not a blocking wait: a signal between a check and the wait
     * would otherwise go unseen until the script ends */
    const struct timespec tick = {0, 20000000};
    int status = 0, stopping = 0;
    double waited = 0.0;
    for (;;) {
        pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid || (r < 0 && errno != EINTR))
            break;
        if (bf_cli_stop && !stopping) {
            stopping = 1;
            kill(-pid, SIGTERM);
        } else if (stopping && waited >= 1.0) {
            kill(-pid, SIGKILL);
        }
        if (stopping)
            waited += 0.02;
        nanosleep(&tick, NULL);
    }
    if (stopping) {
        kill(-pid, SIGKILL); /* what is left of its group (ffmpeg) */
        remove_begun(mp4, &mp4_0);
        remove_begun(gif, &gif_0);
        fprintf(stderr, "ballfilm: interrupted: animate stopped; no movie "
                        "was written\n");
        return BF_INTERRUPTED;
    }
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    fprintf(stderr, "ballfilm: error: %s ended by signal %d\n", py,
            WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return BF_EINTERNAL;
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
    int rc = run_script(py, args, argc, argv);
    free(args);
    return rc;
}
