/* Surface temperature of records and sweep points (study/temperature.h). */
#include "study/temperature.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/history.h"
#include "solve/gmres_cycle.h"

int rs_temperature_coupled(const rs_case *c) { return c->mu_table.n || c->tau_c0_table.n; }

/* The factors of cell i at its temperature T_used[i] (those of the tables given). */
static void set_factors(rs_temperature_run *t, size_t i)
{
  if (t->mu_factor) t->mu_factor[i] = rs_history_eval(t->mu_table, t->T_used[i]) / t->mu_rest;
  if (t->yield_factor)
    t->yield_factor[i] = rs_history_eval(t->tau_table, t->T_used[i]) / t->tau_rest;
}

int rs_temperature_run_create(rs_temperature_run *t, const rs_case *c, const rs_model *m,
                              rs_msg *msg)
{
  memset(t, 0, sizeof *t);
  if (!c->temperature.on) return RS_OK;
  const rs_grid *g = &m->grid;
  const size_t n = (size_t)g->n;
  rs_thermal_params par = c->temperature;
  if (c->rig.on && c->mode == RS_MODE_TRANSIENT) {
    /* a rig's heat comes around again: the kernel covers the paths of the whole run */
    rs_inputs in;
    rs_model_inputs_at(m, 0.0, &in);
    par.path_max = in.velocity * c->end_time + g->nx * g->dx;
  }
  int status = rs_thermal_create(&t->th, &par, g->nx, g->ny, g->dx, g->area, msg);
  if (status != RS_OK) return status;
  t->on = 1;
  t->coupling = c->temperature_coupling;
  t->fric = malloc(n * sizeof *t->fric);
  t->plast = malloc(n * sizeof *t->plast);
  t->q = malloc(n * sizeof *t->q);
  t->T1 = malloc(n * sizeof *t->T1);
  t->T2 = malloc(n * sizeof *t->T2);
  t->contact = malloc(n);
  if (rs_temperature_coupled(c)) { /* from the contact temperature of cold surfaces */
    const double *b = t->th.beta, *Tb = c->temperature.bulk;
    const double T0 = (b[0] * Tb[0] + b[1] * Tb[1]) / (b[0] + b[1]);
    t->T_used = malloc(n * sizeof *t->T_used);
    for (size_t i = 0; t->T_used && i < n; i++) t->T_used[i] = T0;
    if (c->mu_table.n) {
      t->mu_table = &c->mu_table;
      t->mu_rest = rs_friction_mu(&m->par.friction, 0.0);
      t->mu_factor = malloc(n * sizeof *t->mu_factor);
    }
    if (c->tau_c0_table.n) {
      t->tau_table = &c->tau_c0_table;
      t->tau_rest = m->par.plasticity.tau_c0;
      t->yield_factor = malloc(n * sizeof *t->yield_factor);
    }
    for (size_t i = 0; t->T_used && i < n; i++) set_factors(t, i);
  }
  if (!t->fric || !t->plast || !t->q || !t->T1 || !t->T2 || !t->contact ||
      (rs_temperature_coupled(c) && !t->T_used) || (c->mu_table.n && !t->mu_factor) ||
      (c->tau_c0_table.n && !t->yield_factor)) {
    rs_temperature_run_free(t);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the temperature of %zu cells", n);
  }
  return RS_OK;
}

void rs_temperature_run_free(rs_temperature_run *t)
{
  if (t->on) rs_thermal_free(&t->th);
  free(t->fric);
  free(t->plast);
  free(t->q);
  free(t->T1);
  free(t->T2);
  free(t->contact);
  free(t->T_used);
  free(t->mu_factor);
  free(t->yield_factor);
  memset(t, 0, sizeof *t);
}

int rs_temperature_print_derived(const rs_case *c, const rs_model *m, FILE *out, rs_msg *msg)
{
  if (!c->temperature.on) return RS_OK;
  rs_temperature_run t;
  int status = rs_temperature_run_create(&t, c, m, msg);
  if (status != RS_OK) return status;
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  const rs_thermal_params *p = &c->temperature;
  double pe[2];
  for (int b = 0; b < 2; b++) /* kappa = lambda/(rho c), mm^2/s */
    pe[b] =
        in.velocity * m->hertz_a * p->density[b] * p->heat_capacity[b] / (2.0 * p->conductivity[b]);
  fprintf(out, "temperature.beta: [%.6g, %.6g]  # W s^(1/2)/(mm^2 K), sqrt(lambda rho c)\n",
          t.th.beta[0], t.th.beta[1]);
  fprintf(out,
          "temperature.kernel_modes: %d  # + a mode of rate 0 and an instantaneous part; step "
          "response within %.3g\n",
          t.th.ker.nmodes, t.th.ker.error);
  fprintf(out,
          "temperature.peclet: [%.4g, %.4g]  # V a/(2 kappa) at t = 0 (1D conduction into the "
          "depth: valid for Pe >> 1)\n",
          pe[0], pe[1]);
  rs_temperature_run_free(&t);
  return RS_OK;
}

void rs_temperature_run_eval(rs_temperature_run *t, const rs_model *m, const rs_work *w,
                             const rs_inputs *in, const double *y, rs_diag *d)
{
  if (!t->on) return;
  rs_thermal_sources(&t->th, m, w, y, t->fric, t->plast, t->q, t->contact);
  rs_thermal_inflow_at(&t->th, in->t);
  rs_thermal_result r;
  if (t->modes)
    rs_thermal_state_eval(&t->th, in->velocity, t->q, t->contact, y + m->lay.neq, t->T1, t->T2,
                          NULL, NULL, &r);
  else
    rs_thermal_march(&t->th, in->velocity, t->q, t->contact, t->T1, t->T2, NULL, NULL, &r);
  d->T_max = r.T_max;
  d->heat_input_1 = r.heat_input[0];
  d->heat_input_2 = r.heat_input[1];
}

void rs_temperature_run_state_factors(rs_temperature_run *t, const rs_model *m, const rs_inputs *in,
                                      const double *y)
{
  if (!t->modes || !t->T_used || !(in->velocity > 0.0)) return;
  rs_thermal_state_temperature(&t->th, in->velocity, y + m->lay.neq, t->T_used);
  for (int i = 0; i < m->grid.n; i++) set_factors(t, (size_t)i);
}

/* The sources of the state (y, yp): the model evaluated there. */
static int sources_at(rs_temperature_run *t, const rs_model *m, rs_work *w, const rs_inputs *in,
                      const double *y, const double *yp, rs_msg *msg)
{
  const int status = rs_model_residual(m, w, in, y, yp, 0.0, NULL);
  if (status != RS_OK) return rs_msg_set(msg, status, "%s", w->msg.text);
  rs_thermal_sources(&t->th, m, w, y, t->fric, t->plast, t->q, t->contact);
  rs_thermal_inflow_at(&t->th, in->t);
  return RS_OK;
}

int rs_temperature_run_steady_modes(rs_temperature_run *t, const rs_model *m, rs_work *w,
                                    const rs_inputs *in, double *y, double *yp, rs_msg *msg)
{
  if (!t->modes) return RS_OK;
  const int neq = m->lay.neq;
  double *rest = calloc((size_t)neq, sizeof *rest);
  if (!rest) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the steady modes");
  const int status = sources_at(t, m, w, in, y, rest, msg);
  free(rest);
  if (status != RS_OK) return status;
  rs_thermal_result r;
  rs_thermal_march_state(&t->th, in->velocity, t->q, t->contact, t->T1, t->T2, NULL, NULL, &r,
                         y + neq);
  rs_thermal_dae_rates(&t->th, in->velocity, t->q, t->contact, y + neq, yp + neq);
  return RS_OK;
}

int rs_temperature_run_rates(rs_temperature_run *t, const rs_model *m, rs_work *w,
                             const rs_inputs *in, const double *y, double *yp, rs_msg *msg)
{
  if (!t->modes) return RS_OK;
  const int status = sources_at(t, m, w, in, y, yp, msg);
  if (status != RS_OK) return status;
  rs_thermal_dae_rates(&t->th, in->velocity, t->q, t->contact, y + m->lay.neq, yp + m->lay.neq);
  return RS_OK;
}

/* Anderson acceleration (type II, docs/model.md §18) of the fixed point T <- G(T) over the
 * contact cells: with the residual f = G(T) - T and the differences dT, df of the last
 * RS_ANDERSON_DEPTH iterates, gamma minimises |f - df gamma| (normal equations) and
 * T <- T + f - (dT + df) gamma. Outside the contact, where no factor acts, T <- G(T). */
#define RS_ANDERSON_DEPTH 5
typedef struct anderson {
  int n, count;            /* cells, differences stored so far (-1: no iterate yet) */
  double *dx, *df;         /* [RS_ANDERSON_DEPTH][n], the newest at count % depth */
  double *x_last, *f_last; /* [n] */
} anderson;

static void anderson_step(anderson *a, const signed char *contact, double *x, const double *gx)
{
  const int n = a->n, depth = RS_ANDERSON_DEPTH;
  if (a->count >= 0) { /* the differences to the last iterate */
    const int slot = a->count % depth;
    for (int i = 0; i < n; i++) {
      a->dx[slot * n + i] = x[i] - a->x_last[i];
      a->df[slot * n + i] = (gx[i] - x[i]) - a->f_last[i];
    }
  }
  a->count++;
  for (int i = 0; i < n; i++) {
    a->x_last[i] = x[i];
    a->f_last[i] = gx[i] - x[i];
  }
  const int mk = a->count < depth ? a->count : depth;
  double A[RS_ANDERSON_DEPTH][RS_ANDERSON_DEPTH + 1], gamma[RS_ANDERSON_DEPTH] = {0};
  for (int p = 0; p < mk; p++) {
    for (int q = 0; q <= mk; q++) {
      const double *v = q < mk ? a->df + (size_t)q * n : a->f_last;
      double sum = 0.0;
      for (int i = 0; i < n; i++)
        if (contact[i]) sum += a->df[p * n + i] * v[i];
      A[p][q] = sum;
    }
    A[p][p] *= 1.0 + 1e-10; /* nearly dependent differences: a tiny ridge */
  }
  for (int p = 0; p < mk; p++) { /* Gaussian elimination with partial pivoting */
    int piv = p;
    for (int r = p + 1; r < mk; r++)
      if (fabs(A[r][p]) > fabs(A[piv][p])) piv = r;
    for (int q = 0; q <= mk; q++) {
      const double tmp = A[p][q];
      A[p][q] = A[piv][q];
      A[piv][q] = tmp;
    }
    for (int r = p + 1; r < mk; r++) {
      const double f = A[p][p] != 0.0 ? A[r][p] / A[p][p] : 0.0;
      for (int q = p; q <= mk; q++) A[r][q] -= f * A[p][q];
    }
  }
  for (int p = mk - 1; p >= 0; p--) {
    double sum = A[p][mk];
    for (int q = p + 1; q < mk; q++) sum -= A[p][q] * gamma[q];
    gamma[p] = A[p][p] != 0.0 ? sum / A[p][p] : 0.0;
  }
  for (int i = 0; i < n; i++) {
    double next = x[i] + a->f_last[i];
    for (int p = 0; p < mk; p++) next -= (a->dx[p * n + i] + a->df[p * n + i]) * gamma[p];
    x[i] = contact[i] ? next : gx[i];
  }
}

/* The slope of a table (piecewise linear in T, constant beyond its ends) at T: that of the
 * segment T lies in, the right one at a node (as rs_history_eval reads it). */
static double table_slope(const rs_history *h, double T)
{
  for (size_t i = 0; i + 1 < h->n; i++)
    if (T >= h->t[i] && T < h->t[i + 1]) return (h->v[i + 1] - h->v[i]) / (h->t[i + 1] - h->t[i]);
  return 0.0;
}

/* Newton on the coupled steady state (docs/model.md §18, "Couplings"): the contact
 * temperature's equation G(T) = T - Phi(T) = 0 over the contact cells, Phi(T) the march of
 * the heat of the steady state y*(T) solved with the factors of T. Its Jacobian
 * I - dPhi/dT, dPhi/dT v = M dq/dy dy*, with dy* = -J^-1 dF/df f'(T) v (J: the steady
 * Jacobian, f'(T): the tables' slopes), applied by GMRES. */
typedef struct coupling_newton {
  rs_temperature_run *t;
  rs_model *m;
  rs_work *w;
  rs_steady *st;
  const double *y; /* the steady state of the linearisation */
  int n, nc, neq;
  int *cell;        /* the contact cells [nc] */
  double *dfdmu;    /* dF/d(mu factor) of cell I's rows, [I * RS_LAW_NROW + row] */
  double *dfdyield; /* dF/d(yield factor), the same */
  int *row, *nrow;  /* those rows' indices in F [I * RS_LAW_NROW + k], their number [n] */
  double *b, *x, *yt, *q0, *qp, *qm, *Tt, *T2t, *fric, *plast; /* scratch */
  signed char *cont;
  unsigned char *fixed; /* contact cells held at T0 in the step [nc] */
  double eta;           /* GMRES's relative tolerance of the step */
  long products;
} coupling_newton;

/* dF/df of each contact cell's rows at the steady state y (the model evaluated there into w):
 * a factor acts on its own cell's law only, whose rows are piecewise linear in it (the bound
 * mu p_n, the yield limit tau_c0 + k_tau u*), so the central difference over 1e-6 of the
 * factor is the derivative to roundoff on the cell's branch. The scaling r is held: the
 * steady state does not depend on it. */
static int factor_derivatives(coupling_newton *cn, const rs_inputs *in, rs_msg *msg)
{
  rs_temperature_run *t = cn->t;
  rs_model *m = cn->m;
  memset(cn->b, 0, (size_t)cn->neq * sizeof *cn->b); /* y' = 0 */
  int status = rs_model_residual(m, cn->w, in, cn->y, cn->b, 0.0, NULL);
  if (status != RS_OK) return rs_msg_set(msg, status, "%s", cn->w->msg.text);
  int row[RS_LAW_NROW];
  double Rp[RS_LAW_NROW], Rm[RS_LAW_NROW];
  for (int j = 0; j < cn->nc; j++) {
    const int I = cn->cell[j];
    for (int f = 0; f < 2; f++) {
      double *factor = f == 0 ? t->mu_factor : t->yield_factor;
      double *d = (f == 0 ? cn->dfdmu : cn->dfdyield) + (size_t)I * RS_LAW_NROW;
      if (!factor) continue;
      const double f0 = factor[I], h = 1e-6 * fmax(fabs(f0), 1e-3);
      factor[I] = f0 + h;
      const int nr = rs_model_cell_rows(m, cn->w, cn->y, I, row, Rp);
      cn->nrow[I] = nr;
      memcpy(cn->row + (size_t)I * RS_LAW_NROW, row, (size_t)nr * sizeof *row);
      factor[I] = f0 - h;
      rs_model_cell_rows(m, cn->w, cn->y, I, row, Rm);
      factor[I] = f0;
      for (int k = 0; k < nr; k++) d[k] = (Rp[k] - Rm[k]) / (2 * h);
    }
  }
  return RS_OK;
}

/* The heat flux q of the state y + h dy into q (the model evaluated into w). */
static int heat_at(coupling_newton *cn, const rs_inputs *in, const double *dy, double h, double *q,
                   rs_msg *msg)
{
  for (int i = 0; i < cn->neq; i++) cn->yt[i] = cn->y[i] + h * dy[i];
  memset(cn->b, 0, (size_t)cn->neq * sizeof *cn->b);
  const int status = rs_model_residual(cn->m, cn->w, in, cn->yt, cn->b, 0.0, NULL);
  if (status != RS_OK) return rs_msg_set(msg, status, "%s", cn->w->msg.text);
  rs_thermal_sources(&cn->t->th, cn->m, cn->w, cn->yt, cn->fric, cn->plast, q, cn->cont);
  return RS_OK;
}

/* Jv = v - dPhi/dT v over the contact cells. */
static int coupling_times(coupling_newton *cn, const rs_inputs *in, const double *v, double *Jv,
                          rs_msg *msg)
{
  rs_temperature_run *t = cn->t;
  cn->products++;
  memset(cn->b, 0, (size_t)cn->neq * sizeof *cn->b);
  double bmax = 0.0;
  for (int j = 0; j < cn->nc; j++) {
    const int I = cn->cell[j], nr = cn->nrow[I], *row = cn->row + (size_t)I * RS_LAW_NROW;
    const double T = t->T_used[I];
    const double smu = t->mu_table ? table_slope(t->mu_table, T) / t->mu_rest * v[j] : 0.0;
    const double sy = t->tau_table ? table_slope(t->tau_table, T) / t->tau_rest * v[j] : 0.0;
    for (int k = 0; k < nr; k++) {
      double d = 0.0;
      if (smu != 0.0) d += cn->dfdmu[(size_t)I * RS_LAW_NROW + k] * smu;
      if (sy != 0.0) d += cn->dfdyield[(size_t)I * RS_LAW_NROW + k] * sy;
      cn->b[row[k]] = -d; /* J dy = -dF/df df */
      bmax = fmax(bmax, fabs(d));
    }
  }
  for (int j = 0; j < cn->nc; j++) Jv[j] = v[j];
  if (bmax == 0.0) return RS_OK; /* no slope: the factors do not move */
  int status = rs_steady_linear_solve(cn->st, cn->b, cn->x, 0.1 * cn->eta, msg);
  if (status != RS_OK) return status;
  /* q is bilinear in y (tractions times slip velocities, those affine in y): the central
   * difference is its derivative exactly, for any step; one of 1e-3 of y keeps roundoff low */
  double ymax = 0.0, xmax = 0.0;
  for (int i = 0; i < cn->neq; i++) {
    ymax = fmax(ymax, fabs(cn->y[i]));
    xmax = fmax(xmax, fabs(cn->x[i]));
  }
  if (!(xmax > 0.0)) return RS_OK;
  const double h = ymax > 0.0 ? 1e-3 * ymax / xmax : 1.0 / xmax;
  if ((status = heat_at(cn, in, cn->x, h, cn->qp, msg)) != RS_OK ||
      (status = heat_at(cn, in, cn->x, -h, cn->qm, msg)) != RS_OK)
    return status;
  /* the march is affine in q: its change under q0 + s dq, over s */
  double q0max = 0.0, dqmax = 0.0;
  for (int i = 0; i < cn->n; i++) {
    cn->qp[i] = (cn->qp[i] - cn->qm[i]) / (2.0 * h);
    q0max = fmax(q0max, fabs(cn->q0[i]));
    dqmax = fmax(dqmax, fabs(cn->qp[i]));
  }
  if (!(dqmax > 0.0)) return RS_OK;
  const double s = q0max > 0.0 ? q0max / dqmax : 1.0 / dqmax;
  for (int i = 0; i < cn->n; i++) cn->qm[i] = cn->q0[i] + s * cn->qp[i];
  rs_inputs inv = *in;
  rs_thermal_result r;
  rs_thermal_march(&t->th, inv.velocity, cn->qm, t->contact, cn->Tt, cn->T2t, NULL, NULL, &r);
  for (int j = 0; j < cn->nc; j++) {
    const int I = cn->cell[j];
    Jv[j] = cn->fixed[j] ? v[j] : v[j] - (cn->Tt[I] - t->T1[I]) / s;
  }
  return RS_OK;
}

typedef struct coupling_op_ctx {
  coupling_newton *cn;
  const rs_inputs *in;
  rs_msg *msg;
} coupling_op_ctx;

static int coupling_apply(void *ctx, const double *v, double *Jv)
{
  const coupling_op_ctx *k = ctx;
  return coupling_times(k->cn, k->in, v, Jv, k->msg);
}

/* Restarted GMRES (solve/gmres_cycle.h) for (I - dPhi/dT) x = rhs over the nc contact cells,
 * from x = 0, to |rhs - A x|_2 <= rtol |rhs|_2. */
#define RS_COUPLING_KRYLOV 30
static int coupling_gmres(coupling_newton *cn, const rs_inputs *in, const double *rhs, double *x,
                          double rtol, rs_msg *msg)
{
  const int nc = cn->nc, mk = nc < RS_COUPLING_KRYLOV ? nc : RS_COUPLING_KRYLOV;
  double *V = malloc((size_t)(mk + 1) * nc * sizeof *V), *Av = malloc((size_t)nc * sizeof *Av);
  int status = V && Av ? RS_OK : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (coupling)");
  double bnorm = 0.0;
  for (int j = 0; j < nc; j++) {
    bnorm += rhs[j] * rhs[j];
    x[j] = 0.0;
  }
  bnorm = sqrt(bnorm);
  coupling_op_ctx ctx = {cn, in, msg};
  for (int restart = 0; restart < 4 && status == RS_OK && bnorm > 0.0; restart++) {
    /* r = rhs - A x */
    if (restart == 0) {
      memcpy(V, rhs, (size_t)nc * sizeof *V);
    } else {
      if ((status = coupling_times(cn, in, x, Av, msg)) != RS_OK) break;
      for (int j = 0; j < nc; j++) V[j] = rhs[j] - Av[j];
    }
    double beta = 0.0;
    for (int j = 0; j < nc; j++) beta += V[j] * V[j];
    beta = sqrt(beta);
    if (beta <= rtol * bnorm) break;
    for (int j = 0; j < nc; j++) V[j] /= beta;
    double res;
    int used;
    status =
        rs_gmres_cycle(nc, mk, coupling_apply, &ctx, V, beta, rtol * bnorm, NULL, x, &res, &used);
    if (status == RS_OK && used > 0 && res <= rtol * bnorm) break;
  }
  free(V);
  free(Av);
  return status;
}

static void coupling_newton_free(coupling_newton *cn)
{
  free(cn->cell);
  free(cn->dfdmu);
  free(cn->dfdyield);
  free(cn->row);
  free(cn->nrow);
  free(cn->b);
  free(cn->x);
  free(cn->yt);
  free(cn->q0);
  free(cn->qp);
  free(cn->qm);
  free(cn->Tt);
  free(cn->T2t);
  free(cn->fric);
  free(cn->plast);
  free(cn->cont);
  free(cn->fixed);
}

static int coupling_newton_alloc(coupling_newton *cn, rs_temperature_run *t, rs_model *m,
                                 rs_steady *st)
{
  const size_t n = (size_t)m->grid.n, neq = (size_t)m->lay.neq;
  *cn = (coupling_newton){.t = t, .m = m, .st = st, .n = (int)n, .neq = (int)neq};
  cn->cell = malloc(n * sizeof *cn->cell);
  cn->dfdmu = calloc(n * RS_LAW_NROW, sizeof *cn->dfdmu);
  cn->dfdyield = calloc(n * RS_LAW_NROW, sizeof *cn->dfdyield);
  cn->row = malloc(n * RS_LAW_NROW * sizeof *cn->row);
  cn->nrow = calloc(n, sizeof *cn->nrow);
  cn->b = malloc(neq * sizeof *cn->b);
  cn->x = malloc(neq * sizeof *cn->x);
  cn->yt = malloc(neq * sizeof *cn->yt);
  cn->q0 = malloc(n * sizeof *cn->q0);
  cn->qp = malloc(n * sizeof *cn->qp);
  cn->qm = malloc(n * sizeof *cn->qm);
  cn->Tt = malloc(n * sizeof *cn->Tt);
  cn->T2t = malloc(n * sizeof *cn->T2t);
  cn->fric = malloc(n * sizeof *cn->fric);
  cn->plast = malloc(n * sizeof *cn->plast);
  cn->cont = malloc(n);
  cn->fixed = malloc(n);
  return cn->cell && cn->dfdmu && cn->dfdyield && cn->row && cn->nrow && cn->b && cn->x && cn->yt &&
         cn->q0 && cn->qp && cn->qm && cn->Tt && cn->T2t && cn->fric && cn->plast && cn->cont &&
         cn->fixed;
}

/* The Newton step dT (over the contact cells, [nc]) at the steady state y of T_used, whose
 * march is t->T1 and heat t->q. */
static int newton_step(coupling_newton *cn, rs_work *w, const double *y, double T0, double *dT,
                       rs_msg *msg)
{
  rs_temperature_run *t = cn->t;
  cn->w = w;
  cn->y = y;
  int status = rs_steady_linearise(cn->st, 0.0, y, msg);
  const rs_inputs *in = rs_steady_inputs(cn->st);
  if (status == RS_OK) status = factor_derivatives(cn, in, msg);
  if (status != RS_OK) return status;
  memcpy(cn->q0, t->q, (size_t)cn->n * sizeof *cn->q0);
  double *rhs = malloc((size_t)cn->nc * sizeof *rhs);
  if (!rhs) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (coupling)");
  memset(cn->fixed, 0, (size_t)cn->nc);
  /* T >= T0 (the heat is dissipation, q >= 0: no contact temperature of a steady state is below
   * that of the cold surfaces in contact): a cell whose step would go below T0 is held at T0 and
   * the step solved again for the others, at most three times. Below T0 the linear model would
   * read the table's slope where the table is often constant (its first node at the bulk
   * temperature), as at the leading cell of a slip zone, heated next to nothing. */
  for (int pass = 0; pass < 4 && status == RS_OK; pass++) {
    for (int j = 0; j < cn->nc; j++) {
      const int I = cn->cell[j];
      rhs[j] = cn->fixed[j] ? T0 - t->T_used[I] : t->T1[I] - t->T_used[I];
    }
    status = coupling_gmres(cn, in, rhs, dT, cn->eta, msg);
    int more = 0;
    for (int j = 0; j < cn->nc && status == RS_OK; j++)
      if (!cn->fixed[j] && t->T_used[cn->cell[j]] + dT[j] < T0) cn->fixed[j] = more = 1;
    if (!more) break;
  }
  free(rhs);
  return status;
}

int rs_temperature_couple(rs_temperature_run *t, rs_model *m, rs_work *w, rs_steady *st, double *y,
                          rs_stats *stats, rs_msg *msg)
{
  if (!t->T_used) return RS_OK;
  const int n = m->grid.n, neq = m->lay.neq;
  m->mu_factor = t->mu_factor;
  m->yield_factor = t->yield_factor;
  double *rest = calloc((size_t)neq, sizeof *rest);
  anderson acc = {.n = n, .count = -1};
  acc.dx = malloc((size_t)RS_ANDERSON_DEPTH * n * sizeof *acc.dx);
  acc.df = malloc((size_t)RS_ANDERSON_DEPTH * n * sizeof *acc.df);
  acc.x_last = malloc((size_t)n * sizeof *acc.x_last);
  acc.f_last = malloc((size_t)n * sizeof *acc.f_last);
  /* Newton: the last accepted iterate (T, y, its march T1 and heat q) and its step */
  const int use_newton = t->coupling == RS_COUPLING_NEWTON;
  int newton = use_newton;
  coupling_newton cn = {0};
  double *T_acc = malloc((size_t)n * sizeof *T_acc), *y_acc = malloc((size_t)neq * sizeof *y_acc);
  double *T1_acc = malloc((size_t)n * sizeof *T1_acc), *q_acc = malloc((size_t)n * sizeof *q_acc);
  double *dT = malloc((size_t)n * sizeof *dT);
  int status = RS_OK, k, have_acc = 0;
  if (!rest || !acc.dx || !acc.df || !acc.x_last || !acc.f_last || !T_acc || !y_acc || !T1_acc ||
      !q_acc || !dT || (newton && !coupling_newton_alloc(&cn, t, m, st)))
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the temperature coupling");
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  const double *b = t->th.beta, *Tb = t->th.par.bulk;
  const double T0 = (b[0] * Tb[0] + b[1] * Tb[1]) / (b[0] + b[1]);
  double change = INFINITY, rise = 0.0, fnorm_acc = INFINITY, fnorm_fail = 0.0, lambda = 1.0;
  const long couplings0 = t->couplings, newton0 = t->newton_steps;
  for (k = 1; k <= RS_COUPLING_MAX && status == RS_OK; k++) {
    status = rs_steady_solve(st, 0.0, y, stats, msg);
    if (status == RS_OK) status = sources_at(t, m, w, &in, y, rest, msg);
    double fnorm = INFINITY;
    if (status == RS_OK) {
      rs_thermal_result r;
      rs_thermal_march(&t->th, in.velocity, t->q, t->contact, t->T1, t->T2, NULL, NULL, &r);
      t->couplings++;
      change = rise = fnorm = 0.0; /* over the contact, where the factors act */
      for (int i = 0; i < n; i++)
        if (t->contact[i]) {
          change = fmax(change, fabs(t->T1[i] - t->T_used[i]));
          rise = fmax(rise, fabs(t->T1[i] - T0));
          fnorm += (t->T1[i] - t->T_used[i]) * (t->T1[i] - t->T_used[i]);
        }
      fnorm = sqrt(fnorm);
      if (change <= RS_COUPLING_TOL * rise || rise == 0.0) break;
    } else if (!(newton && have_acc && status == RS_ERR_SOLVER)) {
      break;
    }
    /* back to Newton once the fixed point has halved |G| from where Newton failed */
    if (use_newton && !newton && fnorm < 0.5 * fnorm_fail) {
      newton = 1;
      have_acc = 0;
      acc.count = -1;
    }
    if (newton && have_acc && !(fnorm <= (1.0 - 1e-4 * lambda) * fnorm_acc)) {
      /* the trial did not lower |G| (or its steady solve failed): a shorter step, else
       * Anderson's fixed point from the last accepted iterate */
      status = RS_OK;
      memcpy(y, y_acc, (size_t)neq * sizeof *y);
      if (lambda > 1.0 / 16.0) {
        lambda *= 0.5;
        for (int j = 0; j < cn.nc; j++)
          t->T_used[cn.cell[j]] = fmax(T_acc[cn.cell[j]] + lambda * dT[j], T0);
        for (int i = 0; i < n; i++) set_factors(t, (size_t)i);
        continue;
      }
      newton = 0;
      fnorm_fail = fnorm_acc;
      memcpy(t->T_used, T_acc, (size_t)n * sizeof *T_acc);
      memcpy(t->T1, T1_acc, (size_t)n * sizeof *T1_acc);
      memcpy(t->q, q_acc, (size_t)n * sizeof *q_acc);
    } else if (newton) { /* accepted: the Newton step from here */
      have_acc = 1;
      fnorm_acc = fnorm;
      memcpy(T_acc, t->T_used, (size_t)n * sizeof *T_acc);
      memcpy(y_acc, y, (size_t)neq * sizeof *y);
      memcpy(T1_acc, t->T1, (size_t)n * sizeof *T1_acc);
      memcpy(q_acc, t->q, (size_t)n * sizeof *q_acc);
      cn.nc = 0;
      for (int i = 0; i < n; i++)
        if (t->contact[i]) cn.cell[cn.nc++] = i;
      rs_msg why = {{0}};
      /* GMRES's tolerance: a tenth of G's relative size, within [1e-6, 1e-3] (an inexact Newton
       * step as accurate as the iterate warrants keeps the quadratic convergence) */
      cn.eta = fmax(1e-6, fmin(1e-3, 0.1 * change / rise));
      if (newton_step(&cn, w, y_acc, T0, dT, &why) == RS_OK) {
        t->newton_steps++;
        lambda = 1.0;
        for (int i = 0; i < n; i++) t->T_used[i] = t->contact[i] ? t->T_used[i] : t->T1[i];
        /* T >= T0, as in newton_step */
        for (int j = 0; j < cn.nc; j++)
          t->T_used[cn.cell[j]] = fmax(t->T_used[cn.cell[j]] + dT[j], T0);
        for (int i = 0; i < n; i++) set_factors(t, (size_t)i);
        continue;
      }
      newton = 0; /* no step (the linearisation failed): the fixed point from here */
      fnorm_fail = fnorm_acc;
    }
    anderson_step(&acc, t->contact, t->T_used, t->T1);
    for (int i = 0; i < n; i++) set_factors(t, (size_t)i);
  }
  t->coupling_products += cn.products;
  if (stats) {
    stats->couplings += t->couplings - couplings0;
    stats->coupling_newton += t->newton_steps - newton0;
    stats->coupling_products += cn.products;
  }
  free(rest);
  free(acc.dx);
  free(acc.df);
  free(acc.x_last);
  free(acc.f_last);
  free(T_acc);
  free(y_acc);
  free(T1_acc);
  free(q_acc);
  free(dT);
  coupling_newton_free(&cn);
  if (status == RS_OK && k > RS_COUPLING_MAX)
    status = rs_msg_set(msg, RS_ERR_SOLVER,
                        "%s: the coupled steady state (%s from the contact temperature) did not "
                        "converge in %d iterations: the contact temperature still changes by %.3g "
                        "degC (rise %.4g degC, tolerance %g of the rise)",
                        t->mu_table && t->tau_table ? "friction.temperature_table, "
                                                      "plasticity.tau_c0_table"
                        : t->mu_table               ? "friction.temperature_table"
                                                    : "plasticity.tau_c0_table",
                        t->mu_table && t->tau_table ? "mu and tau_c0"
                        : t->mu_table               ? "mu"
                                                    : "tau_c0",
                        RS_COUPLING_MAX, change, rise, RS_COUPLING_TOL);
  return status;
}
