/* Timings of the discrete 2D normal problem alone (rs_normal2d_solve, model.md §3):
 * Carter's case (cases/carter2d.yaml, q = 178.9 N/mm, grid +-1.05 a) on grids of
 * 100..MAXCELLS cells; per grid the median of REPS solves (ms) and the active-set
 * iterations. The model set-up (influence coefficients, FFT plans) is outside the
 * timed region.
 * Usage: rollsim_bench_normal [REPS] [MAXCELLS]   (default 5, 3200) */
#include <stdio.h>
#include <stdlib.h>

#include "rollsim/model.h"
#include "rollsim/normal.h"
#include "util.h" /* rs_wall_clock */

static int cmp(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp);
  return v[(n - 1) / 2];
}

int main(int argc, char **argv) {
  const int reps = argc > 1 ? atoi(argv[1]) : 5;
  const int maxcells = argc > 2 ? atoi(argv[2]) : 3200;
  const int grids[] = {100, 200, 400, 800, 1600, 3200};
  enum { NG = 6 };
  printf("Carter normal problem (rs_normal2d_solve), median of %d, ms\n", reps);
  printf("%6s %10s %5s\n", "cells", "solve", "iter");
  double *t = malloc((size_t)reps * sizeof *t);
  for (int g = 0; g < NG && grids[g] <= maxcells; g++) {
    rs_case c;
    rs_msg msg = {{0}};
    char cells[48];
    snprintf(cells, sizeof cells, "grid.cells=%d", grids[g]);
    const char *sets[] = {cells};
    rs_model m;
    if (rs_case_load(&c, RS_CARTER_CASE, sets, 1, &msg) != RS_OK ||
        rs_model_create(&m, &c, &msg) != RS_OK) {
      fprintf(stderr, "%s\n", msg.text);
      return 1;
    }
    double *pn = malloc((size_t)m.n * sizeof *pn);
    int iter = 0;
    for (int r = 0; r < reps; r++) {
      double delta;
      const double t0 = rs_wall_clock();
      if (rs_normal2d_solve(&m.el, m.x, m.radius, m.normal_load, pn, &delta, &iter, &msg) !=
          RS_OK) {
        fprintf(stderr, "%s\n", msg.text);
        return 1;
      }
      t[r] = rs_wall_clock() - t0;
    }
    printf("%6d %10.3f %5d\n", grids[g], 1e3 * median(t, reps), iter);
    fflush(stdout);
    free(pn);
    rs_model_free(&m);
    rs_case_free(&c);
  }
  free(t);
  return 0;
}
