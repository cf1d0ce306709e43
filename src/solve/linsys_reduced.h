/* Private: a direct SUNLinearSolver for the CSR generalized Jacobian that
 * rs_model_jacobian assembles (no extra unknowns), much cheaper than factoring the
 * whole matrix with KLU (docs/model.md §9 "Linear algebra at scale").
 *
 * Only the traction rows that involve the slip velocity couple densely (through the
 * elastic operator); every other row has a few entries. The model says which (rs_work
 * dense, pivot, filled by each assembly), and the solver eliminates the sparse rows by
 * a Schur complement:
 *   - "dense" rows D: the h dense traction rows; one "dense" unknown per such row,
 *     the model's pivot: p_i, or u_pl,i when the cell's yield row fixes p_i (the
 *     traction row then determines the plastic flow);
 *   - the other rows S and unknowns Z form a square sparse block J_SZ (block
 *     triangular along the material flow), factored by KLU;
 *   - the h x h Schur complement J_DD - J_DZ J_SZ^-1 J_SD is factored by LAPACK
 *     dgetrf (only dense unknowns that appear in sparse rows, the plastic flows,
 *     contribute a correction).
 * A matrix identical to that of the last setup keeps the factorisations.
 * If either factorisation is singular the solver falls back to the full KLU
 * factorisation (the solver given at creation) for that matrix. */
#ifndef ROLLSIM_LINSYS_REDUCED_H
#define ROLLSIM_LINSYS_REDUCED_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

/* neq: size of the system; n: the rows that may be dense (rows 0..n-1: the traction
 * rows, or every row with friction memory, whose memory rows in the contact involve the
 * slip velocity too and are eliminated on mu); dense, pivot: the model's row structure
 * for them, read at every setup (rs_work dense/pivot, owned by the
 * caller, filled by the assembly before the setup). J: the CSR SUNSparseMatrix the
 * Jacobian is assembled in; the solver always works on J, whatever matrix the
 * caller passes to setup and solve: KINSOL zeroes the whole matrix it is given
 * before every Jacobian evaluation (SUNMatZero), which for the capacity of a
 * dense traction block costs as much as the factorisation, so KINSOL is given a
 * 1-entry placeholder and the Jacobian function fills J. fallback: a
 * SUNLinSol_KLU for J (not owned). */
SUNLinearSolver rs_lsreduced_create(int n, int neq, const unsigned char *dense, const int *pivot,
                                    SUNMatrix J, SUNLinearSolver fallback, SUNContext ctx);

/* Counters since creation: solves, Schur sizes summed over setups, setups that
 * fell back to the full KLU factorisation. */
typedef struct rs_lsreduced_stats {
  long setups, solves, fallbacks, analyses;
  long reuses;         /* setups with a matrix identical to the last one: factorisations kept */
  long dense_rows_sum; /* sum of h over setups */
} rs_lsreduced_stats;
void rs_lsreduced_get_stats(SUNLinearSolver LS, rs_lsreduced_stats *st);

#endif
