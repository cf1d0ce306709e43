/* Private: the sparse generalized Jacobian in a SUNSparseMatrix (CSR) with a KLU
 * linear solver. Rows of the traction block are dense in adhesion and have a
 * single entry at a bound; entries that are structurally zero are left out, so
 * the sparsity pattern changes with the active set. KLU's refactorisation
 * reuses the pivot order of the first factorisation and meets zero pivots when
 * rows flip between the two kinds (docs/model.md §9): the symbolic analysis is
 * redone (SUNLinSol_KLUReInit, partial) whenever the branches changed. */
#ifndef ROLLSIM_LINSYS_H
#define ROLLSIM_LINSYS_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include "physics/model.h"
#include "solve/steady.h"

typedef struct rs_linsys {
  SUNMatrix J;
  SUNLinearSolver LS;
  unsigned char *branch_at_analysis; /* branches of the last symbolic analysis [n] */
  int analysed;
  long jac_evals, analyses;
  /* Optional (rs_linsys_use_reduced): the Schur-complement solver of linsys_reduced.h
   * on J, with LS as its fallback, and the 1-entry matrix KINSOL is given instead of J. */
  SUNLinearSolver reduced;
  SUNMatrix placeholder;
} rs_linsys;

int rs_linsys_create(rs_linsys *ls, const rs_model *m, N_Vector tmpl, SUNContext ctx);
/* Solve with the Schur-complement solver (linsys_reduced.h) instead of KLU on the
 * whole matrix, reading the row structure from w (the work the Jacobian is assembled
 * with); only for models without extra unknowns. */
int rs_linsys_use_reduced(rs_linsys *ls, const rs_model *m, const rs_work *w, SUNContext ctx);
void rs_linsys_free(rs_linsys *ls);
/* The linear solver and matrix to give KINSOL (KINSetLinearSolver): KLU and J, or
 * the reduced solver and the placeholder. */
SUNLinearSolver rs_linsys_solver(const rs_linsys *ls);
SUNMatrix rs_linsys_matrix(const rs_linsys *ls);
/* Assemble the Jacobian at (inputs, y, yp, cj) into ls->J; with KLU on the whole matrix
 * redo its symbolic analysis at the next setup if the branches changed (the reduced
 * solver tracks the pattern itself). */
int rs_linsys_assemble(rs_linsys *ls, const rs_model *m, rs_work *w, const rs_inputs *in,
                       const double *y, const double *yp, double cj);
/* Factorisations so far: KLU setups, or the reduced solver's setups that did not
 * keep the last factorisation (matrix unchanged); and KLU symbolic analyses. */
long rs_linsys_factorizations(const rs_linsys *ls);
long rs_linsys_analyses(const rs_linsys *ls);

/* Silences SUNDIALS' own error printing; failures are reported through rs_msg. */
void rs_sundials_silent(int error_code, const char *module, const char *function, char *msg,
                        void *user_data);

/* A SUNDIALS set-up call, checked on its own: on failure `msg` names the call and the
 * enclosing function jumps to its `fail` label. */
#define RS_SUN_CHECK(call, msg, what)                                                              \
  do {                                                                                             \
    if ((call) != 0) {                                                                             \
      rs_msg_set(msg, RS_ERR_INTERNAL, "could not set up the %s: %s failed", what, #call);         \
      goto fail;                                                                                   \
    }                                                                                              \
  } while (0)

#endif
