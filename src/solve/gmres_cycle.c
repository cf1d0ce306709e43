/* One GMRES cycle on plain arrays (solve/gmres_cycle.h). */
#include "solve/gmres_cycle.h"

#include <math.h>
#include <stddef.h>

int rs_gmres_cycle(int n, int mk, rs_gmres_op op, void *ctx, double *V, double beta, double tol,
                   const double *div, double *x, double *res, int *used)
{
  double H[RS_GMRES_CYCLE_MAX + 1][RS_GMRES_CYCLE_MAX], cs[RS_GMRES_CYCLE_MAX],
      sn[RS_GMRES_CYCLE_MAX], g[RS_GMRES_CYCLE_MAX + 1], yk[RS_GMRES_CYCLE_MAX];
  if (mk > RS_GMRES_CYCLE_MAX) mk = RS_GMRES_CYCLE_MAX;
  g[0] = beta;
  int k = 0;
  for (; k < mk; k++) {
    double *v = V + (size_t)(k + 1) * n;
    const int flag = op(ctx, V + (size_t)k * n, v);
    if (flag != 0) return flag;
    for (int i = 0; i <= k; i++) {
      double dot = 0.0;
      for (int j = 0; j < n; j++) dot += v[j] * V[(size_t)i * n + j];
      H[i][k] = dot;
      for (int j = 0; j < n; j++) v[j] -= dot * V[(size_t)i * n + j];
    }
    double hn = 0.0;
    for (int j = 0; j < n; j++) hn += v[j] * v[j];
    hn = sqrt(hn);
    H[k + 1][k] = hn;
    if (hn > 0.0)
      for (int j = 0; j < n; j++) v[j] /= hn;
    for (int i = 0; i < k; i++) { /* the earlier rotations */
      const double a = H[i][k], b = H[i + 1][k];
      H[i][k] = cs[i] * a + sn[i] * b;
      H[i + 1][k] = -sn[i] * a + cs[i] * b;
    }
    const double rr = hypot(H[k][k], H[k + 1][k]);
    cs[k] = rr > 0.0 ? H[k][k] / rr : 1.0;
    sn[k] = rr > 0.0 ? H[k + 1][k] / rr : 0.0;
    H[k][k] = rr;
    H[k + 1][k] = 0.0;
    g[k + 1] = -sn[k] * g[k];
    g[k] = cs[k] * g[k];
    if (fabs(g[k + 1]) <= tol || hn == 0.0) {
      k++;
      break;
    }
  }
  for (int i = k - 1; i >= 0; i--) { /* H y = g */
    double sum = g[i];
    for (int l = i + 1; l < k; l++) sum -= H[i][l] * yk[l];
    yk[i] = H[i][i] != 0.0 ? sum / H[i][i] : 0.0;
  }
  for (int i = 0; i < k; i++)
    for (int j = 0; j < n; j++)
      x[j] += div ? yk[i] * V[(size_t)i * n + j] / div[j] : yk[i] * V[(size_t)i * n + j];
  *res = fabs(g[k]);
  *used = k;
  return 0;
}
