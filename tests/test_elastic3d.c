/* The 3D influence coefficients (physics/elastic3d.h) against independent paths:
 *
 * 1. Every closed-form rectangle integral against numerical quadrature of the point-load
 *    formulas: composite Gauss-Legendre over the loaded cell when the field point lies
 *    outside it; polar coordinates about the field point when it lies inside (the
 *    kernels are homogeneous of degree -1, so Int Int K dA = Int K(cos t, sin t) rho(t) dt
 *    with rho(t) the distance to the cell boundary, smooth between the corner angles).
 *    Tolerance: the quadrature's own error (difference of two resolutions) plus the
 *    closed form's rounding: 1e-13 of the coefficient near the loaded cell, and long
 *    double's epsilon amplified by the cancellation r^2 / (dx dy) of the corner sums far
 *    from it.
 * 2. Symmetry: A_xy = A_yx; A_xx, A_yy, A_zz even and A_xy odd in kx and ky, checked on
 *    the closed form evaluated at mirrored offsets (the tables store one quadrant).
 * 3. Far cells: A = dx dy K(offset) (1 + O((d/r)^2)), the cell average of a smooth
 *    kernel; the relative difference must fall as 1/r^2.
 * 4. FFT products against direct sums on a random field, non-square grid, with and
 *    without the padded column: 1e-12 of max |u| (FFT rounding is ~1e-15).
 * 5. The 2D limit: sums of A over a strip of 2K+1 cells in y, differences between
 *    offsets kx and 0, against the 2D line kernel (rs_elastic2d). The finite strip
 *    misses tails |y| > Y = (K + 1/2) dy, which change the difference by exactly
 *    -c dx x^2 (3 nu - 1)/(2 Y^2) (xx) and +c (1 - nu) dx x^2/(2 Y^2) (zz), c = 1/(pi G),
 *    up to O((x/Y)^4): asserted to 1 % of that prediction.
 * 6. The eigenvalue bound used by the normal solver: below the smallest eigenvalue of
 *    the dense A_zz (LAPACK dsyev) on a small grid. */
#include "physics/elastic2d.h"
#include "physics/elastic3d.h"
#include "test_quadrature.h"
#include "test_support.h"

#include <float.h>
#include <stdlib.h>

extern void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
                   double *w, double *work, const int *lwork, int *info);

static const double G = 82000.0, NU = 0.28;

/* Point-load displacement differences at (x, y): xx, xy, yy, zz (per unit force). */
static void point_load(double x, double y, double k[4])
{
  const double r = hypot(x, y), r3 = r * r * r, c = 1.0 / (RS_PI * G);
  k[0] = c * ((1.0 - NU) / r + NU * x * x / r3);
  k[1] = c * NU * x * y / r3;
  k[2] = c * ((1.0 - NU) / r + NU * y * y / r3);
  k[3] = c * (1.0 - NU) / r;
}

typedef struct rule {
  int n;
  double node[64], weight[64];
} rule;

/* Kernel integrated over [x1, x2] x [y1, y2] (field point at the origin, outside the
 * rectangle): panels x panels tensor Gauss-Legendre panels. */
static void quad_outside(double x1, double x2, double y1, double y2, int panels, const rule *q,
                         double out[4])
{
  const double hx = (x2 - x1) / panels, hy = (y2 - y1) / panels;
  for (int c = 0; c < 4; c++) out[c] = 0.0;
  for (int a = 0; a < panels; a++)
    for (int b = 0; b < panels; b++)
      for (int i = 0; i < q->n; i++)
        for (int j = 0; j < q->n; j++) {
          const double x = x1 + hx * (a + 0.5 * (1.0 + q->node[i]));
          const double y = y1 + hy * (b + 0.5 * (1.0 + q->node[j]));
          double k[4];
          point_load(x, y, k);
          const double w = 0.25 * hx * hy * q->weight[i] * q->weight[j];
          for (int c = 0; c < 4; c++) out[c] += w * k[c];
        }
}

static int cmp_double(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Same for the origin inside the rectangle, in polar coordinates about it:
 * Int K(cos t, sin t) rho(t) dt, split at the corner angles, panels per piece. */
static void quad_inside(double x1, double x2, double y1, double y2, int panels, const rule *q,
                        double out[4])
{
  double corner[5] = {atan2(y1, x1), atan2(y1, x2), atan2(y2, x2), atan2(y2, x1)};
  qsort(corner, 4, sizeof corner[0], cmp_double);
  corner[4] = corner[0] + 2.0 * RS_PI;
  for (int c = 0; c < 4; c++) out[c] = 0.0;
  for (int piece = 0; piece < 4; piece++) {
    const double h = (corner[piece + 1] - corner[piece]) / panels;
    for (int a = 0; a < panels; a++)
      for (int i = 0; i < q->n; i++) {
        const double t = corner[piece] + h * (a + 0.5 * (1.0 + q->node[i]));
        const double ct = cos(t), st = sin(t);
        double rho = INFINITY; /* distance to the boundary along t */
        if (ct > 0.0) rho = fmin(rho, x2 / ct);
        if (ct < 0.0) rho = fmin(rho, x1 / ct);
        if (st > 0.0) rho = fmin(rho, y2 / st);
        if (st < 0.0) rho = fmin(rho, y1 / st);
        double k[4];
        point_load(ct, st, k);
        for (int c = 0; c < 4; c++) out[c] += 0.5 * h * q->weight[i] * k[c] * rho;
      }
  }
}

/* Closed form at offset (sx, sy) from the loaded dx x dy cell against quadrature. */
static void check_against_quadrature(const rule *q, double dx, double dy, double sx, double sy,
                                     const char *what, double worst[2])
{
  const double x1 = sx - 0.5 * dx, x2 = sx + 0.5 * dx, y1 = sy - 0.5 * dy, y2 = sy + 0.5 * dy;
  const int inside = x1 <= 0.0 && x2 >= 0.0 && y1 <= 0.0 && y2 >= 0.0;
  double coarse[4], fine[4], closed[4];
  if (inside) {
    quad_inside(x1, x2, y1, y2, 4, q, coarse);
    quad_inside(x1, x2, y1, y2, 8, q, fine);
  } else {
    quad_outside(x1, x2, y1, y2, 6, q, coarse);
    quad_outside(x1, x2, y1, y2, 12, q, fine);
  }
  rs_elastic3d_rect(dx, dy, sx, sy, G, NU, closed);
  static const char *name[4] = {"xx", "xy", "yy", "zz"};
  const double scale = fabs(fine[3]); /* A_zz: the size of every coefficient here */
  /* The closed form's rounding: each corner term is of size r log(r/d) while the sum is of
   * size dx dy / r, so long double's rounding is amplified by about r^2 / (dx dy) times a
   * logarithm and the eight corner terms; 64 covers both. Near cells keep 1e-13. */
  const double r2 = sx * sx + sy * sy;
  const double round_rel = fmax(1e-13, 64.0 * LDBL_EPSILON * r2 / (dx * dy));
  for (int c = 0; c < 4; c++) {
    const double quad_err = fabs(fine[c] - coarse[c]);
    const double tol = 4.0 * quad_err + round_rel * scale;
    const double diff = fabs(closed[c] - fine[c]);
    worst[0] = fmax(worst[0], diff / scale);
    worst[1] = fmax(worst[1], quad_err / scale);
    if (diff > tol) {
      printf("FAIL %s A_%s at (%g, %g): closed %.15g, quadrature %.15g (est. error %.2g)\n", what,
             name[c], sx, sy, closed[c], fine[c], quad_err);
      ts_failures++;
    }
  }
}

static void check_closed_forms(void)
{
  rule q = {.n = 20};
  if (tq_gauss_legendre(q.n, q.node, q.weight) != 0) {
    printf("FAIL Gauss-Legendre rule\n");
    ts_failures++;
    return;
  }
  const double dx = 0.1, dy = 0.07;
  static const int offsets[][2] = {{0, 0},  {1, 0},  {-1, 0},   {0, 1},     {0, -1},
                                   {1, 1},  {-1, 1}, {1, -1},   {2, 1},     {3, -2},
                                   {-5, 4}, {20, 7}, {-50, 30}, {200, 150}, {-400, 300}};
  double worst[2] = {0.0, 0.0};
  for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; k++)
    check_against_quadrature(&q, dx, dy, offsets[k][0] * dx, offsets[k][1] * dy, "cell", worst);
  /* Field points off the cell centres, inside and on the edge of the loaded cell. */
  check_against_quadrature(&q, dx, dy, 0.3 * dx, -0.2 * dy, "inside", worst);
  check_against_quadrature(&q, dx, dy, 0.5 * dx, 0.1 * dy, "edge", worst);
  check_against_quadrature(&q, dx, dy, 0.7 * dx, 0.0, "outside", worst);
  printf("     closed form vs quadrature: largest difference %.3g A_zz (quadrature error "
         "estimate up to %.3g A_zz)\n",
         worst[0], worst[1]);
  ts_check_true("closed-form coefficients match quadrature of the point-load formulas",
                ts_failures == 0);

  /* Symmetries of the closed form itself. */
  double sym = 0.0;
  for (size_t k = 1; k < sizeof offsets / sizeof offsets[0]; k++) {
    const double sx = offsets[k][0] * dx, sy = offsets[k][1] * dy;
    double a[4], mx[4], my[4];
    rs_elastic3d_rect(dx, dy, sx, sy, G, NU, a);
    rs_elastic3d_rect(dx, dy, -sx, sy, G, NU, mx);
    rs_elastic3d_rect(dx, dy, sx, -sy, G, NU, my);
    for (int c = 0; c < 4; c++) {
      const double sign = c == 1 ? -1.0 : 1.0, scale = fabs(a[3]);
      sym = fmax(sym, fmax(fabs(mx[c] - sign * a[c]), fabs(my[c] - sign * a[c])) / scale);
    }
  }
  ts_check("closed form: even (xx, yy, zz) / odd (xy) in x and y, relative to A_zz", sym, 0.0,
           1e-15);

  /* Far field: cell average ~ point load, difference falling as 1/r^2. */
  double rel_prev = 0.0;
  for (int f = 10; f <= 160; f *= 2) {
    const double sx = f * dx, sy = 0.6 * f * dy;
    double a[4], k[4];
    rs_elastic3d_rect(dx, dy, sx, sy, G, NU, a);
    point_load(sx, sy, k);
    double rel = 0.0;
    for (int c = 0; c < 4; c++) rel = fmax(rel, fabs(a[c] / (dx * dy * k[c]) - 1.0));
    const double r2 = sx * sx + sy * sy;
    printf("     far cell at %d cells: |A/(dx dy K) - 1| = %.3g, bound (dx^2+dy^2)/r^2 = %.3g\n", f,
           rel, (dx * dx + dy * dy) / r2);
    TS_CHECK(rel <= (dx * dx + dy * dy) / r2, "far cell %d: %g", f, rel);
    if (rel_prev > 0.0)
      TS_CHECK(fabs(rel_prev / rel - 4.0) < 0.2, "second order: ratio %g", rel_prev / rel);
    rel_prev = rel;
  }
}

/* The tables behind rs_elastic3d_coef against the closed form at every offset class. */
static void check_tables(void)
{
  const int nx = 7, ny = 5;
  const double dx = 0.1, dy = 0.07;
  rs_elastic3d el;
  rs_msg msg = {{0}};
  if (rs_elastic3d_create(&el, nx, ny, dx, dy, G, NU, &msg) != RS_OK) {
    printf("FAIL create: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double worst = 0.0, transpose = 0.0, zero_coupling = 0.0;
  for (int ky = -(ny - 1); ky <= ny - 1; ky++)
    for (int kx = -(nx - 1); kx <= nx; kx++) {
      double a[4];
      rs_elastic3d_rect(dx, dy, kx * dx, ky * dy, G, NU, a);
      const double got[4] = {
          rs_elastic3d_coef(&el, 0, 0, kx, ky), rs_elastic3d_coef(&el, 0, 1, kx, ky),
          rs_elastic3d_coef(&el, 1, 1, kx, ky), rs_elastic3d_coef(&el, 2, 2, kx, ky)};
      for (int c = 0; c < 4; c++) worst = fmax(worst, fabs(got[c] - a[c]) / fabs(a[3]));
      transpose = fmax(transpose, fabs(rs_elastic3d_coef(&el, 1, 0, kx, ky) - got[1]));
      for (int t = 0; t < 2; t++)
        zero_coupling = fmax(zero_coupling, fabs(rs_elastic3d_coef(&el, 2, t, kx, ky)) +
                                                fabs(rs_elastic3d_coef(&el, t, 2, kx, ky)));
    }
  ts_check("tables + symmetry = closed form at every offset (relative to A_zz)", worst, 0.0, 1e-15);
  ts_check("A_xy = A_yx exactly", transpose, 0.0, 0.0);
  ts_check("no normal-tangential coupling (identical bodies)", zero_coupling, 0.0, 0.0);
  rs_elastic3d_free(&el);
  rs_elastic3d bad;
  TS_CHECK(rs_elastic3d_create(&bad, 0, 3, dx, dy, G, NU, &msg) == RS_ERR_INPUT, "nx = 0");
  TS_CHECK(rs_elastic3d_create(&bad, 3, 3, dx, dy, G, 0.6, &msg) == RS_ERR_INPUT, "nu = 0.6");
  printf("     (bad input message: %s)\n", msg.text);
}

/* FFT products against direct sums, random tractions, nx x ny cells (23 x 17: a padded row
 * longer than 2 nx, where every kernel's transform is real; 24 x 17: exactly 2 nx, where
 * A_xy is read at the Nyquist offset and keeps its imaginary parts). */
static void check_fft(int nx, int ny)
{
  const int n = nx * ny, nout = (nx + 1) * ny;
  rs_elastic3d el;
  rs_elastic3d_work work;
  rs_msg msg = {{0}};
  if (rs_elastic3d_create(&el, nx, ny, 0.05, 0.08, G, NU, &msg) != RS_OK ||
      rs_elastic3d_work_create(&work, &el, &msg) != RS_OK) {
    printf("FAIL create: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double *p = malloc(3 * (size_t)n * sizeof *p), *u = malloc(6 * (size_t)nout * sizeof *u);
  unsigned long state = 12345; /* linear congruential generator, values in [-1, 1) */
  for (int i = 0; i < 3 * n; i++) {
    state = state * 6364136223846793005UL + 1442695040888963407UL;
    p[i] = (double)(state >> 11) / 4503599627370496.0 - 1.0;
  }
  const double *px = p, *py = p + n, *pn = p + 2 * n;
  for (int padded = 0; padded <= 1; padded++) {
    const int nxo = nx + padded;
    double *fx = u, *fy = u + nout, *fz = u + 2 * nout, *dx_ = u + 3 * nout, *dy_ = u + 4 * nout,
           *dz = u + 5 * nout;
    rs_elastic3d_apply_tang(&el, &work, px, py, fx, fy, nxo);
    rs_elastic3d_apply_norm(&el, &work, pn, fz, nxo);
    rs_elastic3d_direct_tang(&el, px, py, dx_, dy_, nxo);
    rs_elastic3d_direct_norm(&el, pn, dz, nxo);
    double diff_t = 0.0, max_t = 0.0, diff_n = 0.0, max_n = 0.0;
    for (int i = 0; i < nxo * ny; i++) {
      diff_t = fmax(diff_t, fmax(fabs(fx[i] - dx_[i]), fabs(fy[i] - dy_[i])));
      max_t = fmax(max_t, fmax(fabs(dx_[i]), fabs(dy_[i])));
      diff_n = fmax(diff_n, fabs(fz[i] - dz[i]));
      max_n = fmax(max_n, fabs(dz[i]));
    }
    char what[128];
    snprintf(what, sizeof what, "FFT = direct, %d x %d, tangential, %s (relative to max |u|)", nx,
             ny, padded ? "with the padded column" : "contact grid");
    ts_check(what, diff_t / max_t, 0.0, 1e-12);
    snprintf(what, sizeof what, "FFT = direct, %d x %d, normal, %s (relative to max |u|)", nx, ny,
             padded ? "with the padded column" : "contact grid");
    ts_check(what, diff_n / max_n, 0.0, 1e-12);
  }
  free(p);
  free(u);
  rs_elastic3d_work_free(&work);
  rs_elastic3d_free(&el);
}

/* Strip sums against the 2D line kernel. */
static void check_2d_limit(void)
{
  const int nx = 12, half = 2000; /* strip ky = -half..half */
  const double d = 0.1;
  rs_elastic3d el;
  rs_elastic2d el2;
  rs_msg msg = {{0}};
  if (rs_elastic3d_create(&el, nx, half + 1, d, d, G, NU, &msg) != RS_OK ||
      rs_elastic2d_create(&el2, nx, d, G, NU, 200.0, &msg) != RS_OK) {
    printf("FAIL create: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double strip_xx[13], strip_zz[13];
  for (int kx = 0; kx <= 10; kx++) {
    strip_xx[kx] = strip_zz[kx] = 0.0;
    for (int ky = -half; ky <= half; ky++) {
      strip_xx[kx] += rs_elastic3d_coef(&el, 0, 0, kx, ky);
      strip_zz[kx] += rs_elastic3d_coef(&el, 2, 2, kx, ky);
    }
  }
  const double c = 1.0 / (RS_PI * G), Y = (half + 0.5) * d;
  double worst_xx = 0.0, worst_zz = 0.0;
  for (int kx = 1; kx <= 10; kx++) {
    const double x = kx * d;
    const double err_xx =
        (strip_xx[kx] - strip_xx[0]) - (rs_elastic2d_tang(&el2, kx) - rs_elastic2d_tang(&el2, 0));
    const double err_zz =
        (strip_zz[kx] - strip_zz[0]) - (rs_elastic2d_norm(&el2, kx) - rs_elastic2d_norm(&el2, 0));
    const double pred_xx = -c * d * x * x * (3.0 * NU - 1.0) / (2.0 * Y * Y);
    const double pred_zz = c * (1.0 - NU) * d * x * x / (2.0 * Y * Y);
    worst_xx = fmax(worst_xx, fabs(err_xx / pred_xx - 1.0));
    worst_zz = fmax(worst_zz, fabs(err_zz / pred_zz - 1.0));
    if (kx == 10)
      printf("     strip at kx = 10: 3D - 2D difference %.4g (xx), %.4g (zz) of the 2D "
             "difference; tail prediction %.4g, %.4g\n",
             err_xx / (rs_elastic2d_tang(&el2, kx) - rs_elastic2d_tang(&el2, 0)),
             err_zz / (rs_elastic2d_norm(&el2, kx) - rs_elastic2d_norm(&el2, 0)),
             pred_xx / (rs_elastic2d_tang(&el2, kx) - rs_elastic2d_tang(&el2, 0)),
             pred_zz / (rs_elastic2d_norm(&el2, kx) - rs_elastic2d_norm(&el2, 0)));
  }
  ts_check("2D limit, xx: strip - line kernel = predicted tail (relative)", worst_xx, 0.0, 0.01);
  ts_check("2D limit, zz: strip - line kernel = predicted tail (relative)", worst_zz, 0.0, 0.01);
  rs_elastic2d_free(&el2);
  rs_elastic3d_free(&el);
}

/* rs_elastic3d_norm_lower_eigenvalue against the dense spectrum. */
static void check_eigenvalue_bound(int nx, int ny, double dx, double dy)
{
  const int n = nx * ny;
  rs_elastic3d el;
  rs_msg msg = {{0}};
  if (rs_elastic3d_create(&el, nx, ny, dx, dy, G, NU, &msg) != RS_OK) {
    printf("FAIL create: %s\n", msg.text);
    ts_failures++;
    return;
  }
  double *a = malloc((size_t)n * n * sizeof *a), *w = malloc((size_t)n * sizeof *w);
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      a[(size_t)i * n + j] = rs_elastic3d_coef(&el, 2, 2, i % nx - j % nx, i / nx - j / nx);
  int lwork = -1, info = 0;
  double query;
  dsyev_("N", "U", &n, a, &n, w, &query, &lwork, &info);
  lwork = (int)query;
  double *work = malloc((size_t)lwork * sizeof *work);
  dsyev_("N", "U", &n, a, &n, w, work, &lwork, &info);
  const double bound = rs_elastic3d_norm_lower_eigenvalue(&el);
  printf("     %d x %d cells %g x %g: lambda_min %.6g, bound %.6g (ratio %.4f), A_zz(0) %.6g\n", nx,
         ny, dx, dy, w[0], bound, bound / w[0], rs_elastic3d_coef(&el, 2, 2, 0, 0));
  ts_check_true("eigenvalue bound is positive and below lambda_min of A_zz",
                info == 0 && bound > 0.0 && bound <= w[0] * (1.0 + 1e-12));
  free(work);
  free(a);
  free(w);
  rs_elastic3d_free(&el);
}

int main(void)
{
  check_closed_forms();
  check_tables();
  check_fft(23, 17);
  check_fft(24, 17);
  check_2d_limit();
  check_eigenvalue_bound(12, 9, 0.1, 0.07);
  check_eigenvalue_bound(20, 6, 0.05, 0.15);
  return ts_failures ? 1 : 0;
}
