/* Surface temperature of records and sweep points (study/temperature.h). */
#include "study/temperature.h"

#include <stdlib.h>
#include <string.h>

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
  if (!t->fric || !t->plast || !t->q || !t->T1 || !t->T2 || !t->contact) {
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
