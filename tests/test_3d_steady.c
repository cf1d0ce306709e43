/* 3D elliptic contact, steady rolling (docs/verification.md 10-13):
 *  - Kalker's linear theory: at tiny creepages (full adhesion) F_x = -G a b C11 xi,
 *    F_y = -G a b (C22 eta + sqrt(a b) C23 phi), M_z = G (a b)^(3/2) C23 eta, for a/b = 1
 *    and a/b = 0.40 (Ry = 4 Rx), nu = 0.28, on 22^2, 44^2 and 88^2 cells over +-1.1a,
 *    +-1.1b. The first-order scheme converges as the grid is refined; the staircase
 *    ellipse of the discrete contact adds a part that does not fall evenly, so the test
 *    asks: every error at most 2 % on the finest grid (target 10), the errors of F_x and of
 *    F_y(eta) falling on every refinement, those of the C23 terms (F_y(phi), M_z(eta)) not
 *    larger on the finest grid than on the coarsest. The spin moment M_z(phi) against C33
 *    (tabulated for a <= b, physics/kalker.h): at most 2.5 % on 88^2, and its first-order
 *    extrapolation from 88^2 and 176^2 within 1 %.
 *  - the 2D limit: a patch with b/a = 18 (Ry = 100 Rx) at pure xi carries on its centre
 *    line the 2D line-contact traction of the same a and p0 (Hertz pressure in both, so
 *    that only the tangential kernels differ): the finite length changes the kernel by
 *    terms of relative size (a/b)^2 ~ 3e-3; tolerance 1 % of p0 mu.
 *  - symmetry: eta -> -eta flips F_y and M_z and keeps F_x (partial slip); with
 *    eta = phi = 0 the field mirrors in y (p_x even, p_y odd), to 1e-9 of max |p|.
 *  - plasticity: tau_c0 -> infinity equals the elastic solution; k_tau = 0 at full sliding
 *    saturates at sum min(mu p_n, tau_c0) dA; frictional and plastic power >= 0.
 * Every steady result is also checked cell by cell by the solver (rs_model_check_steady:
 * slip opposite to p, plastic flow along p). */
#include <stdlib.h>

#include "physics/kalker.h"
#include "solve/steady.h"
#include "test_support.h"

/* Steady solution and its quantities; y (allocated) if ys is not NULL. */
static int solve(rs_case *c, rs_model *m, rs_diag *d, double **ys)
{
  rs_msg msg = {{0}};
  if (rs_model_from_case(m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return 1;
  }
  double *y = calloc((size_t)m->lay.neq, sizeof *y), *yp = calloc((size_t)m->lay.neq, sizeof *yp);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  rs_steady_free(s);
  if (status == RS_OK) {
    rs_work w;
    rs_work_create(&w, m);
    status = ts_diagnostics(m, &w, 0.0, y, yp, d, NULL, NULL, NULL);
    rs_work_free(&w);
  }
  if (status != RS_OK) {
    printf("FAIL steady 3D solve: %s\n", msg.text);
    ts_failures++;
  }
  free(yp);
  if (ys)
    *ys = y;
  else
    free(y);
  return status != RS_OK;
}

static void kalker(double ratio)
{
  const int grids[3] = {22, 44, 88};
  double err[5][3]; /* F_x(xi), F_y(eta), M_z(eta), F_y(phi), M_z(phi) on each grid */
  double a_over_b = 0.0;
  for (int g = 0; g < 3; g++) {
    const double small = 1e-7; /* creepage; spin in 1/mm */
    for (int q = 0; q < 3; q++) {
      rs_case c;
      ts_ellipse_case(&c, grids[g], ratio, q == 0 ? -small : 0.0, q == 1 ? -small : 0.0,
                      q == 2 ? -small : 0.0);
      rs_model m;
      rs_diag d;
      if (solve(&c, &m, &d, NULL)) return;
      rs_kalker k;
      rs_msg msg = {{0}};
      const double a = m.hertz_a, b = m.hertz_b, ab = a * b, G = c.shear_modulus;
      a_over_b = a / b;
      if (rs_kalker_coefficients(a / b, c.poisson_ratio, &k, &msg) != RS_OK) {
        printf("FAIL Kalker table: %s\n", msg.text);
        ts_failures++;
        rs_model_free(&m);
        return;
      }
      if (q == 0) err[0][g] = d.Fx / (G * ab * k.c11 * small) - 1.0;
      if (q == 1) {
        err[1][g] = d.Fy / (G * ab * k.c22 * small) - 1.0;
        err[2][g] = d.Mz / (-G * pow(ab, 1.5) * k.c23 * small) - 1.0;
      }
      if (q == 2) {
        err[3][g] = d.Fy / (G * ab * sqrt(ab) * k.c23 * small) - 1.0;
        err[4][g] = d.Mz / (G * ab * ab * k.c33 * small) - 1.0;
      }
      if (d.count[RS_SLIP] + d.count[RS_PLASTIC] != 0) {
        printf("FAIL a tiny creepage must leave the contact in full adhesion\n");
        ts_failures++;
      }
      rs_model_free(&m);
    }
  }
  static const char *const what[5] = {"F_x(xi) vs C11", "F_y(eta) vs C22", "M_z(eta) vs C23",
                                      "F_y(phi) vs C23", "M_z(phi) vs C33"};
  for (int q = 0; q < 5; q++) {
    char label[160];
    printf("a/b = %.3f, %s: relative error %+.4f / %+.4f / %+.4f on 22^2 / 44^2 / 88^2 "
           "(order 44->88: %.2f)\n",
           a_over_b, what[q], err[q][0], err[q][1], err[q][2],
           log(fabs(err[q][1] / err[q][2])) / log(2.0));
    /* M_z(phi) carries the largest first-order error (the spin's traction grows towards the
     * patch's edge, where the staircase ellipse cuts cells): 6 % on 44^2, so 2.5 % on 88^2. */
    snprintf(label, sizeof label, "a/b = %.2f, %s: |error| on 88^2", a_over_b, what[q]);
    ts_check(label, fabs(err[q][2]), 0.0, q == 4 ? 0.025 : 0.02);
    if (q < 2) {
      snprintf(label, sizeof label, "a/b = %.2f, %s: error falls on every refinement", a_over_b,
               what[q]);
      ts_check_true(label, fabs(err[q][1]) < fabs(err[q][0]) && fabs(err[q][2]) < fabs(err[q][1]));
    } else {
      snprintf(label, sizeof label, "a/b = %.2f, %s: finest error below the coarsest", a_over_b,
               what[q]);
      ts_check_true(label, fabs(err[q][2]) < fabs(err[q][0]));
    }
  }
  /* The spin moment extrapolated to zero cell size with the scheme's first order from 88^2
   * and 176^2, M = 2 M_176 - M_88, against C33: within 1 % (the table's three digits give
   * up to 0.4 %; the extrapolation's own error, from the part of the error that is not
   * first order, is below 0.5 % on these grids). */
  rs_case c;
  const double small = 1e-7;
  ts_ellipse_case(&c, 176, ratio, 0.0, 0.0, -small);
  rs_model m;
  rs_diag d;
  if (solve(&c, &m, &d, NULL)) return;
  rs_kalker k;
  rs_msg msg = {{0}};
  const double ab = m.hertz_a * m.hertz_b;
  rs_kalker_coefficients(m.hertz_a / m.hertz_b, c.poisson_ratio, &k, &msg);
  const double e176 = d.Mz / (c.shear_modulus * ab * ab * k.c33 * small) - 1.0;
  rs_model_free(&m);
  char label[160];
  printf("a/b = %.3f, M_z(phi) vs C33: relative error %+.4f on 176^2, extrapolated %+.4f\n",
         a_over_b, e176, 2.0 * e176 - err[4][2]);
  snprintf(label, sizeof label, "a/b = %.2f, M_z(phi) extrapolated from 88^2, 176^2 vs C33",
           a_over_b);
  ts_check(label, 2.0 * e176 - err[4][2], 0.0, 0.01);
}

static void limit_2d(void)
{
  const int nx = 40, ny = 21;
  rs_case c;
  ts_ellipse_case(&c, nx, 100.0, -1e-3, 0.0, 0.0);
  c.cells_y = ny;
  c.extent = c.extent_y = 1.05;
  c.normal_load.value = 5000.0;
  c.normal_solution = RS_NORMAL_HERTZ;
  rs_model m;
  rs_diag d;
  double *y = NULL;
  if (solve(&c, &m, &d, &y)) return;
  /* the 2D line contact of the same a and p0: q = pi a p0 / 2, a^2 = 4 q R (1 - nu)/(pi G) */
  rs_case c2;
  ts_carter_case(&c2, nx);
  c2.mu = c.mu;
  c2.creepage.value = c.creepage.value;
  c2.normal_solution = RS_NORMAL_HERTZ;
  const double a = m.hertz_a, p0 = m.hertz_p0, q = RS_PI * a * p0 / 2.0;
  c2.normal_load.value = q;
  c2.radius = a * a * RS_PI * c2.shear_modulus / (4.0 * q * (1.0 - c2.poisson_ratio));
  c2.extent = 1.05;
  rs_model m2;
  rs_diag d2;
  double *y2 = NULL;
  if (!solve(&c2, &m2, &d2, &y2)) {
    const int row = ny / 2; /* y = 0 */
    double diff = 0.0;
    for (int i = 0; i < nx; i++) diff = fmax(diff, fabs(y[row * nx + i] - y2[i]));
    printf("2D limit: b/a = %.1f, centre row y = %.2g mm\n", m.hertz_b / m.hertz_a, m.grid.y[row]);
    ts_check("2D limit: max |p_x(centre line) - p_x(2D)| / (mu p0)", diff / (c.mu * p0), 0.0, 0.01);
    free(y2);
    rs_model_free(&m2);
  }
  free(y);
  rs_model_free(&m);
}

static void symmetry(void)
{
  rs_case c;
  rs_model m;
  rs_diag dp, dm;
  double *y = NULL;
  ts_ellipse_case(&c, 22, 2.0, -1e-3, 5e-4, 0.0);
  if (solve(&c, &m, &dp, NULL)) return;
  rs_model_free(&m);
  ts_ellipse_case(&c, 22, 2.0, -1e-3, -5e-4, 0.0);
  if (solve(&c, &m, &dm, NULL)) return;
  rs_model_free(&m);
  printf("partial slip: F_x %.6g N, F_y %.6g N, M_z %.6g N mm, slip cells %d\n", dp.Fx, dp.Fy,
         dp.Mz, dp.count[RS_SLIP]);
  ts_check_true("partial slip (the symmetry is not trivial)", dp.count[RS_SLIP] > 0);
  ts_check("eta -> -eta: F_x kept (relative)", dm.Fx / dp.Fx, 1.0, 1e-9);
  ts_check("eta -> -eta: F_y flips (relative)", dm.Fy / dp.Fy, -1.0, 1e-9);
  ts_check("eta -> -eta: M_z flips (relative)", dm.Mz / dp.Mz, -1.0, 1e-9);
  ts_ellipse_case(&c, 22, 2.0, -1e-3, 0.0, 0.0);
  if (solve(&c, &m, &dp, &y)) return;
  const int nx = m.grid.nx, ny = m.grid.ny, n = m.grid.n;
  double pmax = 0.0, asym = 0.0;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      const int I = j * nx + i, M = (ny - 1 - j) * nx + i;
      pmax = fmax(pmax, hypot(y[I], y[n + I]));
      asym = fmax(asym, fmax(fabs(y[I] - y[M]), fabs(y[n + I] + y[n + M])));
    }
  ts_check("eta = phi = 0: p_x(x, -y) = p_x(x, y), p_y(x, -y) = -p_y(x, y), / max |p|", asym / pmax,
           0.0, 1e-9);
  free(y);
  rs_model_free(&m);
}

static void plastic_limits(void)
{
  rs_case c;
  rs_model m;
  rs_diag de, dh, ds;
  ts_ellipse_case(&c, 22, 2.0, -1e-3, 3e-4, 0.0);
  if (solve(&c, &m, &de, NULL)) return;
  rs_model_free(&m);
  c.has_plasticity = 1;
  c.tau_c0 = 1e9;
  c.k_tau = 1000.0;
  c.tau_c_min = 1e8;
  if (solve(&c, &m, &dh, NULL)) return;
  rs_model_free(&m);
  ts_check("tau_c0 = 1e9: F_x equals the elastic (relative)", dh.Fx / de.Fx, 1.0, 1e-9);
  ts_check("tau_c0 = 1e9: F_y equals the elastic (relative)", dh.Fy / de.Fy, 1.0, 1e-9);
  ts_check_true("tau_c0 = 1e9: no plastic cell", dh.count[RS_PLASTIC] == 0);
  /* full sliding along x with perfect plasticity: |p| = min(mu p_n, tau_c0) everywhere */
  ts_ellipse_case(&c, 22, 2.0, -0.05, 0.0, 0.0);
  c.has_plasticity = 1;
  c.tau_c0 = 100.0;
  c.k_tau = 0.0;
  c.tau_c_min = 10.0;
  double *y = NULL;
  if (solve(&c, &m, &ds, &y)) return;
  double bound = 0.0, magnitude = 0.0;
  for (int i = 0; i < m.grid.n; i++) {
    bound += fmin(m.bound[i], c.tau_c0) * m.grid.area;
    magnitude += hypot(y[i], y[m.grid.n + i]) * m.grid.area;
  }
  printf("k_tau = 0 at full sliding: F_x %.8g N, sum |p| dA %.8g N, sum min(mu p_n, tau_c0) dA "
         "= %.8g N (%d plastic, %d slip cells)\n",
         ds.Fx, magnitude, bound, ds.count[RS_PLASTIC], ds.count[RS_SLIP]);
  /* |p| = min(mu p_n, tau_c0) in every contact cell, exactly; the direction of p follows the
   * slip, which the elastic displacements tilt off x by |Du_el/Dt| / (V |xi|) ~ 1e-3: F_x is
   * below the sum of |p| by the cosine of that angle, ~1e-6 */
  ts_check("k_tau = 0, full sliding: sum |p| dA / sum min(mu p_n, tau_c0) dA", magnitude / bound,
           1.0, 1e-9);
  ts_check("k_tau = 0, full sliding: F_x / sum min(mu p_n, tau_c0) dA", ds.Fx / bound, 1.0, 1e-5);
  ts_check_true("k_tau = 0, full sliding: plastic and slipping cells present",
                ds.count[RS_PLASTIC] > 0 && ds.count[RS_SLIP] > 0);
  ts_check_true("frictional power >= 0", ds.frictional_power >= 0.0);
  ts_check_true("plastic power >= 0", ds.plastic_power >= 0.0);
  free(y);
  rs_model_free(&m);
}

int main(void)
{
  kalker(1.0);
  kalker(4.0);
  limit_2d();
  symmetry();
  plastic_limits();
  return ts_failures ? 1 : 0;
}
