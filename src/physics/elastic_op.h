/* The elastic operator of the contact grid (docs/model.md §2): tangential displacement
 * differences u = A p from the tractions, and the normal ones u_z = A_zz p_n, for the
 * kernel of the grid's dimension. Created from a grid; products direct or by FFT
 * (chosen by the kernel), their scratch in an rs_elastic_work so that a product never
 * writes through a const operator. The 2D line kernel (physics/elastic2d.h) is the first
 * implementation; the 3D Boussinesq-Cerruti kernel plugs in beside it (a case of
 * rs_elastic_op.dim, the same functions). */
#ifndef ROLLSIM_ELASTIC_OP_H
#define ROLLSIM_ELASTIC_OP_H

#include "physics/elastic2d.h"
#include "physics/elastic3d.h"
#include "physics/grid.h"
#include "base/status.h"

typedef struct rs_elastic_op {
  int dim;   /* 2: plane-strain line kernel; 3: Boussinesq-Cerruti (half-spaces) */
  int ncomp; /* tangential components */
  int nx, ny;
  rs_elastic2d line; /* dim 2 */
  rs_elastic3d surf; /* dim 3 */
} rs_elastic_op;

typedef struct rs_elastic_work {
  rs_elastic2d_work line;
  rs_elastic3d_work surf;
} rs_elastic_work;

/* The grid's ny decides: 1 with unit width (y_lo = y_hi = 0) the 2D line kernel,
 * otherwise 3D. 2D: reference_length is L of the line kernel (docs/model.md §2). */
int rs_elastic_op_create(rs_elastic_op *op, const rs_grid *g, double shear_modulus,
                         double poisson_ratio, double reference_length, rs_msg *msg);
void rs_elastic_op_free(rs_elastic_op *op);
int rs_elastic_work_create(rs_elastic_work *w, const rs_elastic_op *op);
void rs_elastic_work_free(rs_elastic_work *w);

/* Tangential influence coefficient: displacement component a at a cell centre per unit
 * traction component b on a cell (kx, ky) cells away (kx = ix_receiver - ix_source,
 * |kx| <= nx, the padded column included). mm/(N/mm^2). */
static inline double rs_elastic_op_coef(const rs_elastic_op *op, int a, int b, int kx, int ky)
{
  if (op->dim == 3) return rs_elastic3d_coef(&op->surf, a, b, kx, ky);
  return rs_elastic2d_tang(&op->line, kx);
}

/* u = A p for the tangential tractions p (ncomp blocks of n cells). With padded, u has
 * ncomp blocks of (nx + 1) ny values: the grid and one column beyond the leading edge
 * (docs/model.md §5: u_el upstream of the first cell); else ncomp blocks of n. */
void rs_elastic_op_tang(const rs_elastic_op *op, rs_elastic_work *w, const double *p, double *u,
                        int padded);

#endif
