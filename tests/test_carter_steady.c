/* Carter's 2D steady rolling solution (docs/verification.md 2): for the reference case
 * a'/a = 1 - |xi| R/(mu a) = 0.6 and F_x/(mu F_n) = 1 - (a'/a)^2 = 0.64. The first-
 * order upwind discretisation converges linearly in dx: relative error < 1.5 % at
 * dx = a/25, < 0.5 % at dx = a/100, observed order in [0.7, 1.3]; the adhesion
 * zone is within 2 cells of 2a'. Also: xi -> -xi flips F_x, and in full adhesion
 * F_x is linear in xi (docs/verification.md 7). Grids: potential contact area +-1.04a
 * so that dx = a/25, a/50, a/100 give 52, 104, 208 cells. */
#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

#include <stdlib.h>

static int solve(rs_case *c, double *fx_rel, int *n_adh, double *dx, double *fx, rs_stats *st)
{
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  rs_steady *s = NULL;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_work w;
  rs_work_create(&w, &m);
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, st, &msg);
  if (status != RS_OK) {
    printf("FAIL steady solve: %s\n", msg.text);
  } else {
    rs_diag d;
    ts_diagnostics(&m, &w, 0.0, y, yp, &d, NULL, NULL, NULL);
    *fx_rel = d.Fx / (m.par.friction.mu * d.Fn);
    *fx = d.Fx;
    *n_adh = d.count[RS_ADHESION];
    *dx = m.grid.dx;
  }
  rs_steady_free(s);
  rs_work_free(&w);
  free(y);
  free(yp);
  rs_model_free(&m);
  return status;
}

int main(void)
{
  const double exact = 0.64, adh_exact = 1.2; /* 2a' in units of a (a = 1.00001 mm) */
  const int cells[3] = {52, 104, 208};
  double err[3], fxr[3];
  for (int k = 0; k < 3; k++) {
    rs_case c;
    ts_carter_case(&c, cells[k]);
    c.extent = 1.04;
    int nadh = 0;
    double dx = 0, fx = 0;
    rs_stats st = {0};
    if (solve(&c, &fxr[k], &nadh, &dx, &fx, &st)) return 1;
    err[k] = fabs(fxr[k] - exact) / exact;
    printf("cells %d dx %.5f: Fx/(mu Fn) = %.6f, rel. error %.3e, adhesion %d cells (%.4f mm), "
           "Newton %ld\n",
           cells[k], dx, fxr[k], err[k], nadh, nadh * dx, st.nonlin_iters);
    char what[128];
    snprintf(what, sizeof what, "adhesion zone length at %d cells, within 2 cells of 2a'",
             cells[k]);
    ts_check(what, nadh * dx, adh_exact * 1.00001, 2.0 * dx);
  }
  ts_check("relative error at dx = a/25 below 1.5 %", err[0], 0.0, 0.015);
  ts_check("relative error at dx = a/100 below 0.5 %", err[2], 0.0, 0.005);
  const double p1 = log2(err[0] / err[1]), p2 = log2(err[1] / err[2]);
  ts_check("observed order a/25 -> a/50", p1, 1.0, 0.3);
  ts_check("observed order a/50 -> a/100", p2, 1.0, 0.3);

  /* Symmetry xi -> -xi, and linearity in full adhesion (|xi| = 1e-8, 1e-8*2). */
  rs_case c;
  ts_carter_case(&c, 52);
  double f_pos, f_neg, f_small, f_small2, r;
  int nadh;
  double dx;
  rs_stats st = {0};
  c.creepage.value = 2.4e-4;
  if (solve(&c, &r, &nadh, &dx, &f_pos, &st)) return 1;
  c.creepage.value = -2.4e-4;
  if (solve(&c, &r, &nadh, &dx, &f_neg, &st)) return 1;
  ts_check("xi -> -xi flips F_x (relative)", f_pos / f_neg, -1.0, 1e-12);
  c.creepage.value = -1e-8;
  if (solve(&c, &r, &nadh, &dx, &f_small, &st)) return 1;
  c.creepage.value = -2e-8;
  if (solve(&c, &r, &nadh, &dx, &f_small2, &st)) return 1;
  ts_check("full adhesion: F_x linear in xi (F(2e-8)/F(1e-8))", f_small2 / f_small, 2.0, 2e-5);
  return ts_failures ? 1 : 0;
}
