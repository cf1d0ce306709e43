/* 2D normal contact on the grid (docs/model.md §3). The direct method is an active-set
 * method in the style of Kalker's NORM (Kalker 1990, §5.1): solve the contact cells'
 * equations A_CC p_C - delta = -h_C, dx sum p_C = load, then drop cells with tension
 * and add cells that penetrate, until neither happens. Large grids use the
 * conjugate-gradient method of normal_cg.c instead (same solution). */
#include "physics/normal.h"
#include "physics/normal3d.h"

#include "physics/normal_methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"

void rs_normal2d_hertz(const double *x, int n, double a, double p0, double *pn)
{
  for (int i = 0; i < n; i++) {
    const double r = x[i] / a;
    pn[i] = fabs(r) < 1.0 ? p0 * sqrt(1.0 - r * r) : 0.0;
  }
}

void rs_normal2d_profile(const double *x, int n, double radius, double *h)
{
  for (int i = 0; i < n; i++) h[i] = x[i] * x[i] / (2.0 * radius);
}

int rs_normal2d_solve_direct(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h,
                             double load, double *pn, double *delta_out, int *iterations,
                             rs_msg *msg)
{
  (void)w; /* dense sums */
  const int n = el->n;
  const double dx = el->dx;
  int *active = malloc((size_t)n * sizeof *active);
  int *index = malloc((size_t)n * sizeof *index);
  int *ipiv = malloc((size_t)(n + 1) * sizeof *ipiv);
  double *mat = malloc((size_t)(n + 1) * (size_t)(n + 1) * sizeof *mat);
  double *rhs = malloc((size_t)(n + 1) * sizeof *rhs);
  int status = RS_OK;
  if (!active || !index || !ipiv || !mat || !rhs) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory in the normal problem (%d cells)", n);
    goto done;
  }
  /* First active set: the Hertz contact |x| < a, so that the loop below usually ends
   * after one or two solves instead of shrinking the contact from the whole grid.
   * Any start gives the same solution. */
  const double h_start = rs_normal2d_start_gap(el, load);
  double hmax = 0.0;
  int nstart = 0;
  for (int i = 0; i < n; i++) {
    hmax = fmax(hmax, h[i]);
    active[i] = h[i] < h_start;
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
     * border -1 and dx against coefficients of 1e-7 (Carter's case) LU loses accuracy
     * as the grid grows; scaling the border to the coefficients keeps it (bench/RESULTS.md). */
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
    status = rs_msg_set(msg, RS_ERR_SOLVER,
                        "normal problem: active set did not settle in %d iterations", max_iter);
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
  return status;
}

int rs_normal2d_solve_with(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h,
                           double load, rs_normal2d_method method, double *pn, double *delta,
                           int *iterations, rs_msg *msg)
{
  if (method == RS_NORMAL2D_AUTO)
    method = el->n >= RS_NORMAL2D_CG_FROM && load > 0.0 ? RS_NORMAL2D_CG : RS_NORMAL2D_DIRECT;
  if (method == RS_NORMAL2D_CG)
    return rs_normal2d_solve_cg(el, w, h, load, pn, delta, iterations, msg);
  return rs_normal2d_solve_direct(el, w, h, load, pn, delta, iterations, msg);
}

int rs_normal2d_solve(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h, double load,
                      double *pn, double *delta, int *iterations, rs_msg *msg)
{
  return rs_normal2d_solve_with(el, w, h, load, RS_NORMAL2D_AUTO, pn, delta, iterations, msg);
}

int rs_normal_solve(const rs_elastic_op *op, rs_elastic_work *w, const double *h, double load,
                    double *pn, double *delta, rs_msg *msg)
{
  if (op->dim == 3)
    return rs_normal3d_solve(&op->surf, &w->surf, h, load, NULL, pn, delta, NULL, msg);
  return rs_normal2d_solve(&op->line, &w->line, h, load, pn, delta, NULL, msg);
}
