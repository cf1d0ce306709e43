/* A grid given in millimetres (grid.x_range, docs/case-file.md) is the same discrete
 * problem as the grid given in Hertz half-widths (grid.extent) when the edges agree:
 * Carter's case on 100 cells over +-1.05a, then on x_range = the edges the first grid
 * got. Cell centres, influence coefficients, normal pressure and the steady traction
 * must be identical (the same arithmetic on the same numbers: tolerance 0), and a
 * shifted range [x_lo - dx, x_hi - dx] with the same cells moves the centres by dx. */
#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

static int solve(rs_case *c, rs_model *m, double **y, rs_msg *msg)
{
  if (rs_model_from_case(m, c, msg) != RS_OK) return 1;
  *y = calloc((size_t)m->lay.neq, sizeof **y);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, m, NULL, msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, *y, &st, msg);
  rs_steady_free(s);
  return status != RS_OK;
}

int main(void)
{
  rs_case c;
  ts_carter_case(&c, 100);
  rs_model a, b, shifted;
  double *ya = NULL, *yb = NULL;
  rs_msg msg = {{0}};
  if (solve(&c, &a, &ya, &msg)) {
    printf("FAIL extent grid: %s\n", msg.text);
    return 1;
  }
  c.grid_from_range = 1;
  c.x_range[0] = a.grid.x_lo;
  c.x_range[1] = a.grid.x_hi;
  if (solve(&c, &b, &yb, &msg)) {
    printf("FAIL x_range grid: %s\n", msg.text);
    return 1;
  }
  printf("edges from extent: [%.17g, %.17g] mm\n", a.grid.x_lo, a.grid.x_hi);
  double dx_cells = 0.0, dcoef = 0.0, dpn = 0.0, dp = 0.0;
  for (int i = 0; i < a.grid.n; i++) {
    dx_cells = fmax(dx_cells, fabs(a.grid.x[i] - b.grid.x[i]));
    dpn = fmax(dpn, fabs(a.pn[i] - b.pn[i]));
  }
  for (int k = -a.grid.n; k <= a.grid.n; k++)
    dcoef = fmax(dcoef, fabs(rs_elastic2d_tang(&a.el.line, k) - rs_elastic2d_tang(&b.el.line, k)));
  for (int i = 0; i < a.lay.neq; i++) dp = fmax(dp, fabs(ya[i] - yb[i]));
  ts_check("same cells: max |x_extent - x_range| (mm)", dx_cells, 0.0, 0.0);
  ts_check("same influence coefficients: max difference", dcoef, 0.0, 0.0);
  ts_check("same normal pressure: max difference (N/mm^2)", dpn, 0.0, 0.0);
  ts_check("same steady state: max difference of every unknown", dp, 0.0, 0.0);

  c.x_range[0] = a.grid.x_lo - a.grid.dx;
  c.x_range[1] = a.grid.x_hi - a.grid.dx;
  if (rs_model_from_case(&shifted, &c, &msg) != RS_OK) {
    printf("FAIL shifted grid: %s\n", msg.text);
    return 1;
  }
  double shift_err = 0.0;
  for (int i = 0; i < a.grid.n; i++)
    shift_err = fmax(shift_err, fabs(shifted.grid.x[i] - (a.grid.x[i] - a.grid.dx)));
  ts_check("shifted range: centres moved by -dx, max error (mm)", shift_err, 0.0, 1e-14);
  rs_model_free(&shifted);
  rs_model_free(&a);
  rs_model_free(&b);
  free(ya);
  free(yb);
  return ts_failures ? 1 : 0;
}
