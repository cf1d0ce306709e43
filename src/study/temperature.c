/* Surface temperature of records and sweep points (study/temperature.h). */
#include "study/temperature.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/history.h"

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

int rs_temperature_couple(rs_temperature_run *t, rs_model *m, rs_work *w, rs_steady *st, double *y,
                          rs_stats *stats, rs_msg *msg)
{
  if (!t->T_used) return RS_OK;
  const int n = m->grid.n;
  m->mu_factor = t->mu_factor;
  m->yield_factor = t->yield_factor;
  double *rest = calloc((size_t)m->lay.neq, sizeof *rest);
  anderson acc = {.n = n, .count = -1};
  acc.dx = malloc((size_t)RS_ANDERSON_DEPTH * n * sizeof *acc.dx);
  acc.df = malloc((size_t)RS_ANDERSON_DEPTH * n * sizeof *acc.df);
  acc.x_last = malloc((size_t)n * sizeof *acc.x_last);
  acc.f_last = malloc((size_t)n * sizeof *acc.f_last);
  int status = RS_OK, k;
  if (!rest || !acc.dx || !acc.df || !acc.x_last || !acc.f_last)
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the temperature coupling");
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  const double *b = t->th.beta, *Tb = t->th.par.bulk;
  const double T0 = (b[0] * Tb[0] + b[1] * Tb[1]) / (b[0] + b[1]);
  double change = INFINITY, rise = 0.0;
  for (k = 1; k <= RS_COUPLING_MAX && status == RS_OK; k++) {
    status = rs_steady_solve(st, 0.0, y, stats, msg);
    if (status == RS_OK) status = sources_at(t, m, w, &in, y, rest, msg);
    if (status != RS_OK) break;
    rs_thermal_result r;
    rs_thermal_march(&t->th, in.velocity, t->q, t->contact, t->T1, t->T2, NULL, NULL, &r);
    t->couplings++;
    change = rise = 0.0; /* over the contact, where the factors act */
    for (int i = 0; i < n; i++)
      if (t->contact[i]) {
        change = fmax(change, fabs(t->T1[i] - t->T_used[i]));
        rise = fmax(rise, fabs(t->T1[i] - T0));
      }
    if (change <= RS_COUPLING_TOL * rise || rise == 0.0) break;
    anderson_step(&acc, t->contact, t->T_used, t->T1);
    for (int i = 0; i < n; i++) set_factors(t, (size_t)i);
  }
  free(rest);
  free(acc.dx);
  free(acc.df);
  free(acc.x_last);
  free(acc.f_last);
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
