/* Steady rolling: KINSOL on F(y, y' = 0) = 0 (docs/model.md §6). With the scaling r
 * of docs/model.md §4 the residual is piecewise linear in the tractions, and exact
 * (semismooth) Newton with the generalized Jacobian settles the active set in a
 * few iterations from p = 0. Plain Newton is tried first, a line search second
 * (docs/model.md §9: the line search backtracks heavily on this non-smooth residual). */
#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <stdlib.h>
#include <string.h>

#include "solve/linsys.h"
#include "solve/gmres.h"
#include "solve/linsys_krylov.h"
#include "solve/nvector_fast.h"
#include "solve/steady.h"

/* A Newton iteration with a fallback behind it (3D plastic continuation points, see
 * solve_at) stops when the residual norm fell by less than 1 - STALL_FACTOR over the last
 * STALL_SPAN iterations: a stalled line search, which takes steps of a few per cent of
 * Newton's until the iteration cap. */
enum { STALL_SPAN = 4 };
#define STALL_FACTOR 0.9

struct rs_steady {
  const rs_model *m;
  SUNContext ctx;     /* the run's (not owned unless own_ctx) */
  SUNContext own_ctx; /* created here when the caller gave none */
  void *kmem;
  N_Vector u, uscale, fscale;
  rs_linsys ls;
  rs_linear linear;      /* resolved choice (never AUTO); DENSE: ls.reduced */
  SUNLinearSolver gmres; /* KRYLOV: SPGMR with the products and preconditioner of kry */
  rs_krylov kry;
  rs_work work;
  double *yp;     /* y' seen by the residual: 0, or cj (y - y_prev) in pseudo-time steps */
  double *y_prev; /* start of the current pseudo-time step */
  double cj;      /* 0: steady; 1/dtau: a backward-Euler step of the rolling transient */
  rs_inputs in;   /* the inputs of the time being solved */
  rs_msg fail;    /* why the model refused an evaluation (then Newton stops at once) */
  int failed;
  long coarse_jac_evals;        /* Jacobian evaluations on coarse grids (grid sequencing) */
  int watch;                    /* stop Newton when it stalls (a fallback follows) */
  int stalled;                  /* ... and it did */
  double fhist[STALL_SPAN + 1]; /* residual norms of the last iterates (ring) */
  /* 3D Newton-Krylov: residuals through kry (rs_krylov_residual) and the forcing term set
   * here before each linear solve (forcing_term) */
  int krylov3d;
  double eta_gamma, eta_prev, eta_next, fnorm_prev;
  double ftol; /* the Newton iteration's stopping test: FNORM_TOL, or an approximate solve's */
  rs_fail_mode fail_fast; /* from a warm start: which fallbacks are left out */
};

/* A model evaluation that failed stops KINSOL at once (-1: unrecoverable) and keeps the
 * reason for the user. */
static int refused(rs_steady *s, const char *why)
{
  s->failed = 1;
  rs_msg_set(&s->fail, RS_ERR_SOLVER, "%s", why);
  return -1;
}

/* y' = cj (y - y_prev) (backward Euler) or 0 (steady). */
static double *rates(rs_steady *s, const double *u)
{
  for (int i = 0; i < s->m->lay.neq; i++)
    s->yp[i] = s->cj > 0.0 ? s->cj * (u[i] - s->y_prev[i]) : 0.0;
  return s->yp;
}

/* Stopping test of the Newton iteration: the max norm of the scaled residual
 * (relative to the largest bound; roundoff is ~1e-12). */
#define FNORM_TOL 1e-10

/* The forcing term eta of the next linear solve (GMRES stops at a scaled residual norm of
 * eta |F|), from the residual f of a new iterate: Eisenstat and Walker's choice 2,
 * eta = gamma (|F_k| / |F_k-1|)^alpha with its safeguard gamma eta_k-1^alpha (when above
 * 0.1) and eta <= 0.9, as KINSOL computes it, with two changes:
 * - no floor eta >= 1e-4, but the Newton iteration's own stopping test (Kelley's
 *   safeguard): no linear residual below half the tolerance. eta multiplies KINSOL's scaled
 *   2-norm while the test measures the max norm; the floor is set on the max norm of F
 *   (eta >= tol / (2 |F|_max)), as if the linear residual's 2-norm to max-norm ratio were
 *   F's. Where it is larger the test fails and Newton takes another iteration, which keeps
 *   the tolerance; a floor on the 2-norm, tol / (2 |F|_2), guarantees the test but solves
 *   the last linear system some ten times past it;
 * - alpha = (1 + sqrt 5)/2 (choice 1's) instead of 2.
 * Both save GMRES iterations and time against KINSOL's own choice 2, for the same results
 * to the Newton tolerance.
 * KINSOL takes the term at the start of an iteration, before the preconditioner's set-up,
 * so it is set here, at each residual of a trial point (the line search's last trial is
 * the iterate). */
static void forcing_term(rs_steady *s, const double *f)
{
  const double *fs = N_VGetArrayPointer(s->fscale);
  double ss = 0.0, fmax_norm = 0.0;
  for (int i = 0; i < s->m->lay.neq; i++) {
    const double r = f[i] * fs[i];
    ss += r * r;
    fmax_norm = fmax(fmax_norm, fabs(r));
  }
  const double fnorm = sqrt(ss), alpha = 0.5 * (1.0 + sqrt(5.0)), g = s->eta_gamma;
  if (!(fnorm > 0.0) || !(s->fnorm_prev > 0.0)) return;
  const double safe = g * pow(s->eta_prev, alpha);
  double eta = fmax(g * pow(fnorm / s->fnorm_prev, alpha), safe < 0.1 ? 0.0 : safe);
  eta = fmin(fmax(eta, 0.5 * s->ftol / fmax_norm), 0.9);
  KINSetEtaConstValue(s->kmem, eta);
  s->eta_next = eta;
}

static int steady_residual(N_Vector u, N_Vector f, void *data)
{
  rs_steady *s = data;
  const double *y = N_VGetArrayPointer(u);
  if (s->krylov3d) { /* the residual and, for a set-up at this point, the linearisation */
    if (rs_krylov_residual(&s->kry, &s->in, y, rates(s, y), s->cj, N_VGetArrayPointer(f)) != RS_OK)
      return refused(s, rs_krylov_error(&s->kry));
  } else if (rs_model_residual(s->m, &s->work, &s->in, y, rates(s, y), s->cj,
                               N_VGetArrayPointer(f)) != RS_OK) {
    return refused(s, s->work.msg.text);
  }
  if (s->krylov3d) forcing_term(s, N_VGetArrayPointer(f));
  return 0;
}

static int steady_jacobian(N_Vector u, N_Vector f, SUNMatrix J, void *data, N_Vector t1,
                           N_Vector t2)
{
  (void)f;
  (void)J;
  (void)t1;
  (void)t2;
  rs_steady *s = data;
  const double *y = N_VGetArrayPointer(u);
  if (rs_linsys_assemble(&s->ls, s->m, &s->work, &s->in, y, rates(s, y), s->cj) != RS_OK)
    return refused(s, s->work.msg.text);
  return 0;
}

/* KRYLOV: the Jacobian is assembled where the preconditioner is set up. */
static int krylov_psetup(N_Vector u, N_Vector uscale, N_Vector fval, N_Vector fscale, void *data)
{
  (void)uscale;
  (void)fval;
  (void)fscale;
  rs_steady *s = data;
  const double *y = N_VGetArrayPointer(u);
  if (s->watch) { /* set up once per Newton iteration, before its linear solve */
    long nni = 0;
    double fnorm = 0.0;
    KINGetNumNonlinSolvIters(s->kmem, &nni);
    KINGetFuncNorm(s->kmem, &fnorm); /* of the iterate nni - 1 */
    const long k = nni - 1;
    s->fhist[k % (STALL_SPAN + 1)] = fnorm;
    if (k >= STALL_SPAN && fnorm > STALL_FACTOR * s->fhist[(k - STALL_SPAN) % (STALL_SPAN + 1)]) {
      s->stalled = 1;
      return -1;
    }
  }
  if (s->krylov3d) { /* the iterate's norm and the term in force for its linear solve */
    KINGetFuncNorm(s->kmem, &s->fnorm_prev);
    s->eta_prev = s->eta_next;
  }
  s->ls.jac_evals++;
  const int status = rs_krylov_setup(&s->kry, &s->in, y, rates(s, y), s->cj);
  if (status == RS_ERR_SOLVER && !rs_krylov_error(&s->kry)[0]) return 1; /* KLU: recoverable */
  return status == RS_OK ? 0 : refused(s, rs_krylov_error(&s->kry));
}

static int krylov_psolve(N_Vector u, N_Vector uscale, N_Vector fval, N_Vector fscale, N_Vector v,
                         void *data)
{
  (void)u;
  (void)uscale;
  (void)fval;
  (void)fscale;
  rs_steady *s = data;
  return rs_krylov_psolve(&s->kry, N_VGetArrayPointer(v)) == RS_OK ? 0 : 1;
}

static int krylov_times(N_Vector v, N_Vector Jv, N_Vector u, sunbooleantype *new_u, void *data)
{
  (void)u;
  (void)new_u;
  rs_steady *s = data;
  return rs_krylov_times(&s->kry, N_VGetArrayPointer(v), N_VGetArrayPointer(Jv)) == RS_OK ? 0 : -1;
}

void rs_steady_free(rs_steady *s)
{
  if (!s) return;
  if (s->kmem) KINFree(&s->kmem);
  if (s->gmres) SUNLinSolFree(s->gmres);
  rs_krylov_free(&s->kry);
  rs_linsys_free(&s->ls);
  if (s->u) N_VDestroy(s->u);
  if (s->uscale) N_VDestroy(s->uscale);
  if (s->fscale) N_VDestroy(s->fscale);
  rs_work_free(&s->work);
  free(s->yp);
  free(s->y_prev);
  if (s->own_ctx) SUNContext_Free(&s->own_ctx);
  free(s);
}

/* AUTO: Newton-Krylov from this many cells (where it overtakes the dense solves on
 * Carter's case), the dense Schur complement below. Plastic models use it too, with a
 * tight forcing term: with the loose one of the elastic case the inexact solves make
 * semismooth Newton cycle between active sets. */
enum { KRYLOV_FROM_CELLS = 300 };
/* Krylov: near-field half band (cells), GMRES basis size, forcing term (1e-3: the fewest
 * GMRES iterations on the elastic creep curve). */
enum { KRYLOV_BAND = 16, KRYLOV_MAXL = 60 };
#define KRYLOV_ETA_PLASTIC 1e-6
#define KRYLOV_ETA         1e-3

int rs_steady_create(rs_steady **out, const rs_model *m, SUNContext ctx, rs_msg *msg)
{
  return rs_steady_create_with(out, m, ctx, RS_LINEAR_AUTO, msg);
}

int rs_steady_create_with(rs_steady **out, const rs_model *m, SUNContext ctx, rs_linear linear,
                          rs_msg *msg)
{
  *out = NULL;
  rs_steady *s = calloc(1, sizeof *s);
  if (!s) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (steady solver)");
  static const char what[] = "steady solver";
  s->m = m;
  if (!ctx && SUNContext_Create(NULL, &s->own_ctx) != 0) {
    free(s);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
  }
  s->ctx = ctx = ctx ? ctx : s->own_ctx;
  const rs_layout *L = &m->lay;
  const int n = L->n, neq = L->neq;
  s->u = N_VNew_Serial(neq, ctx);
  s->uscale = N_VNew_Serial(neq, ctx);
  s->fscale = N_VNew_Serial(neq, ctx);
  s->yp = calloc((size_t)neq, sizeof *s->yp);
  s->y_prev = calloc((size_t)neq, sizeof *s->y_prev);
  /* The fast paths know the per-cell unknowns only (2D); 3D is Newton-Krylov. */
  const int three = m->el.dim == 3;
  if (three)
    linear = RS_LINEAR_KRYLOV;
  else if (L->nextra != 0)
    linear = RS_LINEAR_KLU;
  if (linear == RS_LINEAR_AUTO)
    linear = n >= KRYLOV_FROM_CELLS ? RS_LINEAR_KRYLOV : RS_LINEAR_DENSE;
  s->linear = linear;
  if (!s->u || !s->uscale || !s->fscale || !s->yp || !s->y_prev ||
      rs_work_create(&s->work, m) != RS_OK ||
      (linear != RS_LINEAR_KRYLOV && rs_linsys_create(&s->ls, m, s->u, ctx) != RS_OK)) {
    rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (steady solver, %d unknowns)", neq);
    goto fail;
  }
  /* KINSOL's work vectors and the Krylov basis are clones of u: optimised kernels. */
  RS_SUN_CHECK(rs_nvector_fast_ops(s->u), msg, what);
  RS_SUN_CHECK(rs_nvector_fast_ops(s->uscale), msg, what);
  RS_SUN_CHECK(rs_nvector_fast_ops(s->fscale), msg, what);
  if (linear == RS_LINEAR_DENSE)
    RS_SUN_CHECK(rs_linsys_use_reduced(&s->ls, m, &s->work, ctx), msg, what);
  if (linear == RS_LINEAR_KRYLOV) {
    /* 3D: our GMRES with its vector work fused (gmres.h); 2D keeps SPGMR */
    if (three) {
      s->gmres = rs_gmres_create(&s->kry, s->u, KRYLOV_MAXL, 4, ctx);
      RS_SUN_CHECK(s->gmres == NULL, msg, what);
    } else {
      s->gmres = SUNLinSol_SPGMR(s->u, SUN_PREC_RIGHT, KRYLOV_MAXL, ctx);
      RS_SUN_CHECK(s->gmres == NULL, msg, what);
      RS_SUN_CHECK(SUNLinSol_SPGMRSetMaxRestarts(s->gmres, 4), msg, what);
      RS_SUN_CHECK(SUNLinSol_SPGMRSetGSType(s->gmres, SUN_CLASSICAL_GS), msg, what);
    }
    RS_SUN_CHECK(rs_krylov_create(&s->kry, m, three ? RS_KRYLOV_BAND_3D : KRYLOV_BAND,
                                  three ? RS_KRYLOV_BAND_3D_Y : 0),
                 msg, what);
    /* 3D: a set-up keeps the factored near field while every cell stays on the branches
     * it had then (cj = 0: the ratio is moot), across Newton iterations and continuation
     * points: the near field's values then change only through the disk laws' curvature
     * and the yield slopes, and GMRES's iterations hardly change. Allowing cells on other
     * branches cost more GMRES iterations than the factorisations it saved. */
    if (three) rs_krylov_set_reuse(&s->kry, 2.0, 0);
  }

  /* Scales: tractions by the largest bound, displacements by the displacement that
   * traction causes on its own cell; every residual row has traction units. */
  double pref = 0.0;
  for (int i = 0; i < n; i++) pref = fmax(pref, m->bound[i]);
  if (!(pref > 0.0)) pref = 1.0;
  const double uref = pref * (rs_elastic_op_coef(&m->el, 0, 0, 0, 0) + m->layer_flex);
  double *us = N_VGetArrayPointer(s->uscale), *fs = N_VGetArrayPointer(s->fscale);
  for (int k = 0; k < rs_at_upl(L, 0, 0); k++) us[k] = 1.0 / pref;
  for (int k = rs_at_upl(L, 0, 0); k < rs_at_extra(L, 0); k++) us[k] = 1.0 / uref;
  for (int i = 0; i < neq; i++) fs[i] = 1.0 / pref;
  for (int i = 0; i < n && L->memory; i++) /* friction memory: mu itself */
    us[rs_at_mu(L, i)] = 1.0 / rs_friction_mu(&m->par.friction, 0.0);
  for (int k = 0; k < L->nextra; k++) /* creepage: its saturation value mu a/R sets the scale */
    us[rs_at_extra(L, k)] = m->par.radius / (rs_friction_mu(&m->par.friction, 0.0) * m->hertz_a);

  s->kmem = KINCreate(ctx);
  RS_SUN_CHECK(s->kmem == NULL, msg, what);
  RS_SUN_CHECK(KINInit(s->kmem, steady_residual, s->u), msg, what);
  RS_SUN_CHECK(KINSetUserData(s->kmem, s), msg, what);
  if (s->gmres) {
    RS_SUN_CHECK(KINSetLinearSolver(s->kmem, s->gmres, NULL), msg, what);
    RS_SUN_CHECK(KINSetJacTimesVecFn(s->kmem, krylov_times), msg, what);
    RS_SUN_CHECK(KINSetPreconditioner(s->kmem, krylov_psetup, krylov_psolve), msg, what);
    /* 2D: the residual is piecewise linear; once the active set is right, an accurate
     * linear solve ends the iteration (a loose forcing term would add iterations).
     * 3D: the disk projections are curved, Newton needs a few more iterations anyway, and
     * Eisenstat and Walker's forcing term (choice 2) saves GMRES iterations (a third of the
     * time or more against the constant terms). Plastic models take gamma = 0.1 (eta <=
     * 0.1) instead of 0.9: where the residual fell slowly the default term stayed near 0.9,
     * GMRES did one iteration per Newton step and the line search stalled. Elastic models
     * keep 0.9 (with 0.1 they took more Newton iterations). */
    if (three) {
      RS_SUN_CHECK(KINSetEtaForm(s->kmem, KIN_ETACONSTANT), msg, what);
      s->krylov3d = 1;
      s->eta_gamma = m->par.plasticity.on ? 0.1 : 0.9;
    } else {
      RS_SUN_CHECK(KINSetEtaForm(s->kmem, KIN_ETACONSTANT), msg, what);
      RS_SUN_CHECK(
          KINSetEtaConstValue(s->kmem, m->par.plasticity.on ? KRYLOV_ETA_PLASTIC : KRYLOV_ETA), msg,
          what);
    }
  } else {
    RS_SUN_CHECK(KINSetLinearSolver(s->kmem, rs_linsys_solver(&s->ls), rs_linsys_matrix(&s->ls)),
                 msg, what);
    RS_SUN_CHECK(KINSetJacFn(s->kmem, steady_jacobian), msg, what);
  }
  RS_SUN_CHECK(KINSetMaxSetupCalls(s->kmem, 1), msg, what);    /* exact Newton */
  RS_SUN_CHECK(KINSetMaxNewtonStep(s->kmem, 1e12), msg, what); /* steps from p = 0 are large */
  /* relative to the largest bound; roundoff is ~1e-12 */
  s->ftol = FNORM_TOL;
  RS_SUN_CHECK(KINSetFuncNormTol(s->kmem, s->ftol), msg, what);
  RS_SUN_CHECK(KINSetScaledStepTol(s->kmem, 1e-13), msg, what);
  RS_SUN_CHECK(KINSetErrHandlerFn(s->kmem, rs_sundials_silent, NULL), msg, what);
  *out = s;
  return RS_OK;
fail:
  rs_steady_free(s);
  return RS_ERR_INTERNAL;
}

/* Newton from y: plain with at most plain_iters iterations, then (if that fails)
 * with a line search and at most search_iters (0: none); RS_OK and the solution in
 * y, or RS_ERR_SOLVER with y unchanged. */
static int newton(rs_steady *s, double *y, int plain_iters, int search_iters, rs_stats *stats,
                  int *kin_flag)
{
  const rs_model *m = s->m;
  const int neq = m->lay.neq;
  double *u = N_VGetArrayPointer(s->u);
  int flag = KIN_MAXITER_REACHED;
  const int strategies[2] = {KIN_NONE, KIN_LINESEARCH}, caps[2] = {plain_iters, search_iters};
  for (int k = 0; k < 2; k++) {
    if (caps[k] <= 0) continue;
    KINSetNumMaxIters(s->kmem, caps[k]);
    memcpy(u, y, (size_t)neq * sizeof *u);
    s->stalled = 0;
    if (s->krylov3d) { /* KINSOL's initial term for choices 1 and 2 */
      s->eta_next = 0.5;
      s->fnorm_prev = 0.0;
      KINSetEtaConstValue(s->kmem, s->eta_next);
    }
    flag = KINSol(s->kmem, s->u, strategies[k], s->uscale, s->fscale);
    if (s->stalled) flag = KIN_LINESEARCH_NONCONV;
    if (flag < 0 && s->gmres) rs_krylov_invalidate(&s->kry); /* what follows factors afresh */
    long iters = 0, fevals = 0, lin_iters = 0;
    KINGetNumNonlinSolvIters(s->kmem, &iters);
    KINGetNumFuncEvals(s->kmem, &fevals);
    if (s->gmres) KINGetNumLinIters(s->kmem, &lin_iters);
    if (stats) {
      stats->nonlin_iters += iters;
      stats->res_evals += fevals;
      /* direct: one solve per Newton iteration; Krylov: GMRES iterations */
      stats->lin_solves += s->gmres ? lin_iters : iters;
    }
    if (flag == KIN_STEP_LT_STPTOL) { /* stalled: accept only a small residual */
      double fnorm = INFINITY;
      KINGetFuncNorm(s->kmem, &fnorm);
      if (fnorm > fmax(1e-9, s->ftol)) flag = KIN_LINESEARCH_NONCONV;
    }
    if (flag >= 0 || s->failed) break;
  }
  *kin_flag = flag;
  if (flag < 0) return RS_ERR_SOLVER;
  memcpy(y, u, (size_t)neq * sizeof *u);
  return RS_OK;
}

/* Fallback after grid sequencing when Newton cycles between active sets (docs/model.md
 * §13; seen with work hardening, where the trailing end of the plastic zone moves by
 * about one cell per iteration): pseudo-transient continuation with backward-Euler steps of the
 * rolling transient, F(y, (y - y_prev)/dtau) = 0, each solved by the same exact
 * Newton. The c_j terms keep the active set close to the previous one, so the steps
 * converge in a few iterations as long as the material rolls less than about one
 * contact length per step: dtau starts at one cell passage, doubles after a step
 * that converged in few iterations, halves after a failed one, and never exceeds
 * half a contact length. The steps follow the physical approach to steady rolling;
 * once a step changes the tractions little, steady Newton is tried from its state. */
enum { STEP_ITERS = 12, STEADY_TRY_ITERS = 15, MAX_PSEUDO_STEPS = 400 };
static int pseudo_time_steps(rs_steady *s, double *y, rs_stats *stats)
{
  const rs_model *m = s->m;
  const int neq = m->lay.neq;
  const double V = s->in.velocity, cell_time = m->grid.dx / V;
  const double dtau_max = fmax(cell_time, m->hertz_a / V);
  double dtau = cell_time;
  int status = RS_ERR_SOLVER, kin_flag = 0;
  double *z = malloc((size_t)neq * sizeof *z);
  if (!z) return RS_ERR_INTERNAL;
  memcpy(z, y, (size_t)neq * sizeof *z);
  for (int step = 0; step < MAX_PSEUDO_STEPS && status != RS_OK && !s->failed; step++) {
    memcpy(s->y_prev, z, (size_t)neq * sizeof *z);
    s->cj = 1.0 / dtau;
    const long before = stats ? stats->nonlin_iters : 0;
    if (newton(s, z, STEP_ITERS, 0, stats, &kin_flag) != RS_OK) { /* too ambitious: shorter */
      memcpy(z, s->y_prev, (size_t)neq * sizeof *z);
      dtau *= 0.5;
      if (dtau < 1e-3 * cell_time) break;
      continue;
    }
    const long used = stats ? stats->nonlin_iters - before : 0;
    double change = 0.0, size = 0.0;
    for (int k = 0; k < m->lay.ncomp * m->lay.n; k++) { /* the tractions */
      change = fmax(change, fabs(z[k] - s->y_prev[k]));
      size = fmax(size, fabs(z[k]));
    }
    if (change <= 1e-3 * size) { /* close to steady: try steady Newton from here */
      s->cj = 0.0;
      memcpy(y, z, (size_t)neq * sizeof *y);
      status = newton(s, y, STEADY_TRY_ITERS, 0, stats, &kin_flag);
      if (status == RS_OK) break;
    }
    if (used <= STEP_ITERS / 2) dtau = fmin(2.0 * dtau, dtau_max);
  }
  s->cj = 0.0;
  free(z);
  return status;
}

/* Last fallback when Newton cycles between active sets (seen with moderate hardening,
 * docs/model.md §13): pseudo-transient continuation, i.e. roll the material through the
 * contact at the inputs of the time being solved (all of them held: velocity, creepage,
 * shift, load, prescribed force and the rig memory's inflow), which is the physical
 * transient and settles on the steady state, trying Newton from the rolled state after
 * every few contact lengths. */
static int pseudo_transient(rs_steady *s, double *y, rs_stats *stats, rs_msg *msg)
{
  const rs_model *m = s->m;
  const int neq = m->lay.neq;
  rs_inputs frozen = s->in;
  rs_inputs_freeze(&frozen);
  const double V = frozen.velocity, contact_length = 2.0 * m->hertz_a;
  const double chunk = 4.0 * contact_length / V, max_time = 400.0 * contact_length / V;
  double *z = calloc((size_t)neq, sizeof *z), *zp = calloc((size_t)neq, sizeof *zp);
  rs_work w = {0};
  int status = (z && zp && rs_work_create(&w, m) == RS_OK) ? RS_OK : RS_ERR_INTERNAL;
  if (status != RS_OK) rs_msg_set(msg, status, "out of memory (pseudo-transient)");
  rs_transient *tr = NULL;
  /* 3D softening: rtol 1e-3. The roll only selects which of several steady states (zeros of
   * the discrete equations, docs/model.md §13) the material reaches, and Newton then solves it
   * from the rolled state; a looser roll reaches the same one, in much less time. */
  const int softening_3d = m->el.dim == 3 && m->par.plasticity.on && m->par.plasticity.k_tau < 0.0;
  rs_transient_opts o = {.rtol = softening_3d ? 1e-3 : 1e-6,
                         .atol = 1e-6,
                         .max_order = 5,
                         .max_steps = 1000000,
                         .max_newton = 10,
                         .t_stop = INFINITY,
                         .frozen = &frozen};
  if (status == RS_OK) rs_model_rest_state(m, z);
  if (status == RS_OK) status = rs_model_consistent_rates(m, &w, &frozen, z, zp, msg);
  if (status == RS_OK) status = rs_transient_create(&tr, m, s->ctx, 0.0, z, zp, &o, msg);
  int kin_flag = 0;
  double tau = 0.0;
  while (status == RS_OK) {
    tau += chunk;
    if (tau > max_time) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "steady solver: Newton cycles between contact regimes and the material "
                          "rolled %.0f contact lengths without settling (t = %g s)",
                          max_time * V / contact_length, s->in.t);
      break;
    }
    status = rs_transient_advance(tr, tau, z, zp, msg);
    if (status != RS_OK) break;
    memcpy(y, z, (size_t)neq * sizeof *y);
    if (newton(s, y, 50, 50, stats, &kin_flag) == RS_OK) break;
    if (s->failed) status = rs_msg_set(msg, RS_ERR_SOLVER, "%s", s->fail.text);
  }
  if (tr && stats) {
    rs_stats st;
    rs_transient_get_stats(tr, &st);
    stats->steps += st.steps;
    stats->nonlin_iters += st.nonlin_iters;
  }
  rs_transient_free(tr);
  rs_work_free(&w);
  free(z);
  free(zp);
  return status;
}

/* The work of an auxiliary solve (a coarser grid, a harder or perfectly plastic model) added
 * to the caller's counts. */
static void add_aux_stats(rs_steady *s, rs_stats *stats, const rs_stats *aux)
{
  if (stats) {
    stats->steps += aux->steps;
    stats->nonlin_iters += aux->nonlin_iters;
    stats->res_evals += aux->res_evals;
    stats->lin_solves += aux->lin_solves;
  }
  s->coarse_jac_evals += aux->jac_evals;
}

/* The steady state of an auxiliary model (sharing s's grid and operator, read only) from z,
 * with s's fail-fast mode; its work added to *aux_stats. */
static int aux_solve(const rs_steady *s, const rs_model *aux, double *z, rs_stats *aux_stats)
{
  rs_steady *as = NULL;
  rs_msg msg = {{0}};
  int status = rs_steady_create(&as, aux, s->ctx, &msg);
  if (status == RS_OK) as->fail_fast = s->fail_fast;
  if (status == RS_OK) status = rs_steady_solve(as, s->in.t, z, aux_stats, &msg);
  rs_steady_free(as);
  return status;
}

/* Grid sequencing (docs/model.md §13): first for a plastic model from rest, the first
 * fallback otherwise. The same problem on a grid of half the cells (solved by this
 * same function, so recursively down to a grid where Newton converges), interpolated
 * to this grid, is a start close enough that the active set settles in a few
 * iterations: the zone boundaries are off by a coarse cell at most, where from p = 0
 * the trailing end of a work-hardening plastic zone moves by about one cell per
 * iteration. */
enum { COARSE_MIN_CELLS = 40, COARSE_MIN_CELLS_3D = 12 };
/* Whether the grid is fine enough to be solved through a coarser one (cells along x; in
 * 3D the grid halves along x and y, and plastic Newton from rest cycles from about 28 x 28
 * cells on). */
static int can_coarsen(const rs_model *m)
{
  const int min = m->el.dim == 3 ? COARSE_MIN_CELLS_3D : COARSE_MIN_CELLS;
  return m->grid.nx >= 2 * min && (m->grid.ny == 1 || m->grid.ny >= 2 * min);
}
/* grid_sequencing: the coarse solution was found but Newton did not converge from
 * its interpolation, which is left in y as the start of the next fallback. */
enum { RS_START_ONLY = -1 };
static int grid_sequencing(rs_steady *s, double *y, int plain, rs_stats *stats)
{
  const rs_model *m = s->m;
  const int nx = m->grid.nx;
  if (!can_coarsen(m)) return RS_ERR_SOLVER;
  rs_model coarse;
  rs_msg cmsg = {{0}};
  if (rs_model_regrid(m, (nx + 1) / 2, &coarse, &cmsg) != RS_OK) return RS_ERR_SOLVER;
  rs_steady *cs = NULL;
  rs_work cw = {0};
  double *yc = calloc((size_t)coarse.lay.neq, sizeof *yc);
  int status = yc && rs_work_create(&cw, &coarse) == RS_OK ? RS_OK : RS_ERR_INTERNAL;
  if (status == RS_OK) status = rs_steady_create(&cs, &coarse, s->ctx, &cmsg);
  if (status == RS_OK) cs->fail_fast = s->fail_fast;
  if (status == RS_OK) status = rs_model_interpolate_state(m, y, &coarse, &cw, &s->in, yc, &cmsg);
  rs_stats cst = {0};
  if (status == RS_OK) status = rs_steady_solve(cs, s->in.t, yc, &cst, &cmsg);
  add_aux_stats(s, stats, &cst);
  double *z = status == RS_OK ? malloc((size_t)m->lay.neq * sizeof *z) : NULL;
  if (status == RS_OK && !z) status = RS_ERR_INTERNAL;
  if (status == RS_OK)
    status = rs_model_interpolate_state(&coarse, yc, m, &s->work, &s->in, z, &cmsg);
  if (status == RS_OK) {
    s->cj = 0.0;
    /* the solution or, when Newton fails (y unchanged), a close start */
    memcpy(y, z, (size_t)m->lay.neq * sizeof *y);
    if (newton(s, y, plain, 40, stats, &(int){0}) != RS_OK) status = RS_START_ONLY;
  }
  free(z);
  free(yc);
  rs_steady_free(cs);
  rs_work_free(&cw);
  rs_model_free(&coarse);
  return status == RS_OK || status == RS_START_ONLY ? status : RS_ERR_SOLVER;
}

/* Weak hardening from rest: a 3D model with Coulomb friction, no memory and no force
 * control whose k_rel = k_tau/(G + k_tau) lies in (0, K_REL_WEAK), where steady Newton's
 * friction weight falls with k_rel (rs_model_evaluate). On the coarsest grid (the one grid
 * sequencing ends on) its Newton from rest can stall at once, while k_rel = K_REL_START
 * converges from rest in a few iterations: so it starts there and continues in k_rel, each
 * step a factor K_REL_STEP, down to the model's. Only the coarsest grid needs it; the finer
 * grids start from the coarser solution (bench/RESULTS.md, issue 42). */
#define K_REL_WEAK     0.07
#define K_REL_START    0.3
#define K_REL_STEP     0.3
#define K_REL_STEP_MIN 1.5
static int weak_hardening(const rs_model *m)
{
  const double k_tau = m->par.plasticity.k_tau;
  return m->el.dim == 3 && m->par.plasticity.on && k_tau > 0.0 &&
         k_tau / (m->par.shear_modulus + k_tau) < K_REL_WEAK &&
         !rs_friction_varies(&m->par.friction) && !m->lay.memory && !m->par.force_control;
}

/* u* times f. A step of the continuation in k_tau keeps each cell's yield limit
 * tau_c0 + k_tau u*, so u* scales with 1/k_tau: a cell that hardened up to the friction
 * bound stays there (tau_c = mu p_n), where the last step's solution taken as it is would
 * put it 1/K_REL_STEP times too far below, and Newton can stall (bench/RESULTS.md, issue 42). */
static void rescale_ustar(const rs_model *m, double *y, double f)
{
  for (int i = 0; i < m->lay.n; i++) y[rs_at_ustar(&m->lay, i)] *= f;
}

/* The start of a weak-hardening model from rest or from a state where its own Newton
 * failed: the steady states of the same model with k_rel = K_REL_START, K_REL_STEP times
 * that, ... while above K_REL_STEP_MIN times the model's, the first from y, each from the
 * last, with u* rescaled to its k_tau (the model's copy shares its grid, operator and normal
 * solution, read only). RS_OK with the last in y (u* rescaled to the model's k_tau), else
 * RS_ERR_SOLVER (y unchanged). */
static int harder_start(rs_steady *s, double *y, rs_stats *stats)
{
  rs_model hard = *s->m;
  rs_stats hst = {0};
  const int neq = s->m->lay.neq;
  double *z = malloc((size_t)neq * sizeof *z);
  const double G = s->m->par.shear_modulus, k_tau = s->m->par.plasticity.k_tau;
  const double k_rel = k_tau / (G + k_tau);
  int status = z ? RS_OK : RS_ERR_INTERNAL;
  if (z) memcpy(z, y, (size_t)neq * sizeof *z);
  double k_prev = k_tau; /* the k_tau of z */
  for (double kr = K_REL_START; status == RS_OK && kr > K_REL_STEP_MIN * k_rel; kr *= K_REL_STEP) {
    hard.par.plasticity.k_tau = G * kr / (1.0 - kr);
    rescale_ustar(s->m, z, k_prev / hard.par.plasticity.k_tau);
    k_prev = hard.par.plasticity.k_tau;
    status = aux_solve(s, &hard, z, &hst);
  }
  add_aux_stats(s, stats, &hst);
  if (status == RS_OK) rescale_ustar(s->m, z, k_prev / k_tau);
  if (status == RS_OK) memcpy(y, z, (size_t)neq * sizeof *y);
  free(z);
  return status == RS_OK ? RS_OK : RS_ERR_SOLVER;
}

/* Softening from rest on the coarsest grid (a 3D model with Coulomb friction, no memory and no
 * force control, k_tau < 0): the steady state of the same model with k_tau = 0 (perfect
 * plasticity) from y as the start, since the perfectly plastic model converges from rest where
 * the softening one's line search can fail, and the softening one converges from it. RS_OK
 * with the start in y (else y unchanged). */
static int perfectly_plastic_start(rs_steady *s, double *y, rs_stats *stats)
{
  rs_model pp = *s->m;
  rs_stats pst = {0};
  const int neq = s->m->lay.neq;
  double *z = malloc((size_t)neq * sizeof *z);
  if (!z) return RS_ERR_INTERNAL;
  memcpy(z, y, (size_t)neq * sizeof *z);
  pp.par.plasticity.k_tau = 0.0;
  const int status = aux_solve(s, &pp, z, &pst);
  add_aux_stats(s, stats, &pst);
  if (status == RS_OK) memcpy(y, z, (size_t)neq * sizeof *y);
  free(z);
  return status == RS_OK ? RS_OK : RS_ERR_SOLVER;
}

/* The steady solve at the inputs in s->in. */
static int solve_at(rs_steady *s, double *y, rs_stats *stats, rs_msg *msg)
{
  const rs_model *m = s->m;
  const int neq = m->lay.neq;
  s->failed = 0;
  int kin_flag = 0;
  s->cj = 0.0;
  double *start = malloc((size_t)neq * sizeof *start);
  if (!start) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  memcpy(start, y, (size_t)neq * sizeof *start);
  /* From rest, a plastic model goes to the coarse grid at once (Newton from p = 0
   * cycles at the trailing end of the plastic zone on fine grids); otherwise Newton
   * first, from the caller's start (continuation). */
  int cold = 1;
  for (int k = 0; k < m->lay.ncomp * m->lay.n && cold; k++) cold = y[k] == 0.0;
  const int plastic = m->par.plasticity.on, three_plastic = m->el.dim == 3 && plastic;
  /* 3D plastic from rest far beyond saturation: Newton (line search, stopped when it stalls)
   * from the full-sliding state first, whose active set is nearly the solution's, instead of
   * the coarse grids, the k_rel continuation and the fallbacks (bench/RESULTS.md, issue 42).
   * If it fails, from rest as before. */
  int status = RS_ERR_SOLVER;
  if (cold && three_plastic && rs_model_sliding_state(m, &s->work, &s->in, y) == RS_OK) {
    s->watch = 1;
    status = newton(s, y, 0, 40, stats, &kin_flag);
    s->watch = 0;
    if (status == RS_OK) {
      cold = 0;
    } else {
      memcpy(y, start, (size_t)neq * sizeof *y);
      s->failed = 0;
    }
  }
  if (cold && weak_hardening(m) && !can_coarsen(m) && harder_start(s, y, stats) == RS_OK) cold = 0;
  if (cold && three_plastic && m->par.plasticity.k_tau < 0.0 && !can_coarsen(m) &&
      !rs_friction_varies(&m->par.friction) && !m->lay.memory && !m->par.force_control &&
      perfectly_plastic_start(s, y, stats) == RS_OK)
    cold = 0;
  const int sequence_first = plastic && cold && can_coarsen(m);
  /* 3D: the fine grid's Newton from the interpolated coarse solution with the line search at
   * once; from full sliding plain Newton uses up its iterations without converging. */
  if (sequence_first) status = grid_sequencing(s, y, three_plastic ? 0 : 10, stats);
  /* Plastic models from a continuation start: plain Newton briefly, then the line
   * search, which converges in a few iterations where plain Newton cycles. In 3D the line
   * search at once: with the inexact early steps of the Eisenstat-Walker forcing term plain
   * Newton takes many more iterations at most continuation points; 3D plastic models from
   * rest too (on the coarsest grid of the sequence plain Newton cycles), and the finer
   * grids' Newton after sequencing (above). 2D's finer grids start plain: from the
   * interpolated coarse solution plain Newton needs fewer iterations than the line search. */
  const int plain = three_plastic ? 0 : !plastic || cold ? 50 : 8;
  /* 3D plastic continuation points on grids that can be coarsened: a stalled line
   * search goes to grid sequencing at once, whose fine-grid Newton then starts with the
   * line search, as plain Newton from the interpolated coarse solution diverges at most
   * such points. Coarse grids rarely stall, so this matters on fine ones. With softening, a
   * step that may fail fast (the sweep then halves it) is watched on the coarsest grid too:
   * a stall there ends the step early, as its halves converge more cheaply than Newton runs
   * to its cap. */
  const int softening = plastic && m->par.plasticity.k_tau < 0.0;
  if (status == RS_ERR_SOLVER && !s->failed) {
    s->watch =
        three_plastic && !cold && (can_coarsen(m) || (softening && s->fail_fast == RS_FAIL_FAST));
    status = newton(s, y, plain, plastic ? 40 : 50, stats, &kin_flag);
    s->watch = 0;
  }
  /* With hardening a 3D step that may fail fast leaves out grid sequencing too: the sweep
   * halves it at once, from the last solution (the steady state is unique there), which
   * converges where Newton from the interpolated coarse solution tends to stall again. */
  const int halved_next =
      three_plastic && !cold && m->par.plasticity.k_tau > 0.0 && s->fail_fast == RS_FAIL_FAST;
  if (status == RS_ERR_SOLVER && !sequence_first && !s->failed && !halved_next)
    status = grid_sequencing(s, y, three_plastic ? 0 : 10, stats);
  /* Pseudo-time from the interpolated coarse solution when there is one (a few steps
   * settle the trailing end of the plastic zone), else from the caller's start. */
  /* Velocity-dependent friction: no rolling fallbacks. Without friction memory the
   * transient of a falling law is ill-posed (its steps collapse), so they would only
   * take long to fail; say so at once. */
  const int varies = rs_friction_varies(&m->par.friction);
  if (status != RS_OK && !s->failed && varies) {
    s->failed = 1;
    rs_msg_set(&s->fail, RS_ERR_SOLVER,
               "steady Newton did not converge at creepage %g with friction.law: %s (a falling "
               "friction law can make Newton cycle between active sets; approach this "
               "creepage by continuation, e.g. a sweep from a lower one)",
               rs_model_creepage(m, &s->in, y), rs_friction_name(m->par.friction.kind));
  }
  /* Weak hardening at a continuation point where Newton failed on every grid: continuation
   * in k_rel from the last start (the interpolated coarse solution when there is one), as
   * from rest. The line search and the fine grid's Newton after sequencing can both stall
   * there, and the pseudo-time steps' steady Newton cycle as well (a low tau_c0 with weak
   * hardening: bench/RESULTS.md, issue 42). From rest the coarsest grid has continued in k_rel
   * already. */
  const int fast = s->fail_fast != RS_FAIL_NEVER && !cold,
            quick = fast && s->fail_fast == RS_FAIL_FAST;
  if (status != RS_OK && !s->failed && !cold && !quick && weak_hardening(m) &&
      harder_start(s, y, stats) == RS_OK)
    status = newton(s, y, 0, 40, stats, &kin_flag);
  if (status != RS_OK && !s->failed && !quick) status = pseudo_time_steps(s, y, stats);
  int rolled = varies; /* the result comes from rolling the material (the physical path) */
  if (status != RS_OK && !s->failed && fast) {
    memcpy(y, start, (size_t)neq * sizeof *y);
    status = rs_msg_set(msg, RS_ERR_SOLVER,
                        "steady Newton did not converge from the last continuation point");
  } else if (status == RS_ERR_SOLVER && !s->failed) {
    memcpy(y, start, (size_t)neq * sizeof *y);
    status = pseudo_transient(s, y, stats, msg);
    rolled = 1;
  }
  if (s->failed) status = rs_msg_set(msg, RS_ERR_SOLVER, "%s", s->fail.text);
  /* Every result is checked (rs_model_check_steady): a zero of the residual that is not
   * a physical steady state is refused; the transient path from the caller's start
   * then decides, and its result must pass the same check. */
  rs_msg why = {{0}};
  if (status == RS_OK && (status = rs_model_check_steady_with(
                              m, rs_steady_evaluated(s, y), &s->work, &s->in, y, &why)) != RS_OK) {
    if (stats) stats->refused++;
    if (!rolled && status == RS_ERR_SOLVER && fast) {
      memcpy(y, start, (size_t)neq * sizeof *y); /* the caller shortens its step */
    } else if (!rolled && status == RS_ERR_SOLVER) {
      memcpy(y, start, (size_t)neq * sizeof *y);
      status = pseudo_transient(s, y, stats, msg);
      if (status == RS_OK)
        status = rs_model_check_steady(m, &s->work, &s->in, y, &why);
      else
        why.text[0] = '\0'; /* msg says why the transient path failed */
    }
    if (status != RS_OK && why.text[0]) rs_msg_set(msg, status, "%s", why.text);
  }
  free(start);
  if (stats) {
    stats->jac_evals = s->ls.jac_evals + s->coarse_jac_evals;
    stats->klu_analyses = rs_linsys_analyses(&s->ls);
  }
  return status;
}

/* Velocity-dependent friction from rest: continuation in the creepage from 0 in steps of
 * 1/CONTINUATION_STEPS of it (in 3D the lateral creepage and the spin scaled with it: all
 * rigid slip grows from rest together), each Newton started on the secant through the last two
 * solutions; a step that fails is halved (down to 1/CONTINUATION_MIN of the creepage). A
 * falling law can have several steady states at one creepage; this follows the branch
 * connected to xi = 0 (the one `rollsim sweep` from a low creepage follows), and Newton
 * from p = 0 at a large creepage fails (plastic Table-1 contact, xi = -1 %); halving rescues
 * a first step that is too long. */
enum { CONTINUATION_STEPS = 16, CONTINUATION_MIN = 1024 };
static int continuation(rs_steady *s, double *y, rs_stats *stats, rs_msg *msg)
{
  const int neq = s->m->lay.neq;
  const double xi = s->in.creepage, eta = s->in.lateral_creepage, phi = s->in.spin;
  double *prev = calloc((size_t)neq, sizeof *prev), *cur = calloc((size_t)neq, sizeof *cur);
  if (!prev || !cur) {
    free(prev);
    free(cur);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (continuation)");
  }
  rs_model_rest_state(s->m, prev);
  rs_model_rest_state(s->m, cur);
  int status = RS_OK, have_prev = 0;
  double lam_prev = 0.0, lam_cur = 0.0, dl = 1.0 / CONTINUATION_STEPS;
  rs_stats total = {0};
  while (lam_cur < 1.0) {
    const double lam = fmin(1.0, lam_cur + dl);
    s->in.creepage = xi * lam;
    s->in.lateral_creepage = eta * lam;
    s->in.spin = phi * lam;
    const double f = have_prev ? (lam - lam_cur) / (lam_cur - lam_prev) : 0.0;
    for (int i = 0; i < neq; i++) y[i] = cur[i] + f * (cur[i] - prev[i]); /* secant */
    rs_stats st = {0};
    status = solve_at(s, y, &st, msg);
    total.steps += st.steps;
    total.nonlin_iters += st.nonlin_iters;
    total.nonlin_fails += st.nonlin_fails;
    total.err_test_fails += st.err_test_fails;
    total.res_evals += st.res_evals;
    total.lin_solves += st.lin_solves;
    total.factorizations += st.factorizations;
    total.refused += st.refused;
    total.jac_evals = st.jac_evals; /* the solver's running totals */
    total.klu_analyses = st.klu_analyses;
    if (status == RS_OK) {
      memcpy(prev, cur, (size_t)neq * sizeof *prev);
      memcpy(cur, y, (size_t)neq * sizeof *cur);
      lam_prev = lam_cur;
      lam_cur = lam;
      have_prev = 1;
    } else if (status == RS_ERR_SOLVER && dl > 1.5 / CONTINUATION_MIN) {
      dl *= 0.5;
    } else {
      break;
    }
  }
  if (status != RS_OK) memcpy(y, cur, (size_t)neq * sizeof *y);
  s->in.creepage = xi;
  s->in.lateral_creepage = eta;
  s->in.spin = phi;
  if (stats) *stats = total;
  free(prev);
  free(cur);
  return status;
}

int rs_steady_solve(rs_steady *s, double t, double *y, rs_stats *stats, rs_msg *msg)
{
  const rs_model *m = s->m;
  rs_model_inputs_at(m, t, &s->in);
  s->in.newton = 1; /* the weights of Newton's evaluations (rs_model_evaluate) */
  if (!(s->in.velocity > 0.0))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "steady rolling needs a rolling velocity > 0 (got %g mm/s at t = %g s)",
                      s->in.velocity, t);
  int cold = 1;
  for (int k = 0; k < m->lay.ncomp * m->lay.n && cold; k++) cold = y[k] == 0.0;
  if (cold && rs_friction_varies(&m->par.friction) && !m->par.force_control)
    return continuation(s, y, stats, msg);
  return solve_at(s, y, stats, msg);
}

void rs_steady_set_fail_fast(rs_steady *s, rs_fail_mode mode) { s->fail_fast = mode; }

const rs_inputs *rs_steady_inputs(const rs_steady *s) { return &s->in; }

int rs_steady_linearise(rs_steady *s, double t, const double *y, rs_msg *msg)
{
  const rs_model *m = s->m;
  rs_model_inputs_at(m, t, &s->in);
  s->in.newton = 1;
  s->cj = 0.0;
  double *yp = rates(s, y);
  int status;
  if (s->gmres) {
    status = rs_krylov_setup(&s->kry, &s->in, y, yp, 0.0);
    if (status == RS_OK) s->ls.jac_evals++;
    if (status != RS_OK)
      return rs_msg_set(msg, RS_ERR_SOLVER, "steady Jacobian at the coupled state: %s",
                        rs_krylov_error(&s->kry)[0] ? rs_krylov_error(&s->kry)
                                                    : "near field singular");
    return RS_OK;
  }
  status = rs_linsys_assemble(&s->ls, m, &s->work, &s->in, y, yp, 0.0);
  if (status != RS_OK)
    return rs_msg_set(msg, RS_ERR_SOLVER, "steady Jacobian at the coupled state: %s",
                      s->work.msg.text);
  if (SUNLinSolSetup(rs_linsys_solver(&s->ls), rs_linsys_matrix(&s->ls)) != 0)
    return rs_msg_set(msg, RS_ERR_SOLVER, "steady Jacobian at the coupled state is singular");
  return RS_OK;
}

int rs_steady_linear_solve(rs_steady *s, const double *b, double *x, double rtol, rs_msg *msg)
{
  const int neq = s->m->lay.neq;
  N_Vector vb = N_VNew_Serial(neq, s->ctx), vx = N_VNew_Serial(neq, s->ctx);
  if (!vb || !vx) {
    if (vb) N_VDestroy(vb);
    if (vx) N_VDestroy(vx);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (steady sensitivity)");
  }
  memcpy(N_VGetArrayPointer(vb), b, (size_t)neq * sizeof *b);
  N_VConst(0.0, vx);
  int flag = 0;
  if (s->gmres) { /* GMRES stops at |fscale (b - J x)|_2 <= delta, as in KINSOL's solves */
    SUNLinSolSetScalingVectors(s->gmres, s->fscale, s->fscale);
    N_Vector sb = N_VClone(vb);
    double delta = 0.0;
    if (sb) {
      N_VProd(vb, s->fscale, sb);
      delta = rtol * sqrt(N_VDotProd(sb, sb));
      N_VDestroy(sb);
    }
    flag = sb ? SUNLinSolSolve(s->gmres, NULL, vx, vb, delta) : -1;
  } else {
    flag = SUNLinSolSolve(rs_linsys_solver(&s->ls), rs_linsys_matrix(&s->ls), vx, vb, 0.0);
  }
  if (flag == 0) memcpy(x, N_VGetArrayPointer(vx), (size_t)neq * sizeof *x);
  N_VDestroy(vb);
  N_VDestroy(vx);
  /* a Krylov solve that reduced the residual short of delta still serves a sensitivity */
  if (flag == SUNLS_RES_REDUCED && s->gmres) flag = 0;
  return flag == 0 ? RS_OK
                   : rs_msg_set(msg, RS_ERR_SOLVER,
                                "steady sensitivity: the linear solve failed (flag %d)", flag);
}

const rs_work *rs_steady_evaluated(rs_steady *s, const double *y)
{
  if (!s->krylov3d || s->cj != 0.0) return NULL;
  return rs_krylov_evaluated_at(&s->kry, &s->in, y, rates(s, y), 0.0);
}

int rs_steady_approximate(rs_steady *s, double t, double *y, double tol, int max_iters,
                          rs_stats *stats)
{
  const rs_model *m = s->m;
  rs_model_inputs_at(m, t, &s->in);
  s->in.newton = 1; /* the weights of Newton's evaluations (rs_model_evaluate) */
  if (!(s->in.velocity > 0.0) || !(tol >= FNORM_TOL) || max_iters < 1) return RS_ERR_SOLVER;
  s->failed = 0;
  s->cj = 0.0;
  s->ftol = tol;
  KINSetFuncNormTol(s->kmem, tol);
  s->watch = 1;
  int kin_flag = 0;
  int status = newton(s, y, 0, max_iters, stats, &kin_flag);
  s->watch = 0;
  s->ftol = FNORM_TOL;
  KINSetFuncNormTol(s->kmem, FNORM_TOL);
  if (s->failed) status = RS_ERR_SOLVER; /* the model refused a point: the caller solves */
  return status;
}
