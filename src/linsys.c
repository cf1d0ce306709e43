/* The KLU-factored sparse generalized Jacobian (see linsys.h). */
#include "linsys.h"

#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

int rs_linsys_create(rs_linsys *ls, const rs_model *m, N_Vector tmpl, SUNContext ctx)
{
  memset(ls, 0, sizeof *ls);
  ls->J = SUNSparseMatrix(m->neq, m->neq, rs_model_jac_capacity(m), CSR_MAT, ctx);
  if (!ls->J) return RS_ERR_INTERNAL;
  ls->LS = SUNLinSol_KLU(tmpl, ls->J, ctx);
  ls->branch_at_analysis = calloc((size_t)m->n, 1);
  if (!ls->LS || !ls->branch_at_analysis) {
    rs_linsys_free(ls);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

void rs_linsys_free(rs_linsys *ls)
{
  if (ls->LS) SUNLinSolFree(ls->LS);
  if (ls->J) SUNMatDestroy(ls->J);
  free(ls->branch_at_analysis);
  memset(ls, 0, sizeof *ls);
}

int rs_linsys_assemble(rs_linsys *ls, const rs_model *m, rs_work *w, double t, const double *y,
                       const double *yp, double cj)
{
  rs_csr csr = {.nrows = 0,
                .cap = SM_NNZ_S(ls->J),
                .rowptr = SM_INDEXPTRS_S(ls->J),
                .col = SM_INDEXVALS_S(ls->J),
                .val = SM_DATA_S(ls->J)};
  rs_model_eval(m, w, t, y, yp, cj, NULL, &csr);
  ls->jac_evals++;
  if (ls->analysed && memcmp(ls->branch_at_analysis, w->branch, (size_t)m->n) != 0) {
    if (SUNLinSol_KLUReInit(ls->LS, ls->J, SM_NNZ_S(ls->J), SUNKLU_REINIT_PARTIAL) != 0)
      return RS_ERR_INTERNAL;
    ls->analysed = 0;
  }
  if (!ls->analysed) {
    memcpy(ls->branch_at_analysis, w->branch, (size_t)m->n);
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
