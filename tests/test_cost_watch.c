/* The long-transient warning (study/warnings.h, rs_cost_watch) on synthetic records with a
 * given wall clock: the projections of both windows against the rule computed here by hand
 * (steps left = window steps x (t_busy - t) / window's simulated time, ETA = steps left x
 * window's wall time per step), with the constant inputs of cases/default.yaml (Hertz
 * half-width a = 1.00001 mm, V = 30000 mm/s, 40 mm rolled: t_busy = min(end, 25 x 2a / V)
 * = end = 1.3333e-3 s). Usage: test_cost_watch cases/default.yaml */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/warnings.h"
#include "io/case.h"

static int failures = 0;

static void check(const char *what, int ok)
{
  if (!ok) {
    printf("FAIL %s\n", what);
    failures++;
  }
}

/* One record into a fresh temporary file; returns the update's result and the text. */
static int record(rs_cost_watch *w, double t, long steps, double now, char *text, size_t len)
{
  FILE *f = tmpfile();
  if (!f) {
    printf("FAIL tmpfile\n");
    exit(1);
  }
  const int warned = rs_cost_watch_update(w, t, steps, now, f);
  rewind(f);
  const size_t n = fread(text, 1, len - 1, f);
  text[n] = '\0';
  fclose(f);
  return warned;
}

/* The ETA in seconds printed in "(... s)." at the end of the warning; -1 if none. */
static double printed_eta(const char *text)
{
  const char *p = strstr(text, "ETA ");
  if (!p) return -1.0;
  p = strchr(p, '(');
  return p ? atof(p + 1) : -1.0;
}

int main(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: test_cost_watch cases/default.yaml\n");
    return 2;
  }
  rs_case c;
  rs_msg msg = {{0}};
  if (rs_case_load(&c, argv[1], NULL, 0, &msg) != RS_OK) {
    printf("FAIL loading %s: %s\n", argv[1], msg.text);
    return 1;
  }
  const double end = c.end_time;
  check("default case: 40 mm at 30000 mm/s", fabs(end - 40.0 / 30000.0) < 1e-15);
  char text[2048];
  rs_cost_watch w;

  /* 1. A start-up whose first steps are dense: 100 steps per 1e-6 s in the first window
   * (0.005 s each: 666 s projected), 200 steps over 3.98e-4 s in the second (0.022 s each:
   * 10.3 s projected). No warning. */
  rs_cost_watch_init(&w, &c, 100, 0.0, 0.0);
  check("1: before half the probe", record(&w, 5e-7, 50, 0.4, text, sizeof text) == 0 && !*text);
  check("1: window start", record(&w, 1e-6, 100, 0.6, text, sizeof text) == 0 && !*text);
  check("1: first projection 666 s, second window opens",
        record(&w, 2e-6, 200, 1.1, text, sizeof text) == 0 && !*text && w.confirming && !w.done);
  check("1: before the confirmation time",
        record(&w, 1e-4, 300, 3.0, text, sizeof text) == 0 && !*text && !w.done);
  check("1: second projection 10.3 s: silent and done",
        record(&w, 4e-4, 400, 5.5, text, sizeof text) == 0 && !*text && w.done);
  check("1: nothing later", record(&w, 5e-4, 100000, 6.0, text, sizeof text) == 0 && !*text);

  /* 2. Steps as dense all along (100 per 1e-6 s and per 0.5 s): the warning comes with the
   * second window (1.1 s to 5.6 s: 900 steps over 9e-6 s), ETA = 0.005 x 100 / 1e-6 x
   * (end - 1.1e-5) = 661 s. */
  rs_cost_watch_init(&w, &c, 100, 0.0, 0.0);
  record(&w, 1e-6, 100, 0.6, text, sizeof text);
  check("2: first window: no warning yet",
        record(&w, 2e-6, 200, 1.1, text, sizeof text) == 0 && !*text && w.confirming);
  const int warned = record(&w, 1.1e-5, 1100, 5.6, text, sizeof text);
  const double want = 0.005 * 100.0 / 1e-6 * (end - 1.1e-5);
  const double eta = printed_eta(text);
  check("2: warned", warned == 1 && strstr(text, "rollsim: warning: a long transient"));
  /* printed as %.0f: 0.5 s */
  check("2: ETA of the second window", fabs(eta - want) <= 0.5);
  if (fabs(eta - want) > 0.5) printf("  ETA %g s, want %g s\n%s", eta, want, text);
  check("2: the window's steps and time printed",
        strstr(text, "the last 900 steps (5 ms each, 100 cells) covered 9e-06 s") != NULL);
  check("2: constant inputs: the steady hint", strstr(text, "simulation.mode: steady") != NULL);
  check("2: once", record(&w, 2e-5, 2000, 6.1, text, sizeof text) == 0 && !*text);

  /* 3. A first projection below the threshold ends the watch, whatever comes later: 100
   * steps per 1e-5 s at 0.005 s each: 66 s projected. */
  rs_cost_watch_init(&w, &c, 100, 0.0, 0.0);
  record(&w, 1e-5, 100, 0.6, text, sizeof text);
  check("3: first projection 66 s: done",
        record(&w, 2e-5, 200, 1.1, text, sizeof text) == 0 && !*text && w.done && !w.confirming);
  check("3: nothing later", record(&w, 3e-5, 100000, 9.0, text, sizeof text) == 0 && !*text);

  /* 4. Slow records: the first after the confirmation time (8.9 s for 5e-5 s from the
   * start: 8.9 / 5e-5 x (end - 5e-5) = 228 s projected) opens the second window all the
   * same; the next record decides (1.5 s for 1e-4 s: 17.7 s projected). */
  rs_cost_watch_init(&w, &c, 1936, 0.0, 0.0);
  check("4: first record late: second window opens",
        record(&w, 5e-5, 558, 8.9, text, sizeof text) == 0 && !*text && w.confirming);
  check("4: second projection 17.7 s: silent",
        record(&w, 1.5e-4, 658, 10.4, text, sizeof text) == 0 && !*text && w.done);

  rs_case_free(&c);
  if (failures) {
    printf("%d failures\n", failures);
    return 1;
  }
  printf("cost watch: all checks passed\n");
  return 0;
}
