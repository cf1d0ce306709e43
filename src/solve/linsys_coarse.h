/* Private: the coarse-grid correction of the 3D Newton-Krylov preconditioner
 * (linsys_krylov.h), the far field that the near-field lines leave out.
 *
 * The grid's cells are aggregated into cx x cy blocks; the coarse space is the tractions
 * constant on a block (prolongation P: a block's value on each of its cells, restriction
 * R = P^T: the sum of its cells' traction rows). The coarse operator is the Galerkin
 * product R J P of the traction rows with each cell's local Jacobian (the rows' derivatives
 * by the traction and the slip velocity) replaced by its block's mean: the elastic part,
 * the sums over the cells i of block I and k of block J of the influence coefficients
 * A(i - k) and A(i + 1 - k) (the slip velocity's transport difference), depends on the grid
 * alone and is tabulated once; a set-up then costs O(blocks^2) and one dense LU (LAPACK)
 * of 2 cx cy unknowns. */
#ifndef ROLLSIM_LINSYS_COARSE_H
#define ROLLSIM_LINSYS_COARSE_H

#include "physics/model.h"

typedef struct rs_coarse {
  int cx, cy, nb;  /* blocks along x and y, nb = cx cy; coarse unknowns 2 nb */
  int *bx, *by;    /* block I's cells: bx[Ix] <= ix < bx[Ix + 1], by alike */
  int *block;      /* each cell's block */
  double *s0, *s1; /* [3][nb nb]: xx, xy, yy sums of A(i - k), A(i + 1 - k), i in I, k in J */
  double *a;       /* the coarse matrix, LU-factored (column-major, 2 nb) */
  int *ipiv;
  double *bm; /* per block: mean of the rows' slip-velocity derivatives [nb][2][2] */
  double *am; /* per block: sum of the rows' traction derivatives [nb][2][2] */
  double *x;  /* coarse right-hand side and solution [2 nb] */
  int ready;  /* factored */
} rs_coarse;

/* The blocks for model m (3D, two components): cx = ceil(nx / size) blocks along x, alike
 * in y. RS_OK, or RS_ERR_INTERNAL (out of memory). */
int rs_coarse_create(rs_coarse *c, const rs_model *m, int size);
void rs_coarse_free(rs_coarse *c);
/* The coarse matrix at the linearisation in w (rs_model_linearise) with (in, cj), factored. */
int rs_coarse_setup(rs_coarse *c, const rs_model *m, const rs_work *w, const rs_inputs *in,
                    double cj);
/* z += P A_c^-1 R r on the traction unknowns. */
void rs_coarse_apply(rs_coarse *c, const rs_model *m, const double *r, double *z);

void rs_coarse_replace(rs_coarse *c, const rs_model *m, const double *r, double *z);

#endif
