/* Steady rolling (docs/model.md §6): KINSOL (exact semismooth Newton) on F(y, y' = 0) = 0,
 * with grid sequencing, pseudo-time steps and a pseudo-transient as fallbacks, and a
 * physical check of every result (rs_model_check_steady). */
#ifndef ROLLSIM_STEADY_H
#define ROLLSIM_STEADY_H

#include "solve/transient.h"

/* Steady rolling (V > 0): a reusable solver so that continuation (creep curves)
 * keeps its allocations. */
typedef struct rs_steady rs_steady;
int rs_steady_create(rs_steady **s, const rs_model *m, SUNContext ctx, rs_msg *msg);
int rs_steady_create_with(rs_steady **s, const rs_model *m, SUNContext ctx, rs_linear linear,
                          rs_msg *msg);
/* Solve F(y, 0) = 0 at time t (inputs evaluated at t); y holds the initial guess
 * on entry, the solution on return. */
int rs_steady_solve(rs_steady *s, double t, double *y, rs_stats *stats, rs_msg *msg);
/* An approximate steady state at time t for a continuation predictor: Newton with the
 * line search from y until the max norm of the scaled residual is below tol (>= the
 * solve's own 1e-10), at most max_iters iterations, no fallbacks and no physical check.
 * Returns RS_OK with the iterate in y, or RS_ERR_SOLVER with y unchanged. */
int rs_steady_approximate(rs_steady *s, double t, double *y, double tol, int max_iters,
                          rs_stats *stats);
/* The model evaluated at the steady state y (y' = 0) by the solver's last residual, if
 * that was at y (3D Newton-Krylov), else NULL: a solution's diagnostics without an
 * evaluation of their own (rs_model_diagnostics_of). Valid until the next solve. */
const rs_work *rs_steady_evaluated(rs_steady *s, const double *y);
/* How a solve from a warm start may fail fast (rs_steady_set_fail_fast; RS_FAIL_NEVER by
 * default). RS_FAIL_FAST: only Newton and grid sequencing, whose coarse solves fail fast too,
 * then RS_ERR_SOLVER with y unchanged, also when the zero found is not a physical steady state:
 * for a continuation that can still shorten its step, which costs far less where the start is
 * far from the solution. RS_FAIL_UNROLLED: the fallbacks too (continuation in k_rel, pseudo-time
 * steps) but not rolling the material from the start, the one that can take thousands of
 * Newton iterations: for a solve whose failure only costs a by-product (the error estimate's
 * coarse grids). Starts from rest take every fallback either way. */
typedef enum { RS_FAIL_NEVER = 0, RS_FAIL_FAST = 1, RS_FAIL_UNROLLED = 2 } rs_fail_mode;
void rs_steady_set_fail_fast(rs_steady *s, rs_fail_mode mode);
void rs_steady_free(rs_steady *s);

/* Solves with the steady Jacobian J = dF/dy (y' = 0) at a steady state y at time t, the
 * solver's own linear algebra (the direct factorisation, or GMRES with the near-field
 * preconditioner): sensitivities of the steady state, dy/ds = -J^-1 dF/ds (docs/model.md §18,
 * "Couplings"). rs_steady_linearise sets J up at y (and the inputs of t, as a solve does);
 * then any number of rs_steady_linear_solve, x = J^-1 b (rtol: the Krylov path's relative
 * residual in the scaled 2-norm; the direct paths solve exactly). The next solve of s sets up
 * its own. RS_ERR_SOLVER when J is singular or GMRES fails. */
int rs_steady_linearise(rs_steady *s, double t, const double *y, rs_msg *msg);
int rs_steady_linear_solve(rs_steady *s, const double *b, double *x, double rtol, rs_msg *msg);
/* The inputs of the last solve or linearisation (those its residual reads: in.newton set). */
const rs_inputs *rs_steady_inputs(const rs_steady *s);

#endif
