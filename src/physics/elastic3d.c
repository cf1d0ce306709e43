/* 3D influence coefficients of piecewise-constant tractions on rectangles, and the
 * products by direct sums (docs/model.md §10; Johnson 1985 §3.2; Kalker 1990 §1.6). The operator
 * (its tables and FFT products) is set up in elastic3d_fft.c. */
#include "physics/elastic3d_internal.h"

#include <math.h>
#include <stdlib.h>

#define PI_L 3.141592653589793238462643383279503L

/* x asinh(y/|x|), with its limit 0 at x = 0. Its mixed derivative d2/dxdy is y^2/r^3;
 * it differs from x ln(y + r) by x ln|x|, a function of x alone that drops out of the
 * corner sum. Odd in x and in y, so mirrored rectangles give mirrored values. */
static long double prim_asinh_x(long double x, long double y)
{
  return x == 0.0L ? 0.0L : x * asinhl(y / fabsl(x));
}

/* y asinh(x/|y|): mixed derivative x^2/r^3. */
static long double prim_asinh_y(long double x, long double y) { return prim_asinh_x(y, x); }

/* -r: mixed derivative x y/r^3. */
static long double prim_minus_r(long double x, long double y) { return -hypotl(x, y); }

/* Int_{x1}^{x2} Int_{y1}^{y2} f_xy dy dx by inclusion-exclusion over the corners. */
static long double corner_sum(long double (*f)(long double, long double), long double x1,
                              long double x2, long double y1, long double y2)
{
  return (f(x2, y2) - f(x1, y2)) - (f(x2, y1) - f(x1, y1));
}

void rs_elastic3d_rect(double dx, double dy, double sx, double sy, double shear_modulus,
                       double poisson_ratio, double coef[4])
{
  /* The field point is at (sx, sy) from the source centre: the kernel's argument
   * x - xi runs over [sx - dx/2, sx + dx/2] (and likewise in y). In long double the
   * cancellation of the corner terms (relative loss ~ (r/dx)^2 eps) stays below 1e-13
   * out to a few hundred cells. */
  const long double x1 = (long double)sx - 0.5L * dx, x2 = (long double)sx + 0.5L * dx;
  const long double y1 = (long double)sy - 0.5L * dy, y2 = (long double)sy + 0.5L * dy;
  const long double int_yy = corner_sum(prim_asinh_x, x1, x2, y1, y2); /* Int y^2/r^3 */
  const long double int_xx = corner_sum(prim_asinh_y, x1, x2, y1, y2); /* Int x^2/r^3 */
  const long double int_xy = corner_sum(prim_minus_r, x1, x2, y1, y2); /* Int x y/r^3 */
  /* Int 1/r = Int (x^2 + y^2)/r^3 */
  const long double nu = poisson_ratio, c = 1.0L / (PI_L * shear_modulus);
  coef[0] = (double)(c * ((1.0L - nu) * (int_xx + int_yy) + nu * int_xx));
  coef[1] = (double)(c * nu * int_xy);
  coef[2] = (double)(c * ((1.0L - nu) * (int_xx + int_yy) + nu * int_yy));
  coef[3] = (double)(c * (1.0L - nu) * (int_xx + int_yy));
}

/* u_i(I) = sum_J sum_j A_ij(I - J) p_j(J) over the components listed (direct sums). */
void rs_elastic3d_direct_tang(const rs_elastic3d *el, const double *px, const double *py,
                              double *ux, double *uy, int nxout)
{
  const int nx = el->nx, ny = el->ny;
  for (int iy = 0; iy < ny; iy++)
    for (int ix = 0; ix < nxout; ix++) {
      double sx = 0.0, sy = 0.0;
      for (int jy = 0; jy < ny; jy++)
        for (int jx = 0; jx < nx; jx++) {
          const int kx = ix - jx, ky = iy - jy, j = jy * nx + jx;
          const double axy = rs_elastic3d_coef(el, 0, 1, kx, ky);
          sx += rs_elastic3d_coef(el, 0, 0, kx, ky) * px[j] + axy * py[j];
          sy += axy * px[j] + rs_elastic3d_coef(el, 1, 1, kx, ky) * py[j];
        }
      ux[iy * nxout + ix] = sx;
      uy[iy * nxout + ix] = sy;
    }
}

void rs_elastic3d_direct_norm(const rs_elastic3d *el, const double *pn, double *uz, int nxout)
{
  const int nx = el->nx, ny = el->ny;
  for (int iy = 0; iy < ny; iy++)
    for (int ix = 0; ix < nxout; ix++) {
      double s = 0.0;
      for (int jy = 0; jy < ny; jy++) {
        const double *row = el->zz + (size_t)abs(iy - jy) * (size_t)(nx + 1);
        for (int jx = 0; jx < nx; jx++) s += row[abs(ix - jx)] * pn[jy * nx + jx];
      }
      uz[iy * nxout + ix] = s;
    }
}
