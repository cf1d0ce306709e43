/* Private: the pieces of Newton-Krylov for the steady/pseudo-time Newton iteration on
 * large grids (docs/model.md §6): exact Jacobian-vector products from the model
 * (rs_model_jv: the contact law's local rows applied to the kinematics of v, the
 * elastic products by FFT), and a KLU-factored near-field preconditioner.
 *
 * Preconditioner: the Jacobian's near field (rs_model_jacobian with a band: tractions
 * of cells at most `band` cells away, on a pattern that does not depend on the contact
 * regimes, so that KLU's symbolic analysis is done once), factored by KLU; in 3D its
 * lines along x, factored and solved four at a time in the lanes of a vector on one pattern
 * and pivot order (linsys_lanes.h; KLU alone for a line whose pivots that order does not
 * suit), coupled by a red-black Gauss-Seidel sweep across y (below). The far field is never
 * assembled: O(n band) entries. */
#ifndef ROLLSIM_LINSYS_KRYLOV_H
#define ROLLSIM_LINSYS_KRYLOV_H

#include <klu.h>
#include <stdint.h>

#include "physics/model.h"
#include "solve/linsys_lanes.h"

/* A part of the near field that KLU factors on its own: the whole matrix, or (3D) the
 * unknowns of the cells of one of the grid's rows (a line along x), which the near field
 * does not couple to the others (its band runs along x only). */
typedef struct rs_klu_part {
  int64_t n;             /* unknowns */
  int64_t *idx;          /* global index of each local unknown (NULL: the whole matrix) */
  int64_t *rowptr, *col; /* local CSR pattern */
  double *val, *x;       /* local values, solve buffer */
  int borrowed;          /* rowptr, col, val are the assembled matrix's (the whole) */
  klu_l_common common;
  klu_l_symbolic *sym;
  klu_l_numeric *num;
} rs_klu_part;

typedef struct rs_krylov {
  const rs_model *m;
  rs_work w;        /* the model at the linearisation point (local Jacobians) */
  rs_work wlin;     /* kinematics of the vectors J is applied to */
  int band, band_y; /* near field: half widths in x and y (cells) */
  rs_inputs in;
  double cj;
  /* near-field matrix, CSR (KLU factors it as the CSC of its transpose) */
  rs_csr near;
  int64_t *rp_old, cap, nnz_old;
  uint64_t ci_hash;       /* of the columns of the last analysed pattern (with rp_old, nnz_old) */
  rs_klu_part *part;      /* nparts: one per line along x (3D), or the whole matrix */
  unsigned char *refresh; /* per part: refactored at the last set-up */
  int nparts;             /* 0 before the first analysis */
  /* line Gauss-Seidel (3D, a band along x only, no extras; see below), the lines' parts
   * taken by nsplit threads (halves of the grid) */
  int ylink, nsplit;
  rs_ylink yl; /* its couplings at the last set-up */
  /* the lines factored and solved side by side (linsys_lanes.h) when lanes_on: groups
   * gfirst[h][c] .. gfirst[h][c + 1] - 1 hold the lines of parity c in half h; ready[q]:
   * part q factored (by the lanes, or by KLU where its lane's pivots did not hold) */
  rs_lanes lanes;
  int lanes_on, gfirst[2][3];
  int *lane_todo; /* the groups a set-up refactors */
  unsigned char *ready;
  long setups, analyses, products;
  long factorizations; /* KLU numeric factorisations and refactorisations */
  long reuses;         /* setups that kept the factored near field */
  /* reuse of the factorisation (rs_krylov_set_reuse): the ratio, and the state it was
   * factored in: cj + V/dx and each cell's active-set signature */
  double reuse_ratio, rate_factored;
  int reuse_cells;
  unsigned char *sig_factored;
  int stale;      /* rs_krylov_invalidate: the next setup factors */
  long lin_iters; /* Krylov iterations (summed by the caller: KINSOL's count) */
  /* the point of the last rs_krylov_residual, whose linearisation w holds (ev_valid) */
  double *y_ev, *yp_ev, cj_ev;
  rs_inputs in_ev;
  int ev_valid;
  int w_at_ev; /* w holds the evaluation at that point (until a set-up elsewhere) */
} rs_krylov;

/* 3D near field: the cell's own line along x, 4 cells each way. The steady rolling
 * operator couples mostly along x (the material derivative of the displacements), and
 * lines do not fill each other in KLU (they are independent blocks). Against a square of
 * 3 x 3 cells it needs far fewer GMRES iterations, increasingly so on fine grids; half
 * widths of 2 or 8 do about as well as 4, the whole line is much slower. */
enum { RS_KRYLOV_BAND_3D = 4, RS_KRYLOV_BAND_3D_Y = 0 };
/* 3D: the lines are coupled by one red-black Gauss-Seidel sweep across y. P^-1 solves the
 * lines of even iy on their own, subtracts their couplings to the lines of odd iy (the
 * Jacobian's entries at iy +- 1 within the band in x: rs_model_near_ylink, applied from a
 * table, nothing assembled), then solves the odd lines: P is the near field plus those
 * couplings, block lower triangular, and costs one triangular solve of the near field and
 * a product of O(n band). Truncating the kernel in y inside the factored matrix makes the
 * preconditioner ill-conditioned; here the couplings only enter a right-hand side. The
 * sweep saves about a third of the GMRES iterations. */
/* The transient's near field: half width 2 along x. With c_j in the iteration matrix the
 * GMRES count hardly depends on the width (within 5 % from 1 to 4 cells), and the narrower
 * band halves KLU's triangular solves. */
enum { RS_KRYLOV_BAND_3D_TRANSIENT = 2 };

int rs_krylov_create(rs_krylov *k, const rs_model *m, int band, int band_y);
void rs_krylov_free(rs_krylov *k);
/* New linearisation point (inputs, y, y', cj): the local laws for J v, and the near
 * field assembled and factored (unless rs_krylov_set_reuse lets the last one serve). */
int rs_krylov_setup(rs_krylov *k, const rs_inputs *in, const double *y, const double *yp,
                    double cj);
/* The residual F at (in, y, yp, cj), as rs_model_residual, evaluated with the local laws'
 * Jacobians into k's work: a set-up at the same point (a Newton iteration's iterate, whose
 * residual came first) then needs no evaluation of its own. Between a set-up and the J v
 * products that use it, no residual may be evaluated this way (the Newton iterations of
 * KINSOL evaluate none there). On failure rs_krylov_error says why. */
int rs_krylov_residual(rs_krylov *k, const rs_inputs *in, const double *y, const double *yp,
                       double cj, double *F);
/* Let setups keep the factored near field while the active set (the cells' branches) is
 * that of the factorisation but for at most max_cells cells, and cj + V/dx is within a
 * factor ratio of its value then (ratio <= 1: refactor at every setup, the default). J v
 * stays exact: only the preconditioner lags. In 3D a set-up that does not keep it whole
 * assembles and refactors only the lines with a cell on another branch than at that line's
 * own factorisation, if cj + V/dx is the same (else every line): a typical set-up changes
 * cells in well under half of the lines. */
void rs_krylov_set_reuse(rs_krylov *k, double ratio, int max_cells);
/* The next setup factors whatever the reuse rule says (after a failed solve). */
void rs_krylov_invalidate(rs_krylov *k);
/* Jv = J v at the point of the last setup (exact up to roundoff). */
int rs_krylov_times(rs_krylov *k, const double *v, double *Jv);
/* v <- P^-1 v. */
int rs_krylov_psolve(rs_krylov *k, double *v);
/* w if it holds the model evaluated at (in, y, yp, cj) (the last residual was evaluated
 * there, and no set-up elsewhere came after it), else NULL. */
const rs_work *rs_krylov_evaluated_at(const rs_krylov *k, const rs_inputs *in, const double *y,
                                      const double *yp, double cj);
/* Why the last model evaluation failed (when setup or times did not return RS_OK). */
const char *rs_krylov_error(const rs_krylov *k);

#endif
