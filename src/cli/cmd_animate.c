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
 * (plots/animate.py, writer_for). */
static void movie_paths(const char *h5, const char *out, char *mp4, char *gif,
                        size_t cap)
{
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

static void animate_usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm animate OUT.h5 [-o MOVIE.mp4] [--fps N] "
            "[--frames N] [--t0 T]\n"
            "                        [--t1 T] [--size WxH] [--field speed|p] "
            "[--xlim A B]\n"
            "                        [--talk] [-q]\n"
            "\n"
            "A movie of a run, one frame per output row (plots/animate.py "
            "with Debian's\n"
            "matplotlib and h5py; MP4 through ffmpeg, else a GIF through "
            "Pillow).\n"
            "\n"
            "  -o, --output MOVIE.mp4\n"
            "                   movie file (default: OUT.mp4 beside OUT.h5)\n"
            "  --fps N          frames per second (default 20)\n"
            "  --frames N       at most N frames, rows spread evenly "
            "(default 200)\n"
            "  --t0 T, --t1 T   the time span shown, s (default: the whole "
            "run)\n"
            "  --size WxH       frame size in pixels (default 960x540)\n"
            "  --talk           frames for a talk: 1920x1080 with fonts to "
            "match\n"
            "  --field F        mac: the field under the markers, speed or p "
            "(default speed)\n"
            "  --xlim A B       film: the x range shown, cm\n"
            "  -q, --quiet      no progress bar\n");
}

/* The script's arguments from the command's (getopt_long's conventions
 * here, one spelling there): args[2..] and the terminating NULL; the
 * input and the movie file into *h5 and *out.  Returns -1 to go on, or
 * the status to end with (--help, a bad option). */
static int animate_args(int argc, char **argv, const char **args,
                        const char **h5, const char **out)
{
    enum { FPS = BF_CLI_LONG, FRAMES, T0, T1, SIZE, FIELD, XLIM, TALK };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"output", required_argument, NULL, 'o'},
        {"quiet", no_argument, NULL, 'q'},
        {"fps", required_argument, NULL, FPS},
        {"frames", required_argument, NULL, FRAMES},
        {"t0", required_argument, NULL, T0},
        {"t1", required_argument, NULL, T1},
        {"size", required_argument, NULL, SIZE},
        {"field", required_argument, NULL, FIELD},
        {"xlim", required_argument, NULL, XLIM},
        {"talk", no_argument, NULL, TALK},
        {NULL, 0, NULL, 0},
    };
    /* how the script spells each option of the table */
    static const char *const spelling[] = {
        "--help", "--output", "--quiet", "--fps", "--frames", "--t0", "--t1",
        "--size", "--field", "--xlim", "--talk",
    };
    const bf_cli_cmd cmd = {"animate", ":ho:q", longopts, animate_usage};
    int n = 2, idx;
    *h5 = *out = NULL;
    for (int c; (c = bf_cli_getopt(&cmd, argc, argv)) != -1;) {
        if (c == BF_CLI_HELP || c == BF_CLI_BAD)
            return c == BF_CLI_HELP ? 0 : BF_EINPUT;
        for (idx = 0; longopts[idx].val != c; idx++)
            ;
        args[n++] = spelling[idx];
        if (c == 'o')
            *out = optarg;
        if (c != 'q' && c != TALK)   /* the options with a value */
            args[n++] = optarg;
        if (c == XLIM) { /* two values: A B */
            if (optind >= argc) {
                bf_cli_error(&cmd, "option '--xlim' needs two values");
                return BF_EINPUT;
            }
            args[n++] = argv[optind++];
        }
    }
    if (optind + 1 != argc) {
        if (optind < argc)
            bf_cli_error(&cmd, "unexpected argument '%s'", argv[optind + 1]);
        else
            animate_usage(stderr);
        return BF_EINPUT;
    }
    *h5 = argv[optind];
    args[n++] = "--";
    args[n++] = *h5;
    args[n] = NULL;
    return -1;
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
static int run_script(const char *py, const char **args, const char *h5,
                      const char *out)
{
    char mp4[PATH_MAX], gif[PATH_MAX];
    movie_paths(h5, out, mp4, gif, sizeof mp4);
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
    /* the script's arguments: at most two for each character of an
     * option (-qo X: --quiet --output X), and five more */
    size_t cap = 6;
    for (int k = 0; k < argc; k++)
        cap += 2 * strlen(argv[k]);
    const char **args = calloc(cap, sizeof *args);
    const char *h5, *out;
    int rc = args ? animate_args(argc, argv, args, &h5, &out) : BF_EINTERNAL;
    if (rc < 0 && bf_cli_no_such_file(h5))
        rc = BF_EINPUT;
    if (rc >= 0) {
        free(args);
        return rc;
    }
    char script[PATH_MAX + 32], tried[3 * (PATH_MAX + 32)];
    if (find_script(script, sizeof script, tried, sizeof tried)) {
        fprintf(stderr, "ballfilm: error: cannot find the plot script "
                        ANIMATE_PY " (tried %s; set BALLFILM_ROOT to the "
                        "folder that holds plots/)\n", tried);
        free(args);
        return BF_EIO;
    }
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
    rc = run_script(py, args, h5, out);
    free(args);
    return rc;
}
