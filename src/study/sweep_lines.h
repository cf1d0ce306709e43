/* Private to the drivers: one continuation line of sweep points solved in memory (the
 * cases derived from the loaded one with typed overrides, models, warm starts and
 * continuation along the last key), for sweeps (serial, over MPI ranks, in parts) and
 * fits. The lines of a sweep are independent (each starts from rest), so a line gives
 * the same numbers whichever process computes it. */
#ifndef ROLLSIM_SWEEP_LINES_H
#define ROLLSIM_SWEEP_LINES_H

#include <signal.h>
#include <stddef.h>

#include "io/case.h"
#include "physics/model.h"
#include "study/run.h"
#include "base/status.h"

/* Called after point j of the line: status RS_OK or RS_ERR_SOLVER (why says why), d its
 * quantities, newton the point's Newton iterations (steady: its continuation step's,
 * intermediate points included; transient: the run's; also in rs_sweep_line.stats for
 * steady points), the line's fields buffer filled (when given and the point has the grid).
 * Returns a status; anything but RS_OK stops the line with it. A line solved in two
 * parts (rs_sweep_line_in_two) calls it out of order and from two threads, one call at
 * a time. */
typedef int (*rs_line_point_fn)(void *ctx, size_t j, int status, const rs_diag *d, long newton,
                                const char *why);

typedef struct rs_sweep_line {
  const rs_case *base;           /* the loaded case (rs_case_load) */
  const rs_case_override *fixed; /* the other axes' values (fits: parameters, other inputs) */
  int nfixed;
  int key; /* the continued (last) key (rs_case_key_index) */
  const double *values;
  size_t n;
  long first_point;  /* >= 0: a point's input error reads "sweep point first_point + j: ...";
                        < 0: "KEY=VALUE: ..." */
  rs_fields *fields; /* the profiles of each point, or NULL */
  rs_line_point_fn point_done;
  void *ctx;
  volatile sig_atomic_t *interrupt_flag; /* transient points stop at it */
  rs_stats *stats;                       /* steady solver statistics added, or NULL */
  long *refined;                         /* continuation steps halved added, or NULL */
  long *midpoints;                       /* approximate midpoints tried added, or NULL */
  long *in_two;                          /* 1 added when solved in two parts, or NULL */
  int estimate; /* steady points: their error estimates (study/errest.h) into d */
} rs_sweep_line;

/* Solve the points key = values[j], j = 0..n-1, each warm-started from the one solved
 * before it, calling point_done after each: in order; from the end with the larger
 * |value| when rs_sweep_line_far_first says so; or in two parts at once when
 * rs_sweep_line_in_two says so. Returns RS_OK, the callback's status, or an
 * input/internal error's (message in msg). */
int rs_sweep_line_eval(const rs_sweep_line *line, rs_msg *msg);

/* Whether a line of n points of case c (its first point) along key is solved from its
 * end with the larger |value| back (a creep curve from saturation towards rest): steady
 * plastic points along a rolling input with a unique steady state (3D, Coulomb friction,
 * no softening), where a point does not depend on the path to it beyond Newton's
 * tolerance and the plastic Newton iterations are fewer in that direction (elastic
 * lines: more, so they run in order). */
int rs_sweep_line_far_first(const rs_case *c, int key, size_t n);

/* Whether a line of n points of case c along key is solved in two parts at once, on two
 * threads, each part from its end with the larger |value| back: steady points along a
 * rolling input with a unique steady state (elastic or plastic), solver.threads 2 with
 * two threads available. */
int rs_sweep_line_in_two(const rs_case *c, int key, size_t n);

#endif
