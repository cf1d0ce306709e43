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

#endif
