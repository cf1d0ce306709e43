/* The KLU-factored sparse generalized Jacobian (see linsys.h). */
#include "solve/linsys.h"
#include "solve/linsys_reduced.h"

#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

int rs_linsys_create(rs_linsys *ls, const rs_model *m, N_Vector tmpl, SUNContext ctx)
{
  memset(ls, 0, sizeof *ls);
  const int neq = m->lay.neq;
  ls->J = SUNSparseMatrix(neq, neq, rs_model_jac_capacity(m, 0, 0), CSR_MAT, ctx);
  if (!ls->J) return RS_ERR_INTERNAL;
  ls->LS = SUNLinSol_KLU(tmpl, ls->J, ctx);
  ls->branch_at_analysis = calloc((size_t)m->grid.n, 1);
  if (!ls->LS || !ls->branch_at_analysis) {
    rs_linsys_free(ls);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

int rs_linsys_use_reduced(rs_linsys *ls, const rs_model *m, const rs_work *w, SUNContext ctx)
{
  /* rows that may be dense: the traction rows, with friction memory every row (the
   * memory rows in the contact are dense too; w->dense flags them) */
  const int neq = m->lay.neq, ntraction = m->lay.memory ? neq : m->lay.ncomp * m->lay.n;
  if (m->lay.nextra != 0 || ls->reduced) return RS_ERR_INTERNAL;
  ls->placeholder = SUNSparseMatrix(neq, neq, 1, CSR_MAT, ctx);
  ls->reduced = rs_lsreduced_create(ntraction, neq, w->dense, w->pivot, ls->J, ls->LS, ctx);
  return ls->placeholder && ls->reduced ? RS_OK : RS_ERR_INTERNAL;
}

SUNLinearSolver rs_linsys_solver(const rs_linsys *ls) { return ls->reduced ? ls->reduced : ls->LS; }

SUNMatrix rs_linsys_matrix(const rs_linsys *ls) { return ls->reduced ? ls->placeholder : ls->J; }

long rs_linsys_factorizations(const rs_linsys *ls)
{
  if (!ls->reduced) return ls->jac_evals;
  rs_lsreduced_stats st;
  rs_lsreduced_get_stats(ls->reduced, &st);
  return st.setups - st.reuses;
}

long rs_linsys_analyses(const rs_linsys *ls)
{
  if (!ls->reduced) return ls->analyses;
  rs_lsreduced_stats st;
  rs_lsreduced_get_stats(ls->reduced, &st);
  return st.analyses + st.fallbacks; /* a fallback re-analyses the whole matrix */
}

void rs_linsys_free(rs_linsys *ls)
{
  if (ls->reduced) SUNLinSolFree(ls->reduced);
  if (ls->placeholder) SUNMatDestroy(ls->placeholder);
  if (ls->LS) SUNLinSolFree(ls->LS);
  if (ls->J) SUNMatDestroy(ls->J);
  free(ls->branch_at_analysis);
  memset(ls, 0, sizeof *ls);
}

int rs_linsys_assemble(rs_linsys *ls, const rs_model *m, rs_work *w, const rs_inputs *in,
                       const double *y, const double *yp, double cj)
{
  rs_csr csr = {.nrows = 0,
                .cap = SM_NNZ_S(ls->J),
                .rowptr = SM_INDEXPTRS_S(ls->J),
                .col = SM_INDEXVALS_S(ls->J),
                .val = SM_DATA_S(ls->J)};
  const int status = rs_model_jacobian(m, w, in, y, yp, cj, 0, 0, &csr);
  if (status != RS_OK) return status;
  ls->jac_evals++;
  if (ls->reduced) return RS_OK;
  if (ls->analysed && memcmp(ls->branch_at_analysis, w->branch, (size_t)m->grid.n) != 0) {
    if (SUNLinSol_KLUReInit(ls->LS, ls->J, SM_NNZ_S(ls->J), SUNKLU_REINIT_PARTIAL) != 0)
      return RS_ERR_INTERNAL;
    ls->analysed = 0;
  }
  if (!ls->analysed) {
    memcpy(ls->branch_at_analysis, w->branch, (size_t)m->grid.n);
    ls->analysed = 1;
    ls->analyses++;
  }
  return RS_OK;
}

void rs_sundials_silent(int error_code, const char *module, const char *function, char *msg,
                        void *user_data)
{
  (void)error_code;
  (void)module;
  (void)function;
  (void)msg;
  (void)user_data;
}
