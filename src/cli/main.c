/* main.c: the ballfilm command line.  Subcommands dispatch to cmd_*.c; the
 * exit status is the run's bf_status (error.h): 0 ok, 1 out of memory or a
 * bug, 2 bad input, 3 unstable, 4 no convergence, 5 I/O error,
 * 6 interrupted. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballfilm/error.h"
#include "ballfilm/version.h"
#include "cli.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: ballfilm [-h | -V] COMMAND [OPTIONS] [ARGS]\n"
            "\n"
            "  -h, --help         this text and every scene key\n"
            "  -V, --version      print the version\n"
            "\n"
            "commands:\n"
            "  run SCENE.ini [-o OUT.h5] [--set section.key=value]... [-q]\n"
            "                     run a scene, write HDF5 (see 'ballfilm run "
            "--help')\n"
            "  sweep SCENE.ini --vary section.key=START:STOP:COUNT... [-o DIR] "
            "[--jobs N]\n"
            "                     run a parameter sweep (see 'ballfilm sweep "
            "--help')\n"
            "  converge SCENE.ini --methods M1,M2,... [--dt ...] [--tol ...] "
            "[--t-end T]\n"
            "                     convergence / work-precision study against "
            "an ARKODE\n"
            "                     reference (see 'ballfilm converge --help')\n"
            "  xdmf OUT.h5 [-o OUT.xmf]\n"
            "                     XDMF sidecar for ParaView/VisIt (see "
            "'ballfilm xdmf --help')\n"
            "  animate OUT.h5 [-o MOVIE.mp4] [--fps N] [--t0 T] [--t1 T]\n"
            "                     a movie of a run (see 'ballfilm animate "
            "--help')\n"
            "  export OUT.h5 --format h5md|extxyz [-o FILE]\n"
            "                     particles for MDAnalysis, VMD, OVITO, ASE "
            "(see 'ballfilm\n"
            "                     export --help')\n"
            "  info OUT.h5        what a run's file holds: scene, status, "
            "counters, energy\n"
            "                     error, every dataset with shape and unit\n"
            "  help               this text and every scene key\n"
            "  version            print the version\n"
            "\n"
            "exit status: 0 ok, 1 out of memory or internal error, 2 bad "
            "input (also a run\n"
            "             that needs more memory than there is), 3 run "
            "unstable, 4 iteration\n"
            "             did not converge, 5 I/O error, 6 interrupted\n");
}

volatile sig_atomic_t bf_cli_stop = 0;

static void on_signal(int sig)
{
    (void)sig;
    bf_cli_stop = 1;
}

/* Before anything else: a signal during set-up must not kill the process
 * half-way (a file created and not yet flushed); the commands check
 * bf_cli_stop and end with status 6.  No SA_RESTART: a blocking wait
 * returns so that the command can react.  An ignored SIGINT stays
 * ignored: a shell starts the background jobs of a script that way so
 * that Ctrl-C at the terminal stops the script and not them; SIGTERM
 * (kill, a batch scheduler) stops the program whatever it inherited. */
static void install_handlers(void)
{
    struct sigaction sa, inherited;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, NULL, &inherited) ||
        inherited.sa_handler != SIG_IGN)
        sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
#ifdef BF_MPI
    /* mpirun (Open MPI) forwards SIGUSR1 to every rank as it is, while it
     * answers SIGINT and SIGTERM by killing the job (docs/reliability.md) */
    sigaction(SIGUSR1, &sa, NULL);
#endif
    /* a signal that arrived while it was blocked (inherited), now caught */
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
#ifdef BF_MPI
    sigaddset(&set, SIGUSR1);
#endif
    sigprocmask(SIG_UNBLOCK, &set, NULL);
}

/* Hidden (for the shell completion, src/cli/ballfilm.bash): every scene
 * key as section.key, one a line, from the key table `run --help` prints
 * (a section header "[name]  doc" at the start of a line, its keys below
 * it indented by two spaces). */
static int print_key_names(void)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (!m)
        return BF_EINTERNAL;
    bf_cli_print_keys(m);
    if (fclose(m))
        return BF_EINTERNAL;
    /* the names printed, each between newlines: a section of several
     * integrators ([integrator]) repeats keys */
    char *seen = calloc(len + 2, 1), section[128] = "", name[300];
    if (!seen) {
        free(text);
        return BF_EINTERNAL;
    }
    seen[0] = '\n';
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (line[0] == '[' && strchr(line, ']')) {
            snprintf(section, sizeof section, "%.*s",
                     (int)(strchr(line, ']') - line - 1), line + 1);
        } else if (line[0] != ' ') {
            section[0] = '\0';
        } else if (section[0] && line[1] == ' ' && line[2] != ' ') {
            snprintf(name, sizeof name, "\n%s.%.*s\n", section,
                     (int)strcspn(line + 2, " "), line + 2);
            if (!strstr(seen, name) && strlen(seen) + strlen(name) <= len) {
                strcat(seen, name + 1);
                fputs(name + 1, stdout);
            }
        }
    }
    free(seen);
    free(text);
    return 0;
}

enum { OPT_KEYS = BF_CLI_LONG };

int main(int argc, char **argv)
{
    install_handlers();
    bf_cli_warm_heap();
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {"complete-keys", no_argument, NULL, OPT_KEYS},
        {NULL, 0, NULL, 0},
    };
    /* '+': the options before the command; the command's own follow it */
    const bf_cli_cmd top = {NULL, "+:hV", longopts, usage};
    for (int c; (c = bf_cli_getopt(&top, argc, argv)) != -1;) {
        if (c == BF_CLI_HELP) {
            printf("\n");
            bf_cli_print_keys(stdout);
            return 0;
        }
        if (c == BF_CLI_BAD)
            return 2;
        if (c == 'V') {
            printf("%s\n", bf_version_string());
            return 0;
        }
        if (c == OPT_KEYS)
            return print_key_names();
    }
    if (optind >= argc) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[optind];
    argc -= optind;
    argv += optind;
    optind = 0; /* glibc's full reset: each command parses its own argv */
    if (!strcmp(cmd, "run")) {
        int rc = bf_cmd_run(argc, argv);
        if (rc == 5) {
            /* After a failed write (disk full) HDF5 keeps the file open
             * internally and its exit handler crashes closing it again
             * (HDF5 1.10.8); our message is out and the file is as good as
             * it will get, so leave without running exit handlers. */
            fflush(stdout);
            fflush(stderr);
            _exit(rc);
        }
        return rc;
    }
    if (!strcmp(cmd, "sweep"))
        return bf_cmd_sweep(argc, argv);
    if (!strcmp(cmd, "converge"))
        return bf_cmd_converge(argc, argv);
    if (!strcmp(cmd, "xdmf"))
        return bf_cmd_xdmf(argc, argv);
    if (!strcmp(cmd, "animate"))
        return bf_cmd_animate(argc, argv);
    if (!strcmp(cmd, "info"))
        return bf_cmd_info(argc, argv);
    if (!strcmp(cmd, "export"))
        return bf_cmd_export(argc, argv);
    if (!strcmp(cmd, "help")) {
        usage(stdout);
        printf("\n");
        bf_cli_print_keys(stdout);
        return 0;
    }
    if (!strcmp(cmd, "version")) {
        printf("%s\n", bf_version_string());
        return 0;
    }
    bf_cli_error(&top, "unknown command '%s'", cmd);
    return 2;
}
