/* Solver timings without file I/O or process start-up (bench/run measures whole
 * rollsim runs): Carter's steady elastic case (cases/carter2d.yaml) on grids of
 * 50..1600 cells; per grid the model set-up (influence coefficients and the
 * discrete normal problem) and the steady tangential solve from p = 0 with each
 * linear-algebra path (median of REPS runs, ms), Newton iterations, and the cost
 * exponent p of t ~ N^p (least squares of log t against log N) of each path.
 * Usage: rollsim_bench_solve [REPS] [MAXCELLS]   (default 5, 1600)
 * The KLU path is the linear algebra of the solver before issue 7. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "physics/model.h"
#include "study/run.h"
#include "solve/steady.h"
#include "bench_util.h"
#include "base/util.h" /* rs_wall_clock */

int main(int argc, char **argv)
{
  const int reps = argc > 1 ? atoi(argv[1]) : 5;
  const int maxcells = argc > 2 ? atoi(argv[2]) : 1600;
  const int grids[] = {50, 100, 200, 400, 800, 1600};
  const rs_linear paths[] = {RS_LINEAR_KLU, RS_LINEAR_DENSE, RS_LINEAR_KRYLOV, RS_LINEAR_AUTO};
  const char *names[] = {"klu", "dense", "krylov", "auto"};
  enum { NP = 4, NG = 6 };
  double logn[NG], logt[NP][NG];
  int ng = 0;
  printf("Carter steady elastic: model set-up (normal problem) and tangential solve, median of %d, "
         "ms\n",
         reps);
  printf("%6s %9s", "cells", "setup");
  for (int k = 0; k < NP; k++) printf(" %9s %5s", names[k], "newt");
  printf("\n");
  double *t = malloc((size_t)reps * sizeof *t);
  for (int g = 0; g < NG && grids[g] <= maxcells; g++, ng++) {
    rs_case c;
    rs_msg msg = {{0}};
    char cells[48];
    snprintf(cells, sizeof cells, "grid.cells=%d", grids[g]);
    const char *sets[] = {cells};
    if (rs_case_load(&c, RS_CARTER_CASE, sets, 1, &msg) != RS_OK) {
      fprintf(stderr, "%s\n", msg.text);
      return 1;
    }
    rs_model m;
    for (int r = 0; r < reps; r++) {
      const double t0 = rs_wall_clock();
      if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
        fprintf(stderr, "%s\n", msg.text);
        return 1;
      }
      t[r] = rs_wall_clock() - t0;
      if (r + 1 < reps) rs_model_free(&m);
    }
    printf("%6d %9.3f", grids[g], 1e3 * bench_median(t, reps));
    logn[g] = log(grids[g]);
    double *y = malloc((size_t)m.lay.neq * sizeof *y);
    for (int k = 0; k < NP; k++) {
      rs_stats st = {0};
      int krep = paths[k] == RS_LINEAR_KLU && grids[g] > 400 ? 1 : reps; /* slow: once */
      for (int r = 0; r < krep; r++) {
        memset(y, 0, (size_t)m.lay.neq * sizeof *y);
        memset(&st, 0, sizeof st);
        rs_steady *s = NULL;
        const double t0 = rs_wall_clock();
        int status = rs_steady_create_with(&s, &m, NULL, paths[k], &msg);
        if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
        t[r] = rs_wall_clock() - t0;
        rs_steady_free(s);
        if (status != RS_OK) {
          fprintf(stderr, "%s: %s\n", names[k], msg.text);
          return 1;
        }
      }
      const double tm = bench_median(t, krep);
      logt[k][g] = log(tm);
      printf(" %9.3f %5ld", 1e3 * tm, st.nonlin_iters);
      fflush(stdout);
    }
    printf("\n");
    free(y);
    rs_model_free(&m);
    rs_case_free(&c);
  }
  printf("cost exponent p (t ~ N^p, least squares over %d grids):", ng);
  for (int k = 0; k < NP; k++) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int g = 0; g < ng; g++) {
      sx += logn[g];
      sy += logt[k][g];
      sxx += logn[g] * logn[g];
      sxy += logn[g] * logt[k][g];
    }
    printf(" %s %.2f", names[k], (ng * sxy - sx * sy) / (ng * sxx - sx * sx));
  }
  printf("\n");
  free(t);
  return 0;
}
