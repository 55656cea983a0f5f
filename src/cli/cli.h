/* cli.h: subcommands of the ballfilm program (private to src/cli). */
#ifndef BALLFILM_CLI_H
#define BALLFILM_CLI_H

#include <stdio.h>

#include <signal.h>

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

#endif
