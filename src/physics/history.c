/* Time histories of inputs (physics/history.h, docs/case-file.md, histories).
 * Piecewise-linear forms (ramp, steps, table) are evaluated exactly at their
 * breakpoints; the sine is mean + amplitude*sin(2 pi f t + phase). */
#include "physics/history.h"
#include "base/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double two_pi = 6.283185307179586476925286766559;

/* Index of the last point with t[i] <= t, or -1 if t < t[0] (binary search). */
static long last_point_at_or_before(const rs_history *h, double t)
{
  if (h->n == 0 || t < h->t[0]) return -1;
  size_t lo = 0, hi = h->n - 1;
  if (t >= h->t[hi]) return (long)hi;
  while (hi - lo > 1) { /* invariant: t[lo] <= t < t[hi] */
    size_t mid = lo + (hi - lo) / 2;
    if (h->t[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  return (long)lo;
}

double rs_history_eval(const rs_history *h, double t)
{
  switch (h->kind) {
  case RS_HISTORY_CONSTANT: return h->value;
  case RS_HISTORY_RAMP:
    if (t <= h->start) return h->from;
    if (t >= h->start + h->duration) return h->to;
    return h->from + (h->to - h->from) * (t - h->start) / h->duration;
  case RS_HISTORY_SINE: return h->mean + h->amplitude * sin(two_pi * h->frequency * t + h->phase);
  case RS_HISTORY_STEPS: {
    if (h->n == 0) return 0.0;
    long i = last_point_at_or_before(h, t);
    return h->v[i < 0 ? 0 : i];
  }
  case RS_HISTORY_TABLE: {
    if (h->n == 0) return 0.0;
    long i = last_point_at_or_before(h, t);
    if (i < 0) return h->v[0];
    if ((size_t)i == h->n - 1) return h->v[h->n - 1];
    double w = (t - h->t[i]) / (h->t[i + 1] - h->t[i]);
    return h->v[i] + w * (h->v[i + 1] - h->v[i]);
  }
  }
  return 0.0;
}

double rs_history_rate(const rs_history *h, double t)
{
  switch (h->kind) {
  case RS_HISTORY_CONSTANT:
  case RS_HISTORY_STEPS: return 0.0;
  case RS_HISTORY_RAMP: /* right derivative: the slope on [start, start + duration) */
    if (t < h->start || t >= h->start + h->duration) return 0.0;
    return (h->to - h->from) / h->duration;
  case RS_HISTORY_SINE:
    return h->amplitude * two_pi * h->frequency * cos(two_pi * h->frequency * t + h->phase);
  case RS_HISTORY_TABLE: {
    long i = last_point_at_or_before(h, t);
    if (i < 0 || (size_t)i + 1 >= h->n) return 0.0;
    return (h->v[i + 1] - h->v[i]) / (h->t[i + 1] - h->t[i]);
  }
  }
  return 0.0;
}

int rs_history_is_constant(const rs_history *h)
{
  switch (h->kind) {
  case RS_HISTORY_CONSTANT: return 1;
  case RS_HISTORY_RAMP: return h->from == h->to;
  case RS_HISTORY_SINE: return h->amplitude == 0.0 || h->frequency == 0.0;
  case RS_HISTORY_STEPS:
  case RS_HISTORY_TABLE:
    for (size_t i = 1; i < h->n; i++)
      if (h->v[i] != h->v[0]) return 0;
    return 1;
  }
  return 1;
}

double rs_history_next_breakpoint(const rs_history *h, double t)
{
  switch (h->kind) {
  case RS_HISTORY_CONSTANT:
  case RS_HISTORY_SINE: return INFINITY;
  case RS_HISTORY_RAMP:
    if (t < h->start) return h->start;
    if (t < h->start + h->duration) return h->start + h->duration;
    return INFINITY;
  case RS_HISTORY_STEPS:
  case RS_HISTORY_TABLE: {
    long i = last_point_at_or_before(h, t); /* t[i] <= t < t[i+1] */
    size_t next = (size_t)(i + 1);
    return next < h->n ? h->t[next] : INFINITY;
  }
  }
  return INFINITY;
}

/* Range [lo, hi] of a sine over [t0, t1]: the ends, plus +-1 peaks of sin
 * (phase pi/2 + 2 pi k, -pi/2 + 2 pi k) that fall inside. */
static void sine_range(const rs_history *h, double t0, double t1, double *lo, double *hi)
{
  double a = rs_history_eval(h, t0), b = rs_history_eval(h, t1);
  *lo = fmin(a, b);
  *hi = fmax(a, b);
  if (h->amplitude == 0.0 || h->frequency == 0.0) return;
  double th0 = two_pi * h->frequency * t0 + h->phase;
  double th1 = two_pi * h->frequency * t1 + h->phase;
  double amp = fabs(h->amplitude);
  /* theta = pi/2 + 2 pi k lies in [th0, th1] <=> ceil((th0 - pi/2)/2pi) <= floor((th1 - pi/2)/2pi)
   */
  int has_top = ceil((th0 - two_pi / 4) / two_pi) <= floor((th1 - two_pi / 4) / two_pi);
  int has_bottom = ceil((th0 + two_pi / 4) / two_pi) <= floor((th1 + two_pi / 4) / two_pi);
  if (h->amplitude < 0) { /* the sine's top is the history's bottom */
    int tmp = has_top;
    has_top = has_bottom;
    has_bottom = tmp;
  }
  if (has_top) *hi = h->mean + amp;
  if (has_bottom) *lo = h->mean - amp;
}

/* Range over [t0, t1] of a piecewise-linear or piecewise-constant history: the
 * extremes are at the ends or at the breakpoints inside. */
static void history_range(const rs_history *h, double t0, double t1, double *lo, double *hi)
{
  if (t1 < t0) {
    double tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  if (h->kind == RS_HISTORY_SINE) {
    sine_range(h, t0, t1, lo, hi);
    return;
  }
  double a = rs_history_eval(h, t0), b = rs_history_eval(h, t1);
  *lo = fmin(a, b);
  *hi = fmax(a, b);
  for (double tb = rs_history_next_breakpoint(h, t0); tb < t1;
       tb = rs_history_next_breakpoint(h, tb)) {
    double v = rs_history_eval(h, tb);
    *lo = fmin(*lo, v);
    *hi = fmax(*hi, v);
  }
}

double rs_history_max_abs(const rs_history *h, double t0, double t1)
{
  double lo, hi;
  history_range(h, t0, t1, &lo, &hi);
  return fmax(fabs(lo), fabs(hi));
}

/* Simpson's rule for |h| on [a, b], n (even) intervals. */
static double simpson_abs(const rs_history *h, double a, double b, int n)
{
  const double dt = (b - a) / n;
  double sum = fabs(rs_history_eval(h, a)) + fabs(rs_history_eval(h, b));
  for (int k = 1; k < n; k++) sum += (k % 2 ? 4.0 : 2.0) * fabs(rs_history_eval(h, a + k * dt));
  return sum * dt / 3.0;
}

double rs_history_integral_abs(const rs_history *h, double t0, double t1)
{
  if (!(t1 > t0)) return 0.0;
  double total = 0.0;
  for (double a = t0; a < t1;) {
    const double b = fmin(rs_history_next_breakpoint(h, a), t1);
    if (h->kind == RS_HISTORY_STEPS) { /* the value of a step holds until the next one */
      total += fabs(rs_history_eval(h, a)) * (b - a);
    } else if (h->kind == RS_HISTORY_SINE) {
      total += simpson_abs(h, a, b, 2 * (32 + (int)fmin(1e6, ceil(32.0 * h->frequency * (b - a)))));
    } else { /* linear pieces: exact, or 64 intervals where |.| has a kink inside */
      const double va = rs_history_eval(h, a), vb = rs_history_eval(h, b);
      total += simpson_abs(h, a, b, va * vb < 0.0 ? 64 : 2);
    }
    a = b;
  }
  return total;
}

double rs_history_min(const rs_history *h, double t0, double t1)
{
  double lo, hi;
  history_range(h, t0, t1, &lo, &hi);
  return lo;
}

void rs_history_free(rs_history *h)
{
  if (!h) return;
  free(h->t);
  free(h->v);
  h->t = h->v = NULL;
  h->n = 0;
}

int rs_history_copy(rs_history *dst, const rs_history *src)
{
  *dst = *src;
  dst->t = dst->v = NULL;
  if (src->n == 0 || !src->t) return RS_OK;
  dst->t = malloc(src->n * sizeof *dst->t);
  dst->v = malloc(src->n * sizeof *dst->v);
  if (!dst->t || !dst->v) {
    rs_history_free(dst);
    return RS_ERR_INTERNAL;
  }
  memcpy(dst->t, src->t, src->n * sizeof *dst->t);
  memcpy(dst->v, src->v, src->n * sizeof *dst->v);
  return RS_OK;
}
