/* The long-transient estimate (study/warnings.h, rs_cost_watch) on synthetic step histories with a
 * synthetic clock (a fixed wall time per step), never on measured wall time. A start-up's step
 * density is taken as rho(t) = rho0 exp(-(t - t_j)/tau) after each input jump t_j, whose steps
 * N(t) integrate analytically; the estimate must recover the steps still to come and the ETA
 * from windows of such a history. Cases: cases/default.yaml (2D, constant inputs: Hertz
 * half-width a = 1.00001 mm, V = 30000 mm/s, contact length 2a/V = 6.66673e-5 s, 40 mm rolled),
 * cases/wheel_rail_3d.yaml (3D, creepage steps at 0 and 1 ms of 2 ms: a = 5.87338 mm, 2a/V =
 * 3.91559e-4 s), cases/sine_creepage.yaml (a creepage that changes continuously).
 * Usage: test_cost_watch CASES_DIR */
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
  } else {
    printf("ok   %s\n", what);
  }
}

static int near(double got, double want, double rel)
{
  const int ok = fabs(got - want) <= rel * fabs(want);
  if (!ok) printf("     got %.10g, want %.10g (rel %.3g)\n", got, want, fabs(got / want - 1));
  return ok;
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

/* The number after `key` in text (-1 if absent). */
static double after(const char *text, const char *key)
{
  const char *p = strstr(text, key);
  return p ? atof(p + strlen(key)) : -1.0;
}

/* A synthetic history: density rho0 exp(-(t - t_j)/tau) after each jump t_j (jumps[0] = 0). */
typedef struct history {
  double rho0, tau;
  const double *jumps;
  int njumps;
} history;

static double steps_at(const history *h, double t)
{
  double n = 0.0;
  for (int j = 0; j < h->njumps && h->jumps[j] < t; j++) {
    const double end = j + 1 < h->njumps && h->jumps[j + 1] < t ? h->jumps[j + 1] : t;
    n += h->rho0 * h->tau * -expm1(-(end - h->jumps[j]) / h->tau);
  }
  return n;
}

static double density_at(const history *h, double t)
{
  double tj = 0.0;
  for (int j = 0; j < h->njumps && h->jumps[j] <= t; j++) tj = h->jumps[j];
  return h->rho0 * exp(-(t - tj) / h->tau);
}

static int load(rs_case *c, const char *dir, const char *name, const char *const *sets, int n)
{
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  rs_msg msg = {{0}};
  if (rs_case_load(c, path, sets, n, &msg) != RS_OK) {
    printf("FAIL loading %s: %s\n", path, msg.text);
    return 0;
  }
  return 1;
}

int main(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: test_cost_watch CASES_DIR\n");
    return 2;
  }
  rs_case c2, c3, cs;
  if (!load(&c2, argv[1], "default.yaml", NULL, 0) ||
      !load(&c3, argv[1], "wheel_rail_3d.yaml", NULL, 0) ||
      !load(&cs, argv[1], "sine_creepage.yaml", NULL, 0))
    return 1;
  const double L2 = 2.0 * 1.00001 / 30000.0, L3 = 2.0 * 5.87338 / 30000.0; /* 2a/V, s */
  char text[4096];

  /* 1. The decay time: the prior with one window (or two too close to tell); measured from two
   * equal windows of an exponential history (their mean densities are rho at the middles times
   * the same factor sinh(x)/x: the ratio is exp(span/tau) exactly); no decay seen: none. */
  check("1: 2D prior 4 contact lengths",
        near(rs_cost_decay_time(&c2, 0.0, 0.0, 0.0, 1e7, 1e-5), 4.0 * L2, 1e-5));
  check("1: 3D prior 1.5 contact lengths",
        near(rs_cost_decay_time(&c3, 0.0, 0.0, 0.0, 1e7, 1e-5), 1.5 * L3, 1e-5));
  {
    const history h = {1e7, 1.7 * L2, (const double[]){0.0}, 1};
    const double w = 2e-4, a = 2e-5; /* windows [a, a + w], [a + w, a + 2w] */
    const double r1 = (steps_at(&h, a + w) - steps_at(&h, a)) / w;
    const double r2 = (steps_at(&h, a + 2 * w) - steps_at(&h, a + w)) / w;
    check("1: measured from windows 0.75 prior decay times apart: tau = 1.7 contact lengths",
          near(rs_cost_decay_time(&c2, 0.0, r1, a + 0.5 * w, r2, a + 1.5 * w), h.tau, 1e-9));
    check("1: windows 1e-5 s apart (< half the prior 2.7e-4 s): the prior",
          near(rs_cost_decay_time(&c2, 0.0, r1, 1e-5, r2, 2e-5), 4.0 * L2, 1e-5));
    check("1: no decay between the same windows: none",
          isinf(rs_cost_decay_time(&c2, 0.0, r2, a + 0.5 * w, r1, a + 1.5 * w)));
  }
  check("1: a creepage that changes continuously: no decay",
        isinf(rs_cost_decay_time(&cs, 0.0, 0.0, 0.0, 1e7, 1e-5)));

  /* 2. Steps still to come = the history's own, exactly, when its decay is the one used: at
   * constant inputs until the end (default.yaml: 40 mm is 20 contact lengths, below the 25 of
   * settling), and across the creepage step of wheel_rail_3d.yaml, whose second transient
   * starts as dense as the first did. */
  {
    const history h = {5e7, 4.0 * L2, (const double[]){0.0}, 1};
    const double t = 1e-4, end = c2.end_time;
    check("2: 2D constant inputs: rho tau (1 - exp(-(end - t)/tau))",
          near(rs_cost_steps_left(&c2, 0.0, t, density_at(&h, t), h.tau),
               steps_at(&h, end) - steps_at(&h, t), 1e-12));
    check("2: 2D, at the present density all along: rho (end - t)",
          near(rs_cost_steps_left(&c2, 0.0, t, density_at(&h, t), INFINITY),
               density_at(&h, t) * (end - t), 1e-12));
  }
  {
    const history h = {2e7, 1.5 * L3, (const double[]){0.0, 1e-3}, 2};
    const double end = c3.end_time;
    for (int k = 0; k < 2; k++) {
      const double t = k ? 1.2e-3 : 1e-4;
      char what[128];
      snprintf(what, sizeof what, "2: 3D, t = %g s: both transients' steps (steps at 0, 1 ms)", t);
      check(what, near(rs_cost_steps_left(&c3, 0.0, t, density_at(&h, t), h.tau),
                       steps_at(&h, end) - steps_at(&h, t), 1e-12));
    }
  }

  /* 3. The whole watch on a synthetic 3D start-up of wheel_rail_3d.yaml with records every 5e-5
   * s (the case's interval) and a clock of `cost` s per step: the history of 2. has 1.93e4 steps
   * in all (as many as a 44 x 44 run of the case, whose start-up the old rule put at 3.65e4 still
   * to come after 1e-4 s). At 5 ms a step the rest takes under 2 minutes: silent; at 12 ms a
   * step it warns, with the history's steps still to come and their time. The windows see the
   * density at their middles, 2.5e-5 s before their ends: exp(2.5e-5/tau) - 1 = 4.4 % more
   * steps than at the end; 6 % covers it. */
  {
    const history h = {2e7, 1.5 * L3, (const double[]){0.0, 1e-3}, 2};
    const double total = steps_at(&h, c3.end_time);
    check("3: the history's steps: 1.9e4", total > 1.8e4 && total < 2.0e4);
    for (int k = 0; k < 2; k++) {
      const double cost = k ? 0.012 : 0.005;
      rs_cost_watch w;
      rs_cost_watch_init(&w, &c3, 1936, 0.0, 0.0);
      int warned = 0;
      double t_warn = 0.0;
      for (int r = 1; r <= 40 && !warned; r++) {
        const double t = 5e-5 * r;
        const long n = (long)steps_at(&h, t);
        warned = record(&w, t, n, cost * n, text, sizeof text);
        t_warn = t;
      }
      const double left = steps_at(&h, c3.end_time) - steps_at(&h, t_warn);
      if (!k) {
        check("3: 5 ms a step (1.5 min in all): no warning", !warned && w.done);
        continue;
      }
      check("3: 12 ms a step (3.9 min in all): warned", warned);
      check("3: steps still to come as the history's (6 %)",
            near(after(text, "the rest needs about "), left, 0.06));
      const char *p = strstr(text, "ETA ");
      p = p ? strchr(p, '(') : NULL;
      check("3: ETA in seconds = steps x 12 ms (6 %)", p && near(atof(p + 1), left * cost, 0.06));
      check("3: the flat estimate is given beside it",
            strstr(text, "if they stayed as dense") != NULL &&
                strstr(text, "after each input step") != NULL);
      check("3: a varying input: no steady hint", strstr(text, "simulation.mode: steady") == NULL);
      printf("%s", text);
    }
  }

  /* 4. A creepage that changes continuously keeps the steps dense: the old rule, the window's
   * density until the end (sine_creepage.yaml with 10 s: 100 steps per 1e-4 s at 5 ms each). */
  {
    cs.end_time = 10.0;
    rs_cost_watch w;
    rs_cost_watch_init(&w, &cs, 100, 0.0, 0.0);
    int warned = 0;
    double t = 0.0;
    for (int r = 1; r <= 200 && !warned; r++) {
      t = 1e-4 * r;
      warned = record(&w, t, 100L * r, 0.5 * r, text, sizeof text);
    }
    const char *p = strstr(text, "ETA ");
    p = p ? strchr(p, '(') : NULL;
    check("4: warned with the second window", warned);
    check("4: steps = 1e6 per s x (10 s - t)",
          near(after(text, "the rest needs about "), 1e6 * (10.0 - t), 0.002));
    check("4: ETA = 5 ms x those steps", p && near(atof(p + 1), 5e3 * (10.0 - t), 0.002));
    check("4: said to stay at this density", strstr(text, "at this density to the end") != NULL);
  }

  /* 5. A first projection below the threshold ends the watch, whatever comes later; a first
   * record after the confirmation time opens the second window all the same. */
  {
    rs_cost_watch w;
    rs_cost_watch_init(&w, &c2, 100, 0.0, 0.0);
    record(&w, 1e-5, 100, 0.6, text, sizeof text);
    check("5: 2D, 100 steps per 1e-5 s at 5 ms each: first projection 13 s: done",
          record(&w, 2e-5, 200, 1.1, text, sizeof text) == 0 && !*text && w.done);
    check("5: nothing later", record(&w, 3e-5, 100000, 9.0, text, sizeof text) == 0 && !*text);
    rs_cost_watch_init(&w, &c3, 1936, 0.0, 0.0);
    check("5: 3D, first record late (8.9 s for 5e-5 s, 177 s projected): second window opens",
          record(&w, 5e-5, 558, 8.9, text, sizeof text) == 0 && !*text && w.confirming);
    check("5: second projection (40 steps in 1.5 s: 31 s): silent and done",
          record(&w, 1.5e-4, 598, 10.4, text, sizeof text) == 0 && !*text && w.done);
  }

  rs_case_free(&c2);
  rs_case_free(&c3);
  rs_case_free(&cs);
  if (failures) {
    printf("%d failures\n", failures);
    return 1;
  }
  printf("cost watch: all checks passed\n");
  return 0;
}
