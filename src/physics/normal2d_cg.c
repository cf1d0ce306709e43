/* The 2D normal problem by the dimension-independent constrained CG (normal_cg.c): the
 * line kernel's products by rs_elastic2d_apply, the start the Hertz ellipse on the
 * half-width estimated from the coefficients (rs_normal2d_start_gap). */
#include "physics/normal_cg.h"
#include "physics/normal_methods.h"

#include <math.h>
#include <stdlib.h>

typedef struct line_product {
  const rs_elastic2d *el;
  rs_elastic2d_work *w;
} line_product;

static void apply_line(void *context, const double *p, double *u)
{
  const line_product *l = context;
  rs_elastic2d_apply(l->el, l->w, l->el->norm, p, u, l->el->n);
}

int rs_normal2d_solve_cg(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h, double load,
                         double *pn, double *delta, int *iterations, rs_msg *msg)
{
  const int n = el->n;
  if (!(load > 0.0))
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "normal problem: the CG method needs a positive load (got %g N/mm)", load);
  double *start = malloc((size_t)n * sizeof *start);
  if (!start)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory in the normal problem (%d cells)", n);
  const double h_start = rs_normal2d_start_gap(el, load);
  for (int i = 0; i < n; i++) start[i] = h[i] < h_start ? sqrt(1.0 - h[i] / h_start) : 0.0;
  /* lambda = (A(0) - A(1))/2 lies below the smallest eigenvalue of A_CC on zero-sum
   * vectors (0.708 (A(0) - A(1)) on 100 to 1000 cells, independent of G, nu, L and dx: a
   * cell-to-cell mode; a subset C only raises it). */
  line_product l = {.el = el, .w = w};
  const rs_normal_operator op = {.n = n,
                                 .cell_area = el->dx,
                                 .lambda =
                                     0.5 * (rs_elastic2d_norm(el, 0) - rs_elastic2d_norm(el, 1)),
                                 .apply = apply_line,
                                 .context = &l};
  const int status = rs_normal_cg_solve(&op, h, load, start, pn, delta, iterations, msg);
  free(start);
  return status;
}
