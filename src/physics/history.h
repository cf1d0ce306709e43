/* Time histories of inputs (docs/case-file.md, histories): constant, ramp, steps,
 * sine, or a CSV table (time,value; linear interpolation). */
#ifndef ROLLSIM_HISTORY_H
#define ROLLSIM_HISTORY_H

#include <stddef.h>

typedef enum rs_history_kind {
  RS_HISTORY_CONSTANT = 0,
  RS_HISTORY_RAMP,
  RS_HISTORY_STEPS,
  RS_HISTORY_SINE,
  RS_HISTORY_TABLE
} rs_history_kind;

typedef struct rs_history {
  rs_history_kind kind;
  double value;                     /* constant */
  double from, to, start, duration; /* ramp: from until start, linear, then to */
  double mean, amplitude, frequency,
      phase;     /* sine: mean + amplitude*sin(2 pi f t + phase), phase in rad */
  size_t n;      /* steps / table: number of points */
  double *t, *v; /* steps / table: times (strictly increasing) and values */
} rs_history;

/* Value at time t (s). Steps hold the value until the next step time; before the
 * first point, steps and tables hold their first value, after the last the last. */
double rs_history_eval(const rs_history *h, double t);
/* Rate d/dt at time t (0 for constant and steps; one-sided (right) at kinks). */
double rs_history_rate(const rs_history *h, double t);
/* 1 if the history is constant in time. */
int rs_history_is_constant(const rs_history *h);
/* Smallest breakpoint (kink or jump) strictly greater than t, or +INFINITY. */
double rs_history_next_breakpoint(const rs_history *h, double t);
/* Largest |value| over [t0, t1] (used for validation and scales). */
double rs_history_max_abs(const rs_history *h, double t0, double t1);
/* Integral of |value| over [t0, t1] (e.g. the distance rolled at a velocity history),
 * piece by piece between breakpoints: exact for constants, steps, ramps and tables (a
 * piece whose sign changes: Simpson's rule on 64 intervals), sines by Simpson's rule on 64
 * intervals per period at least. */
double rs_history_integral_abs(const rs_history *h, double t0, double t1);
/* Minimum value over [t0, t1]. */
double rs_history_min(const rs_history *h, double t0, double t1);
void rs_history_free(rs_history *h);
/* Deep copy. Returns RS_OK or RS_ERR_INTERNAL (out of memory). */
int rs_history_copy(rs_history *dst, const rs_history *src);

#endif
