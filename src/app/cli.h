/* Internal to the drivers (src/app): per-subcommand help, plausibility warnings, the
 * fields of one record kept for sweep files. */
#ifndef ROLLSIM_APP_CLI_H
#define ROLLSIM_APP_CLI_H

#include <stdio.h>

#include "rollsim/case.h"
#include "rollsim/run.h"
#include "rollsim/sweep.h"

/* ---- help.c: the subcommands and their help ---- */

/* Help of subcommand `cmd` ("run", "check", "sweep", ...; NULL or "" for the overview).
 * Returns 0, or -1 for an unknown subcommand (nothing printed then). */
int rs_cli_help(const char *cmd, FILE *out);
/* 1 if `cmd` is a subcommand rollsim knows. */
int rs_cli_is_command(const char *cmd);
/* `check` of a case with a sweep: block: the swept keys, their values and units. */
void rs_cli_print_sweep(FILE *out, const rs_sweep *s);

/* ---- heap.c: the process's memory ---- */

/* The heap in transparent huge pages where the C library and the kernel allow it (glibc on
 * Linux; nothing under AddressSanitizer or with ROLLSIM_SMALL_PAGES set in the
 * environment): first touches of memory, 4 KiB page faults otherwise, were a large part of
 * a 3D steady chain's start (heap.c). Called first thing by the command line's main, never
 * by the library. */
void rs_cli_heap_setup(void);

/* ---- warnings.c: plausible but suspicious inputs (stderr; never an error) ---- */

/* Creepages that look like percentages (|xi| >= 0.05) or lie far beyond full sliding
 * (|xi| > RS_WARN_SATURATION_FACTOR mu a/R, Carter's saturation creepage of the elastic
 * 2D contact). `max_abs` is the largest |xi| of the run (a history's maximum, or of a
 * sweep's values), `where` names its origin ("rolling.creepage", "sweep:
 * rolling.creepage"). Returns the number of warnings printed. */
#define RS_WARN_PERCENT           0.05
#define RS_WARN_SATURATION_FACTOR 10.0
int rs_warn_creepage(const rs_case *c, double max_abs, const char *where, FILE *err);
/* The case's own creepage input (nothing with a prescribed tangential force). */
int rs_warn_case(const rs_case *c, FILE *err);
/* The swept creepages of a sweep (when rolling.creepage is swept). */
int rs_warn_sweep(const rs_case *base, const rs_sweep *s, FILE *err);

/* Cost of a transient run projected from its first steps. The rate of the first steps
 * (wall time per simulated second: IDA steps per second times the cost of a step, which
 * grows with the cells) is measured over a window that leaves the first half of
 * RS_COST_PROBE_SECONDS out, from the first output record after half of it to the first
 * after all of it (from the start when no record came in the first half). It holds while the
 * solution changes: for the rest of the run when an input varies, but at constant inputs only
 * until the run has settled to steady rolling (RS_COST_SETTLE_LENGTHS contact lengths 2a after
 * its start, by when a start-up from rest is steady), after which IDA's steps grow by orders of
 * magnitude. If the projected rest exceeds RS_COST_WARN_SECONDS, the projection is made once
 * more from a second window, from the end of the first to the next record after
 * RS_COST_CONFIRM_SECONDS (at least one record later): a start-up from rest takes its densest
 * steps first, so the first window alone over-estimates. If the second projection exceeds it
 * too: one warning with that estimate (ETA) and a hint. */
#define RS_COST_PROBE_SECONDS   1.0
#define RS_COST_CONFIRM_SECONDS 5.0
#define RS_COST_WARN_SECONDS    120.0
#define RS_COST_SETTLE_LENGTHS  25.0
typedef struct rs_cost_watch {
  const rs_case *c;
  int cells;
  double t0, started; /* simulated start time, wall clock at start */
  int sampled;        /* the window's start was taken */
  double t_a, wall_a; /* the window's start: simulated time, wall clock */
  long steps_a;
  int confirming; /* the first projection exceeded the threshold; the second window is open */
  int done;       /* the estimate was made (warned or not) */
} rs_cost_watch;
void rs_cost_watch_init(rs_cost_watch *w, const rs_case *c, int cells, double t0, double started);
/* After an output record at simulated time t with `steps` IDA steps so far, at wall clock
 * `now` (rs_wall_clock(), the clock of `started`). Returns 1 when it warned. */
int rs_cost_watch_update(rs_cost_watch *w, double t, long steps, double now, FILE *err);

/* ---- sweep_fields.c: fields of one point ---- */

int rs_fields_alloc(rs_fields *f, int n);
void rs_fields_free(rs_fields *f);
void rs_fields_copy(rs_fields *f, int n, const double *y, const double *pn, const double *slip,
                    const double *tauc, const signed char *regime, const double *mu);
/* The profile fields a sweep of case c stores: output.fields, tau_c only with plasticity,
 * mu with a velocity-dependent friction law; none in 3D (a 3D sweep file holds the forces
 * and counts; a warning says so on stderr when `warn` and fields were asked for). */
unsigned rs_sweep_profile_fields(const rs_case *c, int warn);

/* Whether every point of the sweep has the grid of the loaded case c (*common; the
 * profiles then share one x axis): the model of c and of each swept value (the other keys
 * at c's values) are compared; a rolling input under a constant normal load leaves the grid
 * as it is and is not built. Common: x (malloc'ed) and n hold the grid; else why says which
 * key changes it. Returns a status (case or model errors). */
int rs_sweep_common_grid(const rs_sweep *s, const rs_case *c, int *common, double **x, int *n,
                         char *why, size_t why_len, rs_msg *msg);

/* ---- merge_cli.c: rollsim merge OUT.nc PART.nc... (args after "merge"); a status ---- */
int rs_cli_merge(int argc, char **argv);

/* ---- fit_cli.c: rollsim fit ---- */
struct rs_fit_opts;
int rs_cli_fit(const rs_case *c, const struct rs_fit_opts *o);

#endif
