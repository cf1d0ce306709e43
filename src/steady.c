/* Steady rolling: KINSOL on F(y, y' = 0) = 0 (model.md §6). With the scaling r
 * of model.md §4 the residual is piecewise linear in the tractions, and exact
 * (semismooth) Newton with the generalized Jacobian settles the active set in a
 * few iterations from p = 0. Plain Newton is tried first, a line search second
 * (model.md §9: the line search backtracks heavily on this non-smooth residual). */
#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>

#include "linsys.h"
#include "rollsim/solver.h"

struct rs_steady {
  const rs_model *m;
  SUNContext ctx;
  void *kmem;
  N_Vector u, uscale, fscale;
  rs_linsys ls;
  rs_work work;
  double *yp_zero;
  double t;
};

static int steady_residual(N_Vector u, N_Vector f, void *data)
{
  rs_steady *s = data;
  return rs_model_eval(s->m, &s->work, s->t, N_VGetArrayPointer(u), s->yp_zero, 0.0,
                       N_VGetArrayPointer(f), NULL);
}

static int steady_jacobian(N_Vector u, N_Vector f, SUNMatrix J, void *data, N_Vector t1,
                           N_Vector t2)
{
  (void)f;
  (void)J;
  (void)t1;
  (void)t2;
  rs_steady *s = data;
  return rs_linsys_assemble(&s->ls, s->m, &s->work, s->t, N_VGetArrayPointer(u), s->yp_zero, 0.0);
}

void rs_steady_free(rs_steady *s)
{
  if (!s) return;
  if (s->kmem) KINFree(&s->kmem);
  rs_linsys_free(&s->ls);
  if (s->u) N_VDestroy(s->u);
  if (s->uscale) N_VDestroy(s->uscale);
  if (s->fscale) N_VDestroy(s->fscale);
  rs_work_free(&s->work);
  free(s->yp_zero);
  if (s->ctx) SUNContext_Free(&s->ctx);
  free(s);
}

int rs_steady_create(rs_steady **out, const rs_model *m, rs_msg *msg)
{
  *out = NULL;
  rs_steady *s = calloc(1, sizeof *s);
  if (!s) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (steady solver)");
  s->m = m;
  const int n = m->n;
  if (SUNContext_Create(NULL, &s->ctx) != 0) goto fail;
  s->u = N_VNew_Serial(m->neq, s->ctx);
  s->uscale = N_VNew_Serial(m->neq, s->ctx);
  s->fscale = N_VNew_Serial(m->neq, s->ctx);
  s->yp_zero = calloc((size_t)m->neq, sizeof *s->yp_zero);
  if (!s->u || !s->uscale || !s->fscale || !s->yp_zero) goto fail;
  if (rs_work_create(&s->work, n) != RS_OK) goto fail;
  if (rs_linsys_create(&s->ls, m, s->u, s->ctx) != RS_OK) goto fail;

  /* Scales: tractions by the largest bound, displacements by the displacement that
   * traction causes on its own cell; every residual row has traction units. */
  double pref = 0.0;
  for (int i = 0; i < n; i++) pref = fmax(pref, m->bound[i]);
  if (!(pref > 0.0)) pref = 1.0;
  const double uref = pref * (rs_elastic2d_tang(&m->el, 0) + m->layer_flex);
  double *us = N_VGetArrayPointer(s->uscale), *fs = N_VGetArrayPointer(s->fscale);
  for (int i = 0; i < n; i++) {
    us[i] = 1.0 / pref;
    us[n + i] = us[2 * n + i] = 1.0 / uref;
  }
  for (int i = 0; i < m->neq; i++) fs[i] = 1.0 / pref;

  s->kmem = KINCreate(s->ctx);
  if (!s->kmem) goto fail;
  int flag = KINInit(s->kmem, steady_residual, s->u);
  flag |= KINSetUserData(s->kmem, s);
  flag |= KINSetLinearSolver(s->kmem, s->ls.LS, s->ls.J);
  flag |= KINSetJacFn(s->kmem, steady_jacobian);
  flag |= KINSetMaxSetupCalls(s->kmem, 1);       /* exact Newton */
  flag |= KINSetMaxNewtonStep(s->kmem, 1e12);    /* steps from p = 0 are large */
  flag |= KINSetFuncNormTol(s->kmem, 1e-12);
  flag |= KINSetScaledStepTol(s->kmem, 1e-15);
  flag |= KINSetNumMaxIters(s->kmem, 200);
  flag |= KINSetErrHandlerFn(s->kmem, rs_sundials_silent, NULL);
  if (flag != 0) goto fail;
  *out = s;
  return RS_OK;
fail:
  rs_steady_free(s);
  return rs_msg_set(msg, RS_ERR_INTERNAL, "could not set up the steady solver (SUNDIALS/KLU)");
}

int rs_steady_solve(rs_steady *s, double t, double *y, rs_stats *stats, rs_msg *msg)
{
  const rs_model *m = s->m;
  const double V = rs_history_eval(&m->velocity, t);
  if (!(V > 0.0))
    return rs_msg_set(msg, RS_ERR_INPUT, "steady rolling needs a rolling velocity > 0 (got %g mm/s at t = %g s)", V, t);
  s->t = t;
  double *u = N_VGetArrayPointer(s->u);
  int flag = 0;
  const int strategies[2] = {KIN_NONE, KIN_LINESEARCH};
  long iters_total = 0, fevals_total = 0;
  for (int k = 0; k < 2; k++) {
    memcpy(u, y, (size_t)m->neq * sizeof *u);
    flag = KINSol(s->kmem, s->u, strategies[k], s->uscale, s->fscale);
    long iters = 0, fevals = 0;
    KINGetNumNonlinSolvIters(s->kmem, &iters);
    KINGetNumFuncEvals(s->kmem, &fevals);
    iters_total += iters;
    fevals_total += fevals;
    if (flag == KIN_STEP_LT_STPTOL) { /* stalled: accept only a small residual */
      double fnorm = INFINITY;
      KINGetFuncNorm(s->kmem, &fnorm);
      if (fnorm > 1e-9) flag = KIN_LINESEARCH_NONCONV;
    }
    if (flag >= 0) break;
  }
  if (stats) {
    stats->nonlin_iters += iters_total;
    stats->res_evals += fevals_total;
    stats->jac_evals = s->ls.jac_evals;
    stats->klu_analyses = s->ls.analyses;
  }
  if (flag < 0) {
    char *name = KINGetReturnFlagName(flag);
    rs_msg_set(msg, RS_ERR_SOLVER, "steady solver (KINSOL) did not converge at t = %g s: %s", t,
               name ? name : "unknown failure");
    free(name);
    return RS_ERR_SOLVER;
  }
  memcpy(y, u, (size_t)m->neq * sizeof *u);
  return RS_OK;
}
