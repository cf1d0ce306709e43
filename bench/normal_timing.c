/* Timings of the discrete 2D normal problem alone (docs/model.md §3): Carter's case
 * (cases/carter2d.yaml, q = 178.9 N/mm, grid +-1.05 a) on grids of 100..3200 cells
 * or the ones given; per grid and method (rs_normal2d_solve_with: DIRECT, CG and
 * AUTO, the one rs_normal2d_solve uses) the median of REPS solves (ms) and the
 * iterations, and the largest pressure difference CG - DIRECT relative to p_max.
 * The model set-up (influence coefficients, FFT plans) is outside the timed region.
 * DIRECT is skipped (-) on grids above MAXDIRECT cells (default 3200: about 6 s each).
 * Usage: rollsim_bench_normal [REPS [CELLS...]]   (default 5; 100 200 400 800 1600 3200)
 * Environment: MAXDIRECT. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "physics/model.h"
#include "study/run.h"
#include "physics/normal.h"
#include "bench_util.h"
#include "base/util.h" /* rs_wall_clock */

int main(int argc, char **argv)
{
  const int reps = argc > 1 ? atoi(argv[1]) : 5;
  const int default_grids[] = {100, 200, 400, 800, 1600, 3200};
  const int ng = argc > 2 ? argc - 2 : 6;
  const char *maxdirect_env = getenv("MAXDIRECT");
  const int maxdirect = maxdirect_env ? atoi(maxdirect_env) : 3200;
  const rs_normal2d_method methods[] = {RS_NORMAL2D_DIRECT, RS_NORMAL2D_CG, RS_NORMAL2D_AUTO};
  const char *names[] = {"direct", "cg", "auto"};
  enum { NM = 3 };
  printf("Carter normal problem (rs_normal2d_solve_with), median of %d, ms\n", reps);
  printf("%6s", "cells");
  for (int k = 0; k < NM; k++) printf(" %10s %5s", names[k], "iter");
  printf(" %12s\n", "|cg-dir|/pmax");
  double *t = malloc((size_t)reps * sizeof *t);
  for (int g = 0; g < ng; g++) {
    const int cells_n = argc > 2 ? atoi(argv[g + 2]) : default_grids[g];
    rs_case c;
    rs_msg msg = {{0}};
    char cells[48];
    snprintf(cells, sizeof cells, "grid.cells=%d", cells_n);
    const char *sets[] = {cells};
    rs_model m;
    if (rs_case_load(&c, RS_CARTER_CASE, sets, 1, &msg) != RS_OK ||
        rs_model_from_case(&m, &c, &msg) != RS_OK) {
      fprintf(stderr, "%s\n", msg.text);
      return 1;
    }
    double *pn[NM];
    rs_elastic_work ew;
    if (rs_elastic_work_create(&ew, &m.el) != RS_OK) return 1;
    printf("%6d", cells_n);
    for (int k = 0; k < NM; k++) {
      pn[k] = malloc((size_t)m.grid.n * sizeof *pn[k]);
      if (methods[k] == RS_NORMAL2D_DIRECT && cells_n > maxdirect) {
        printf(" %10s %5s", "-", "-");
        continue;
      }
      int iter = 0;
      for (int r = 0; r < reps; r++) {
        double delta;
        const double t0 = rs_wall_clock();
        if (rs_normal2d_solve_with(&m.el.line, &ew.line, m.gap, m.normal_load, methods[k], pn[k],
                                   &delta, &iter, &msg) != RS_OK) {
          fprintf(stderr, "%s: %s\n", names[k], msg.text);
          return 1;
        }
        t[r] = rs_wall_clock() - t0;
      }
      printf(" %10.3f %5d", 1e3 * bench_median(t, reps), iter);
      fflush(stdout);
    }
    if (cells_n <= maxdirect) {
      double diff = 0.0, pmax = 0.0;
      for (int i = 0; i < m.grid.n; i++) {
        diff = fmax(diff, fabs(pn[1][i] - pn[0][i]));
        pmax = fmax(pmax, pn[0][i]);
      }
      printf(" %12.2e", diff / pmax);
    }
    printf("\n");
    for (int k = 0; k < NM; k++) free(pn[k]);
    rs_elastic_work_free(&ew);
    rs_model_free(&m);
    rs_case_free(&c);
  }
  free(t);
  return 0;
}
