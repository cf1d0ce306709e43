/* The command line (src/cli): per-subcommand help, the process's heap, and the
 * subcommands that only the command line has (merge, status, fit's report). */
#ifndef ROLLSIM_CLI_CLI_H
#define ROLLSIM_CLI_CLI_H

#include <stdio.h>

#include "io/case.h"
#include "study/run.h"
#include "study/sweep.h"

/* ---- help.c: the subcommands and their help ---- */

/* Help of subcommand `cmd` ("run", "check", "sweep", ...; NULL or "" for the overview).
 * Returns 0, or -1 for an unknown subcommand (nothing printed then). */
int rs_cli_help(const char *cmd, FILE *out);
/* 1 if `cmd` is a subcommand rollsim knows. */
int rs_cli_is_command(const char *cmd);
/* `check` of a case with a sweep: block: the swept keys, their values and units (forces in
 * N for contact.dimension 3, N/mm in 2D). */
void rs_cli_print_sweep(FILE *out, const rs_sweep *s, int dimension);

/* ---- heap.c: the process's memory ---- */

/* The heap in transparent huge pages where the C library and the kernel allow it (glibc on
 * Linux; nothing under AddressSanitizer or with ROLLSIM_SMALL_PAGES set in the
 * environment): first touches of memory, 4 KiB page faults otherwise, were a large part of
 * a 3D steady chain's start (heap.c). Called first thing by the command line's main, never
 * by the library. */
void rs_cli_heap_setup(void);

/* ---- merge_cli.c: rollsim merge OUT.nc PART.nc... (args after "merge"); a status ---- */
int rs_cli_merge(int argc, char **argv);

/* ---- status_cli.c: rollsim status FILE.nc... (args after "status"); a status ---- */
int rs_cli_status(int argc, char **argv);

/* ---- fit_cli.c: rollsim fit ---- */
struct rs_fit_opts;
int rs_cli_fit(const rs_case *c, const struct rs_fit_opts *o);

#endif
