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

/* ---- warnings.c: plausible but suspicious inputs (stderr; never an error) ---- */

/* Creepages that look like percentages (|xi| >= 0.05) or lie far beyond full sliding
 * (|xi| > RS_WARN_SATURATION_FACTOR mu a/R, Carter's saturation creepage of the elastic
 * 2D contact). `max_abs` is the largest |xi| of the run (a history's maximum, or of a
 * sweep's values), `where` names its origin ("rolling.creepage", "sweep:
 * rolling.creepage"). Returns the number of warnings printed. */
#define RS_WARN_PERCENT           0.05
#define RS_WARN_SATURATION_FACTOR 10.0
int rs_warn_creepage(const rs_case *c, double max_abs, const char *where, FILE *err);
/* The case's own creepage inputs (nothing with a prescribed tangential force); in 3D the
 * lateral creepage too, for a percentage. */
int rs_warn_case(const rs_case *c, FILE *err);
/* The swept creepages of a sweep (where rolling.creepage or rolling.lateral_creepage is
 * swept), the case's own otherwise. */
int rs_warn_sweep(const rs_case *base, const rs_sweep *s, FILE *err);

/* Cost of a transient run projected from its first steps. The density of IDA's steps (steps
 * per simulated second) and the wall time per step are measured over a window that leaves the
 * first half of RS_COST_PROBE_SECONDS out, from the first output record after half of it to the
 * first after all of it (from the start when no record came in the first half). A start-up
 * takes its densest steps first: the density falls as the transient settles, by e every few
 * contact lengths 2a rolled (the passage time 2a/V; rs_cost_decay_time). Its decay time is
 * measured where two windows lie far enough apart in simulated time (half the prior decay time
 * or more), else taken as RS_COST_DECAY_LENGTHS_2D or _3D contact lengths (the slowest decays of
 * the shipped and bench start-ups, rounded up: 2D Carter (L = 200 mm) about 3.5, 3D 0.5 to 1.1;
 * the estimate errs long). The steps still to come (rs_cost_steps_left) decay so from the
 * present density: until the end, or at constant inputs until the run has settled (at most
 * RS_COST_SETTLE_LENGTHS contact lengths after its start); each jump of a steps history
 * (creepage, load, ...) starts another transient as dense as the present one was at its start
 * (the present density traced back along the decay). Inputs that
 * change continuously (ramps, sines, tables, the twin-disc rig) keep the steps dense: the
 * present density holds to the end there. If the projected rest exceeds RS_COST_WARN_SECONDS,
 * the projection is made once more from a second window, from the end of the first to the next
 * record after RS_COST_CONFIRM_SECONDS (at least one record later); if it exceeds the threshold
 * too: one warning with that estimate (ETA), the steps at the present density all along beside
 * it, and a hint. */
#define RS_COST_PROBE_SECONDS    1.0
#define RS_COST_CONFIRM_SECONDS  5.0
#define RS_COST_WARN_SECONDS     120.0
#define RS_COST_SETTLE_LENGTHS   25.0
#define RS_COST_DECAY_LENGTHS_2D 4.0
#define RS_COST_DECAY_LENGTHS_3D 1.5
typedef struct rs_cost_watch {
  const rs_case *c;
  int cells;
  double t0, started; /* simulated start time, wall clock at start */
  int sampled;        /* the window's start was taken */
  double t_a, wall_a; /* the window's start: simulated time, wall clock */
  long steps_a;
  double rho1, tmid1; /* the last window's step density (1/s) and middle (s); 0 before one */
  int confirming;     /* the first projection exceeded the threshold; the second window is open */
  int done;           /* the estimate was made (warned or not) */
} rs_cost_watch;
void rs_cost_watch_init(rs_cost_watch *w, const rs_case *c, int cells, double t0, double started);
/* After an output record at simulated time t with `steps` IDA steps so far, at wall clock
 * `now` (rs_wall_clock(), the clock of `started`). Returns 1 when it warned. */
int rs_cost_watch_update(rs_cost_watch *w, double t, long steps, double now, FILE *err);
/* The decay time (s) of the step density of case c (run from t0) from two windows' densities
 * rho1, rho2 (steps per simulated second) around the times tmid1 < tmid2; the prior when they
 * lie too close (rho1 = 0: one window only); INFINITY when the density does not decay (no decay
 * measured, or inputs that change continuously). */
double rs_cost_decay_time(const rs_case *c, double t0, double rho1, double tmid1, double rho2,
                          double tmid2);
/* The IDA steps still to come after time t of case c (run from t0) at a density rho (steps
 * per simulated second) at t that decays with time constant tau (INFINITY: stays). */
double rs_cost_steps_left(const rs_case *c, double t0, double t, double rho, double tau);

/* ---- sweep_fields.c: fields of one point ---- */

int rs_fields_alloc(rs_fields *f, int n);
void rs_fields_free(rs_fields *f);
void rs_fields_copy(rs_fields *f, int n, const double *y, const double *pn, const double *slip,
                    const double *tauc, const signed char *regime, const double *mu);
/* The profile fields a sweep of case c stores: output.fields, tau_c only with plasticity,
 * mu with a velocity-dependent friction law; none in 3D (a 3D sweep file holds the forces
 * and counts; a warning says so on stderr when `warn` and fields were asked for). */
unsigned rs_sweep_profile_fields(const rs_case *c, int warn);

/* Whether every point of the sweep has the grid of the base case (*common; the profiles
 * then share one x axis): the model of the base case and of each swept value (the other
 * keys at the base case's values) are compared. Common: x (malloc'ed) and n hold the
 * grid; else why says which key changes it. Returns a status (case or model errors). */
int rs_sweep_common_grid(const rs_sweep *s, const char *case_path, const char *const *sets,
                         int nsets, int *common, double **x, int *n, char *why, size_t why_len,
                         rs_msg *msg);

/* ---- merge_cli.c: rollsim merge OUT.nc PART.nc... (args after "merge"); a status ---- */
int rs_cli_merge(int argc, char **argv);

/* ---- fit_cli.c: rollsim fit ---- */
struct rs_fit_opts;
int rs_cli_fit(const rs_case *c, const char *case_path, const char *const *sets, int nsets,
               const struct rs_fit_opts *o);

#endif
