/* Per-point cost of a steady sweep line (bench/robust3d; never run by ctest): the case's
 * sweep solved as `rollsim sweep` solves it (the same continuation line, far-first order,
 * midpoints and fallbacks), without the netCDF file, printing for every point in the
 * order solved: its index, the swept value, its Newton iterations, its wall time and
 * F_x/(mu F_n). Only the last swept key is run (the others at their first value: give
 * them with --set).
 * Usage: rollsim_bench_points CASE.yaml [--set KEY=VALUE]... */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h" /* rs_wall_clock */
#include "io/case.h"
#include "io/case_sweep.h"
#include "study/sweep_lines.h"

typedef struct points {
  const double *values;
  double mu, last;
  int failed;
} points;

static int point_done(void *ctx, size_t j, int status, const rs_diag *d, long newton,
                      const char *why)
{
  points *p = ctx;
  const double now = rs_wall_clock();
  if (status != RS_OK) {
    p->failed++;
    printf("%3zu %12.6g %7ld %9.4f failed: %s\n", j, p->values[j], newton, now - p->last, why);
  } else {
    printf("%3zu %12.6g %7ld %9.4f %10.6f\n", j, p->values[j], newton, now - p->last,
           d->Fx / (p->mu * d->Fn));
  }
  fflush(stdout);
  p->last = now;
  return RS_OK;
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: %s CASE.yaml [--set KEY=VALUE]...\n", argv[0]);
    return 2;
  }
  const char **sets = calloc((size_t)argc + 1, sizeof *sets);
  int nsets = 0;
  for (int i = 2; i < argc; i++) {
    if (!strcmp(argv[i], "--set") && i + 1 < argc)
      sets[nsets++] = argv[++i];
    else {
      fprintf(stderr, "%s: unknown argument %s\n", argv[0], argv[i]);
      return 2;
    }
  }
  rs_msg msg = {{0}};
  rs_sweep sw;
  rs_case c;
  if (rs_case_load(&c, argv[1], sets, nsets, &msg) != RS_OK) {
    fprintf(stderr, "%s\n", msg.text);
    return 2;
  }
  if (rs_sweep_load(&sw, &c, &msg) != RS_OK) {
    fprintf(stderr, "%s\n", msg.text);
    rs_case_free(&c);
    return 2;
  }
  const rs_sweep_axis *ax = &sw.axes[sw.naxes - 1];
  /* the other axes at their first values */
  rs_case_override *fixed = calloc((size_t)sw.naxes, sizeof *fixed);
  for (int a = 0; a < sw.naxes - 1; a++)
    fixed[a] =
        (rs_case_override){.key = rs_case_key_index(sw.axes[a].key), .value = sw.axes[a].values[0]};
  points p = {.values = ax->values, .mu = c.mu};
  rs_stats stats = {0};
  long refined = 0, midpoints = 0;
  volatile sig_atomic_t stop = 0;
  const rs_sweep_line line = {.base = &c,
                              .fixed = fixed,
                              .nfixed = sw.naxes - 1,
                              .key = rs_case_key_index(ax->key),
                              .values = ax->values,
                              .n = (size_t)ax->n,
                              .first_point = -1,
                              .point_done = point_done,
                              .ctx = &p,
                              .interrupt_flag = &stop,
                              .stats = &stats,
                              .refined = &refined,
                              .midpoints = &midpoints};
  printf("#  j %12s %7s %9s %10s\n", ax->key, "newton", "wall[s]", "Fx/(muFn)");
  const double t0 = rs_wall_clock();
  p.last = t0;
  const int status = rs_sweep_line_eval(&line, &msg);
  printf("# total: newton %ld, GMRES %ld, halved %ld, midpoints %ld, wall %.3f s, failed %d\n",
         stats.nonlin_iters, stats.lin_solves, refined, midpoints, rs_wall_clock() - t0, p.failed);
  if (status != RS_OK) fprintf(stderr, "%s\n", msg.text);
  rs_case_free(&c);
  rs_sweep_free(&sw);
  free(fixed);
  free(sets);
  return status == RS_OK && !p.failed ? 0 : 3;
}
