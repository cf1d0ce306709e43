/* Timings of the 3D elastic products and of the 3D normal solve (physics/elastic3d.h,
 * physics/normal3d.h) on the wheel-rail Hertz case of test_normal3d (F = 10 kN, Rx = 460,
 * Ry = 300 mm, G = 82000, nu = 0.28; grid n x n over +-1.1a x +-1.1b). Medians of repeated
 * runs; also the discrete solution's a, b (second moments) and p_max against Hertz.
 * Usage: rollsim_bench_3d [CELLS...] (default 32 64 128). Never run by ctest. */
#include "physics/elastic3d.h"
#include "physics/normal3d.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../bench/bench_util.h"
#include "base/util.h"

static void run(int cells)
{
  const double G = 82000.0, nu = 0.28, load = 10000.0, A = 0.5 / 460.0, B = 0.5 / 300.0;
  rs_msg msg = {{0}};
  rs_hertz_ellipse hz;
  rs_hertz3d(load, A, B, G, nu, &hz, &msg);
  const rs_grid3d grid = {.nx = cells,
                          .ny = cells,
                          .x0 = -1.1 * hz.a,
                          .y0 = -1.1 * hz.b,
                          .dx = 2.2 * hz.a / cells,
                          .dy = 2.2 * hz.b / cells};
  const int n = cells * cells;
  rs_elastic3d el;
  rs_elastic3d_work work;
  double t0 = rs_wall_clock();
  if (rs_elastic3d_create(&el, cells, cells, grid.dx, grid.dy, G, nu, &msg) != RS_OK ||
      rs_elastic3d_work_create(&work, &el, &msg) != RS_OK) {
    printf("%s\n", msg.text);
    return;
  }
  const double t_create = rs_wall_clock() - t0;
  double *h = malloc((size_t)n * sizeof *h), *pn = malloc((size_t)n * sizeof *pn);
  double *ux = malloc((size_t)(n + cells) * sizeof *ux),
         *uy = malloc((size_t)(n + cells) * sizeof *uy);
  rs_normal3d_gap(&grid, A, B, h);
  rs_hertz3d_pressure(&hz, &grid, pn);
  enum { REPS = 31 };
  double t_tang[REPS], t_norm[REPS], t_solve[9];
  const int inner = cells <= 32 ? 50 : cells <= 64 ? 10 : 2;
  for (int r = 0; r < REPS; r++) {
    t0 = rs_wall_clock();
    for (int k = 0; k < inner; k++) rs_elastic3d_apply_tang(&el, &work, pn, h, ux, uy, cells + 1);
    t_tang[r] = (rs_wall_clock() - t0) / inner;
    t0 = rs_wall_clock();
    for (int k = 0; k < inner; k++) rs_elastic3d_apply_norm(&el, &work, pn, ux, cells + 1);
    t_norm[r] = (rs_wall_clock() - t0) / inner;
  }
  int iters = 0;
  double delta = 0.0;
  for (int r = 0; r < 9; r++) {
    t0 = rs_wall_clock();
    rs_normal3d_solve(&el, &work, h, load, NULL, pn, &delta, &iters, &msg);
    t_solve[r] = rs_wall_clock() - t0;
  }
  double sum = 0.0, mxx = 0.0, myy = 0.0, pmax = 0.0;
  for (int j = 0; j < cells; j++)
    for (int i = 0; i < cells; i++) {
      const double x = grid.x0 + (i + 0.5) * grid.dx, y = grid.y0 + (j + 0.5) * grid.dy;
      const double p = pn[j * cells + i];
      sum += p;
      mxx += x * x * p;
      myy += y * y * p;
      pmax = fmax(pmax, p);
    }
  printf("%4d x %-4d padded %4d x %-4d create %8.2f ms  tang product %8.3f ms  normal product "
         "%8.3f ms  normal solve %8.2f ms (%3d CG it.)  errors a %+.2e b %+.2e p0 %+.2e\n",
         cells, cells, work.mx, work.my, 1e3 * t_create, 1e3 * bench_median(t_tang, REPS),
         1e3 * bench_median(t_norm, REPS), 1e3 * bench_median(t_solve, 9), iters,
         sqrt(5.0 * mxx / sum) / hz.a - 1.0, sqrt(5.0 * myy / sum) / hz.b - 1.0,
         pmax / hz.p0 - 1.0);
  free(h);
  free(pn);
  free(ux);
  free(uy);
  rs_elastic3d_work_free(&work);
  rs_elastic3d_free(&el);
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    run(32);
    run(64);
    run(128);
  }
  for (int i = 1; i < argc; i++) run(atoi(argv[i]));
  return 0;
}
