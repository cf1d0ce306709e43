/* The elastic operator of the contact grid (physics/elastic_op.h). */
#include "physics/elastic_op.h"

#include <string.h>

int rs_elastic_op_create(rs_elastic_op *op, const rs_grid *g, double shear_modulus,
                         double poisson_ratio, double reference_length, rs_msg *msg)
{
  memset(op, 0, sizeof *op);
  op->nx = g->nx;
  op->ny = g->ny;
  if (g->ny == 1 && g->y_lo == 0.0 && g->y_hi == 0.0) {
    op->dim = 2;
    op->ncomp = 1;
    return rs_elastic2d_create(&op->line, g->nx, g->dx, shear_modulus, poisson_ratio,
                               reference_length, msg);
  }
  op->dim = 3;
  op->ncomp = 2;
  return rs_elastic3d_create(&op->surf, g->nx, g->ny, g->dx, g->dy, shear_modulus, poisson_ratio,
                             msg);
}

void rs_elastic_op_free(rs_elastic_op *op)
{
  if (op->dim == 2) rs_elastic2d_free(&op->line);
  if (op->dim == 3) rs_elastic3d_free(&op->surf);
  memset(op, 0, sizeof *op);
}

int rs_elastic_work_create(rs_elastic_work *w, const rs_elastic_op *op)
{
  memset(w, 0, sizeof *w);
  if (op->dim == 3) {
    rs_msg msg;
    return rs_elastic3d_work_create(&w->surf, &op->surf, &msg);
  }
  return rs_elastic2d_work_create(&w->line, &op->line);
}

void rs_elastic_work_free(rs_elastic_work *w)
{
  rs_elastic2d_work_free(&w->line);
  if (w->surf.grid) rs_elastic3d_work_free(&w->surf);
}

void rs_elastic_op_tang(const rs_elastic_op *op, rs_elastic_work *w, const double *p, double *u,
                        int padded)
{
  const int nxout = op->nx + (padded ? 1 : 0);
  if (op->dim == 3) {
    const int n = op->nx * op->ny;
    rs_elastic3d_apply_tang(&op->surf, &w->surf, p, p + n, u, u + (size_t)nxout * op->ny, nxout);
    return;
  }
  rs_elastic2d_apply(&op->line, &w->line, op->line.tang, p, u, nxout);
}
