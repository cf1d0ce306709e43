/* The elastic operator of the contact grid (rollsim/elastic_op.h). */
#include "rollsim/elastic_op.h"

#include <string.h>

int rs_elastic_op_create(rs_elastic_op *op, const rs_grid *g, double shear_modulus,
                         double poisson_ratio, double reference_length, rs_msg *msg)
{
  memset(op, 0, sizeof *op);
  if (g->ny != 1)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "3D contact (a grid of %d x %d cells) is not available yet", g->nx, g->ny);
  op->dim = 2;
  op->ncomp = 1;
  op->nx = g->nx;
  op->ny = 1;
  return rs_elastic2d_create(&op->line, g->nx, g->dx, shear_modulus, poisson_ratio,
                             reference_length, msg);
}

void rs_elastic_op_free(rs_elastic_op *op)
{
  if (op->dim == 2) rs_elastic2d_free(&op->line);
  memset(op, 0, sizeof *op);
}

int rs_elastic_work_create(rs_elastic_work *w, const rs_elastic_op *op)
{
  memset(w, 0, sizeof *w);
  return rs_elastic2d_work_create(&w->line, &op->line);
}

void rs_elastic_work_free(rs_elastic_work *w) { rs_elastic2d_work_free(&w->line); }

void rs_elastic_op_tang(const rs_elastic_op *op, rs_elastic_work *w, const double *p, double *u,
                        int padded)
{
  rs_elastic2d_apply(&op->line, &w->line, op->line.tang, p, u, op->nx + (padded ? 1 : 0));
}
