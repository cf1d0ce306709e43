/* The dimension-independent constrained CG (physics/normal_cg.h) on the 2D line kernel:
 * the same solver the 3D problem uses, given "u = A p" from rs_elastic2d, the gap
 * x^2/(2R) and the cell width, against the existing 2D direct active-set method on
 * Carter's case (docs/verification.md 2: q = 178.9 N/mm, R = 500 mm, G = 82000, nu = 0.28,
 * L = 200 mm), 300 cells over +-1.05a, at the full load and at 0.3 of it.
 * Tolerances as in test_normal_cg: the unique discrete solution, CG stops at 1e-11 p_max
 * with lambda = (A(0) - A(1))/2 below the smallest eigenvalue on zero-sum pressures
 * (0.708 (A(0) - A(1)) for the 2D kernel), LU accurate to 4e-11 p_max: the
 * pressures agree to 1e-10 p_max, the approach to 2e-10; the load to 1e-12. */
#include "physics/elastic2d.h"
#include "physics/normal.h"
#include "physics/normal_cg.h"
#include "test_support.h"

#include <stdlib.h>

typedef struct line_kernel {
  const rs_elastic2d *el;
  rs_elastic2d_work *w;
} line_kernel;

static void apply_line_kernel(void *context, const double *p, double *u)
{
  const line_kernel *k = context;
  rs_elastic2d_apply(k->el, k->w, k->el->norm, p, u, k->el->n);
}

int main(void)
{
  const int n = 300;
  const double q = 178.9, R = 500.0, G = 82000.0, nu = 0.28;
  double a, p0;
  rs_hertz2d(q, R, G, nu, &a, &p0);
  const double dx = 2.1 * a / n;
  rs_elastic2d el;
  rs_msg msg = {{0}};
  if (rs_elastic2d_create(&el, n, dx, G, nu, 200.0, &msg) != RS_OK) {
    printf("FAIL %s\n", msg.text);
    return 1;
  }
  rs_elastic2d_work w;
  rs_elastic2d_work_create(&w, &el);
  line_kernel kernel = {&el, &w};
  double *x = malloc(n * sizeof *x), *h = malloc(n * sizeof *h);
  double *p_cg = malloc(n * sizeof *p_cg), *p_dir = malloc(n * sizeof *p_dir);
  for (int i = 0; i < n; i++) {
    x[i] = -1.05 * a + (i + 0.5) * dx;
    h[i] = x[i] * x[i] / (2.0 * R);
  }
  const rs_normal_operator op = {.n = n,
                                 .cell_area = dx,
                                 .lambda =
                                     0.5 * (rs_elastic2d_norm(&el, 0) - rs_elastic2d_norm(&el, 1)),
                                 .apply = apply_line_kernel,
                                 .context = &kernel};
  for (int pass = 0; pass < 2; pass++) {
    const double load = pass ? 0.3 * q : q;
    double d_cg = 0.0, d_dir = 0.0;
    int it = 0;
    if (rs_normal_cg_solve(&op, h, load, NULL, p_cg, &d_cg, &it, &msg) != RS_OK ||
        rs_normal2d_solve_with(&el, &w, h, load, RS_NORMAL2D_DIRECT, p_dir, &d_dir, NULL, &msg) !=
            RS_OK) {
      printf("FAIL %s\n", msg.text);
      ts_failures++;
      continue;
    }
    double pmax = 0.0, diff = 0.0, sum = 0.0;
    for (int i = 0; i < n; i++) {
      pmax = fmax(pmax, p_dir[i]);
      diff = fmax(diff, fabs(p_cg[i] - p_dir[i]));
      sum += p_cg[i];
    }
    printf("-- load %g N/mm: %d CG iterations\n", load, it);
    ts_check("2D through the generic CG: pressure - direct, relative to p_max", diff / pmax, 0.0,
             1e-10);
    ts_check("2D through the generic CG: approach - direct (relative)", d_cg / d_dir - 1.0, 0.0,
             2e-10);
    ts_check("2D through the generic CG: load dx sum p (relative)", sum * dx / load, 1.0, 1e-12);
  }
  free(x);
  free(h);
  free(p_cg);
  free(p_dir);
  rs_elastic2d_work_free(&w);
  rs_elastic2d_free(&el);
  return ts_failures ? 1 : 0;
}
