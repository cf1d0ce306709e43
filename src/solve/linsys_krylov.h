/* Private: the pieces of Newton-Krylov for the steady/pseudo-time Newton
 * iteration on large grids (model.md §6): exact Jacobian-vector products with
 * the elastic block applied by FFT, and a KLU-factored near-field preconditioner.
 *
 * Products: every row of the generalized Jacobian that rs_model_eval assembles is
 * sparse except the traction rows of cells in adhesion or plastic flow, which are
 * r (dv_s/dy + cj dv_s/dy'). v_s is affine in (y, y'), so those rows applied to v
 * are r v_s evaluated by the model itself at (v, cj v) with the rigid slip and the
 * inflow state set to zero (a shallow copy of the model, "lin"): the physics stays
 * in rs_model_eval, and the elastic product inside it is an FFT convolution. The
 * sparse rows are applied from the assembled matrix.
 *
 * Preconditioner: the Jacobian assembled with the dense rows cut to the band
 * |i - j| <= band of their traction columns (the near field), factored by KLU. The
 * far field is never assembled: the sparse rows and the near field are O(n band). */
#ifndef ROLLSIM_LINSYS_KRYLOV_H
#define ROLLSIM_LINSYS_KRYLOV_H

#include <klu.h>
#include <stdint.h>

#include "rollsim/model.h"

typedef struct rs_krylov {
  const rs_model *m;
  rs_model lin; /* shallow copy of *m: constant inputs at t, no rigid slip, no inflow */
  rs_work wlin;
  int band;
  double t, cj, r;
  unsigned char *dense; /* [n]: traction row i is dense */
  double *vp;           /* [neq] */
  /* near-field matrix, CSR (KLU factors it as the CSC of its transpose) */
  int64_t *rp, *ci, *rp_old, *ci_old, cap, nnz_old;
  double *vx;
  klu_l_common common;
  klu_l_symbolic *sym;
  klu_l_numeric *num;
  long setups, analyses, products;
} rs_krylov;

/* Models with the 3 n per-cell unknowns only (no force-control row). */
int rs_krylov_create(rs_krylov *k, const rs_model *m, int band);
void rs_krylov_free(rs_krylov *k);
/* New Jacobian: full is the generalized Jacobian at (t, y, y', cj) as assembled by
 * rs_model_eval with full->band = the band of k (CSR, neq rows: every sparse row,
 * the near field of the dense ones). Factors it as the preconditioner. */
int rs_krylov_setup(rs_krylov *k, const rs_csr *full, double t, double cj);
/* Jv = J v (exact up to roundoff). full: the matrix of the last setup (its sparse
 * rows are exact; the dense rows are applied by FFT). */
int rs_krylov_times(rs_krylov *k, const rs_csr *full, const double *v, double *Jv);
/* v <- P^-1 v. */
int rs_krylov_psolve(rs_krylov *k, double *v);

#endif
