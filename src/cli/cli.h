/* cli.h: subcommands of the ballfilm program (private to src/cli). */
#ifndef BALLFILM_CLI_H
#define BALLFILM_CLI_H

#include <getopt.h> /* getopt_long: glibc declares it without _GNU_SOURCE */
#include <signal.h>
#include <stdio.h>

/* Set by SIGINT/SIGTERM, whose handler main() installs before anything
 * else: every command stops at its next check with status 6. */
extern volatile sig_atomic_t bf_cli_stop;

int bf_cmd_run(int argc, char **argv);
int bf_cmd_sweep(int argc, char **argv);
int bf_cmd_converge(int argc, char **argv);
int bf_cmd_xdmf(int argc, char **argv);
int bf_cmd_animate(int argc, char **argv);
int bf_cmd_info(int argc, char **argv);
int bf_cmd_export(int argc, char **argv);
/* Write OUT.xmf beside OUT.h5 after a run; a failure is a warning.
 * Returns the sidecar's status (6 when SIGINT/SIGTERM stopped it). */
int bf_cli_write_xdmf(const char *h5_path);

/* heap.c: the start of the heap on one 2 MiB page made ready at once, and
 * freed blocks kept for reuse (a small run's start-up is mostly first
 * touches of memory). */
void bf_cli_warm_heap(void);
/* Create ./out if missing; 0 on success (else prints why). */
int bf_cli_mkdir_out(void);
void bf_cli_print_keys(FILE *f);

/* opts.c: one command's options for getopt_long.  shortopts begins with
 * ':' (a missing value is told apart) and holds 'h', which with --help
 * prints usage(stdout).  main() resets getopt (optind = 0) before it
 * hands argv to a command. */
typedef struct bf_cli_cmd {
    const char *name; /* "run"; NULL for the program itself */
    const char *shortopts;
    const struct option *longopts;
    void (*usage)(FILE *f);
} bf_cli_cmd;
/* Codes of long options without a short one start here. */
enum { BF_CLI_LONG = 256 };
/* What bf_cli_getopt returns besides an option's code and -1 (the
 * operands are argv[optind..argc-1]): --help was given and printed
 * (the command returns 0), or a bad option was reported (status 2). */
enum { BF_CLI_HELP = -2, BF_CLI_BAD = -3 };
int bf_cli_getopt(const bf_cli_cmd *c, int argc, char **argv);
/* "ballfilm: error: MESSAGE; see 'ballfilm CMD --help'" on stderr. */
void bf_cli_error(const bf_cli_cmd *c, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* 1 (and the message "PATH: no such file") when the input file path
 * does not exist: status 2 before any reader opens it; 0 when it is
 * there or cannot be looked at (the reader then says why). */
int bf_cli_no_such_file(const char *path);

#endif
