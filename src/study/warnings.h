/* Plausible but suspicious inputs, and the projected cost of a transient run: warnings on
 * stderr that never stop a run (warnings.c). */
#ifndef ROLLSIM_STUDY_WARNINGS_H
#define ROLLSIM_STUDY_WARNINGS_H

#include <stdio.h>

#include "io/case.h"
#include "io/case_sweep.h"

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
 * grows with the cells) is taken over a window that leaves the first half of
 * RS_COST_PROBE_SECONDS out, from the first output record after half of it to the first
 * after all of it (from the start when no record came in the first half). It holds while the
 * solution changes: for the rest of the run when an input varies, but at constant inputs only until
 * the run has settled to steady rolling (RS_COST_SETTLE_LENGTHS contact lengths 2a after its start:
 * a start-up from rest is within 1e-4 of steady after 11.5-25 contact lengths for L = 20-2000 mm,
 * README), after which IDA's steps grow by orders of magnitude. If the projected rest exceeds
 * RS_COST_WARN_SECONDS, the projection is made once more from a second window, from the end of
 * the first to the next record after RS_COST_CONFIRM_SECONDS (at least one record later): a
 * start-up from rest takes its densest steps first (in 3D most of its steps fall in the first of
 * 25 contact lengths), so the first window alone over-estimates such runs by an order of
 * magnitude. If the second projection exceeds it too: one
 * warning with that estimate (ETA) and a hint. */
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

#endif
