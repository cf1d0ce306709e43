/* Histories (physics/history.h): each form evaluated at chosen times against
 * hand-computed values, its rate (right derivative at kinks), breakpoints, and
 * the range helpers used for validation. */
#include "physics/history.h"
#include "base/status.h"

#include <math.h>
#include <stdio.h>

static int failures = 0;

/* Piecewise-linear values at the chosen times are exact in binary up to one
 * rounding; sines get 1e-12 relative to their amplitude scale. */
static void check(const char *what, double got, double want, double tol)
{
  int ok = isinf(want) ? got == want : fabs(got - want) <= tol;
  if (!ok) {
    printf("FAIL %s: got %.17g, want %.17g (tol %g)\n", what, got, want, tol);
    failures++;
  }
}

static const double exact = 1e-15;

static void test_constant(void)
{
  rs_history h = {.kind = RS_HISTORY_CONSTANT, .value = 3.0};
  check("constant eval", rs_history_eval(&h, 12.0), 3.0, 0);
  check("constant rate", rs_history_rate(&h, 1.0), 0.0, 0);
  check("constant is_constant", rs_history_is_constant(&h), 1, 0);
  check("constant breakpoint", rs_history_next_breakpoint(&h, 0.0), INFINITY, 0);
  check("constant max_abs", rs_history_max_abs(&h, 0, 1), 3.0, 0);
  check("constant integral", rs_history_integral_abs(&h, 0.5, 2.5), 6.0, exact);
  check("empty integral", rs_history_integral_abs(&h, 1.0, 1.0), 0.0, 0);
}

static void test_ramp(void)
{
  /* from 1 until t = 0.5, linear to 3 at t = 1.5, then 3 */
  rs_history h = {.kind = RS_HISTORY_RAMP, .from = 1.0, .to = 3.0, .start = 0.5, .duration = 1.0};
  check("ramp before start", rs_history_eval(&h, 0.0), 1.0, 0);
  check("ramp midpoint", rs_history_eval(&h, 1.0), 2.0, exact);
  check("ramp quarter", rs_history_eval(&h, 0.75), 1.5, exact);
  check("ramp after end", rs_history_eval(&h, 2.0), 3.0, 0);
  check("ramp rate inside", rs_history_rate(&h, 1.0), 2.0, exact);
  check("ramp rate at start (right)", rs_history_rate(&h, 0.5), 2.0, exact);
  check("ramp rate at end (right)", rs_history_rate(&h, 1.5), 0.0, 0);
  check("ramp rate before", rs_history_rate(&h, 0.2), 0.0, 0);
  check("ramp breakpoint before start", rs_history_next_breakpoint(&h, 0.0), 0.5, 0);
  check("ramp breakpoint at start", rs_history_next_breakpoint(&h, 0.5), 1.5, 0);
  check("ramp breakpoint at end", rs_history_next_breakpoint(&h, 1.5), INFINITY, 0);
  check("ramp max_abs [0,1]", rs_history_max_abs(&h, 0.0, 1.0), 2.0, exact);
  check("ramp min [0,2]", rs_history_min(&h, 0.0, 2.0), 1.0, 0);
  check("ramp is_constant", rs_history_is_constant(&h), 0, 0);
  rs_history down = {
      .kind = RS_HISTORY_RAMP, .from = 0.0, .to = -2.0, .start = 0.0, .duration = 0.5};
  check("falling ramp max_abs", rs_history_max_abs(&down, 0.0, 1.0), 2.0, 0);
  check("falling ramp min", rs_history_min(&down, 0.0, 1.0), -2.0, 0);
  check("falling ramp min [0,0.25]", rs_history_min(&down, 0.0, 0.25), -1.0, exact);
  /* integral of |.|: 0.5 * 1 + the ramp's mean 2 over 1 + 0.5 * 3 */
  check("ramp integral [0,2]", rs_history_integral_abs(&h, 0.0, 2.0), 4.0, 4 * exact);
  check("ramp integral [0.25,1]", rs_history_integral_abs(&h, 0.25, 1.0), 1.0, 4 * exact);
  check("falling ramp integral [0,1]", rs_history_integral_abs(&down, 0.0, 1.0), 1.5, 4 * exact);
  /* a ramp through zero: |.| has a kink at t = 0.5 (two triangles of 1 * 0.5 / 2) */
  rs_history through = {
      .kind = RS_HISTORY_RAMP, .from = -1.0, .to = 1.0, .start = 0.0, .duration = 1.0};
  check("ramp through zero integral [0,1]", rs_history_integral_abs(&through, 0.0, 1.0), 0.5,
        4 * exact);
}

static void test_steps(void)
{
  double t[] = {0.0, 1.0, 2.0}, v[] = {1.0, 2.0, -5.0};
  rs_history h = {.kind = RS_HISTORY_STEPS, .n = 3, .t = t, .v = v};
  check("steps before first", rs_history_eval(&h, -1.0), 1.0, 0);
  check("steps holding", rs_history_eval(&h, 0.5), 1.0, 0);
  check("steps at a step time", rs_history_eval(&h, 1.0), 2.0, 0);
  check("steps just before the next", rs_history_eval(&h, 1.999), 2.0, 0);
  check("steps after last", rs_history_eval(&h, 3.0), -5.0, 0);
  check("steps rate", rs_history_rate(&h, 0.5), 0.0, 0);
  check("steps breakpoint before first", rs_history_next_breakpoint(&h, -1.0), 0.0, 0);
  check("steps breakpoint inside", rs_history_next_breakpoint(&h, 0.5), 1.0, 0);
  check("steps breakpoint at a step", rs_history_next_breakpoint(&h, 1.0), 2.0, 0);
  check("steps breakpoint at last", rs_history_next_breakpoint(&h, 2.0), INFINITY, 0);
  check("steps max_abs [0,1.5]", rs_history_max_abs(&h, 0.0, 1.5), 2.0, 0);
  check("steps max_abs [0,2]", rs_history_max_abs(&h, 0.0, 2.0), 5.0, 0);
  check("steps min [0,1.5]", rs_history_min(&h, 0.0, 1.5), 1.0, 0);
  check("steps min [0,3]", rs_history_min(&h, 0.0, 3.0), -5.0, 0);
  /* each value held until the next step time: 1 (before the first) + 1 + 2 + 5 */
  check("steps integral [-1,3]", rs_history_integral_abs(&h, -1.0, 3.0), 9.0, 4 * exact);
  check("steps integral [0.5,1.5]", rs_history_integral_abs(&h, 0.5, 1.5), 1.5, 4 * exact);

  rs_history copy;
  check("steps copy status", rs_history_copy(&copy, &h), RS_OK, 0);
  v[1] = 100.0; /* the copy is deep */
  check("steps copy eval", rs_history_eval(&copy, 1.5), 2.0, 0);
  check("steps copy points", (double)copy.n, 3.0, 0);
  rs_history_free(&copy);
  check("steps free", copy.t == NULL && copy.v == NULL && copy.n == 0, 1, 0);
}

static void test_sine(void)
{
  const double pi = 3.14159265358979323846;
  /* 1 + 2 sin(2 pi 50 t): quarter period 5 ms */
  rs_history h = {
      .kind = RS_HISTORY_SINE, .mean = 1.0, .amplitude = 2.0, .frequency = 50.0, .phase = 0.0};
  check("sine at 0", rs_history_eval(&h, 0.0), 1.0, 1e-12);
  check("sine at quarter period", rs_history_eval(&h, 0.005), 3.0, 1e-12);
  check("sine at half period", rs_history_eval(&h, 0.01), 1.0, 1e-12);
  check("sine at three quarters", rs_history_eval(&h, 0.015), -1.0, 1e-12);
  check("sine rate at 0", rs_history_rate(&h, 0.0), 2.0 * 2.0 * pi * 50.0, 1e-9);
  check("sine rate at quarter period", rs_history_rate(&h, 0.005), 0.0, 1e-9);
  check("sine breakpoint", rs_history_next_breakpoint(&h, 0.0), INFINITY, 0);
  check("sine max_abs over a period", rs_history_max_abs(&h, 0.0, 0.02), 3.0, 1e-12);
  check("sine min over a period", rs_history_min(&h, 0.0, 0.02), -1.0, 1e-12);
  check("sine min over the rising quarter", rs_history_min(&h, 0.0, 0.004), 1.0, 1e-12);
  check("sine max_abs over the rising quarter", rs_history_max_abs(&h, 0.0, 0.004),
        1.0 + 2.0 * sin(0.4 * pi), 1e-12);
  rs_history shifted = h;
  shifted.phase = pi / 2;
  check("sine with phase pi/2 at 0", rs_history_eval(&shifted, 0.0), 3.0, 1e-12);
  rs_history negative = h;
  negative.amplitude = -2.0;
  check("negative amplitude at quarter period", rs_history_eval(&negative, 0.005), -1.0, 1e-12);
  check("negative amplitude min", rs_history_min(&negative, 0.0, 0.008), -1.0, 1e-12);
  check("negative amplitude max_abs [0, 8 ms]", rs_history_max_abs(&negative, 0.0, 0.008), 1.0,
        1e-12);
  /* integral of |1 + 2 sin(wt)| over a period: (2 pi / 3 + 4 sqrt 3) / w, the negative lobe
   * (7 pi / 6 < wt < 11 pi / 6) counted positive. Simpson's rule is O(h^4) on the smooth
   * parts; the two kinks of |.| cost O(h^2) each: 1.3e-6 of the integral over one period
   * (128 intervals), 6e-8 over ten (704); 1e-5 allowed. */
  const double w = 2.0 * pi * 50.0, lobes = (2.0 * pi / 3.0 + 4.0 * sqrt(3.0)) / w;
  check("sine integral over a period", rs_history_integral_abs(&h, 0.0, 0.02), lobes, 1e-5 * lobes);
  check("sine integral over 10 periods", rs_history_integral_abs(&h, 0.0, 0.2), 10.0 * lobes,
        1e-5 * 10.0 * lobes);
  rs_history positive = h; /* mean 3: no sign change, the integral is the mean's */
  positive.mean = 3.0;
  check("sine integral without a sign change", rs_history_integral_abs(&positive, 0.0, 0.02), 0.06,
        1e-9 * 0.06);
}

static void test_table(void)
{
  double t[] = {0.0, 1.0, 3.0}, v[] = {0.0, 10.0, 0.0};
  rs_history h = {.kind = RS_HISTORY_TABLE, .n = 3, .t = t, .v = v};
  check("table interpolation", rs_history_eval(&h, 0.5), 5.0, exact);
  check("table interpolation (2nd segment)", rs_history_eval(&h, 2.0), 5.0, exact);
  check("table at a point", rs_history_eval(&h, 1.0), 10.0, 0);
  check("table before first", rs_history_eval(&h, -1.0), 0.0, 0);
  check("table after last", rs_history_eval(&h, 4.0), 0.0, 0);
  check("table rate", rs_history_rate(&h, 0.5), 10.0, exact);
  check("table rate at a point (right)", rs_history_rate(&h, 1.0), -5.0, exact);
  check("table rate after last", rs_history_rate(&h, 3.0), 0.0, 0);
  check("table breakpoint", rs_history_next_breakpoint(&h, 0.5), 1.0, 0);
  check("table breakpoint at a point", rs_history_next_breakpoint(&h, 1.0), 3.0, 0);
  check("table max_abs", rs_history_max_abs(&h, 0.0, 3.0), 10.0, 0);
  check("table max_abs between points", rs_history_max_abs(&h, 1.5, 2.5), 7.5, exact);
  check("table min", rs_history_min(&h, 0.5, 2.0), 5.0, exact);
  check("table is_constant", rs_history_is_constant(&h), 0, 0);
  check("table integral", rs_history_integral_abs(&h, 0.0, 3.0), 15.0, 16 * exact);
  double ts[] = {0.0, 2.0}, vs[] = {-1.0, 1.0}; /* through zero at t = 1: two triangles */
  rs_history cross = {.kind = RS_HISTORY_TABLE, .n = 2, .t = ts, .v = vs};
  check("table integral through zero", rs_history_integral_abs(&cross, 0.0, 2.0), 1.0, 4 * exact);
}

int main(void)
{
  test_constant();
  test_ramp();
  test_steps();
  test_sine();
  test_table();
  if (failures) {
    printf("%d failure(s)\n", failures);
    return 1;
  }
  printf("all history checks passed\n");
  return 0;
}
