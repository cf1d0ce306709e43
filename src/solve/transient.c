/* Transient rolling: IDA (variable-order, variable-step BDF with error control)
 * on the semi-discrete DAE, each step's nonlinear system solved by KINSOL with
 * the generalized Jacobian, factored by the Schur-complement solver or by KLU
 * (model.md §6). */
#include <ida/ida.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>

#include "solve/linsys.h"
#include "solve/nvector_fast.h"
#include "solve/nls_kinsol.h"
#include "rollsim/solver.h"

struct rs_transient {
  const rs_model *m;
  SUNContext ctx;
  void *ida;
  N_Vector y, yp, atol;
  SUNNonlinearSolver nls;
  rs_linsys ls;
  rs_work work;
  double cj; /* of the step being solved: sets the residual scaling r */
  double t;
  volatile sig_atomic_t *interrupt;
  int (*step_hook)(void *ctx, double t, const double *y);
  void *hook_ctx;
  rs_stats before_restart; /* IDA's counters of the segments before the last IDAReInit */
};

/* IDA's own counters since the last (re)initialisation. */
static void ida_counters(const rs_transient *tr, rs_stats *st)
{
  memset(st, 0, sizeof *st);
  IDAGetNumSteps(tr->ida, &st->steps);
  IDAGetNumNonlinSolvIters(tr->ida, &st->nonlin_iters);
  IDAGetNumNonlinSolvConvFails(tr->ida, &st->nonlin_fails);
  IDAGetNumErrTestFails(tr->ida, &st->err_test_fails);
  IDAGetNumResEvals(tr->ida, &st->res_evals);
}

static int dae_residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector rr, void *data)
{
  rs_transient *tr = data;
  if (tr->interrupt && *tr->interrupt) return -1; /* unrecoverable: IDA stops at once */
  return rs_model_eval(tr->m, &tr->work, t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), tr->cj,
                       N_VGetArrayPointer(rr), NULL);
}

void rs_transient_free(rs_transient *tr)
{
  if (!tr) return;
  if (tr->ida) IDAFree(&tr->ida);
  if (tr->nls) SUNNonlinSolFree(tr->nls);
  rs_linsys_free(&tr->ls);
  if (tr->y) N_VDestroy(tr->y);
  if (tr->yp) N_VDestroy(tr->yp);
  if (tr->atol) N_VDestroy(tr->atol);
  rs_work_free(&tr->work);
  if (tr->ctx) SUNContext_Free(&tr->ctx);
  free(tr);
}

int rs_transient_create(rs_transient **out, const rs_model *m, double t0, const double *y0,
                        const double *yp0, const rs_transient_opts *o, rs_msg *msg)
{
  *out = NULL;
  rs_transient *tr = calloc(1, sizeof *tr);
  if (!tr) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (transient solver)");
  tr->m = m;
  tr->t = t0;
  tr->interrupt = o->interrupt;
  tr->step_hook = o->step_hook;
  tr->hook_ctx = o->hook_ctx;
  const int n = m->n;
  N_Vector id = NULL; /* differential/algebraic components (force control) */
  if (SUNContext_Create(NULL, &tr->ctx) != 0) goto fail;
  tr->y = N_VNew_Serial(m->neq, tr->ctx);
  tr->yp = N_VNew_Serial(m->neq, tr->ctx);
  tr->atol = N_VNew_Serial(m->neq, tr->ctx);
  if (!tr->y || !tr->yp || !tr->atol) goto fail;
  /* IDA's work vectors are clones of y: they inherit the optimised kernels. */
  if (rs_nvector_fast_ops(tr->y) != RS_OK || rs_nvector_fast_ops(tr->yp) != RS_OK ||
      rs_nvector_fast_ops(tr->atol) != RS_OK)
    goto fail;
  memcpy(N_VGetArrayPointer(tr->y), y0, (size_t)m->neq * sizeof *y0);
  memcpy(N_VGetArrayPointer(tr->yp), yp0, (size_t)m->neq * sizeof *yp0);
  /* Absolute tolerances: tractions in N/mm^2 as given; plastic displacements in mm,
   * scaled to the contact size (model.md §9: about 1e-4 rtol a). */
  double *at = N_VGetArrayPointer(tr->atol);
  for (int i = 0; i < n; i++) {
    at[i] = o->atol;
    at[n + i] = at[2 * n + i] = 1e-4 * o->rtol * m->hertz_a;
  }
  /* With force control the creepage is an algebraic unknown fixed by a constraint on
   * differential ones (sum p dx = F_x): left out of the error test, as IDA allows. */
  if (m->force_control) {
    at[3 * n] = 1e-4 * o->rtol;
    if (!(id = N_VNew_Serial(m->neq, tr->ctx)) || rs_nvector_fast_ops(id) != RS_OK) goto fail;
    N_VConst(1.0, id);
    N_VGetArrayPointer(id)[3 * n] = 0.0;
  }
  if (rs_work_create(&tr->work, n) != RS_OK) goto fail;
  if (rs_linsys_create(&tr->ls, m, tr->y, tr->ctx) != RS_OK) goto fail;
  /* Linear algebra: the Schur-complement solver (linsys_reduced.h) whenever the model
   * has the 3 n per-cell unknowns only, KLU on the whole matrix otherwise (as the
   * steady solver does). */
  const rs_linear linear = m->neq != 3 * n ? RS_LINEAR_KLU : o->linear;
  if (linear != RS_LINEAR_KLU && rs_linsys_use_reduced(&tr->ls, m, tr->ctx) != RS_OK) goto fail;
  tr->cj = 0.0;
  tr->nls = rs_nls_kinsol_create(m, &tr->work, &tr->ls, &tr->cj, o->max_newton, tr->y, tr->ctx);
  if (!tr->nls) goto fail;
  tr->ida = IDACreate(tr->ctx);
  if (!tr->ida) goto fail;
  int flag = IDAInit(tr->ida, dae_residual, t0, tr->y, tr->yp);
  flag |= IDASVtolerances(tr->ida, o->rtol, tr->atol);
  flag |= IDASetUserData(tr->ida, tr);
  flag |= IDASetNonlinearSolver(tr->ida, tr->nls);
  flag |= IDASetMaxOrd(tr->ida, o->max_order);
  flag |= IDASetMaxNumSteps(tr->ida, o->max_steps > 0 ? o->max_steps : 1000000);
  flag |= IDASetErrHandlerFn(tr->ida, rs_sundials_silent, NULL);
  if (isfinite(o->t_stop)) flag |= IDASetStopTime(tr->ida, o->t_stop);
  if (o->max_step > 0.0) flag |= IDASetMaxStep(tr->ida, o->max_step);
  if (id) {
    flag |= IDASetId(tr->ida, id);
    flag |= IDASetSuppressAlg(tr->ida, SUNTRUE);
    N_VDestroy(id);
    id = NULL;
  }
  if (flag != 0) goto fail;
  *out = tr;
  return RS_OK;
fail:
  if (id) N_VDestroy(id);
  rs_transient_free(tr);
  return rs_msg_set(msg, RS_ERR_INTERNAL, "could not set up the transient solver (SUNDIALS/KLU)");
}

/* With a step hook: one IDA step at a time, the hook after each, then the solution
 * at tout interpolated from the last step (IDA's dense output). */
static int advance_by_steps(rs_transient *tr, double tout, sunrealtype *tret, int *hook_status)
{
  sunrealtype tn = 0.0;
  IDAGetCurrentTime(tr->ida, &tn);
  int flag = IDA_SUCCESS;
  while (tn < tout) {
    flag = IDASolve(tr->ida, tout, tret, tr->y, tr->yp, IDA_ONE_STEP);
    if (flag < 0) return flag;
    tn = *tret;
    *hook_status = tr->step_hook(tr->hook_ctx, tn, N_VGetArrayPointer(tr->y));
    if (*hook_status != RS_OK) return flag;
    if (flag == IDA_TSTOP_RETURN) break;
  }
  if (tn != tout) {
    if ((flag = IDAGetDky(tr->ida, tout, 0, tr->y)) < 0 ||
        (flag = IDAGetDky(tr->ida, tout, 1, tr->yp)) < 0)
      return flag;
  }
  *tret = tout;
  return IDA_SUCCESS;
}

int rs_transient_advance(rs_transient *tr, double tout, double *y, double *yp, rs_msg *msg)
{
  sunrealtype tret = tr->t;
  int hook_status = RS_OK;
  const int flag = tr->step_hook ? advance_by_steps(tr, tout, &tret, &hook_status)
                                 : IDASolve(tr->ida, tout, &tret, tr->y, tr->yp, IDA_NORMAL);
  if (hook_status != RS_OK)
    return rs_msg_set(msg, hook_status, "at t = %.9g s: recording the state leaving the contact "
                                        "failed",
                      tret);
  if (flag < 0 && tr->interrupt && *tr->interrupt) {
    IDAGetCurrentTime(tr->ida, &tret);
    return rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted at t = %.6g s", tret);
  }
  if (flag < 0) {
    char *name = IDAGetReturnFlagName(flag);
    sunrealtype h = 0.0;
    IDAGetCurrentStep(tr->ida, &h);
    IDAGetCurrentTime(tr->ida, &tret);
    const char *why = flag == IDA_CONV_FAIL   ? "the contact problem of a time step had no solution "
                                                "(Newton failed repeatedly)"
                      : flag == IDA_ERR_FAIL  ? "the error test failed repeatedly"
                      : flag == IDA_TOO_MUCH_WORK ? "solver.max_steps reached"
                                                  : "solver error";
    rs_msg_set(msg, RS_ERR_SOLVER, "transient solver failed at t = %.9g s (step %.3g s): %s [%s]",
               tret, h, why, name ? name : "?");
    free(name);
    return RS_ERR_SOLVER;
  }
  tr->t = tret;
  memcpy(y, N_VGetArrayPointer(tr->y), (size_t)tr->m->neq * sizeof *y);
  memcpy(yp, N_VGetArrayPointer(tr->yp), (size_t)tr->m->neq * sizeof *yp);
  return RS_OK;
}

int rs_transient_restart(rs_transient *tr, double t, const double *y, const double *yp,
                         double t_stop, rs_msg *msg)
{
  rs_stats seg;
  ida_counters(tr, &seg);
  tr->before_restart.steps += seg.steps;
  tr->before_restart.nonlin_iters += seg.nonlin_iters;
  tr->before_restart.nonlin_fails += seg.nonlin_fails;
  tr->before_restart.err_test_fails += seg.err_test_fails;
  tr->before_restart.res_evals += seg.res_evals;
  memcpy(N_VGetArrayPointer(tr->y), y, (size_t)tr->m->neq * sizeof *y);
  memcpy(N_VGetArrayPointer(tr->yp), yp, (size_t)tr->m->neq * sizeof *yp);
  int flag = IDAReInit(tr->ida, t, tr->y, tr->yp);
  if (flag == 0 && isfinite(t_stop)) flag = IDASetStopTime(tr->ida, t_stop);
  if (flag != 0)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not restart the integrator at t = %.9g s", t);
  tr->t = t;
  return RS_OK;
}

void rs_transient_get_stats(const rs_transient *tr, rs_stats *st)
{
  ida_counters(tr, st);
  st->steps += tr->before_restart.steps;
  st->nonlin_iters += tr->before_restart.nonlin_iters;
  st->nonlin_fails += tr->before_restart.nonlin_fails;
  st->err_test_fails += tr->before_restart.err_test_fails;
  st->res_evals += tr->before_restart.res_evals;
  st->jac_evals = tr->ls.jac_evals;
  st->klu_analyses = rs_linsys_analyses(&tr->ls);
  st->factorizations = rs_linsys_factorizations(&tr->ls);
}
