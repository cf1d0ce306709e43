/* Hertz solution of an elliptic contact and the complete elliptic integrals
 * (physics/normal3d.h; Johnson 1985 §4.2; Abramowitz & Stegun 17.6). */
#include "physics/normal3d.h"

#include <math.h>

#include "physics/elastic2d.h"

/* K, E and D = (K - E)/k^2 for the complementary modulus kc in (0, 1] by the AGM:
 *   a_0 = 1, b_0 = kc, c_0 = k;  a_(n+1) = (a_n + b_n)/2, b_(n+1) = sqrt(a_n b_n),
 *   c_(n+1) = (a_n - b_n)/2 = c_n^2 / (4 a_(n+1));
 *   K = pi / (2 a_inf),  K - E = K sum_(n>=0) 2^(n-1) c_n^2.
 * D carries the sum divided by k^2 (g_n = c_n/k, g_0 = 1, g_(n+1) = k g_n^2/(4 a_(n+1))),
 * exact also as k -> 0, where D -> pi/4 and K - E would cancel. */
static void elliptic_kd(double kc, double *K, double *E, double *D)
{
  const double k = sqrt((1.0 - kc) * (1.0 + kc));
  double a = 1.0, b = kc, g = 1.0, weight = 0.5, sum = 0.5; /* n = 0 term: 2^-1 g_0^2 */
  for (int n = 0; n < 64 && (fabs(a - b) > 1e-17 * a || weight * g * g > 1e-18 * sum); n++) {
    const double a_next = 0.5 * (a + b);
    g = k * g * g / (4.0 * a_next);
    b = sqrt(a * b);
    a = a_next;
    weight *= 2.0;
    sum += weight * g * g;
  }
  *K = RS_PI / (2.0 * a);
  *D = *K * sum;
  *E = *K - k * k * *D;
}

void rs_elliptic_ke(double kc, double *K, double *E)
{
  double D;
  elliptic_kd(kc, K, E, &D);
}

/* Ratio larger/smaller curvature of the Hertz ellipse with minor/major = kc:
 * (E/kc^2 - K)/(K - E) = (K - D)/(kc^2 D), from E = K - k^2 D (no cancellation). */
static double curvature_ratio(double kc)
{
  double K, E, D;
  elliptic_kd(kc, &K, &E, &D);
  return (K - D) / (kc * kc * D);
}

int rs_hertz3d(double load, double curv_x, double curv_y, double shear_modulus,
               double poisson_ratio, rs_hertz_ellipse *hz, rs_msg *msg)
{
  if (!(load > 0.0) || !isfinite(load))
    return rs_msg_set(msg, RS_ERR_INPUT, "Hertz 3D: the load must be positive (got %g N)", load);
  if (!(curv_x > 0.0) || !(curv_y > 0.0) || !isfinite(curv_x) || !isfinite(curv_y))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "Hertz 3D: the gap curvatures must be positive (got A = %g, B = %g "
                      "1/mm)",
                      curv_x, curv_y);
  if (!(shear_modulus > 0.0) || !(poisson_ratio > -1.0 && poisson_ratio <= 0.5))
    return rs_msg_set(msg, RS_ERR_INPUT, "Hertz 3D: G = %g N/mm^2, nu = %g out of range",
                      shear_modulus, poisson_ratio);
  const double small = fmin(curv_x, curv_y), ratio = fmax(curv_x, curv_y) / small;
  /* Bisection on ln(kc): curvature_ratio falls from infinity (kc -> 0) to 1 (kc = 1). */
  double hi = 1.0, lo = 0.5;
  while (curvature_ratio(lo) <= ratio && lo > 1e-150) {
    hi = lo;
    lo *= 0.5;
  }
  double kc = ratio == 1.0 ? 1.0 : sqrt(lo * hi);
  for (int it = 0; it < 200 && ratio != 1.0; it++) {
    kc = sqrt(lo * hi);
    if (!(kc > lo && kc < hi)) break; /* adjacent doubles */
    if (curvature_ratio(kc) > ratio)
      lo = kc;
    else
      hi = kc;
  }
  double K, E, D;
  elliptic_kd(kc, &K, &E, &D);
  const double e_star = shear_modulus / (1.0 - poisson_ratio);
  const double major = cbrt(3.0 * load * D / (2.0 * RS_PI * e_star * small));
  const double minor = kc * major;
  hz->major_along_x = curv_x <= curv_y;
  hz->a = hz->major_along_x ? major : minor;
  hz->b = hz->major_along_x ? minor : major;
  hz->p0 = 3.0 * load / (2.0 * RS_PI * major * minor);
  hz->approach = hz->p0 * minor * K / e_star;
  hz->eccentricity = sqrt((1.0 - kc) * (1.0 + kc));
  return RS_OK;
}

void rs_hertz3d_pressure(const rs_hertz_ellipse *hz, const rs_grid3d *grid, double *pn)
{
  for (int j = 0; j < grid->ny; j++) {
    const double y = (grid->y0 + (j + 0.5) * grid->dy) / hz->b;
    for (int i = 0; i < grid->nx; i++) {
      const double x = (grid->x0 + (i + 0.5) * grid->dx) / hz->a, s = 1.0 - x * x - y * y;
      pn[(size_t)j * grid->nx + i] = s > 0.0 ? hz->p0 * sqrt(s) : 0.0;
    }
  }
}

double rs_normal3d_gap(const rs_grid3d *grid, double curv_x, double curv_y, double *h)
{
  double hmax = 0.0;
  for (int j = 0; j < grid->ny; j++) {
    const double y = grid->y0 + (j + 0.5) * grid->dy;
    for (int i = 0; i < grid->nx; i++) {
      const double x = grid->x0 + (i + 0.5) * grid->dx, g = curv_x * x * x + curv_y * y * y;
      h[(size_t)j * grid->nx + i] = g;
      hmax = fmax(hmax, g);
    }
  }
  return hmax;
}
