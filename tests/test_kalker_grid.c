/* Kalker's linear theory at the recommended grid (docs/verification.md 10): at four nodes
 * of Kalker's table (a/b = 0.2, a/b = 1, b/a = 0.5 and b/a = 0.1, nu = 0.25), an elastic
 * ellipse in full adhesion at one tiny creepage at a time (xi, eta, phi) on 64^2 and 128^2
 * cells over +-1.05 a, +-1.05 b:
 *   C11 = -F_x / (G ab xi), C22 = -F_y / (G ab eta), C33 = -M_z / (G (ab)^2 phi) (a <= b),
 *   each extrapolated with the scheme's first order, C = 2 C_128 - C_64, and
 *   C23 = M_z / (G (ab)^1.5 eta) and C23 = -F_y / (G (ab)^1.5 phi) as they are on 128^2
 *   (their error is not first order: it changes sign between 32^2, 64^2 and 128^2, and
 *   2 C_128 - C_64 misses by 1.3 % at b/a = 0.1)
 * are within 1 % of the typed table (physics/kalker.h: Kalker 1990, Table E.3). 1 % is the
 * target of issue 44: over all 57 nodes this recipe is within 0.83 % (bench/kalker_coefficients,
 * bench/RESULTS.md), the table's last digit being worth up to 0.4 % (1.19), so a wrong sign,
 * normalisation or kernel fails it. The creepage, 1e-8, leaves every cell in adhesion (at
 * 1e-6 a few cells at the edge, where p_n -> 0, slip on 128^2); the solution is then linear
 * in the creepage, and the two C23, one coefficient by reciprocity from two different
 * solves, agree to 1e-5 on each grid (the steady solver's tolerance: the discrete operator
 * is reciprocal as the continuous one is; measured 1e-10 to 1e-6). */
#include <stdlib.h>

#include "physics/kalker.h"
#include "physics/normal3d.h"
#include "solve/steady.h"
#include "test_support.h"

enum { N_GRIDS = 2 };
static const int grids[N_GRIDS] = {64, 128};

/* Ry/Rx (Rx = 100 mm) of a Hertz ellipse with the given a/b, by bisection on ln(Ry/Rx):
 * a/b falls as Ry grows. */
static double radius_ratio_for(double a_over_b)
{
  double lo = -12.0, hi = 12.0;
  for (int i = 0; i < 80; i++) {
    const double mid = 0.5 * (lo + hi);
    rs_hertz_ellipse hz;
    rs_msg msg = {{0}};
    rs_hertz3d(10000.0, 1.0 / 200.0, 1.0 / (200.0 * exp(mid)), 82000.0, 0.25, &hz, &msg);
    if (hz.a / hz.b > a_over_b)
      lo = mid;
    else
      hi = mid;
  }
  return exp(0.5 * (lo + hi));
}

/* F_x, F_y, M_z of the steady full-adhesion solution; nonzero on failure. */
static int solve(double ratio, int n, int kind, double small, rs_diag *d, double *ab)
{
  rs_case c;
  ts_ellipse_case(&c, n, ratio, kind == 0 ? small : 0.0, kind == 1 ? small : 0.0,
                  kind == 2 ? small : 0.0);
  c.extent = c.extent_y = 1.05;
  c.normal_load.value = 10000.0;
  c.poisson_ratio = 0.25;
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return 1;
  }
  *ab = m.hertz_a * m.hertz_b;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  rs_steady_free(s);
  if (status == RS_OK) {
    rs_work w;
    rs_work_create(&w, &m);
    status = ts_diagnostics(&m, &w, 0.0, y, yp, d, NULL, NULL, NULL);
    rs_work_free(&w);
  }
  if (status != RS_OK) {
    printf("FAIL steady 3D solve: %s\n", msg.text);
    ts_failures++;
  } else if (d->count[RS_SLIP] + d->count[RS_PLASTIC] != 0) {
    printf("FAIL a creepage of 1e-8 must leave the contact in adhesion (%d cells slip)\n",
           d->count[RS_SLIP] + d->count[RS_PLASTIC]);
    ts_failures++;
  }
  free(y);
  free(yp);
  rs_model_free(&m);
  return status != RS_OK;
}

static void node(int row)
{
  const double small = 1e-8, G = 82000.0, a_over_b = rs_kalker_row_ratio(row);
  const double ratio = radius_ratio_for(a_over_b);
  static const char *const what[5] = {"C11 from F_x(xi)", "C22 from F_y(eta)", "C23 from M_z(eta)",
                                      "C23 from F_y(phi)", "C33 from M_z(phi)"};
  double c[5][N_GRIDS];
  for (int g = 0; g < N_GRIDS; g++)
    for (int kind = 0; kind < 3; kind++) {
      rs_diag d;
      double ab;
      if (solve(ratio, grids[g], kind, small, &d, &ab)) return;
      if (kind == 0) c[0][g] = -d.Fx / (G * ab * small);
      if (kind == 1) {
        c[1][g] = -d.Fy / (G * ab * small);
        c[2][g] = d.Mz / (G * pow(ab, 1.5) * small);
      }
      if (kind == 2) {
        c[3][g] = -d.Fy / (G * pow(ab, 1.5) * small);
        c[4][g] = -d.Mz / (G * ab * ab * small);
      }
    }
  char label[160];
  for (int q = 0; q < 5; q++) {
    const double want = rs_kalker_table(q < 3 ? q : q - 1, row, 1);
    if (isnan(want)) continue; /* C33 for a > b: not tabulated */
    const int first_order = q != 2 && q != 3;
    const double ext = first_order ? 2.0 * c[q][1] - c[q][0] : c[q][1];
    printf("a/b = %.3g, nu = 0.25, %s: %.4f (64^2), %.4f (128^2), recommended %.4f, table %g\n",
           a_over_b, what[q], c[q][0], c[q][1], ext, want);
    snprintf(label, sizeof label, "a/b = %.3g, %s%s / table - 1", a_over_b, what[q],
             first_order ? ", 2 C_128 - C_64" : " on 128^2");
    ts_check(label, ext / want - 1.0, 0.0, 0.01);
  }
  for (int g = 0; g < N_GRIDS; g++) {
    snprintf(label, sizeof label, "a/b = %.3g, %d^2: the two C23 agree (reciprocity)", a_over_b,
             grids[g]);
    ts_check(label, c[3][g] / c[2][g] - 1.0, 0.0, 1e-5);
  }
}

int main(void)
{
  node(1);  /* a/b = 0.2 */
  node(9);  /* a/b = 1 */
  node(14); /* b/a = 0.5 */
  node(18); /* b/a = 0.1 */
  return ts_failures ? 1 : 0;
}
