/* Private: a SUNNonlinearSolver (rootfinding type) for IDA that solves each BDF
 * step's system F(t, ypred + ycor, yppred + cj ycor) = 0 with KINSOL's exact
 * Newton and the generalized Jacobian (model.md §6, §9), so the contact regimes
 * are re-resolved in every step. The linear solver is that of ls (linsys.h): KLU
 * on the whole matrix, or the Schur-complement solver of linsys_reduced.h. */
#ifndef ROLLSIM_NLS_KINSOL_H
#define ROLLSIM_NLS_KINSOL_H

#include <sundials/sundials_nonlinearsolver.h>

#include "solve/linsys.h"

/* The transient integrator the solver serves: the DAE residual reads the current cj
 * from it (it sets the scaling r), and the inputs at a time come from it (held ones
 * when frozen). */
struct rs_transient;
double *rs_transient_cj_slot(struct rs_transient *tr);
const rs_inputs *rs_transient_inputs(struct rs_transient *tr, double t);

/* max_iters: Newton iterations per step before the step is declared failed. */
SUNNonlinearSolver rs_nls_kinsol_create(const rs_model *m, rs_work *w, rs_linsys *ls,
                                        struct rs_transient *tr, int max_iters, N_Vector tmpl,
                                        SUNContext ctx);

#endif
