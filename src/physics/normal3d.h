/* 3D normal contact (docs/model.md §3, §10): the Hertz solution of an elliptic contact and
 * the discrete problem on the grid of rs_elastic3d.
 *
 * Hertz (Johnson 1985 §4.2, eqs. 4.39; identical elastic constants, so the combined
 * modulus is E* = G/(1 - nu)): the gap h = A x^2 + B y^2 is closed by the pressure
 * p = p0 sqrt(1 - x^2/a^2 - y^2/b^2) on the ellipse with semi-axes a (along x) and b
 * (along y). The major axis lies along the direction of the smaller curvature. With
 * k = sqrt(1 - (minor/major)^2) the eccentricity, kc = minor/major = sqrt(1 - k^2) and
 * K, E the complete elliptic integrals of modulus k:
 *   larger curvature / smaller = (E/kc^2 - K) / (K - E)      (fixes kc)
 *   major^3 = 3 F (K - E) / (2 pi E* k^2 A_small)
 *   minor = kc major,  p0 = 3 F / (2 pi a b),  delta = p0 minor K / E*.
 * Circle (A = B = 1/(2R)): a^3 = 3 F R (1 - nu)/(4 G), delta = a^2/R. */
#ifndef ROLLSIM_NORMAL3D_H
#define ROLLSIM_NORMAL3D_H

#include "physics/elastic3d.h"
#include "base/status.h"

typedef struct rs_hertz_ellipse {
  double a, b;         /* semi-axes along x and along y, mm */
  double p0;           /* peak pressure 3 F / (2 pi a b), N/mm^2 */
  double approach;     /* delta, mm */
  double eccentricity; /* k = sqrt(1 - (minor/major)^2) */
  int major_along_x;   /* 1: a >= b (curvature along x <= along y); 0: b > a */
} rs_hertz_ellipse;

/* Complete elliptic integrals K and E for the complementary modulus kc = sqrt(1 - k^2)
 * in (0, 1], by the arithmetic-geometric mean (Abramowitz & Stegun 17.6; the series
 * E = K (1 - sum 2^(n-1) c_n^2) with c_(n+1) = c_n^2 / (4 a_(n+1)) free of cancellation).
 * K to rounding also for kc -> 0 (k -> 1), where K ~ ln(4/kc); E = K - k^2 (K - E)/k^2
 * then loses eps ln(4/kc) to cancellation (1e-14 relative at kc = 1e-12). */
void rs_elliptic_ke(double kc, double *K, double *E);

/* Hertz elliptic contact for the load (N), the gap curvatures curv_x = A = 1/(2 Rx) and
 * curv_y = B = 1/(2 Ry) (1/mm, > 0), G and nu. The eccentricity is found by bisection
 * on ln(kc) to the last bit (the curvature ratio is monotone in kc), so any ratio of
 * curvatures works, from a circle to a line-like contact. */
int rs_hertz3d(double load, double curv_x, double curv_y, double shear_modulus,
               double poisson_ratio, rs_hertz_ellipse *hz, rs_msg *msg);

/* Cell centres of an nx x ny grid: x_i = x0 + (i + 1/2) dx, y_j = y0 + (j + 1/2) dy,
 * index j nx + i. */
typedef struct rs_grid3d {
  int nx, ny;
  double x0, y0; /* lower corner of the grid, mm */
  double dx, dy; /* cell sizes, mm */
} rs_grid3d;

/* Hertz pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2) (0 outside) at the cell centres. */
void rs_hertz3d_pressure(const rs_hertz_ellipse *hz, const rs_grid3d *grid, double *pn);

/* Undeformed gap h = A x^2 + B y^2 at the cell centres; returns max h. */
double rs_normal3d_gap(const rs_grid3d *grid, double curv_x, double curv_y, double *h);

/* The discrete 3D normal problem on el's grid (physics/normal_cg.h) with products
 * A_zz p by FFT (work: scratch for them), for any undeformed gap h[nx ny] (mm) and the
 * load (N). start: a start pressure or NULL (uniform). pn[nx ny]: the pressure;
 * approach (may be NULL); iterations: CG iterations (may be NULL). */
int rs_normal3d_solve(const rs_elastic3d *el, rs_elastic3d_work *work, const double *gap,
                      double load, const double *start, double *pn, double *approach,
                      int *iterations, rs_msg *msg);

#endif
