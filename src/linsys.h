/* Private: the sparse generalized Jacobian in a SUNSparseMatrix (CSR) with a KLU
 * linear solver. Rows of the traction block are dense in adhesion and have a
 * single entry at a bound; entries that are structurally zero are left out, so
 * the sparsity pattern changes with the active set. KLU's refactorisation
 * reuses the pivot order of the first factorisation and meets zero pivots when
 * rows flip between the two kinds (model.md §9): the symbolic analysis is
 * redone (SUNLinSol_KLUReInit, partial) whenever the branches changed. */
#ifndef ROLLSIM_LINSYS_H
#define ROLLSIM_LINSYS_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include "rollsim/model.h"
#include "rollsim/solver.h"

typedef struct rs_linsys {
  SUNMatrix J;
  SUNLinearSolver LS;
  unsigned char *branch_at_analysis; /* branches of the last symbolic analysis [n] */
  int analysed;
  long jac_evals, analyses;
} rs_linsys;

int rs_linsys_create(rs_linsys *ls, const rs_model *m, N_Vector tmpl, SUNContext ctx);
void rs_linsys_free(rs_linsys *ls);
/* Assemble the Jacobian at (t, y, yp, cj) into ls->J; redo KLU's symbolic
 * analysis at the next setup if the branches changed. */
int rs_linsys_assemble(rs_linsys *ls, const rs_model *m, rs_work *w, double t, const double *y,
                       const double *yp, double cj);

/* Silences SUNDIALS' own error printing; failures are reported through rs_msg. */
void rs_sundials_silent(int error_code, const char *module, const char *function, char *msg,
                        void *user_data);

#endif
