/* The conjugate-gradient normal solver (normal_cg.c) against the direct active-set
 * method (docs/verification.md: an independent path through the code) on grids that take
 * the CG path, Carter's case at its load (contact over 95 % of the grid) and at 0.3
 * of it (contact over half the grid, as within a normal-load history).
 *
 * Tolerances. Both methods solve the same discrete problem, whose solution is unique
 * (A is positive definite on zero-sum pressures). An error e of the pressure leaves a
 * gap residual r = A_CC e on the contact cells, and ||e||_2 <= ||r||_2 / lambda_min with
 * lambda_min = 0.708 (A(0) - A(1)); CG stops at ||r||_2 <= 1e-11 (A(0) - A(1))/2 p_max,
 * and the direct LU's residual (evaluated in long double) gives 4e-11 p_max on 1000
 * cells. So the pressures agree to 1e-10 p_max. delta is the mean over the contact of
 * A p + h, which is about sum_j A_ij p_j: a pressure error of 1e-10 p_max moves it by
 * at most 1e-10 p_max / mean(p) ~ 1.3e-10 relative: 2e-10 |delta|.
 * Complementarity with the gap from direct sums: p >= 0 exactly; gap within
 * 1e-12 (h_max + |delta|) (the solvers' penetration tolerance) of 0 on the contact
 * and above -that outside. The load: dx sum p = load, 1e-12 relative. The CG pressure
 * on 1000 cells matches Hertz (a, p0 within 1 %, as test_normal_hertz on 100 cells). */
#include "physics/model.h"
#include "physics/normal.h"
#include "test_support.h"

#include <stdlib.h>

/* Gap h - delta + A p at every cell by direct sums (not the FFT path). */
static void gap_direct(const rs_model *m, const double *pn, double delta, double *gap)
{
  for (int i = 0; i < m->grid.n; i++) {
    double g = m->grid.x[i] * m->grid.x[i] / (2.0 * m->par.radius) - delta;
    for (int j = 0; j < m->grid.n; j++) g += rs_elastic2d_norm(&m->el.line, i - j) * pn[j];
    gap[i] = g;
  }
}

static void check_grid(int cells, double load_fraction)
{
  rs_case c;
  ts_carter_case(&c, cells);
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return;
  }
  const int n = m.grid.n;
  const double load = load_fraction * m.normal_load;
  double *p_dir = malloc((size_t)n * sizeof *p_dir);
  double *p_cg = malloc((size_t)n * sizeof *p_cg);
  double *p_auto = malloc((size_t)n * sizeof *p_auto);
  double *gap = malloc((size_t)n * sizeof *gap);
  double d_dir = 0.0, d_cg = 0.0, d_auto = 0.0;
  int it_dir = 0, it_cg = 0, it_auto = 0;
  rs_elastic_work ew;
  rs_elastic_work_create(&ew, &m.el);
  printf("-- %d cells, load %g N/mm\n", cells, load);
  int st = rs_normal2d_solve_with(&m.el.line, &ew.line, m.gap, load, RS_NORMAL2D_DIRECT, p_dir,
                                  &d_dir, &it_dir, &msg);
  if (st == RS_OK)
    st = rs_normal2d_solve_with(&m.el.line, &ew.line, m.gap, load, RS_NORMAL2D_CG, p_cg, &d_cg,
                                &it_cg, &msg);
  if (st == RS_OK)
    st = rs_normal2d_solve(&m.el.line, &ew.line, m.gap, load, p_auto, &d_auto, &it_auto, &msg);
  if (st != RS_OK) {
    printf("FAIL solve: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  printf("     iterations: direct %d (active set), CG %d\n", it_dir, it_cg);

  double pmax = 0.0, dp = 0.0, pmin_cg = INFINITY, sum_dir = 0.0, sum_cg = 0.0, hmax = 0.0;
  int same_as_cg = 1;
  for (int i = 0; i < n; i++) {
    pmax = fmax(pmax, p_dir[i]);
    dp = fmax(dp, fabs(p_cg[i] - p_dir[i]));
    pmin_cg = fmin(pmin_cg, p_cg[i]);
    sum_dir += p_dir[i];
    sum_cg += p_cg[i];
    hmax = fmax(hmax, m.grid.x[i] * m.grid.x[i] / (2.0 * m.par.radius));
    same_as_cg = same_as_cg && p_auto[i] == p_cg[i];
  }
  ts_check("pressure CG - direct, relative to p_max", dp / pmax, 0.0, 1e-10);
  ts_check("approach delta CG - direct, relative", (d_cg - d_dir) / fabs(d_dir), 0.0, 2e-10);
  ts_check("load dx sum p, CG (relative)", m.grid.dx * sum_cg / load, 1.0, 1e-12);
  ts_check("load dx sum p, direct (relative)", m.grid.dx * sum_dir / load, 1.0, 1e-12);
  ts_check_true("no tension in the CG pressure (p >= 0)", pmin_cg >= 0.0);
  ts_check_true("rs_normal2d_solve takes the CG path on this grid",
                n >= RS_NORMAL2D_CG_FROM && same_as_cg && d_auto == d_cg && it_auto == it_cg);

  gap_direct(&m, p_cg, d_cg, gap);
  const double tol_gap = 1e-12 * (hmax + fabs(d_cg));
  double gap_contact = 0.0, gap_min_out = INFINITY;
  int in_contact = 0;
  for (int i = 0; i < n; i++) {
    if (p_cg[i] > 0.0) {
      gap_contact = fmax(gap_contact, fabs(gap[i]));
      in_contact++;
    } else {
      gap_min_out = fmin(gap_min_out, gap[i]);
    }
  }
  printf("     contact cells %d of %d\n", in_contact, n);
  ts_check("CG: |gap| on the contact, relative to h_max + |delta|",
           gap_contact / (hmax + fabs(d_cg)), 0.0, tol_gap / (hmax + fabs(d_cg)));
  ts_check_true("CG: no penetration outside the contact (gap >= -tol)", gap_min_out >= -tol_gap);

  if (load_fraction == 1.0 && cells >= 1000) {
    double second = 0.0;
    for (int i = 0; i < n; i++) second += m.grid.x[i] * m.grid.x[i] * p_cg[i] * m.grid.dx;
    const double a_est = 2.0 * sqrt(second / load); /* Int x^2 p / Int p = a^2/4 */
    ts_check("CG: a from the pressure vs Hertz, 1 %", a_est, m.hertz_a, 0.01 * m.hertz_a);
    ts_check("CG: p_max vs Hertz p0, 1 %", pmax, m.hertz_p0, 0.01 * m.hertz_p0);
  }
done:
  free(p_dir);
  free(p_cg);
  free(p_auto);
  free(gap);
  rs_elastic_work_free(&ew);
  rs_model_free(&m);
}

int main(void)
{
  check_grid(300, 1.0);
  check_grid(300, 0.3);
  check_grid(1000, 1.0);
  check_grid(1000, 0.3);
  /* The CG method needs a load to carry: an error, not a guess. */
  rs_case c;
  ts_carter_case(&c, 300);
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) == RS_OK) {
    double *pn = malloc((size_t)m.grid.n * sizeof *pn);
    rs_elastic_work ew;
    rs_elastic_work_create(&ew, &m.el);
    ts_check_true("CG with zero load returns an error",
                  rs_normal2d_solve_with(&m.el.line, &ew.line, m.gap, 0.0, RS_NORMAL2D_CG, pn, NULL,
                                         NULL, &msg) != RS_OK);
    rs_elastic_work_free(&ew);
    free(pn);
    rs_model_free(&m);
  }
  return ts_failures ? 1 : 0;
}
