/* Kalker's creepage coefficients (physics/kalker.h): sanity of the typed table and the
 * properties of the interpolation.
 * - Table: C11 = C22 at nu = 0 in every row (at nu = 0 the half-space kernel is
 *   isotropic in x-y, so longitudinal and lateral creepage are equivalent); every
 *   coefficient grows with nu in every row, and C22, C23 grow with a/b along every
 *   column (C11 too, except its shallow minimum near a/b = 0.3 at nu = 0.5); and each
 *   column is smooth: its log-log slope against a/b changes by at most 0.25 from one row
 *   interval to the next (the table's largest change is 0.13), a check shown to catch the 1.15-for-
 *   1.25 slip of one source copy (it makes the slope jump by 1.36).
 * - Interpolation: table values returned exactly at the nodes; between adjacent nodes
 *   (in a/b, and in nu) the interpolant is monotone and stays between the node values,
 *   also at a Poisson ratio off the nodes; continuous through a/b = 1; outside the
 *   table an input error.
 * - Signs of the linear forces (docs/model.md §1): xi < 0 gives F_x > 0; eta > 0 and phi > 0
 *   give F_y < 0. */
#include "physics/kalker.h"
#include "test_support.h"

static double coefficient(const rs_kalker *c, int which)
{
  return which == 0 ? c->c11 : which == 1 ? c->c22 : which == 2 ? c->c23 : c->c33;
}

/* Largest change of the log-log slope d ln C / d ln(a/b) between consecutive row
 * intervals of a column: the coefficients behave like powers of a/b locally (C23 ~
 * (a/b)^(1/2) for slender patches across the rolling direction, ~ (a/b)^(3/2)/ln along
 * it), so a typing slip shows as a jump of the slope. */
static double slope_jump(const double *column, int rows)
{
  double worst = 0.0, prev = 0.0;
  for (int r = 0; r + 1 < rows; r++) {
    const double slope =
        log(column[r + 1] / column[r]) / log(rs_kalker_row_ratio(r + 1) / rs_kalker_row_ratio(r));
    if (r > 0) worst = fmax(worst, fabs(slope - prev));
    prev = slope;
  }
  return worst;
}

static void check_table(void)
{
  double worst = 0.0, column[RS_KALKER_ROWS];
  for (int w = 0; w < 3; w++)
    for (int j = 0; j < RS_KALKER_NUS; j++) {
      for (int r = 0; r < RS_KALKER_ROWS; r++) column[r] = rs_kalker_table(w, r, j);
      worst = fmax(worst, slope_jump(column, RS_KALKER_ROWS));
    }
  ts_check("table: log-log slope changes by at most 0.25 between row intervals", worst, 0.0, 0.25);
  for (int r = 0; r < RS_KALKER_ROWS; r++) column[r] = rs_kalker_table(2, r, 1);
  column[7] = 1.15; /* the slip in one source copy (C23, a/b = 0.8, nu = 0.25) */
  printf("     with C23(0.8, 0.25) = 1.15 instead of 1.25 the slope would jump by %.2f\n",
         slope_jump(column, RS_KALKER_ROWS));
  ts_check_true("the slope check detects the 1.15-for-1.25 slip",
                slope_jump(column, RS_KALKER_ROWS) > 0.25);

  /* C33 (a <= b): smooth in the same sense, falling with a/b in every column (the spin
   * moment per (ab)^2 grows as the patch narrows along the rolling direction), growing with
   * nu below a/b = 0.9, equal at 0.9 and falling at 1.0 (the table's crossing), NaN for a > b. */
  double c33[RS_KALKER_C33_ROWS], c33_worst = 0.0;
  int c33_falls = 1;
  for (int j = 0; j < RS_KALKER_NUS; j++) {
    for (int r = 0; r < RS_KALKER_C33_ROWS; r++) c33[r] = rs_kalker_table(3, r, j);
    c33_worst = fmax(c33_worst, slope_jump(c33, RS_KALKER_C33_ROWS));
    for (int r = 0; r + 1 < RS_KALKER_C33_ROWS; r++) c33_falls = c33_falls && c33[r + 1] < c33[r];
  }
  ts_check("table: C33's log-log slope changes by at most 0.25 between row intervals", c33_worst,
           0.0, 0.25);
  for (int r = 0; r < RS_KALKER_C33_ROWS; r++) c33[r] = rs_kalker_table(3, r, 1);
  c33[3] = 2.23; /* a transposed-digit slip of 2.32 (a/b = 0.4, nu = 0.25) */
  printf("     with C33(0.4, 0.25) = 2.23 instead of 2.32 the slope would jump by %.2f\n",
         slope_jump(c33, RS_KALKER_C33_ROWS));
  ts_check_true("the slope check detects a 2.23-for-2.32 slip in C33",
                slope_jump(c33, RS_KALKER_C33_ROWS) > 0.25);
  ts_check_true("table: C33 falls with a/b in every nu column", c33_falls);
  int c33_nu = 1;
  for (int r = 0; r < RS_KALKER_C33_ROWS; r++)
    for (int j = 0; j + 1 < RS_KALKER_NUS; j++) {
      const double lo = rs_kalker_table(3, r, j), hi = rs_kalker_table(3, r, j + 1);
      c33_nu = c33_nu && (r < 8 ? hi > lo : r == 8 ? hi == lo : hi < lo);
    }
  ts_check_true("table: C33 grows with nu below a/b = 0.9, flat at 0.9, falls at 1", c33_nu);
  ts_check_true("table: C33 is NaN (not tabulated) for a > b",
                isnan(rs_kalker_table(3, RS_KALKER_C33_ROWS, 1)) &&
                    isnan(rs_kalker_table(3, RS_KALKER_ROWS - 1, 1)));

  int iso = 1, nu_grows = 1, ratio_grows = 1;
  for (int r = 0; r < RS_KALKER_ROWS; r++) {
    iso = iso && rs_kalker_table(0, r, 0) == rs_kalker_table(1, r, 0);
    for (int w = 0; w < 3; w++)
      for (int j = 0; j + 1 < RS_KALKER_NUS; j++)
        nu_grows = nu_grows && rs_kalker_table(w, r, j + 1) > rs_kalker_table(w, r, j);
    if (r + 1 < RS_KALKER_ROWS)
      for (int w = 0; w < 3; w++)
        for (int j = 0; j < RS_KALKER_NUS; j++) {
          const int exempt = w == 0 && j == 2 && rs_kalker_row_ratio(r) < 0.45;
          if (!exempt && !(rs_kalker_table(w, r + 1, j) > rs_kalker_table(w, r, j))) {
            printf("     not growing: coefficient %d, nu %.2f, a/b %.3g -> %.3g\n", w, 0.25 * j,
                   rs_kalker_row_ratio(r), rs_kalker_row_ratio(r + 1));
            ratio_grows = 0;
          }
        }
  }
  ts_check_true("table: C11 = C22 at nu = 0 for every a/b", iso);
  ts_check_true("table: every coefficient grows with nu in every row", nu_grows);
  ts_check_true("table: coefficients grow with a/b (C11 at nu = 0.5 below a/b = 0.45 exempt)",
                ratio_grows);
}

static void check_interpolation(void)
{
  rs_msg msg = {{0}};
  rs_kalker c, lo, hi;
  int exact = 1, status_ok = 1;
  for (int r = 0; r < RS_KALKER_ROWS; r++)
    for (int j = 0; j < RS_KALKER_NUS; j++) {
      status_ok =
          status_ok && rs_kalker_coefficients(rs_kalker_row_ratio(r), 0.25 * j, &c, &msg) == RS_OK;
      for (int w = 0; w < 3; w++) exact = exact && coefficient(&c, w) == rs_kalker_table(w, r, j);
      exact = exact && (r < RS_KALKER_C33_ROWS ? c.c33 == rs_kalker_table(3, r, j) : isnan(c.c33));
    }
  ts_check_true("table values returned exactly at every node (a/b, nu)", exact && status_ok);

  /* Between adjacent rows, at node and off-node Poisson ratios: monotone, bounded. */
  static const double nus[] = {0.0, 0.25, 0.5, 0.28, 0.1};
  int monotone = 1;
  for (size_t v = 0; v < sizeof nus / sizeof nus[0]; v++)
    for (int r = 0; r + 1 < RS_KALKER_ROWS; r++) {
      const double s0 = r < 10 ? rs_kalker_row_ratio(r) : 2.0 - 1.0 / rs_kalker_row_ratio(r);
      rs_kalker_coefficients(rs_kalker_row_ratio(r), nus[v], &lo, &msg);
      rs_kalker_coefficients(rs_kalker_row_ratio(r + 1), nus[v], &hi, &msg);
      double prev[3] = {coefficient(&lo, 0), coefficient(&lo, 1), coefficient(&lo, 2)};
      for (int k = 1; k <= 50; k++) {
        const double s = s0 + 0.1 * k / 50.0, ratio = s <= 1.0 ? s : 1.0 / (2.0 - s);
        rs_kalker_coefficients(ratio, nus[v], &c, &msg);
        for (int w = 0; w < 3; w++) {
          const double a = coefficient(&lo, w), b = coefficient(&hi, w), x = coefficient(&c, w);
          const double slack = 1e-12 * fabs(b);
          const int between = x >= fmin(a, b) - slack && x <= fmax(a, b) + slack;
          const int ordered = (b >= a) ? x >= prev[w] - slack : x <= prev[w] + slack;
          if (!between || !ordered) {
            printf("     not monotone: coefficient %d, nu %.2f, a/b %.4g\n", w, nus[v], ratio);
            monotone = 0;
          }
          prev[w] = x;
        }
      }
    }
  ts_check_true("interpolation in a/b monotone and bounded between adjacent nodes", monotone);

  /* In nu between the nu nodes, at every row and halfway between rows. */
  monotone = 1;
  for (int r = 0; r < RS_KALKER_ROWS; r++)
    for (int half = 0; half <= 1 && (half == 0 || r + 1 < RS_KALKER_ROWS); half++) {
      const double ratio =
          half ? sqrt(rs_kalker_row_ratio(r) * rs_kalker_row_ratio(r + 1)) : rs_kalker_row_ratio(r);
      for (int j = 0; j + 1 < RS_KALKER_NUS; j++) {
        rs_kalker_coefficients(ratio, 0.25 * j, &lo, &msg);
        rs_kalker_coefficients(ratio, 0.25 * (j + 1), &hi, &msg);
        double prev[3] = {lo.c11, lo.c22, lo.c23};
        for (int k = 1; k <= 25; k++) {
          rs_kalker_coefficients(ratio, 0.25 * j + 0.01 * k, &c, &msg);
          for (int w = 0; w < 3; w++) {
            const double a = coefficient(&lo, w), b = coefficient(&hi, w), x = coefficient(&c, w);
            if (x < fmin(a, b) || x > fmax(a, b) || (b >= a ? x < prev[w] : x > prev[w]))
              monotone = 0;
            prev[w] = x;
          }
        }
      }
    }
  ts_check_true("interpolation in nu monotone and bounded between the nu columns", monotone);

  rs_kalker_coefficients(1.0 - 1e-9, 0.28, &lo, &msg);
  rs_kalker_coefficients(1.0 + 1e-9, 0.28, &hi, &msg);
  ts_check("continuous through a/b = 1 (C23 at nu = 0.28)", hi.c23 - lo.c23, 0.0, 1e-8);
  ts_check_true("C33 defined up to a/b = 1, NaN beyond", !isnan(lo.c33) && isnan(hi.c33));
  int c33_monotone = 1;
  for (int r = 0; r + 1 < RS_KALKER_C33_ROWS; r++) {
    double prev = rs_kalker_table(3, r, 1);
    for (int k = 1; k <= 50; k++) {
      rs_kalker_coefficients(rs_kalker_row_ratio(r) + 0.1 * k / 50.0, 0.25, &c, &msg);
      c33_monotone = c33_monotone && c.c33 <= prev && c.c33 >= rs_kalker_table(3, r + 1, 1);
      prev = c.c33;
    }
  }
  ts_check_true("C33 interpolation in a/b monotone and bounded (nu = 0.25)", c33_monotone);
  TS_CHECK(rs_kalker_coefficients(0.05, 0.28, &c, &msg) == RS_ERR_INPUT, "a/b = 0.05");
  TS_CHECK(rs_kalker_coefficients(12.0, 0.28, &c, &msg) == RS_ERR_INPUT, "a/b = 12");
  TS_CHECK(rs_kalker_coefficients(1.0, 0.6, &c, &msg) == RS_ERR_INPUT, "nu = 0.6");
  printf("     (out of range: %s)\n", msg.text);
  rs_kalker_coefficients(3.33864 / 2.5114, 0.28, &c, &msg);
  printf("     wheel-rail ellipse a/b = %.4f, nu = 0.28: C11 %.4f, C22 %.4f, C23 %.4f\n",
         3.33864 / 2.5114, c.c11, c.c22, c.c23);
}

static void check_signs(void)
{
  rs_kalker c;
  rs_msg msg = {{0}};
  rs_kalker_coefficients(1.0, 0.28, &c, &msg);
  double fx, fy, mz;
  rs_kalker_forces(&c, 82000.0, 3.0, 2.0, -1e-4, 0.0, 0.0, &fx, &fy, &mz);
  ts_check_true("xi < 0 gives F_x > 0 and no F_y, no M_z", fx > 0.0 && fy == 0.0 && mz == 0.0);
  rs_kalker_forces(&c, 82000.0, 3.0, 2.0, 0.0, 1e-4, 0.0, &fx, &fy, &mz);
  ts_check_true("eta > 0 gives F_y < 0, M_z > 0 and no F_x", fy < 0.0 && mz > 0.0 && fx == 0.0);
  rs_kalker_forces(&c, 82000.0, 3.0, 2.0, 0.0, 0.0, 1e-4, &fx, &fy, &mz);
  ts_check_true("phi > 0 gives F_y < 0 (C23 > 0) and M_z < 0 (C33 > 0)", fy < 0.0 && mz < 0.0);
  rs_kalker_coefficients(2.0, 0.28, &c, &msg);
  rs_kalker_forces(&c, 82000.0, 3.0, 1.5, 0.0, 1e-4, 0.0, &fx, &fy, &mz);
  ts_check_true("a > b without spin: M_z = G (ab)^(3/2) C23 eta is defined", mz > 0.0);
  rs_kalker_forces(&c, 82000.0, 3.0, 1.5, 0.0, 0.0, 1e-4, &fx, &fy, &mz);
  ts_check_true("a > b with spin: M_z unknown (NaN), F_y defined", isnan(mz) && fy < 0.0);
}

int main(void)
{
  check_table();
  check_interpolation();
  check_signs();
  return ts_failures ? 1 : 0;
}
