/* 2D normal contact on the grid (model.md §3). The direct method is an active-set
 * method in the style of Kalker's NORM (Kalker 1990, §5.1): solve the contact cells'
 * equations A_CC p_C - delta = -h_C, dx sum p_C = load, then drop cells with tension
 * and add cells that penetrate, until neither happens. Large grids use the
 * conjugate-gradient method of normal_cg.c instead (same solution). */
#include "physics/normal_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"


void rs_hertz2d(double load, double radius, double shear_modulus, double poisson_ratio,
                double *a, double *p0)
{
  *a = sqrt(4.0 * load * radius * (1.0 - poisson_ratio) / (RS_PI * shear_modulus));
  *p0 = 2.0 * load / (RS_PI * *a);
}

void rs_normal2d_hertz(const double *x, int n, double a, double p0, double *pn)
{
  for (int i = 0; i < n; i++) {
    const double r = x[i] / a;
    pn[i] = fabs(r) < 1.0 ? p0 * sqrt(1.0 - r * r) : 0.0;
  }
}

double rs_normal2d_start_width(const rs_elastic2d *el, double radius, double load)
{
  /* a = sqrt(2 q R K) with K = 2(1-nu)/(pi G) read off the far field of the
   * coefficients (A(k) ~ -K dx ln|k dx| + const). */
  const int n = el->n;
  if (n < 8 || !(load > 0.0)) return INFINITY;
  const double K =
      (rs_elastic2d_norm(el, n / 4) - rs_elastic2d_norm(el, n / 2)) / (el->dx * log(2.0));
  return K > 0.0 ? sqrt(2.0 * load * radius * K) : INFINITY;
}

double rs_normal2d_profile(const double *x, int n, double radius, double *h)
{
  double hmax = 0.0;
  for (int i = 0; i < n; i++) {
    h[i] = x[i] * x[i] / (2.0 * radius);
    hmax = fmax(hmax, h[i]);
  }
  return hmax;
}

int rs_normal2d_solve_direct(const rs_elastic2d *el, const double *x, double radius, double load,
                             double *pn, double *delta_out, int *iterations, rs_msg *msg)
{
  const int n = el->n;
  const double dx = el->dx;
  int *active = malloc((size_t)n * sizeof *active);
  int *index = malloc((size_t)n * sizeof *index);
  int *ipiv = malloc((size_t)(n + 1) * sizeof *ipiv);
  double *mat = malloc((size_t)(n + 1) * (size_t)(n + 1) * sizeof *mat);
  double *rhs = malloc((size_t)(n + 1) * sizeof *rhs);
  double *h = malloc((size_t)n * sizeof *h);
  int status = RS_OK;
  if (!active || !index || !ipiv || !mat || !rhs || !h) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory in the normal problem (%d cells)", n);
    goto done;
  }
  /* First active set: the Hertz contact |x| < a, so that the loop below usually ends
   * after one or two solves instead of shrinking the contact from the whole grid.
   * Any start gives the same solution. */
  const double a_start = rs_normal2d_start_width(el, radius, load);
  const double hmax = rs_normal2d_profile(x, n, radius, h);
  int nstart = 0;
  for (int i = 0; i < n; i++) {
    active[i] = fabs(x[i]) < a_start;
    nstart += active[i];
    pn[i] = 0.0;
  }
  if (nstart == 0)
    for (int i = 0; i < n; i++) active[i] = 1;
  const int max_iter = 4 * n + 10;
  double delta = 0.0;
  int iter;
  for (iter = 1; iter <= max_iter; iter++) {
    int m = 0;
    for (int i = 0; i < n; i++)
      if (active[i]) index[m++] = i;
    if (m == 0) {
      status = rs_msg_set(msg, RS_ERR_SOLVER, "normal problem: no cell remains in contact");
      goto done;
    }
    /* Column-major (m+1)x(m+1) system; unknowns p_C then delta/A(0), the load row
     * sum p_C = load/dx times A(0): a border of the size of the coefficients. With the
     * border -1 and dx against coefficients of 1e-7 (Carter's case) LU lost accuracy
     * as the grid grew: the bound ||gap residual||_2 / lambda_min on the pressure
     * error was 2.2e-9 p_max on 1600 cells (6.2e-11 on 300), scaled 1.0e-10 (3.8e-12). */
    const int ld = m + 1;
    const double scale = rs_elastic2d_norm(el, 0) != 0.0 ? fabs(rs_elastic2d_norm(el, 0)) : 1.0;
    for (int c = 0; c < m; c++) {
      for (int r = 0; r < m; r++)
        mat[(size_t)c * ld + r] = rs_elastic2d_norm(el, index[r] - index[c]);
      mat[(size_t)c * ld + m] = scale;
      rhs[c] = -h[index[c]];
    }
    for (int r = 0; r < m; r++) mat[(size_t)m * ld + r] = -scale;
    mat[(size_t)m * ld + m] = 0.0;
    rhs[m] = scale * load / dx;
    int nrhs = 1, info = 0;
    dgesv_(&ld, &nrhs, mat, &ld, ipiv, rhs, &ld, &info);
    if (info != 0) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "normal problem: singular contact system (LAPACK dgesv info %d)", info);
      goto done;
    }
    delta = scale * rhs[m];
    memset(pn, 0, (size_t)n * sizeof *pn);
    int changed = 0;
    for (int c = 0; c < m; c++) {
      pn[index[c]] = rhs[c];
      if (rhs[c] < 0.0) { /* tension: leave the contact */
        active[index[c]] = 0;
        changed = 1;
      }
    }
    if (changed) continue;
    /* Penetration check outside the contact cells. */
    const double tol = 1e-12 * (hmax + fabs(delta));
    for (int i = 0; i < n; i++) {
      if (active[i]) continue;
      double gap = h[i] - delta;
      for (int j = 0; j < n; j++) gap += rs_elastic2d_norm(el, i - j) * pn[j];
      if (gap < -tol) {
        active[i] = 1;
        changed = 1;
      }
    }
    if (!changed) break;
  }
  if (iter > max_iter) {
    status = rs_msg_set(msg, RS_ERR_SOLVER, "normal problem: active set did not settle in %d iterations",
                        max_iter);
    goto done;
  }
  if (delta_out) *delta_out = delta;
  if (iterations) *iterations = iter;
done:
  free(active);
  free(index);
  free(ipiv);
  free(mat);
  free(rhs);
  free(h);
  return status;
}

int rs_normal2d_solve_with(const rs_elastic2d *el, const double *x, double radius, double load,
                           rs_normal2d_method method, double *pn, double *delta, int *iterations,
                           rs_msg *msg)
{
  if (method == RS_NORMAL2D_AUTO)
    method = el->n >= RS_NORMAL2D_CG_FROM && load > 0.0 ? RS_NORMAL2D_CG : RS_NORMAL2D_DIRECT;
  if (method == RS_NORMAL2D_CG)
    return rs_normal2d_solve_cg(el, x, radius, load, pn, delta, iterations, msg);
  return rs_normal2d_solve_direct(el, x, radius, load, pn, delta, iterations, msg);
}

int rs_normal2d_solve(const rs_elastic2d *el, const double *x, double radius, double load,
                      double *pn, double *delta, int *iterations, rs_msg *msg)
{
  return rs_normal2d_solve_with(el, x, radius, load, RS_NORMAL2D_AUTO, pn, delta, iterations,
                                msg);
}
