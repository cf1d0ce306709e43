/* A 3D model on a gap given by the caller (rs_model_params.gap_at), the way wheel-rail
 * patches enter the solvers (docs/model.md "Undeformed gap from the caller"):
 *  - the Hertz gap x^2/(2 Rx) + y^2/(2 Ry) given as a function on the same grid gives the
 *    same steady solution bit for bit as the radii (the same numbers reach the solver);
 *  - that gap centred at (x0, y0) on a grid shifted by (x0, y0) gives the same contact moved:
 *    the elastic kernels depend on cell offsets only and the rigid slip is uniform without
 *    spin, so F_x, F_y agree to rounding (1e-9 of mu F_n) and the moment about the grid's
 *    origin is the centred one plus x0 F_y - y0 F_x; the pressure moves with it, cell for
 *    cell to 1e-9 of p0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "solve/steady.h"
#include "test_support.h"

typedef struct quad {
  double x0, y0, rx, ry;
} quad;

static double quad_gap(const void *ctx, double x, double y)
{
  const quad *q = ctx;
  return (x - q->x0) * (x - q->x0) / (2.0 * q->rx) + (y - q->y0) * (y - q->y0) / (2.0 * q->ry);
}

typedef struct result {
  rs_diag d;
  double *pn; /* [n] */
  double dx, dy, p0;
} result;

static int solve(const rs_model_params *par, result *r)
{
  rs_msg msg = {{0}};
  rs_model m;
  if (rs_model_create(&m, par, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return 1;
  }
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  rs_steady_free(s);
  if (status == RS_OK) {
    rs_work w;
    rs_work_create(&w, &m);
    status = ts_diagnostics(&m, &w, 0.0, y, yp, &r->d, NULL, NULL, NULL);
    rs_work_free(&w);
  }
  if (status != RS_OK) {
    printf("FAIL steady solve: %s\n", msg.text);
    ts_failures++;
  }
  r->pn = malloc((size_t)m.grid.n * sizeof *r->pn);
  if (r->pn) memcpy(r->pn, m.pn, (size_t)m.grid.n * sizeof *r->pn);
  r->p0 = m.hertz_p0;
  r->dx = m.grid.dx;
  r->dy = (m.grid.y_hi - m.grid.y_lo) / m.grid.ny;
  free(y);
  free(yp);
  rs_model_free(&m);
  return status != RS_OK;
}

int main(void)
{
  rs_case c;
  ts_ellipse_case(&c, 24, 1.6, -2e-3, 1e-3, 0.0); /* partial slip, a/b = 0.79 */
  rs_model_params par;
  rs_model_params_from_case(&c, &par);
  /* the grid over +-1.1 a x +-1.1 b of the Hertz ellipse, given as ranges */
  rs_model probe;
  rs_msg msg = {{0}};
  if (rs_model_create(&probe, &par, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  const double a = probe.hertz_a, b = probe.hertz_b, mu_fn = c.mu * c.normal_load.value;
  rs_model_free(&probe);
  par.grid_from_range = 1;
  par.x_range[0] = -1.1 * a;
  par.x_range[1] = 1.1 * a;
  par.y_range[0] = -1.1 * b;
  par.y_range[1] = 1.1 * b;
  result radii, given, moved;
  if (solve(&par, &radii)) return 1;

  quad q = {0.0, 0.0, par.radius, par.radius_y};
  par.gap_at = quad_gap;
  par.gap_ctx = &q;
  if (solve(&par, &given)) return 1;
  ts_check("the Hertz gap as a function = the radii: F_x bit for bit", given.d.Fx, radii.d.Fx, 0.0);
  ts_check("F_y bit for bit", given.d.Fy, radii.d.Fy, 0.0);
  ts_check("M_z bit for bit", given.d.Mz, radii.d.Mz, 0.0);

  /* the shift: a whole number of cells, so the shifted grid's centres are the centred ones'
   * moved (up to the rounding of the ranges) */
  const double dx = radii.dx, dy = radii.dy;
  q.x0 = 3.0 * dx;
  q.y0 = -2.0 * dy;
  par.x_range[0] += q.x0;
  par.x_range[1] += q.x0;
  par.y_range[0] += q.y0;
  par.y_range[1] += q.y0;
  if (solve(&par, &moved)) return 1;
  const double tol = 1e-9 * mu_fn;
  ts_check("the moved contact: F_x the same (N)", moved.d.Fx, radii.d.Fx, tol);
  ts_check("the moved contact: F_y the same (N)", moved.d.Fy, radii.d.Fy, tol);
  ts_check("the moved contact: M_z about the origin = M_z + x0 F_y - y0 F_x (N mm)", moved.d.Mz,
           radii.d.Mz + q.x0 * radii.d.Fy - q.y0 * radii.d.Fx, tol * a);
  double dp = 0.0;
  for (int i = 0; radii.pn && moved.pn && i < 24 * 24; i++)
    dp = fmax(dp, fabs(moved.pn[i] - radii.pn[i]));
  ts_check("the moved pressure, cell for cell (largest difference, N/mm^2)", dp, 0.0,
           1e-9 * radii.p0);
  free(radii.pn);
  free(given.pn);
  free(moved.pn);
  return ts_failures ? 1 : 0;
}
