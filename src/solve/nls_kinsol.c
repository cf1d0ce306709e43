/* The nonlinear solver inside IDA (see nls_kinsol.h). IDA gives the predictor y0, the error
 * weights w and a tolerance; we solve for the correction ycor, with u-scaling w and
 * f-scaling w / (diagonal of the iteration matrix), so that the scaled norms measure the
 * correction in IDA's weighted norm: on the direct path by modified Newton of our own
 * (direct_solve), on the Krylov path by KINSOL's exact Newton. */
#include "solve/nls_kinsol.h"

#include <ida/ida.h>
#include <kinsol/kinsol.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>

#include "solve/gmres_cycle.h"

typedef struct nls_content {
  const rs_model *m;
  rs_work *w;
  rs_linsys *ls;
  rs_krylov *kry; /* Newton-Krylov instead of ls (NULL: direct) */
  rs_nls_host host;
  int max_iters;
  SUNNonlinSolSysFn sysfn;
  void *ida_mem;
  void *kmem;
  N_Vector uscale, fscale;
  double *ybuf, *ypbuf;
  long last_iters, last_fails; /* of the last solve only: IDA accumulates both */
  double forcing, tol_cur;     /* Krylov: the largest forcing term; IDA's tolerance of this solve */
  /* Direct path (no kry): the Newton iteration's own vectors, and what the factorisation
   * held by ls was set up at: its c_j and the branches of its cells. */
  N_Vector fval, delta, rhs;
  /* With a tail (host.tail): a view of the contact part of IDA's correction, the contact's
   * weights, and full-length copies of a correction and a residual for IDA's system function. */
  N_Vector ycor_c, w_c, ycor_full, f_full;
  unsigned char *branch_held;
  /* With host.couple_jv on the direct path: GMRES's basis [(COUPLE_KRYLOV + 1) neq] and
   * scratch vectors for C v and P^-1 C v. */
  double *basis;
  N_Vector cv, pcv;
  double cj_held;
  int held;
  int warm; /* the contact solve starts from the correction given (host.couple's passes) */
} nls_content;

#define CONTENT(nls) ((nls_content *)(nls)->content)

/* IDA's system function on the contact unknowns: with a tail the correction is completed to
 * full length (tail 0: the contact rows do not depend on it) and the contact rows returned. */
static int sys(nls_content *c, N_Vector ycor, N_Vector f)
{
  if (!c->host.tail) return c->sysfn(ycor, f, c->ida_mem);
  const size_t bytes = (size_t)c->m->lay.neq * sizeof(double);
  memcpy(N_VGetArrayPointer(c->ycor_full), N_VGetArrayPointer(ycor), bytes);
  const int flag = c->sysfn(c->ycor_full, c->f_full, c->ida_mem);
  memcpy(N_VGetArrayPointer(f), N_VGetArrayPointer(c->f_full), bytes);
  return flag;
}

/* Largest |v_i| s_i. */
static double scaled_max_norm(N_Vector v, N_Vector scale)
{
  const double *x = N_VGetArrayPointer(v), *s = N_VGetArrayPointer(scale);
  const sunindextype len = N_VGetLength(v);
  double norm = 0.0;
  for (sunindextype i = 0; i < len; i++) norm = fmax(norm, fabs(x[i]) * s[i]);
  return norm;
}

/* Newton-Krylov's forcing term from the residual of a new iterate: GMRES reduces the scaled
 * residual to about the Newton test (eta = tol / |F|_max), so that an iteration in an
 * unchanged regime set is the last one, within [ETA_MIN, forcing]: the constant term forcing
 * alone stopped short of the test and cost another Newton iteration (a residual with its laws
 * and a set-up). KINSOL reads the term at the start of an iteration, so it is set at each
 * residual. */
#define ETA_MIN 1e-3
static int kin_residual(N_Vector ycor, N_Vector f, void *data)
{
  nls_content *c = data;
  const int flag = sys(c, ycor, f);
  if (flag == 0) {
    const double fmax_norm = scaled_max_norm(f, c->fscale);
    const double eta = fmax_norm > 0.0 ? c->tol_cur / fmax_norm : c->forcing;
    KINSetEtaConstValue(c->kmem, fmin(fmax(eta, ETA_MIN), c->forcing));
  }
  return flag < 0 ? -1 : (flag > 0 ? 1 : 0); /* > 0 recoverable: KINSOL/IDA try again */
}

/* The point of the Newton iteration: y = ypred + ycor, y' = yppred + cj ycor into the
 * buffers; its time and cj. */
static void newton_point(nls_content *c, N_Vector ycor, double *tcur_out, double *cj_out)
{
  sunrealtype tcur, cj;
  N_Vector ypred, yppred, yn, ypn, res;
  void *udata;
  IDAGetNonlinearSystemData(c->ida_mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
  const double *dc = N_VGetArrayPointer(ycor), *yv = N_VGetArrayPointer(ypred),
               *ypv = N_VGetArrayPointer(yppred);
  for (int i = 0; i < c->m->lay.neq; i++) {
    c->ybuf[i] = yv[i] + dc[i];
    c->ypbuf[i] = ypv[i] + cj * dc[i];
  }
  *tcur_out = tcur;
  *cj_out = cj;
}

/* Newton-Krylov (c->kry): the near-field preconditioner at the Newton point, the
 * model's exact J v, and the preconditioner's solve. */
static int krylov_psetup(N_Vector ycor, N_Vector uscale, N_Vector fval, N_Vector fscale, void *data)
{
  (void)uscale;
  (void)fval;
  (void)fscale;
  nls_content *c = data;
  double tcur, cj;
  newton_point(c, ycor, &tcur, &cj);
  const int status =
      rs_krylov_setup(c->kry, c->host.inputs_at(c->host.ctx, tcur), c->ybuf, c->ypbuf, cj);
  if (status == RS_ERR_SOLVER && !rs_krylov_error(c->kry)[0]) return 1; /* KLU: recoverable */
  return status == RS_OK ? 0 : -1;
}

static int krylov_psolve(N_Vector u, N_Vector uscale, N_Vector fval, N_Vector fscale, N_Vector v,
                         void *data)
{
  (void)u;
  (void)uscale;
  (void)fval;
  (void)fscale;
  nls_content *c = data;
  return rs_krylov_psolve(c->kry, N_VGetArrayPointer(v)) == RS_OK ? 0 : 1;
}

static int krylov_times(N_Vector v, N_Vector Jv, N_Vector u, sunbooleantype *new_u, void *data)
{
  (void)u;
  (void)new_u;
  nls_content *c = data;
  return rs_krylov_times(c->kry, N_VGetArrayPointer(v), N_VGetArrayPointer(Jv)) == RS_OK ? 0 : -1;
}

static SUNNonlinearSolver_Type nls_gettype(SUNNonlinearSolver nls)
{
  (void)nls;
  return SUNNONLINEARSOLVER_ROOTFIND;
}

/* The length of a Newton step d from the point u as KINSOL measures it (its scaled step
 * test): the largest |d_i| / (1 / uscale_i + |u_i|). */
static double scaled_step(N_Vector d, N_Vector u, N_Vector uscale)
{
  const double *dv = N_VGetArrayPointer(d), *uv = N_VGetArrayPointer(u),
               *s = N_VGetArrayPointer(uscale);
  const sunindextype len = N_VGetLength(d);
  double norm = 0.0;
  for (sunindextype i = 0; i < len; i++)
    norm = fmax(norm, fabs(dv[i]) / (1.0 / s[i] + fabs(uv[i])));
  return norm;
}

/* Factorisation of the iteration matrix at the current Newton point (the one of the last
 * residual evaluation: w holds its branches). */
static int direct_setup(nls_content *c, N_Vector ycor)
{
  double tcur, cj;
  newton_point(c, ycor, &tcur, &cj);
  if (rs_linsys_assemble(c->ls, c->m, c->w, c->host.inputs_at(c->host.ctx, tcur), c->ybuf, c->ypbuf,
                         cj) != RS_OK)
    return -1;
  c->held = 0;
  const int flag = SUNLinSolSetup(rs_linsys_solver(c->ls), rs_linsys_matrix(c->ls));
  if (flag != 0) return flag > 0 ? 1 : -1;
  memcpy(c->branch_held, c->w->branch, (size_t)c->m->grid.n);
  c->cj_held = cj;
  c->held = 1;
  return 0;
}

/* Modified Newton on the direct path. In a fixed set of branches the 2D residual is affine
 * in the unknowns and its Jacobian depends on c_j only (through cj dF/dy' and the scaling
 * r), so a factorisation serves as long as every cell stays on the branches it was set up
 * with and c_j stays near: it is kept across iterations and steps, and the iteration then
 * contracts at a rate set by the change of c_j. A fresh one is set up at the current point
 * when a cell changed branch (the semismooth Jacobian of the old branches is wrong there),
 * c_j moved by more than a factor CJ_WINDOW (the factor of the Krylov path's
 * preconditioner), or an iteration reduced the residual by less than RATE_REFRESH (laws not
 * affine in a branch: velocity-dependent friction, friction memory, hardening). Convergence:
 * the max norm of the scaled residual within 1/100 of IDA's tolerance (at the predictor within
 * 1/10000), KINSOL's tests as exact Newton had them. A looser test (the tolerance itself, as on
 * the Krylov path) lets the Newton error into IDA's error estimate: on the plastic twin-disc
 * rig the steps then collapse. A step shorter than the test that leaves the residual above it
 * ends the solve with a fresh factorisation (accepted within IDA's tolerance itself, as KINSOL's
 * step test was) and refreshes a kept one. */
static int coupled_step(nls_content *c, N_Vector delta);
enum { DIRECT_OK = 0, DIRECT_FAILED = 1, DIRECT_STOP = -1 };
#define CJ_WINDOW    4.0
#define RATE_REFRESH 0.2
static int direct_solve(nls_content *c, N_Vector ycor, double tol, double cj)
{
  const double ftol = 0.01 * tol;
  if (!c->warm) N_VConst(0.0, ycor);
  int flag = sys(c, ycor, c->fval);
  if (flag != 0) return flag < 0 ? DIRECT_STOP : DIRECT_FAILED;
  double fnorm = scaled_max_norm(c->fval, c->fscale);
  if (fnorm <= 0.01 * ftol) return DIRECT_OK; /* the predictor solves the step */
  int keep = c->held && cj <= CJ_WINDOW * c->cj_held && c->cj_held <= CJ_WINDOW * cj;
  int coupled = 0; /* the coupling's Jacobian term in the step (host.couple_jv) */
  for (int it = 1; it <= c->max_iters; it++) {
    int fresh = 0;
    if (!keep || memcmp(c->w->branch, c->branch_held, (size_t)c->m->grid.n) != 0) {
      if ((flag = direct_setup(c, ycor)) != 0) return flag < 0 ? DIRECT_STOP : DIRECT_FAILED;
      keep = fresh = 1;
    }
    N_VScale(-1.0, c->fval, c->rhs);
    flag = SUNLinSolSolve(rs_linsys_solver(c->ls), rs_linsys_matrix(c->ls), c->delta, c->rhs, 0.0);
    if (flag == 0 && coupled) flag = coupled_step(c, c->delta);
    if (flag != 0) return flag < 0 ? DIRECT_STOP : DIRECT_FAILED;
    N_VLinearSum(1.0, ycor, 1.0, c->delta, ycor);
    c->last_iters = it;
    if ((flag = sys(c, ycor, c->fval)) != 0) return flag < 0 ? DIRECT_STOP : DIRECT_FAILED;
    const double fnew = scaled_max_norm(c->fval, c->fscale);
    if (fnew <= ftol) return DIRECT_OK;
    if (scaled_step(c->delta, ycor, c->uscale) <= ftol) {
      if (fresh) return fnew <= tol ? DIRECT_OK : DIRECT_FAILED;
      keep = 0;
    }
    if (fnew > RATE_REFRESH * fnorm) {
      keep = 0;
      coupled = c->host.couple_jv != NULL;
    }
    fnorm = fnew;
  }
  return DIRECT_FAILED;
}

static int contact_solve(nls_content *c, N_Vector ycor, N_Vector w, sunrealtype tol, void *mem);

/* The exact coupling on the direct path (coupled_step, from the first iteration of a solve that
 * contracted by less than RATE_REFRESH on: the residual is exact from the start, and where the
 * coupling is weak the contact's own Jacobian contracts it fast enough, each product costing
 * about half an iteration). The preconditioned coupling P^-1 C is
 * the loop gain of the step's heat on the contact's factors, usually a fraction (about 0.1 on
 * cases/hot_creep_curve.yaml); where the first product shows it below COUPLE_NEUMANN the step is
 * the Neumann series' first two terms, (I - P^-1 C) P^-1 (-F), within COUPLE_NEUMANN^2 of the
 * exact one for one product, else GMRES (at most COUPLE_KRYLOV products) to COUPLE_ETA. */
#define COUPLE_NEUMANN 0.3
#define COUPLE_KRYLOV  10
#define COUPLE_ETA     1e-2

/* x <- (I + P^-1 C) x, P the held factorisation (scaled: x holds u-scaled values, s the
 * scales). */
static int coupled_op(nls_content *c, const double *s, const double *x, double *out)
{
  const int neq = c->m->lay.neq;
  double *cv = N_VGetArrayPointer(c->cv);
  for (int i = 0; i < neq; i++) out[i] = x[i] / s[i]; /* unscaled, as scratch */
  memset(cv, 0, (size_t)neq * sizeof *cv);
  if (c->host.couple_jv(c->host.ctx, out, cv) != RS_OK) return -1;
  const int flag =
      SUNLinSolSolve(rs_linsys_solver(c->ls), rs_linsys_matrix(c->ls), c->pcv, c->cv, 0.0);
  if (flag != 0) return flag;
  const double *pcv = N_VGetArrayPointer(c->pcv);
  for (int i = 0; i < neq; i++) out[i] = x[i] + s[i] * pcv[i];
  return 0;
}

static double dot(const double *a, const double *b, int n)
{
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += a[i] * b[i];
  return sum;
}

/* The Newton step of the coupled contact rows on the direct path: delta holds P^-1 (-F) on
 * entry and receives the solution of (I + P^-1 C) d = P^-1 (-F), i.e. (P + C) d = -F, in the
 * u-scaled norm from d = delta (the uncoupled step): the residual there, -P^-1 C delta, is the
 * Neumann series' next term (taken as the step's correction when small) and GMRES's first basis
 * vector otherwise (modified Gram-Schmidt, Givens rotations, one cycle). */
typedef struct coupled_ctx {
  nls_content *c;
  const double *s;
} coupled_ctx;

static int coupled_apply(void *ctx, const double *x, double *out)
{
  const coupled_ctx *k = ctx;
  return coupled_op(k->c, k->s, x, out);
}

static int coupled_step(nls_content *c, N_Vector delta)
{
  const int neq = c->m->lay.neq, mk = COUPLE_KRYLOV;
  const double *s = N_VGetArrayPointer(c->uscale);
  double *d = N_VGetArrayPointer(delta), *V = c->basis;
  double *b = V + (size_t)mk * neq; /* the right-hand side, in the last basis slot (free until
                                      the last iteration, when it is no longer needed) */
  for (int i = 0; i < neq; i++) b[i] = d[i] * s[i];
  const double bnorm = sqrt(dot(b, b, neq));
  if (!(bnorm > 0.0)) return 0;
  /* r0 = b - A b = -(P^-1 C b), scaled */
  int flag = coupled_op(c, s, b, V);
  if (flag != 0) return flag;
  for (int i = 0; i < neq; i++) V[i] = b[i] - V[i];
  const double beta = sqrt(dot(V, V, neq));
  if (beta <= COUPLE_NEUMANN * bnorm) { /* d = (I - P^-1 C) P^-1 (-F) */
    for (int j = 0; j < neq; j++) d[j] += V[j] / s[j];
    return 0;
  }
  for (int i = 0; i < neq; i++) V[i] /= beta;
  coupled_ctx ctx = {c, s};
  double res;
  int used;
  return rs_gmres_cycle(neq, mk, coupled_apply, &ctx, V, beta, COUPLE_ETA * bnorm, s, d, &res,
                        &used);
}

/* The tail's rows at the point ycor the contact rows converged to (the full system evaluated
 * there first when Newton's last evaluation was elsewhere). */
static int tail_at(nls_content *c, N_Vector ycor, void *mem)
{
  const size_t bytes = (size_t)c->m->lay.neq * sizeof(double);
  if (memcmp(N_VGetArrayPointer(c->ycor_full), N_VGetArrayPointer(ycor), bytes) != 0) {
    memcpy(N_VGetArrayPointer(c->ycor_full), N_VGetArrayPointer(ycor), bytes);
    if (c->sysfn(c->ycor_full, c->f_full, mem) != 0) return SUN_NLS_CONV_RECVR;
  }
  sunrealtype tcur, cj;
  N_Vector ypred, yppred, yn, ypn, res;
  void *udata;
  IDAGetNonlinearSystemData(mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
  return c->host.tail(c->host.ctx, cj, N_VGetArrayPointer(ypred), N_VGetArrayPointer(yppred),
                      N_VGetArrayPointer(ycor)) == RS_OK
             ? SUN_NLS_SUCCESS
             : -1;
}

/* Contact solves per step with host.couple before the step is declared failed. */
#define COUPLE_PASSES 30

/* The exact coupling's step: the contact rows (whose evaluations eliminate the tail) to the
 * contact's Newton test, then the tail's rows at the converged point, as without coupling. */
static int coupled_solve(nls_content *c, N_Vector ycor, sunrealtype tol, void *mem)
{
  *c->host.tail_rows = 0;
  int flag = contact_solve(c, c->ycor_c, c->w_c, tol, mem);
  *c->host.tail_rows = 1;
  if (flag != SUN_NLS_SUCCESS) return flag;
  return tail_at(c, ycor, mem);
}

/* With a tail: the contact rows on views of the first neq entries, then the tail's rows at
 * the converged point (the last residual evaluation was there; if Newton's last evaluation
 * was elsewhere, one more at the point). */
static int nls_solve(SUNNonlinearSolver nls, N_Vector y0, N_Vector ycor, N_Vector w,
                     sunrealtype tol, sunbooleantype call_lsetup, void *mem)
{
  (void)y0;
  (void)call_lsetup; /* the direct path decides itself when to refactor; Krylov: the local
                      * laws of J v are rebuilt at every iteration, the near-field
                      * preconditioner may lag */
  nls_content *c = CONTENT(nls);
  if (!c->host.tail) return contact_solve(c, ycor, w, tol, mem);
  N_VSetArrayPointer(N_VGetArrayPointer(ycor), c->ycor_c);
  const double *wv = N_VGetArrayPointer(w);
  double *wc = N_VGetArrayPointer(c->w_c);
  for (int i = 0; i < c->m->lay.neq; i++) wc[i] = c->host.weight_scale * wv[i];
  long iters = 0;
  if (c->host.couple_begin) { /* the exact coupling: the step's predictors */
    sunrealtype tcur, cj;
    N_Vector ypred, yppred, yn, ypn, res;
    void *udata;
    IDAGetNonlinearSystemData(mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
    c->host.couple_begin(c->host.ctx, cj, N_VGetArrayPointer(ypred), N_VGetArrayPointer(yppred));
    const int flag = coupled_solve(c, ycor, tol, mem);
    c->host.couple_begin(c->host.ctx, 0.0, NULL, NULL);
    return flag;
  }
  if (c->host.couple) { /* the coupling's data from the predicted tail */
    sunrealtype tcur, cj;
    N_Vector ypred, yppred, yn, ypn, res;
    void *udata;
    double change;
    IDAGetNonlinearSystemData(mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
    c->host.inputs_at(c->host.ctx, tcur);
    if (c->host.couple(c->host.ctx, N_VGetArrayPointer(ypred), N_VGetArrayPointer(ycor), wc,
                       &change) != RS_OK)
      return -1;
  }
  for (int pass = 0;; pass++) {
    c->warm = pass > 0;
    *c->host.tail_rows = 0;
    int flag = contact_solve(c, c->ycor_c, c->w_c, tol, mem);
    *c->host.tail_rows = 1;
    c->warm = 0;
    iters += c->last_iters;
    c->last_iters = iters;
    if (flag != SUN_NLS_SUCCESS) return flag;
    if ((flag = tail_at(c, ycor, mem)) != SUN_NLS_SUCCESS) return flag;
    if (!c->host.couple) return SUN_NLS_SUCCESS;
    sunrealtype tcur, cj;
    N_Vector ypred, yppred, yn, ypn, res;
    void *udata;
    IDAGetNonlinearSystemData(mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
    /* the contact's own Newton test (direct_solve: 1/100 of IDA's tolerance) */
    double change = 0.0;
    if (c->host.couple(c->host.ctx, N_VGetArrayPointer(ypred), N_VGetArrayPointer(ycor), wc,
                       &change) != RS_OK)
      return -1;
    if (change <= (c->kry ? 1.0 : 0.01) * tol) return SUN_NLS_SUCCESS;
    if (pass + 1 >= COUPLE_PASSES) { /* IDA reduces the step and tries again */
      c->last_fails = 1;
      return SUN_NLS_CONV_RECVR;
    }
  }
}

/* The contact rows (the whole system without a tail). */
static int contact_solve(nls_content *c, N_Vector ycor, N_Vector w, sunrealtype tol, void *mem)
{
  c->ida_mem = mem;
  sunrealtype tcur, cj;
  N_Vector ypred, yppred, yn, ypn, res;
  void *udata;
  IDAGetNonlinearSystemData(mem, &tcur, &ypred, &yppred, &yn, &ypn, &res, &cj, &udata);
  *c->host.cj_slot = cj;

  /* Scales: each residual row divided by its diagonal of the iteration matrix
   * (1 for traction rows by the choice of r; r (cj + V/dx) for the transport rows). */
  const rs_model *m = c->m;
  const rs_layout *L = &m->lay;
  const rs_inputs *in = c->host.inputs_at(c->host.ctx, tcur);
  const double r = rs_model_scaling(m, in, cj);
  const double diag_transport = r * (cj + in->velocity / m->grid.dx);
  const double *wv = N_VGetArrayPointer(w);
  double *us = N_VGetArrayPointer(c->uscale), *fs = N_VGetArrayPointer(c->fscale);
  const int ntraction = rs_at_upl(L, 0, 0), ncell = rs_at_extra(L, 0);
  double wmax = 0.0;
  for (int i = 0; i < ntraction; i++) wmax = fmax(wmax, wv[i]);
  for (int i = 0; i < L->neq; i++) {
    us[i] = wv[i];
    /* the force row (force control) is a mean traction: the strictest traction weight */
    fs[i] = i < ntraction ? wv[i] : i < ncell ? wv[i] / diag_transport : wmax;
  }
  if (L->memory) { /* memory rows: diagonal r (d_c (cj + V/dx) + s0) at least */
    const rs_friction *f = &m->par.friction;
    const double diag_memory =
        r * (f->memory_distance * (cj + in->velocity / m->grid.dx) + f->memory_velocity);
    for (int i = rs_at_mu(L, 0); i < ncell; i++) fs[i] = wv[i] / diag_memory;
  }
  c->last_iters = 0;
  c->last_fails = 0;
  if (!c->kry) {
    const int status = direct_solve(c, ycor, tol, cj);
    if (status == DIRECT_STOP) return -1; /* the residual refused (interrupt): IDA stops */
    if (status == DIRECT_FAILED) {
      c->last_fails = 1;
      c->held = 0; /* the retry with a smaller step starts from a fresh factorisation */
      return SUN_NLS_CONV_RECVR;
    }
    return SUN_NLS_SUCCESS;
  }
  /* IDA asks for the correction to tol in its weighted norm; KINSOL tests the max norm of
   * the scaled residual (about the correction) against a fraction of it. Direct solves
   * (above) converge fast near the solution and keep 1/100; Newton-Krylov iterations cost
   * GMRES solves and stop at tol itself: the max norm bounds IDA's weighted RMS norm, so
   * this is still IDA's own Newton test at least, and the forces stay as close to a
   * tight-tolerance run as before. */
  c->tol_cur = tol;
  KINSetFuncNormTol(c->kmem, tol);
  KINSetScaledStepTol(c->kmem, tol);
  if (!c->warm) N_VConst(0.0, ycor);
  const int flag = KINSol(c->kmem, ycor, KIN_NONE, c->uscale, c->fscale);
  long iters = 0;
  KINGetNumNonlinSolvIters(c->kmem, &iters);
  c->last_iters = iters;
  long lin_iters = 0;
  KINGetNumLinIters(c->kmem, &lin_iters);
  c->kry->lin_iters += lin_iters;
  if (flag == KIN_SYSFUNC_FAIL) return -1; /* the residual refused (interrupt): IDA stops */
  int ok = flag >= 0;
  if (flag == KIN_STEP_LT_STPTOL) {
    double fnorm = 1e300;
    KINGetFuncNorm(c->kmem, &fnorm);
    ok = fnorm <= tol;
  }
  if (!ok) {
    c->last_fails = 1;
    rs_krylov_invalidate(c->kry); /* the retry starts from a fresh factorisation */
    return SUN_NLS_CONV_RECVR;    /* IDA reduces the step and tries again */
  }
  return SUN_NLS_SUCCESS;
}

static int nls_free(SUNNonlinearSolver nls)
{
  if (!nls) return SUN_NLS_SUCCESS;
  nls_content *c = CONTENT(nls);
  if (c) {
    if (c->kmem) KINFree(&c->kmem);
    if (c->uscale) N_VDestroy(c->uscale);
    if (c->fscale) N_VDestroy(c->fscale);
    if (c->fval) N_VDestroy(c->fval);
    if (c->delta) N_VDestroy(c->delta);
    if (c->rhs) N_VDestroy(c->rhs);
    if (c->ycor_c) N_VDestroy(c->ycor_c);
    if (c->w_c) N_VDestroy(c->w_c);
    if (c->ycor_full) N_VDestroy(c->ycor_full);
    if (c->cv) N_VDestroy(c->cv);
    if (c->pcv) N_VDestroy(c->pcv);
    free(c->basis);
    if (c->f_full) N_VDestroy(c->f_full);
    free(c->branch_held);
    free(c->ybuf);
    free(c->ypbuf);
    free(c);
  }
  nls->content = NULL;
  SUNNonlinSolFreeEmpty(nls);
  return SUN_NLS_SUCCESS;
}

static int nls_setsysfn(SUNNonlinearSolver nls, SUNNonlinSolSysFn fn)
{
  CONTENT(nls)->sysfn = fn;
  return SUN_NLS_SUCCESS;
}

/* IDA's convergence test (a contraction-rate estimate for modified Newton) does
 * not apply to exact semismooth Newton: KINSOL's residual and step tests are used. */
static int nls_setctestfn(SUNNonlinearSolver nls, SUNNonlinSolConvTestFn fn, void *data)
{
  (void)nls;
  (void)fn;
  (void)data;
  return SUN_NLS_SUCCESS;
}

/* IDA asks for 4 iterations (tuned for modified Newton); a change of active set
 * needs a few more, so our own limit stands. */
static int nls_setmaxiters(SUNNonlinearSolver nls, int maxiters)
{
  (void)nls;
  (void)maxiters;
  return SUN_NLS_SUCCESS;
}

static int nls_getnumiters(SUNNonlinearSolver nls, long *iters)
{
  *iters = CONTENT(nls)->last_iters; /* IDA accumulates */
  return SUN_NLS_SUCCESS;
}

static int nls_getcuriter(SUNNonlinearSolver nls, int *iter)
{
  *iter = (int)CONTENT(nls)->last_iters;
  return SUN_NLS_SUCCESS;
}

static int nls_getnumconvfails(SUNNonlinearSolver nls, long *fails)
{
  *fails = CONTENT(nls)->last_fails; /* IDA accumulates */
  return SUN_NLS_SUCCESS;
}

SUNNonlinearSolver rs_nls_kinsol_create(const rs_model *m, rs_work *w, rs_linsys *ls,
                                        rs_krylov *kry, SUNLinearSolver gmres, double forcing,
                                        rs_nls_host host, int max_iters, N_Vector tmpl,
                                        SUNContext ctx)
{
  SUNNonlinearSolver nls = SUNNonlinSolNewEmpty(ctx);
  if (!nls) return NULL;
  nls->ops->gettype = nls_gettype;
  nls->ops->solve = nls_solve;
  nls->ops->free = nls_free;
  nls->ops->setsysfn = nls_setsysfn;
  nls->ops->setctestfn = nls_setctestfn;
  nls->ops->setmaxiters = nls_setmaxiters;
  nls->ops->getnumiters = nls_getnumiters;
  nls->ops->getcuriter = nls_getcuriter;
  nls->ops->getnumconvfails = nls_getnumconvfails;
  nls_content *c = calloc(1, sizeof *c);
  nls->content = c;
  if (!c) goto fail;
  c->m = m;
  c->w = w;
  c->ls = ls;
  c->host = host;
  c->max_iters = max_iters > 0 ? max_iters : 10;
  c->uscale = N_VClone(tmpl);
  c->fscale = N_VClone(tmpl);
  c->ybuf = malloc((size_t)m->lay.neq * sizeof *c->ybuf);
  c->ypbuf = malloc((size_t)m->lay.neq * sizeof *c->ypbuf);
  if (!c->uscale || !c->fscale || !c->ybuf || !c->ypbuf) goto fail;
  if (host.tail) {
    c->ycor_c = N_VCloneEmpty(tmpl);
    c->w_c = N_VClone(tmpl);
    c->ycor_full = N_VNew_Serial(host.neq_full, ctx);
    c->f_full = N_VNew_Serial(host.neq_full, ctx);
    if (!c->ycor_c || !c->w_c || !c->ycor_full || !c->f_full) goto fail;
    N_VConst(0.0, c->ycor_full);
  }
  if (host.couple_jv && !kry) {
    c->cv = N_VClone(tmpl);
    c->pcv = N_VClone(tmpl);
    c->basis = malloc((size_t)(COUPLE_KRYLOV + 1) * m->lay.neq * sizeof *c->basis);
    if (!c->cv || !c->pcv || !c->basis) goto fail;
  }
  if (!kry) { /* the direct path: modified Newton of its own (direct_solve) */
    c->fval = N_VClone(tmpl);
    c->delta = N_VClone(tmpl);
    c->rhs = N_VClone(tmpl);
    c->branch_held = malloc((size_t)m->grid.n);
    if (!c->fval || !c->delta || !c->rhs || !c->branch_held ||
        SUNLinSolInitialize(rs_linsys_solver(ls)) != 0)
      goto fail;
    return nls;
  }
  c->kmem = KINCreate(ctx);
  c->forcing = forcing;
  c->kry = kry;
  /* each set-up call on its own (the caller reports a NULL solver) */
  if (!c->kmem || KINInit(c->kmem, kin_residual, tmpl) != 0 || KINSetUserData(c->kmem, c) != 0 ||
      KINSetLinearSolver(c->kmem, gmres, NULL) != 0 ||
      KINSetJacTimesVecFn(c->kmem, krylov_times) != 0 ||
      KINSetPreconditioner(c->kmem, krylov_psetup, krylov_psolve) != 0 ||
      KINSetEtaForm(c->kmem, KIN_ETACONSTANT) != 0 || KINSetEtaConstValue(c->kmem, forcing) != 0)
    goto fail;
  if (KINSetMaxSetupCalls(c->kmem, 1) != 0 || KINSetMaxNewtonStep(c->kmem, 1e12) != 0 ||
      KINSetNumMaxIters(c->kmem, c->max_iters) != 0 ||
      KINSetErrHandlerFn(c->kmem, rs_sundials_silent, NULL) != 0)
    goto fail;
  return nls;
fail:
  nls_free(nls);
  return NULL;
}
