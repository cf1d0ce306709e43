/* Steady rolling with local plasticity on fine grids (issue 7): the paper's Figure 7
 * case (Carter, mu = 0.5, tau_c0 = 35 N/mm^2, xi = -4e-4) from rest at 400 cells for
 * hardening, perfectly plastic and softening layers. Newton from p = 0 cycles on such
 * grids (the trailing end of a work-hardening plastic zone moves by about one cell
 * per iteration); the solver must still return a solution, i.e. a state that
 *  - satisfies the discrete equations: max |F| <= 1e-9 max g (F in traction units;
 *    the Newton tolerance is 1e-10 max g in the scaled norm);
 *  - is admissible: |p| <= min(g, tau_c) (1 + 1e-9) in every cell;
 *  - has u* >= 0 that never decreases along the material path (u*_I >= u*_{I+1};
 *    material enters fresh at the leading edge I = n-1, and D(u*) / Dt = |D u_pl / Dt|).
 * Also the grid tools of grid sequencing: a model regridded to its own size is the
 * same model; regridded to half the cells it carries the same load; interpolation
 * between grids is exact for linear fields between the outer cell centres. */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

static void check_solution(double k_rel, int cells)
{
  rs_case c;
  ts_fig7_case(&c, cells, k_rel);
  rs_model m;
  rs_msg msg = {{0}};
  char what[160];
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return;
  }
  const int n = m.grid.n;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  double *F = calloc((size_t)m.lay.neq, sizeof *F);
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  snprintf(what, sizeof what, "k_rel = %g, %d cells: steady solve from rest (%ld Newton its)",
           k_rel, cells, st.nonlin_iters);
  ts_check_true(what, status == RS_OK);
  if (status == RS_OK) {
    ts_residual(&m, &w, 0.0, y, yp, 0.0, F);
    double fbig = 0.0, gmax = 0.0, excess = 0.0, usmin = INFINITY, decrease = 0.0, usmax = 0.0;
    for (int i = 0; i < m.lay.neq; i++) fbig = fmax(fbig, fabs(F[i]));
    for (int i = 0; i < n; i++) {
      const double g = m.bound[i], lim = fmin(g, rs_model_yield_limit(&m, i, y[2 * n + i]));
      gmax = fmax(gmax, g);
      excess = fmax(excess, fabs(y[i]) - lim);
      usmin = fmin(usmin, y[2 * n + i]);
      usmax = fmax(usmax, y[2 * n + i]);
      if (i + 1 < n) decrease = fmax(decrease, y[2 * n + i + 1] - y[2 * n + i]);
    }
    snprintf(what, sizeof what, "k_rel = %g: max |F| / max g", k_rel);
    ts_check(what, fbig / gmax, 0.0, 1e-9);
    snprintf(what, sizeof what, "k_rel = %g: max(|p| - min(g, tau_c)) / max g", k_rel);
    ts_check(what, fmax(excess, 0.0) / gmax, 0.0, 1e-9);
    snprintf(what, sizeof what, "k_rel = %g: min u* (mm)", k_rel);
    ts_check(what, fmin(usmin, 0.0), 0.0, 1e-15);
    snprintf(what, sizeof what, "k_rel = %g: largest decrease of u* along the path / max u*",
             k_rel);
    ts_check(what, usmax > 0.0 ? decrease / usmax : 0.0, 0.0, 1e-9);
  }
  rs_steady_free(s);
  rs_work_free(&w);
  free(y);
  free(yp);
  free(F);
  rs_model_free(&m);
}

static void check_regrid(void)
{
  rs_case c;
  ts_fig7_case(&c, 120, 0.6);
  rs_model m, same, half;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK ||
      rs_model_regrid(&m, m.grid.n, &same, &msg) != RS_OK ||
      rs_model_regrid(&m, m.grid.n / 2, &half, &msg) != RS_OK) {
    printf("FAIL regrid: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double dp = 0.0, dcoef = 0.0;
  for (int i = 0; i < m.grid.n; i++) dp = fmax(dp, fabs(same.pn[i] - m.pn[i]));
  for (int k = -m.grid.n; k <= m.grid.n; k++)
    dcoef =
        fmax(dcoef, fabs(rs_elastic2d_tang(&same.el.line, k) - rs_elastic2d_tang(&m.el.line, k)));
  ts_check("regrid to the same size: max |delta p_n| / p0", dp / m.hertz_p0, 0.0, 1e-14);
  ts_check("regrid to the same size: max |delta A(k)| / A(0)",
           dcoef / rs_elastic2d_tang(&m.el.line, 0), 0.0, 1e-14);
  double load = 0.0;
  for (int i = 0; i < half.grid.n; i++) load += half.pn[i] * half.grid.dx;
  ts_check("regrid to half the cells: dx sum p_n / q", load / c.normal_load.value, 1.0, 1e-10);
  ts_check("regrid to half the cells: same extent", half.grid.n * half.grid.dx,
           m.grid.n * m.grid.dx, 1e-12);

  /* Linear u_pl and u* from the coarse grid are reproduced on the fine one between
   * the outer coarse centres. */
  double *yc = calloc((size_t)half.lay.neq, sizeof *yc),
         *yf = calloc((size_t)m.lay.neq, sizeof *yf);
  for (int i = 0; i < half.grid.n; i++) {
    yc[half.grid.n + i] = 2.0 * half.grid.x[i] + 1.0;
    yc[2 * half.grid.n + i] = 3.0 - half.grid.x[i];
  }
  rs_work w;
  rs_work_create(&w, &m);
  const rs_inputs in = ts_inputs(&m, 0.0);
  rs_model_interpolate_state(&half, yc, &m, &w, &in, yf, &msg);
  double err = 0.0;
  for (int i = 0; i < m.grid.n; i++) {
    if (m.grid.x[i] < half.grid.x[0] || m.grid.x[i] > half.grid.x[half.grid.n - 1]) continue;
    err = fmax(err, fabs(yf[m.grid.n + i] - (2.0 * m.grid.x[i] + 1.0)));
    err = fmax(err, fabs(yf[2 * m.grid.n + i] - (3.0 - m.grid.x[i])));
  }
  ts_check("interpolation of linear fields, max error", err, 0.0, 1e-12);
  rs_work_free(&w);
  free(yc);
  free(yf);
  rs_model_free(&half);
  rs_model_free(&same);
  rs_model_free(&m);
}

int main(void)
{
  check_regrid();
  const double k_rel[] = {0.98, 0.6, 0.3, 0.1, 0.0, -0.333};
  for (int k = 0; k < 6; k++) check_solution(k_rel[k], 400);
  return ts_failures ? 1 : 0;
}
