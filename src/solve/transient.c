/* Transient rolling: IDA (variable-order, variable-step BDF with error control)
 * on the semi-discrete DAE, each step's nonlinear system solved by KINSOL with
 * the generalized Jacobian, factored by the Schur-complement solver or by KLU
 * (docs/model.md §6). */
#include <ida/ida.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>

#include "solve/linsys.h"
#include "solve/gmres.h"
#include "solve/linsys_krylov.h"
#include "solve/nvector_fast.h"
#include "solve/nls_kinsol.h"
#include "solve/transient.h"

/* Temperature modes that forget within fewer cells than this are out of IDA's error test
 * (rs_transient_create). */
#define FAST_MODE_CELLS 10.0

/* A traction's error weight takes the larger of its own size and this fraction of the run's
 * largest friction bound mu p0 (error_weights; docs/model.md §9). */
#define TRACTION_WEIGHT_FLOOR 0.3

struct rs_transient {
  const rs_model *m;
  SUNContext own_ctx; /* created here when the caller gave none */
  void *ida;
  N_Vector y, yp, atol;
  double rtol;
  SUNNonlinearSolver nls;
  rs_linsys ls;
  SUNLinearSolver gmres; /* 3D: Newton-Krylov with kry */
  rs_krylov kry;
  rs_work work;
  double cj; /* of the step being solved: sets the residual scaling r */
  double t;
  const rs_inputs *frozen; /* NULL, or the inputs held whatever the time */
  rs_inputs in;            /* the inputs of the last evaluation */
  volatile sig_atomic_t *interrupt;
  int (*step_hook)(void *ctx, double t, const double *y, const double *yp);
  void *hook_ctx;
  rs_stats before_restart; /* IDA's counters of the segments before the last IDAReInit */
  /* The temperature modes (opts.thermal, NULL: none): neq_full = neq + their count; the heat
   * sources of the last residual evaluation (scratch [n] each), and a vector of the contact
   * unknowns only for the contact solvers. */
  rs_thermal *thermal;
  int neq_full;
  double *fric, *plast, *q, *theta; /* theta: the modes of a step's solve [their count] */
  signed char *contact;
  N_Vector tmpl_c;
  int tail_rows; /* 0: the residual leaves the modes' rows out (nls_kinsol.h) */
  const rs_transient_coupling *coupling; /* NULL: the contact does not read the temperature */
  double *T1;                            /* with coupling: scratch [n] */
  /* The exact coupling (rs_transient_coupling.fixed_point = 0): the step's predicted modes and
   * their rates (IDA's, full length: NULL outside a step's solve) and c_j; the point of the last
   * evaluation (its contact unknowns, work and inputs), the modes the step leaves there and its
   * heat; dF/df of each contact cell's rows there (valid: computed at that point); scratch. */
  const double *pred, *ratepred;
  double cj_step;
  double *y_pt, *theta_pt, *cor, *theta_s, *cor_s, *Ts, *dq, *dfric, *dplast, *vp;
  const rs_work *w_pt;
  rs_inputs in_pt;
  double *dfdmu, *dfdyield;
  int *rows, *nrow, deriv_valid;
  rs_work wlin; /* the kinematics of a direction */
  long products;
  double weight_scale; /* sqrt(neq_full/neq): IDA's error weights times it (error_weights) */
  double p_floor;      /* N/mm^2: the smallest traction size of the error weights */
};

int rs_transient_neq(const rs_model *m, const rs_thermal *thermal)
{
  return m->lay.neq + (thermal ? rs_thermal_nstate(thermal) : 0);
}

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

/* IDA's error weights, 1/(rtol |y| + atol), except for the tractions: 1/(rtol max(|p|,
 * p_floor) + atol), p_floor = TRACTION_WEIGHT_FLOOR mu p0. What users read of a traction is
 * its share of the forces, an absolute error over the cell's area; held to rtol |p| alone, the
 * small tractions of the adhesion cells at the leading edge set the step (2D: in nearly every
 * step) while adding least to the forces (docs/model.md §9). 3D: both components of a cell's
 * traction (and plastic displacement) take the vector's length |v| instead of each
 * component's own size. A component that is zero by symmetry (p_y of a slipping cell on the
 * centre line) would be held to atol, while its direction follows the slip direction and so
 * the Newton solve's inexactness: the error test then fails at every step size. */
static int error_weights(N_Vector yv, N_Vector ewt, void *data)
{
  const rs_transient *tr = data;
  const rs_layout *L = &tr->m->lay;
  const double *y = N_VGetArrayPointer(yv), *at = N_VGetArrayPointer(tr->atol);
  double *w = N_VGetArrayPointer(ewt);
  for (int k = 0; k < tr->neq_full; k++) w[k] = tr->rtol * fabs(y[k]) + at[k];
  for (int I = 0; I < L->n && L->ncomp == 1; I++) {
    const int k = rs_at_p(L, 0, I);
    w[k] = tr->rtol * fmax(fabs(y[k]), tr->p_floor) + at[k];
  }
  for (int I = 0; I < L->n && L->ncomp == 2; I++) {
    const int vec[2][2] = {{rs_at_p(L, 0, I), rs_at_p(L, 1, I)},
                           {rs_at_upl(L, 0, I), rs_at_upl(L, 1, I)}};
    for (int q = 0; q < 2; q++) {
      double len = sqrt(y[vec[q][0]] * y[vec[q][0]] + y[vec[q][1]] * y[vec[q][1]]);
      if (q == 0) len = fmax(len, tr->p_floor);
      w[vec[q][0]] = tr->rtol * len + at[vec[q][0]];
      w[vec[q][1]] = tr->rtol * len + at[vec[q][1]];
    }
  }
  /* With the temperature modes IDA's norm, an RMS over all unknowns, would average the contact's
   * errors with the modes' (the fast ones masked out of the error test, but counted) and loosen
   * the contact's error test by up to the square root of the counts' ratio: every weight times
   * that root keeps the contact's part of the norm what it is without the modes, the slow
   * modes' part adding to it. */
  const double scale = tr->thermal ? tr->weight_scale : 1.0;
  for (int k = 0; k < tr->neq_full; k++) {
    if (!(w[k] > 0.0)) return -1;
    w[k] = scale / w[k];
  }
  return 0;
}

/* The inputs at time t (held ones when frozen). */
static const rs_inputs *inputs_at(rs_transient *tr, double t)
{
  if (tr->frozen)
    tr->in = *tr->frozen;
  else
    rs_model_inputs_at(tr->m, t, &tr->in);
  return &tr->in;
}

static const rs_inputs *host_inputs(void *tr, double t) { return inputs_at(tr, t); }

static int dae_residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector rr, void *data)
{
  rs_transient *tr = data;
  if (tr->interrupt && *tr->interrupt) return -1; /* unrecoverable: IDA stops at once */
  /* a model that cannot be evaluated (the normal problem failed) is not cured by a
   * smaller step: unrecoverable, the reason stays in tr->work.msg (Krylov: the
   * linearisation's work, see rs_krylov_residual, as the set-up at the iterate then needs
   * no evaluation of its own) */
  const int status =
      tr->gmres ? rs_krylov_residual(&tr->kry, inputs_at(tr, t), N_VGetArrayPointer(y),
                                     N_VGetArrayPointer(yp), tr->cj, N_VGetArrayPointer(rr))
                : rs_model_residual(tr->m, &tr->work, inputs_at(tr, t), N_VGetArrayPointer(y),
                                    N_VGetArrayPointer(yp), tr->cj, N_VGetArrayPointer(rr));
  if (status != RS_OK && tr->gmres)
    rs_msg_set(&tr->work.msg, status, "%s", rs_krylov_error(&tr->kry));
  if (status == RS_OK && tr->thermal) { /* this evaluation's heat sources, the modes' rows */
    const int neq = tr->m->lay.neq;
    const double *yv = N_VGetArrayPointer(y);
    rs_thermal_sources(tr->thermal, tr->m, tr->gmres ? &tr->kry.w : &tr->work, yv, tr->fric,
                       tr->plast, tr->q, tr->contact);
    rs_thermal_inflow_at(tr->thermal, tr->in.t); /* a rig's heat coming around again */
    if (tr->tail_rows)
      rs_thermal_dae_residual(tr->thermal, tr->in.velocity, tr->q, tr->contact, yv + neq,
                              N_VGetArrayPointer(yp) + neq, N_VGetArrayPointer(rr) + neq);
  }
  return status == RS_OK ? 0 : -1;
}

/* The modes' rows of a step, solved exactly at the converged contact point (nls_kinsol.h):
 * the sources are those of the last residual evaluation, which was there. */
static int solve_tail(void *data, double cj, const double *ypred, const double *yppred,
                      double *ycor)
{
  rs_transient *tr = data;
  const int neq = tr->m->lay.neq;
  if (tr->pred && tr->w_pt && tr->in.velocity > 0.0) { /* the exact coupling solved them there */
    memcpy(ycor + neq, tr->cor, (size_t)(tr->neq_full - neq) * sizeof *ycor);
    return RS_OK;
  }
  rs_thermal_dae_solve(tr->thermal, tr->in.velocity, tr->q, tr->contact, cj, ypred + neq,
                       yppred + neq, tr->theta, ycor + neq);
  return RS_OK;
}

/* mu(T), tau_c0(T): the factors of the temperatures of the modes at the step's point
 * ypred + ycor, and the largest change they make to a contact cell's bound or yield limit, in
 * the traction's weight wc (rs_transient_coupling). Without rolling (no material path, no
 * temperature) the factors are held. */
static int couple_step(void *data, const double *ypred, const double *ycor, const double *wc,
                       double *change)
{
  rs_transient *tr = data;
  const rs_transient_coupling *cp = tr->coupling;
  const rs_layout *L = &tr->m->lay;
  const double *bound = tr->m->bound; /* the scale of a cell's bound: that at t = 0 */
  const int neq = L->neq, nm = tr->neq_full - neq;
  *change = 0.0;
  if (!(tr->in.velocity > 0.0)) return RS_OK;
  for (int k = 0; k < nm; k++) tr->theta[k] = ypred[neq + k] + ycor[neq + k];
  rs_thermal_state_temperature(tr->thermal, tr->in.velocity, tr->theta, tr->T1);
  for (int i = 0; i < L->n; i++) {
    double d = 0.0;
    if (cp->mu_factor) {
      const double f = rs_history_eval(cp->mu_table, tr->T1[i]) / cp->mu_rest;
      d += fabs(f - cp->mu_factor[i]) * bound[i];
      cp->mu_factor[i] = f;
    }
    if (cp->yield_factor) {
      const double f = rs_history_eval(cp->tau_table, tr->T1[i]) / cp->tau_rest;
      d += fabs(f - cp->yield_factor[i]) * cp->tau_rest;
      cp->yield_factor[i] = f;
    }
    cp->T_used[i] = tr->T1[i];
    if (!tr->contact[i]) continue;
    double weight = wc[rs_at_p(L, 0, i)];
    if (L->ncomp == 2) weight = fmax(weight, wc[rs_at_p(L, 1, i)]);
    *change = fmax(*change, d * weight);
  }
  return RS_OK;
}

/* The factors of mu(T), tau_c0(T) at each cell's temperature T, as couple_step. */
static void set_factors(const rs_transient_coupling *cp, int n, const double *T)
{
  for (int i = 0; i < n; i++) {
    if (cp->mu_factor) cp->mu_factor[i] = rs_history_eval(cp->mu_table, T[i]) / cp->mu_rest;
    if (cp->yield_factor) cp->yield_factor[i] = rs_history_eval(cp->tau_table, T[i]) / cp->tau_rest;
    cp->T_used[i] = T[i];
  }
}

/* The exact coupling's evaluation hook (rs_work.before_laws): within a step's solve, the heat of
 * the point (its kinematics are in w), the modes the step leaves under it (the step's rows solved
 * exactly from the predictor, whatever the modes' part of the point) and the factors of their
 * temperatures, which the laws then read. Without rolling the factors are held. */
static int coupled_laws(void *data, const rs_work *w, const rs_inputs *in, const double *y)
{
  rs_transient *tr = data;
  if (!tr->pred || !(in->velocity > 0.0)) return RS_OK;
  const rs_model *m = tr->m;
  const int neq = m->lay.neq;
  /* the point of the last evaluation again (the factorisation's set-up there): as it was */
  if (w == tr->w_pt && in->t == tr->in_pt.t && !memcmp(y, tr->y_pt, (size_t)neq * sizeof *y))
    return RS_OK;
  rs_thermal_sources(tr->thermal, m, w, y, tr->fric, tr->plast, tr->q, tr->contact);
  rs_thermal_inflow_at(tr->thermal, in->t);
  rs_thermal_dae_solve(tr->thermal, in->velocity, tr->q, tr->contact, tr->cj_step, tr->pred + neq,
                       tr->ratepred + neq, tr->theta_pt, tr->cor);
  rs_thermal_state_temperature(tr->thermal, in->velocity, tr->theta_pt, tr->T1);
  set_factors(tr->coupling, m->grid.n, tr->T1);
  memcpy(tr->y_pt, y, (size_t)neq * sizeof *y);
  tr->w_pt = w;
  tr->in_pt = *in;
  tr->deriv_valid = 0;
  return RS_OK;
}

/* The start (ypred non-NULL: IDA's predictor and its rates, full length) and the end (NULL) of a
 * step's solve with the exact coupling. */
static int couple_begin(void *data, double cj, const double *ypred, const double *yppred)
{
  rs_transient *tr = data;
  tr->pred = ypred;
  tr->ratepred = yppred;
  tr->cj_step = cj;
  tr->w_pt = NULL;
  return RS_OK;
}

/* dF/df of each contact cell's rows at the point of the last evaluation: a factor acts on its
 * own cell's law only, whose rows are piecewise linear in it (the bound mu p_n, the yield limit
 * tau_c0 + k_tau u*), so the central difference over 1e-6 of the factor is the derivative to
 * roundoff on the cell's branch (as the steady coupling's, study/temperature.c). */
static void factor_derivatives(rs_transient *tr)
{
  const rs_transient_coupling *cp = tr->coupling;
  const rs_model *m = tr->m;
  double Rp[RS_LAW_NROW], Rm[RS_LAW_NROW];
  for (int I = 0; I < m->grid.n; I++) {
    tr->nrow[I] = 0;
    if (!tr->contact[I]) continue;
    for (int f = 0; f < 2; f++) {
      double *factor = f == 0 ? cp->mu_factor : cp->yield_factor;
      double *d = (f == 0 ? tr->dfdmu : tr->dfdyield) + (size_t)I * RS_LAW_NROW;
      int *row = tr->rows + (size_t)I * RS_LAW_NROW;
      if (!factor) continue;
      const double f0 = factor[I], h = 1e-6 * fmax(fabs(f0), 1e-3);
      factor[I] = f0 + h;
      const int nr = rs_model_cell_rows(m, tr->w_pt, tr->y_pt, I, row, Rp);
      factor[I] = f0 - h;
      rs_model_cell_rows(m, tr->w_pt, tr->y_pt, I, row, Rm);
      factor[I] = f0;
      tr->nrow[I] = nr;
      for (int k = 0; k < nr; k++) d[k] = (Rp[k] - Rm[k]) / (2 * h);
    }
  }
  tr->deriv_valid = 1;
}

/* Jv += J_ctheta dtheta/dy v over the contact rows (neq) at the point of the last evaluation:
 * the change of the heat in the direction v (v' = c_j v), of the modes the step leaves under it
 * (the step's solve is affine in the heat: its change under q + s dq, over s), of the cells'
 * temperatures (linear in the modes), of the factors (the tables' slopes) and of the rows. */
static int coupling_product(rs_transient *tr, const double *v, double *Jv)
{
  const rs_transient_coupling *cp = tr->coupling;
  const rs_model *m = tr->m;
  const int n = m->grid.n, neq = m->lay.neq;
  if (!tr->pred || !tr->w_pt || !(tr->in_pt.velocity > 0.0)) return RS_OK;
  tr->products++;
  if (!tr->deriv_valid) factor_derivatives(tr);
  const double cj = tr->cj_step, V = tr->in_pt.velocity;
  for (int k = 0; k < neq; k++) tr->vp[k] = cj * v[k];
  rs_model_power_jv(m, tr->w_pt, &tr->wlin, &tr->in_pt, cj, tr->y_pt, v, tr->vp, tr->dfric,
                    tr->dplast);
  const double frac = tr->thermal->par.plastic_heat_fraction;
  double qmax = 0.0, dqmax = 0.0;
  for (int i = 0; i < n; i++) {
    tr->dq[i] = 1e-3 * (tr->dfric[i] + frac * tr->dplast[i]);
    qmax = fmax(qmax, fabs(tr->q[i]));
    dqmax = fmax(dqmax, fabs(tr->dq[i]));
  }
  if (!(dqmax > 0.0)) return RS_OK;
  const double s = qmax > 0.0 ? qmax / dqmax : 1.0 / dqmax;
  for (int i = 0; i < n; i++) tr->dq[i] = tr->q[i] + s * tr->dq[i];
  rs_thermal_dae_solve(tr->thermal, V, tr->dq, tr->contact, cj, tr->pred + neq, tr->ratepred + neq,
                       tr->theta_s, tr->cor_s);
  rs_thermal_state_temperature(tr->thermal, V, tr->theta_s, tr->Ts);
  for (int I = 0; I < n; I++) {
    const int nr = tr->nrow[I];
    if (!nr) continue;
    const double dT = (tr->Ts[I] - cp->T_used[I]) / s, T = cp->T_used[I];
    const double smu = cp->mu_factor ? rs_history_rate(cp->mu_table, T) / cp->mu_rest * dT : 0.0;
    const double sy =
        cp->yield_factor ? rs_history_rate(cp->tau_table, T) / cp->tau_rest * dT : 0.0;
    const int *row = tr->rows + (size_t)I * RS_LAW_NROW;
    for (int k = 0; k < nr; k++)
      Jv[row[k]] += tr->dfdmu[(size_t)I * RS_LAW_NROW + k] * smu +
                    tr->dfdyield[(size_t)I * RS_LAW_NROW + k] * sy;
  }
  return RS_OK;
}

/* The direct path's product (rs_nls_host.couple_jv). */
static int couple_jv(void *data, const double *v, double *Cv)
{
  return coupling_product(data, v, Cv);
}

void rs_transient_free(rs_transient *tr)
{
  if (!tr) return;
  if (tr->ida) IDAFree(&tr->ida);
  if (tr->nls) SUNNonlinSolFree(tr->nls);
  if (tr->gmres) SUNLinSolFree(tr->gmres);
  rs_krylov_free(&tr->kry);
  rs_linsys_free(&tr->ls);
  if (tr->y) N_VDestroy(tr->y);
  if (tr->yp) N_VDestroy(tr->yp);
  if (tr->atol) N_VDestroy(tr->atol);
  if (tr->tmpl_c && tr->tmpl_c != tr->y) N_VDestroy(tr->tmpl_c);
  free(tr->fric);
  free(tr->plast);
  free(tr->q);
  free(tr->theta);
  free(tr->contact);
  free(tr->T1);
  free(tr->y_pt);
  free(tr->theta_pt);
  free(tr->cor);
  free(tr->theta_s);
  free(tr->cor_s);
  free(tr->Ts);
  free(tr->dq);
  free(tr->dfric);
  free(tr->dplast);
  free(tr->vp);
  free(tr->dfdmu);
  free(tr->dfdyield);
  free(tr->rows);
  free(tr->nrow);
  rs_work_free(&tr->wlin);
  rs_work_free(&tr->work);
  if (tr->own_ctx) SUNContext_Free(&tr->own_ctx);
  free(tr);
}

int rs_transient_create(rs_transient **out, const rs_model *m, SUNContext ctx, double t0,
                        const double *y0, const double *yp0, const rs_transient_opts *o,
                        rs_msg *msg)
{
  *out = NULL;
  rs_transient *tr = calloc(1, sizeof *tr);
  if (!tr) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (transient solver)");
  static const char what[] = "transient solver";
  tr->m = m;
  if (!ctx && SUNContext_Create(NULL, &tr->own_ctx) != 0) {
    free(tr);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
  }
  ctx = ctx ? ctx : tr->own_ctx;
  tr->t = t0;
  tr->interrupt = o->interrupt;
  tr->step_hook = o->step_hook;
  tr->hook_ctx = o->hook_ctx;
  tr->frozen = o->frozen;
  const rs_layout *L = &m->lay;
  const int neq = L->neq;
  tr->thermal = o->thermal;
  tr->tail_rows = 1;
  tr->neq_full = rs_transient_neq(m, o->thermal);
  tr->weight_scale = sqrt((double)tr->neq_full / neq);
  const int nfull = tr->neq_full;
  N_Vector id = NULL; /* differential/algebraic components (force control) */
  tr->y = N_VNew_Serial(nfull, ctx);
  tr->yp = N_VNew_Serial(nfull, ctx);
  tr->atol = N_VNew_Serial(nfull, ctx);
  tr->tmpl_c = tr->thermal ? N_VNew_Serial(neq, ctx) : tr->y;
  if (tr->thermal) {
    const size_t n = (size_t)m->grid.n;
    tr->fric = malloc(n * sizeof *tr->fric);
    tr->plast = malloc(n * sizeof *tr->plast);
    tr->q = malloc(n * sizeof *tr->q);
    tr->contact = malloc(n);
    tr->theta = malloc((size_t)(nfull - neq) * sizeof *tr->theta);
    tr->coupling = o->coupling;
    int exact_ok = 1;
    if (tr->coupling) {
      tr->T1 = malloc(n * sizeof *tr->T1);
    }
    if (tr->coupling && !tr->coupling->fixed_point) {
      const size_t nm = (size_t)(nfull - neq), nr = n * RS_LAW_NROW;
      tr->y_pt = malloc((size_t)neq * sizeof *tr->y_pt);
      tr->vp = malloc((size_t)neq * sizeof *tr->vp);
      tr->theta_pt = malloc(nm * sizeof *tr->theta_pt);
      tr->cor = malloc(nm * sizeof *tr->cor);
      tr->theta_s = malloc(nm * sizeof *tr->theta_s);
      tr->cor_s = malloc(nm * sizeof *tr->cor_s);
      tr->Ts = malloc(n * sizeof *tr->Ts);
      tr->dq = malloc(n * sizeof *tr->dq);
      tr->dfric = malloc(n * sizeof *tr->dfric);
      tr->dplast = malloc(n * sizeof *tr->dplast);
      tr->dfdmu = calloc(nr, sizeof *tr->dfdmu);
      tr->dfdyield = calloc(nr, sizeof *tr->dfdyield);
      tr->rows = calloc(nr, sizeof *tr->rows);
      tr->nrow = calloc(n, sizeof *tr->nrow);
      exact_ok = tr->y_pt && tr->vp && tr->theta_pt && tr->cor && tr->theta_s && tr->cor_s &&
                 tr->Ts && tr->dq && tr->dfric && tr->dplast && tr->dfdmu && tr->dfdyield &&
                 tr->rows && tr->nrow && rs_work_create_kinematics(&tr->wlin, m) == RS_OK;
    }
    if (!tr->fric || !tr->plast || !tr->q || !tr->theta || !tr->contact || !tr->tmpl_c ||
        (tr->coupling && !tr->T1) || !exact_ok) {
      rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (transient solver, temperature modes)");
      goto fail;
    }
  }
  /* Linear algebra: the Schur-complement solver (linsys_reduced.h) whenever a 2D model
   * has the per-cell unknowns only, KLU on the whole matrix otherwise (as the steady
   * solver does); 3D: Newton-Krylov (the dense elastic block is 2N x 2N). */
  const int krylov = m->el.dim == 3;
  const rs_linear linear = krylov ? RS_LINEAR_KRYLOV : L->nextra > 0 ? RS_LINEAR_KLU : o->linear;
  if (!tr->y || !tr->yp || !tr->atol || rs_work_create(&tr->work, m) != RS_OK ||
      (!krylov && rs_linsys_create(&tr->ls, m, tr->tmpl_c, ctx) != RS_OK)) {
    rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (transient solver, %d unknowns)", nfull);
    goto fail;
  }
  /* IDA's work vectors are clones of y: they inherit the optimised kernels. */
  RS_SUN_CHECK(rs_nvector_fast_ops(tr->y), msg, what);
  RS_SUN_CHECK(rs_nvector_fast_ops(tr->yp), msg, what);
  RS_SUN_CHECK(rs_nvector_fast_ops(tr->atol), msg, what);
  if (tr->thermal) RS_SUN_CHECK(rs_nvector_fast_ops(tr->tmpl_c), msg, what);
  memcpy(N_VGetArrayPointer(tr->y), y0, (size_t)nfull * sizeof *y0);
  memcpy(N_VGetArrayPointer(tr->yp), yp0, (size_t)nfull * sizeof *yp0);
  /* Absolute tolerances: tractions in N/mm^2 as given; plastic displacements in mm,
   * scaled to the contact size (docs/model.md §9: about 1e-4 rtol a). */
  double *at = N_VGetArrayPointer(tr->atol);
  for (int k = 0; k < rs_at_upl(L, 0, 0); k++) at[k] = o->atol;
  for (int k = rs_at_upl(L, 0, 0); k < rs_at_extra(L, 0); k++) at[k] = 1e-4 * o->rtol * m->hertz_a;
  /* friction memory: mu is of order 0.1 to 1 */
  for (int k = 0; k < L->n && L->memory; k++) at[rs_at_mu(L, k)] = 1e-3 * o->rtol;
  /* temperature modes (the fast ones out of the error test, below): each mode's share of the
   * temperature to rtol kelvin,
   * |w_k theta_k|/(beta sqrt(V)) (the rate-0 mode with w_0) */
  if (tr->thermal) {
    const rs_thermal *th = tr->thermal;
    const int K = th->ker.nmodes, n = m->grid.n;
    const double V = rs_history_max_abs(&m->par.velocity, t0, fmax(m->par.end_time, t0));
    const double sv = V > 0.0 ? sqrt(V) : 1.0;
    for (int b = 0; b < 2; b++)
      for (int k = 0; k <= K; k++) {
        const double wk = k == K ? th->ker.weight0 : th->ker.weight[k];
        const double a = o->rtol * th->beta[b] * sv / wk;
        for (int i = 0; i < n; i++) at[neq + (b * (K + 1) + k) * n + i] = a;
      }
  }
  /* With force control the creepage is an algebraic unknown fixed by a constraint on
   * differential ones (sum p dA = F_x): left out of the error test, as IDA allows. */
  /* The fast temperature modes are left out of the error test too: their sources are the heat
   * of the contact, -p . v_s, whose slip velocity holds the BDF derivatives of the tractions,
   * exact only to about the Newton error over the step; a mode that forgets within a few cells
   * follows those sources as they come, and its error estimate does not fall with the step. Modes
   * with a memory of FAST_MODE_CELLS cells or more (rate dx <= 1/FAST_MODE_CELLS, and the mode
   * of rate 0) average the sources over their path and stay in the test: they carry the heat
   * over the contact and set the steps where the contact alone would allow long ones (full
   * sliding). docs/model.md §18. */
  if (L->nextra > 0 || tr->thermal) {
    id = N_VNew_Serial(nfull, ctx);
    RS_SUN_CHECK(id == NULL, msg, what);
    RS_SUN_CHECK(rs_nvector_fast_ops(id), msg, what);
    N_VConst(1.0, id);
    for (int k = 0; k < L->nextra; k++) {
      at[rs_at_extra(L, k)] = 1e-4 * o->rtol;
      N_VGetArrayPointer(id)[rs_at_extra(L, k)] = 0.0;
    }
    const rs_thermal *th = tr->thermal;
    const int K = th ? th->ker.nmodes : 0, n = m->grid.n;
    for (int b = 0; th && b < 2; b++)
      for (int k = 0; k < K; k++)
        if (th->ker.rate[k] * th->dx > 1.0 / FAST_MODE_CELLS)
          for (int i = 0; i < n; i++) N_VGetArrayPointer(id)[neq + (b * (K + 1) + k) * n + i] = 0.0;
  }
  if (linear == RS_LINEAR_DENSE || linear == RS_LINEAR_AUTO)
    RS_SUN_CHECK(rs_linsys_use_reduced(&tr->ls, m, &tr->work, ctx), msg, what);
  if (krylov) {
    /* GMRES with classical Gram-Schmidt, as the steady solver's (gmres.h): modified
     * Gram-Schmidt's sequential vector sums cost time for the same iteration counts. */
    tr->gmres = rs_gmres_create(&tr->kry, tr->tmpl_c, 60, 4, ctx);
    RS_SUN_CHECK(tr->gmres == NULL, msg, what);
    RS_SUN_CHECK(rs_krylov_create(&tr->kry, m, RS_KRYLOV_BAND_3D_TRANSIENT, RS_KRYLOV_BAND_3D_Y),
                 msg, what);
    /* The near field is refactored when cj + V/dx moved by a factor 4 or more than two
     * cells changed branch (linsys_krylov.c), not at every Newton iteration: each changed
     * cell perturbs the preconditioner, and these limits gave the least time for about the
     * same GMRES count on the bench's start-ups. */
    rs_krylov_set_reuse(&tr->kry, 4.0, 2);
  }
  const int exact = tr->coupling && !tr->coupling->fixed_point;
  if (exact) { /* every evaluation of the contact rows reads the factors of its own step */
    tr->work.before_laws = coupled_laws;
    tr->work.before_laws_ctx = tr;
    tr->kry.w.before_laws = coupled_laws;
    tr->kry.w.before_laws_ctx = tr;
  }
  tr->cj = 0.0;
  const rs_nls_host host = {.cj_slot = &tr->cj,
                            .inputs_at = host_inputs,
                            .ctx = tr,
                            .tail = tr->thermal ? solve_tail : NULL,
                            .neq_full = nfull,
                            .tail_rows = &tr->tail_rows,
                            .weight_scale = 1.0 / tr->weight_scale,
                            .couple = tr->coupling && !exact ? couple_step : NULL,
                            .couple_begin = exact ? couple_begin : NULL,
                            .couple_jv = exact && !krylov ? couple_jv : NULL};
  /* Newton-Krylov: the largest forcing term follows the tolerance, 30 rtol within [1e-3, 0.1]
   * (the term itself follows the Newton test, nls_kinsol.c). A loose tolerance's Newton test is
   * loose too, and a tight linear solve there only costs GMRES iterations; at tight tolerances
   * looser linear solves let the semismooth iteration fail (rtol 1e-6 with terms up to 0.3:
   * 2,017 failed solves). */
  const double forcing = fmin(0.1, fmax(1e-3, 30.0 * o->rtol));
  tr->nls = rs_nls_kinsol_create(m, &tr->work, &tr->ls, krylov ? &tr->kry : NULL, tr->gmres,
                                 forcing, host, o->max_newton, tr->tmpl_c, ctx);
  RS_SUN_CHECK(tr->nls == NULL, msg, what);
  tr->ida = IDACreate(ctx);
  RS_SUN_CHECK(tr->ida == NULL, msg, what);
  RS_SUN_CHECK(IDAInit(tr->ida, dae_residual, t0, tr->y, tr->yp), msg, what);
  RS_SUN_CHECK(IDASetUserData(tr->ida, tr), msg, what);
  tr->rtol = o->rtol;
  /* The steady solver's pseudo-transient (frozen inputs) only selects the steady state that
   * Newton then solves: it keeps the plain weights, and 2D without temperature modes IDA's. */
  tr->p_floor =
      o->frozen ? 0.0 : TRACTION_WEIGHT_FLOOR * rs_friction_mu(&m->par.friction, 0.0) * m->hertz_p0;
  if (o->frozen && L->ncomp == 1 && !tr->thermal)
    RS_SUN_CHECK(IDASVtolerances(tr->ida, o->rtol, tr->atol), msg, what);
  else
    RS_SUN_CHECK(IDAWFtolerances(tr->ida, error_weights), msg, what);
  RS_SUN_CHECK(IDASetNonlinearSolver(tr->ida, tr->nls), msg, what);
  RS_SUN_CHECK(IDASetMaxOrd(tr->ida, o->max_order), msg, what);
  RS_SUN_CHECK(IDASetMaxNumSteps(tr->ida, o->max_steps > 0 ? o->max_steps : 1000000), msg, what);
  RS_SUN_CHECK(IDASetErrHandlerFn(tr->ida, rs_sundials_silent, NULL), msg, what);
  if (isfinite(o->t_stop)) RS_SUN_CHECK(IDASetStopTime(tr->ida, o->t_stop), msg, what);
  if (o->max_step > 0.0) RS_SUN_CHECK(IDASetMaxStep(tr->ida, o->max_step), msg, what);
  /* Friction memory: a memory distance too short for the contact lets the friction weaken
   * faster than the contact unloads; where the adhesion zone vanishes the quasi-static
   * problem then loses its solution and the step collapses without bound. A floor of a
   * tenth of rtol of a cell passage (of the time scale without rolling), at least 1e-6,
   * makes that a failure; a well-posed memory case's steps stay ten times above it. */
  if (L->memory) {
    const double V = rs_history_max_abs(&m->par.velocity, t0, fmax(m->par.end_time, t0));
    const double passage = V > 0.0 ? m->grid.dx / V : m->par.time_scale;
    RS_SUN_CHECK(IDASetMinStep(tr->ida, fmax(1e-6, 0.1 * o->rtol) * passage), msg, what);
  }
  if (id) {
    RS_SUN_CHECK(IDASetId(tr->ida, id), msg, what);
    RS_SUN_CHECK(IDASetSuppressAlg(tr->ida, SUNTRUE), msg, what);
    N_VDestroy(id);
    id = NULL;
  }
  *out = tr;
  return RS_OK;
fail:
  if (id) N_VDestroy(id);
  rs_transient_free(tr);
  return RS_ERR_INTERNAL;
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
    *hook_status =
        tr->step_hook(tr->hook_ctx, tn, N_VGetArrayPointer(tr->y), N_VGetArrayPointer(tr->yp));
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
    return rs_msg_set(msg, hook_status,
                      "at t = %.9g s: recording the state leaving the contact "
                      "failed",
                      tret);
  if (flag < 0 && tr->interrupt && *tr->interrupt) {
    IDAGetCurrentTime(tr->ida, &tret);
    return rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted at t = %.6g s", tret);
  }
  if (flag < 0 && tr->work.msg.text[0]) { /* the model could not be evaluated */
    IDAGetCurrentTime(tr->ida, &tret);
    return rs_msg_set(msg, RS_ERR_SOLVER, "at t = %.9g s: %s", tret, tr->work.msg.text);
  }
  if (flag < 0) {
    char *name = IDAGetReturnFlagName(flag);
    sunrealtype h = 0.0;
    IDAGetCurrentStep(tr->ida, &h);
    IDAGetCurrentTime(tr->ida, &tret);
    const char *why = flag == IDA_CONV_FAIL  ? "the contact problem of a time step had no solution "
                                               "(Newton failed repeatedly)"
                      : flag == IDA_ERR_FAIL ? "the error test failed repeatedly"
                      : flag == IDA_TOO_MUCH_WORK ? "solver.max_steps reached"
                                                  : "solver error";
    rs_msg_set(msg, RS_ERR_SOLVER, "transient solver failed at t = %.9g s (step %.3g s): %s [%s]%s",
               tret, h, why, name ? name : "?",
               tr->m->lay.memory && flag != IDA_TOO_MUCH_WORK
                   ? "; with friction memory a too short friction.memory_distance does this: "
                     "the friction weakens faster than the contact unloads and the "
                     "quasi-static problem loses its solution (raise memory_distance)"
                   : "");
    free(name);
    return RS_ERR_SOLVER;
  }
  tr->t = tret;
  memcpy(y, N_VGetArrayPointer(tr->y), (size_t)tr->neq_full * sizeof *y);
  memcpy(yp, N_VGetArrayPointer(tr->yp), (size_t)tr->neq_full * sizeof *yp);
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
  memcpy(N_VGetArrayPointer(tr->y), y, (size_t)tr->neq_full * sizeof *y);
  memcpy(N_VGetArrayPointer(tr->yp), yp, (size_t)tr->neq_full * sizeof *yp);
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
  st->jac_evals = tr->ls.jac_evals + tr->kry.setups;
  st->klu_analyses = rs_linsys_analyses(&tr->ls) + tr->kry.analyses;
  st->factorizations = rs_linsys_factorizations(&tr->ls) + tr->kry.factorizations;
  st->lin_solves = tr->kry.lin_iters; /* Newton-Krylov: GMRES iterations (else 0) */
  st->coupling_products = tr->products;
}

/* solver.rtol auto: in proportion to the cell size, so that the time integration's error
 * stays a fraction of the grid's (first order in dx), within [1e-6, 3e-3]. The measurements
 * behind the factor are in docs/model.md §9 (bench/startup_accuracy). */
double rs_transient_auto_rtol(const rs_model *m)
{
  if (!(m->hertz_a > 0.0)) return 1e-6;
  return fmax(1e-6, fmin(3e-3, 0.06 * m->grid.dx / m->hertz_a));
}
