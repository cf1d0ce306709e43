/* Kalker's creepage coefficients by monotone interpolation in his table
 * (physics/kalker.h: sources, conventions, the cross-check of the typed values). */
#include "physics/kalker.h"

#include <math.h>

/* Kalker 1990, Table E.3 (transcribed from CONTACT, src/m_hertz.f90; see kalker.h).
 * [row][coefficient C11, C22, C23][nu = 0, 0.25, 0.5]; rows a/b = 0.1..1.0, then
 * b/a = 0.9..0.1. */
static const double kalker_table[RS_KALKER_ROWS][3][RS_KALKER_NUS] = {
    {{2.51, 3.31, 4.85}, {2.51, 2.52, 2.53}, {0.334, 0.473, 0.731}}, /* a/b = 0.1 */
    {{2.59, 3.37, 4.81}, {2.59, 2.63, 2.66}, {0.483, 0.603, 0.809}}, /* 0.2 */
    {{2.68, 3.44, 4.80}, {2.68, 2.75, 2.81}, {0.607, 0.715, 0.889}}, /* 0.3 */
    {{2.78, 3.53, 4.82}, {2.78, 2.88, 2.98}, {0.720, 0.823, 0.977}}, /* 0.4 */
    {{2.88, 3.62, 4.83}, {2.88, 3.01, 3.14}, {0.827, 0.929, 1.07}},  /* 0.5 */
    {{2.98, 3.72, 4.91}, {2.98, 3.14, 3.31}, {0.930, 1.03, 1.18}},   /* 0.6 */
    {{3.09, 3.81, 4.97}, {3.09, 3.28, 3.48}, {1.03, 1.14, 1.29}},    /* 0.7 */
    {{3.19, 3.91, 5.05}, {3.19, 3.41, 3.65}, {1.13, 1.25, 1.40}},    /* 0.8 */
    {{3.29, 4.01, 5.12}, {3.29, 3.54, 3.82}, {1.23, 1.36, 1.51}},    /* 0.9 */
    {{3.40, 4.12, 5.20}, {3.40, 3.67, 3.98}, {1.33, 1.47, 1.63}},    /* 1.0 (circle) */
    {{3.51, 4.22, 5.30}, {3.51, 3.81, 4.16}, {1.44, 1.59, 1.77}},    /* b/a = 0.9 */
    {{3.65, 4.36, 5.42}, {3.65, 3.99, 4.39}, {1.58, 1.75, 1.94}},    /* 0.8 */
    {{3.82, 4.54, 5.58}, {3.82, 4.21, 4.67}, {1.76, 1.95, 2.18}},    /* 0.7 */
    {{4.06, 4.78, 5.80}, {4.06, 4.50, 5.04}, {2.01, 2.23, 2.50}},    /* 0.6 */
    {{4.37, 5.10, 6.11}, {4.37, 4.90, 5.56}, {2.35, 2.62, 2.96}},    /* 0.5 */
    {{4.84, 5.57, 6.57}, {4.84, 5.48, 6.31}, {2.88, 3.24, 3.70}},    /* 0.4 */
    {{5.57, 6.34, 7.34}, {5.57, 6.40, 7.51}, {3.79, 4.32, 5.01}},    /* 0.3 */
    {{6.96, 7.78, 8.82}, {6.96, 8.14, 9.79}, {5.72, 6.63, 7.89}},    /* 0.2 */
    {{10.7, 11.7, 12.9}, {10.7, 12.8, 16.0}, {12.2, 14.6, 18.0}},    /* 0.1 */
};

/* Kalker 1990, Table E.3, the spin-moment coefficient C33 for a <= b (see kalker.h):
 * [row a/b = 0.1..1.0][nu = 0, 0.25, 0.5]. */
static const double kalker_c33[RS_KALKER_C33_ROWS][RS_KALKER_NUS] = {
    {6.42, 8.28, 11.7}, /* a/b = 0.1 */
    {3.46, 4.27, 5.66}, /* 0.2 */
    {2.49, 2.96, 3.72}, /* 0.3 */
    {2.02, 2.32, 2.77}, /* 0.4 */
    {1.74, 1.93, 2.22}, /* 0.5 */
    {1.56, 1.68, 1.86}, /* 0.6 */
    {1.43, 1.50, 1.60}, /* 0.7 */
    {1.34, 1.37, 1.42}, /* 0.8 */
    {1.27, 1.27, 1.27}, /* 0.9 */
    {1.21, 1.19, 1.16}, /* 1.0 (circle) */
};

double rs_kalker_row_ratio(int row)
{
  return row < 10 ? 0.1 * (row + 1) : 1.0 / (0.1 * (RS_KALKER_ROWS - row));
}

double rs_kalker_table(int which, int row, int nu_index)
{
  if (which == 3) return row < RS_KALKER_C33_ROWS ? kalker_c33[row][nu_index] : NAN;
  return kalker_table[row][which][nu_index];
}

/* Fritsch-Butland slope at an interior node of uniformly spaced data from the secants
 * on either side: harmonic mean when they agree in sign, else 0 (a local extremum). */
static double interior_slope(double left, double right)
{
  return left * right > 0.0 ? 2.0 * left * right / (left + right) : 0.0;
}

/* End slope from the three-point formula, limited to keep the end interval monotone. */
static double end_slope(double near, double far)
{
  double d = 0.5 * (3.0 * near - far);
  if (d * near <= 0.0)
    d = 0.0;
  else if (near * far < 0.0 && fabs(d) > 3.0 * fabs(near))
    d = 3.0 * near;
  return d;
}

/* Monotone cubic Hermite interpolant through y[0..n-1] at unit spacing, at node k + t,
 * 0 <= t <= 1 (t = 0 returns y[k] exactly). */
static double pchip(const double *y, int n, int k, double t)
{
  if (t == 0.0) return y[k];
  if (k == n - 1) return y[k]; /* the last node (t = 0 there) */
  const double secant = y[k + 1] - y[k];
  const double left = k > 0 ? y[k] - y[k - 1] : 0.0;
  const double right = k + 2 < n ? y[k + 2] - y[k + 1] : 0.0;
  const double d0 = k > 0 ? interior_slope(left, secant) : end_slope(secant, right);
  const double d1 = k + 2 < n ? interior_slope(secant, right) : end_slope(secant, left);
  const double t2 = t * t, t3 = t2 * t;
  return (2.0 * t3 - 3.0 * t2 + 1.0) * y[k] + (t3 - 2.0 * t2 + t) * d0 +
         (-2.0 * t3 + 3.0 * t2) * y[k + 1] + (t3 - t2) * d1;
}

/* Node index and fraction of x on nodes 0, 1, ..., n-1 (x in [0, n-1]); values within
 * 1e-9 of a node are that node, so table nodes are hit exactly despite rounding. */
static void locate(double x, int n, int *k, double *t)
{
  const double nearest = floor(x + 0.5);
  if (fabs(x - nearest) < 1e-9) x = nearest;
  *k = (int)floor(x);
  if (*k > n - 1) *k = n - 1;
  if (*k < 0) *k = 0;
  *t = x - *k;
}

int rs_kalker_coefficients(double a_over_b, double poisson_ratio, rs_kalker *c, rs_msg *msg)
{
  if (!(a_over_b >= 0.1 * (1.0 - 1e-12) && a_over_b <= 10.0 * (1.0 + 1e-12)))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "Kalker's coefficients: semi-axis ratio a/b = %g is outside the table "
                      "(0.1 to 10)",
                      a_over_b);
  if (!(poisson_ratio >= 0.0 && poisson_ratio <= 0.5))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "Kalker's coefficients: Poisson ratio %g is outside the table (0 to 0.5)",
                      poisson_ratio);
  /* s = a/b up to 1, then 2 - b/a; node i at s = 0.1 (i + 1). */
  const double s = a_over_b <= 1.0 ? a_over_b : 2.0 - 1.0 / a_over_b;
  int row, nu_node;
  double t_row, t_nu;
  locate(10.0 * s - 1.0, RS_KALKER_ROWS, &row, &t_row);
  locate(4.0 * poisson_ratio, RS_KALKER_NUS, &nu_node, &t_nu);
  double out[3];
  for (int which = 0; which < 3; which++) {
    double at_nu[RS_KALKER_NUS], column[RS_KALKER_ROWS];
    for (int j = 0; j < RS_KALKER_NUS; j++) {
      for (int r = 0; r < RS_KALKER_ROWS; r++) column[r] = kalker_table[r][which][j];
      at_nu[j] = pchip(column, RS_KALKER_ROWS, row, t_row);
    }
    out[which] = pchip(at_nu, RS_KALKER_NUS, nu_node, t_nu);
  }
  c->c11 = out[0];
  c->c22 = out[1];
  c->c23 = out[2];
  c->c33 = NAN; /* tabulated for a <= b only */
  if (row < RS_KALKER_C33_ROWS - 1 || (row == RS_KALKER_C33_ROWS - 1 && t_row == 0.0)) {
    double at_nu[RS_KALKER_NUS], column[RS_KALKER_C33_ROWS];
    for (int j = 0; j < RS_KALKER_NUS; j++) {
      for (int r = 0; r < RS_KALKER_C33_ROWS; r++) column[r] = kalker_c33[r][j];
      at_nu[j] = pchip(column, RS_KALKER_C33_ROWS, row, t_row);
    }
    c->c33 = pchip(at_nu, RS_KALKER_NUS, nu_node, t_nu);
  }
  return RS_OK;
}

void rs_kalker_forces(const rs_kalker *c, double shear_modulus, double a, double b, double xi,
                      double eta, double phi, double *fx, double *fy, double *mz)
{
  const double gab = shear_modulus * a * b, root = sqrt(a * b);
  *fx = -gab * c->c11 * xi;
  *fy = -gab * (c->c22 * eta + root * c->c23 * phi);
  if (mz) *mz = gab * root * (c->c23 * eta - (phi != 0.0 ? root * c->c33 * phi : 0.0));
}
