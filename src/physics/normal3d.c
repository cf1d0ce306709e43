/* The discrete 3D normal problem (docs/model.md §3, §10): the dimension-independent
 * constrained CG (normal_cg.c) with A_zz products by FFT convolution. */
#include "physics/normal3d.h"

#include "physics/normal_cg.h"

typedef struct zz_product {
  const rs_elastic3d *el;
  rs_elastic3d_work *work;
} zz_product;

static void apply_zz(void *context, const double *p, double *u)
{
  const zz_product *z = context;
  rs_elastic3d_apply_norm(z->el, z->work, p, u, z->el->nx);
}

int rs_normal3d_solve(const rs_elastic3d *el, rs_elastic3d_work *work, const double *gap,
                      double load, const double *start, double *pn, double *approach,
                      int *iterations, rs_msg *msg)
{
  zz_product z = {.el = el, .work = work};
  /* lambda: the rigorous lower bound of the spectrum of A_zz on the grid (about 0.99 of
   * the smallest eigenvalue, test_elastic3d); any positive value below it is valid. */
  const rs_normal_operator op = {.n = el->nx * el->ny,
                                 .cell_area = el->dx * el->dy,
                                 .lambda = rs_elastic3d_norm_lower_eigenvalue(el),
                                 .apply = apply_zz,
                                 .context = &z};
  return rs_normal_cg_solve(&op, gap, load, start, pn, approach, iterations, msg);
}
