/* Twin-disc bookkeeping during a transient run (see rig_protocol.h). */
#include "study/rig_protocol.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void rs_rig_run_free(rs_rig_run *r)
{
  rs_rig_memory_free(&r->mem);
  rs_rig_memory_free(&r->heat);
  free(r->heat_buf);
  free(r->window_start);
  free(r->slip_start);
  free(r->slip_end);
  free(r->time_start);
  free(r->time_end);
  free(r->exit_buf);
  rs_work_free(&r->w);
  memset(r, 0, sizeof *r);
}

int rs_rig_run_create(rs_rig_run *r, const rs_case *c, const rs_model *m, rs_run_result *res,
                      rs_msg *msg)
{
  memset(r, 0, sizeof *r);
  r->c = c;
  r->m = m;
  r->res = res;
  const rs_twin_disc *rig = &c->rig;
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  const double V = in.velocity, L = m->grid.nx * m->grid.dx;
  const double two_pi = 2.0 * RS_PI;
  /* the exit state of the trailing cell of every row: u_pl (ncomp), u* */
  const int width = (m->lay.ncomp + 1) * m->grid.ny;
  int status = rs_rig_memory_create(&r->mem, width, (two_pi * rig->radius_1 - L) / V,
                                    (two_pi * rig->radius_2 - L) / V, rig->recovery, msg);
  if (status != RS_OK) return status;
  const size_t ns = rig->nsteps;
  r->window_start = malloc(ns * sizeof(double));
  r->slip_start = malloc(ns * sizeof(double));
  r->slip_end = malloc(ns * sizeof(double));
  r->time_start = malloc(ns * sizeof(double));
  r->time_end = malloc(ns * sizeof(double));
  res->rig_nsteps = ns;
  res->rig_step_mu = malloc(ns * sizeof(double));
  res->rig_step_slip = malloc(ns * sizeof(double));
  if (!r->window_start || !r->slip_start || !r->slip_end || !r->time_start || !r->time_end ||
      !res->rig_step_mu || !res->rig_step_slip) {
    rs_rig_run_free(r);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc protocol)");
  }
  double revs = 0.0;
  for (size_t j = 0; j < ns; j++) {
    r->time_start[j] = revs * rig->revolution_time;
    revs += rig->steps[j].revolutions;
    r->time_end[j] = j + 1 == ns ? c->end_time : revs * rig->revolution_time;
    r->window_start[j] = r->time_end[j] - rig->average_window * (r->time_end[j] - r->time_start[j]);
    r->slip_start[j] = rig->steps[j].slip_start;
    r->slip_end[j] = rig->steps[j].slip_end;
    res->rig_step_mu[j] = res->rig_step_slip[j] = NAN;
  }
  r->nrev = (size_t)ceil(revs - 1e-9);
  if (width > 2 && !(r->exit_buf = malloc((size_t)width * sizeof *r->exit_buf))) {
    rs_rig_run_free(r);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc memory)");
  }
  res->rig_rev_mu = malloc((r->nrev ? r->nrev : 1) * sizeof(double));
  if (!res->rig_rev_mu) {
    rs_rig_run_free(r);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc protocol)");
  }
  res->rig_nrev = r->nrev;
  for (size_t k = 0; k < r->nrev; k++) res->rig_rev_mu[k] = NAN;
  if (rs_work_create(&r->w, m) != RS_OK) {
    rs_rig_run_free(r);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc power)");
  }
  return RS_OK;
}

int rs_rig_run_heat(rs_rig_run *r, rs_temperature_run *temp, rs_msg *msg)
{
  const rs_model *m = r->m;
  rs_thermal *th = &temp->th;
  const int width = 2 * (th->ker.nmodes + 1) * m->grid.ny;
  int status = rs_rig_memory_create(&r->heat, width, r->mem.delay[0], r->mem.delay[1], 1.0, msg);
  if (status != RS_OK) return status;
  r->temp = temp;
  if (!(r->heat_buf = malloc((size_t)width * sizeof *r->heat_buf)))
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc heat memory)");
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  /* the free path of each disc: from the trailing edge around to the leading edge */
  const double path[2] = {r->mem.delay[0] * in.velocity, r->mem.delay[1] * in.velocity};
  return rs_thermal_rig_attach(th, &r->heat, path, in.velocity, msg);
}

rs_output_rig rs_rig_run_output(const rs_rig_run *r)
{
  return (rs_output_rig){.nsteps = r->c->rig.nsteps,
                         .nrevolutions = r->nrev,
                         .slip_start = r->slip_start,
                         .slip_end = r->slip_end,
                         .time_start = r->time_start,
                         .time_end = r->time_end,
                         .window_start = r->window_start,
                         .revolution_time = r->c->rig.revolution_time,
                         .recovery = r->c->rig.recovery,
                         .temperature = r->temp != NULL,
                         .bulk = r->temp && (r->c->temperature.disc_mass[0] > 0.0 ||
                                             r->c->temperature.disc_mass[1] > 0.0)};
}

/* Integral of the linear function through (t0, f0), (t1, f1) over [a, b] n [t0, t1]. */
static double overlap_integral(double t0, double f0, double t1, double f1, double a, double b)
{
  const double lo = fmax(a, t0), hi = fmin(b, t1);
  if (!(hi > lo) || !(t1 > t0)) return 0.0;
  const double flo = f0 + (f1 - f0) * (lo - t0) / (t1 - t0);
  const double fhi = f0 + (f1 - f0) * (hi - t0) / (t1 - t0);
  return 0.5 * (flo + fhi) * (hi - lo);
}

/* A completed revolution's temperatures (of duration T, s): written, and with
 * temperature.disc_mass each disc's bulk temperature raised by its heat input over the
 * revolution / (m c) (2D: the heat per mm of width times the discs' width). */
static int revolution_heat(rs_rig_run *r, size_t rev, double T)
{
  rs_thermal *th = &r->temp->th;
  const rs_case *c = r->c;
  const double width = c->dimension == 3 ? 1.0 : c->rig.width;
  for (int b = 0; b < 2; b++) {
    const double mass = c->temperature.disc_mass[b];
    if (mass > 0.0)
      th->par.bulk[b] += r->rev_heat[b] * width / (mass * c->temperature.heat_capacity[b]);
  }
  r->res->rig_bulk[0] = th->par.bulk[0];
  r->res->rig_bulk[1] = th->par.bulk[1];
  const double v[7] = {isfinite(r->rev_T_max) ? r->rev_T_max : NAN,
                       r->rev_inlet[0] / T,
                       r->rev_inlet[1] / T,
                       r->rev_heat[0],
                       r->rev_heat[1],
                       th->par.bulk[0],
                       th->par.bulk[1]};
  return r->out ? rs_output_put_revolution_temperature(r->out, rev, v, &r->msg) : RS_OK;
}

int rs_rig_run_step(void *ctx, double t, const double *y, const double *yp)
{
  rs_rig_run *r = ctx;
  const rs_model *m = r->m;
  const rs_layout *L = &m->lay;
  /* the trailing cell of each row (x lowest): u_pl components, then u* (rs_model_inflow) */
  const int nc = L->ncomp, nx = m->grid.nx, ny = m->grid.ny;
  double exit_2d[2], *exit_state = ny == 1 && nc == 1 ? exit_2d : r->exit_buf;
  for (int iy = 0; iy < ny; iy++) {
    for (int c = 0; c < nc; c++) exit_state[iy * (nc + 1) + c] = y[rs_at_upl(L, c, iy * nx)];
    exit_state[iy * (nc + 1) + nc] = y[rs_at_ustar(L, iy * nx)];
  }
  int status = rs_rig_memory_record(&r->mem, t, exit_state, &r->msg);
  if (status != RS_OK) return status;
  if (r->temp) { /* the modes leaving the trailing cells, per body, mode and row */
    const int n = m->grid.n, MM = 2 * (r->temp->th.ker.nmodes + 1);
    for (int j = 0; j < MM; j++)
      for (int iy = 0; iy < ny; iy++) r->heat_buf[j * ny + iy] = y[L->neq + j * n + iy * nx];
    if ((status = rs_rig_memory_record(&r->heat, t, r->heat_buf, &r->msg)) != RS_OK) return status;
  }
  double fx = 0.0;
  for (int i = 0; i < m->grid.n; i++) fx += y[rs_at_p(L, 0, i)] * m->grid.area;
  /* The slip jumps where a held step starts: the segment ending at t takes its left
   * limit, the next one starts from the value at t. */
  rs_inputs in, before;
  rs_model_inputs_at(m, t, &in);
  rs_model_inputs_at(m, nextafter(t, -INFINITY), &before);
  const double mu = fx / m->normal_load, slip_next = -rs_model_creepage(m, &in, y);
  const double slip = r->started ? -rs_model_creepage(m, &before, y) : slip_next;
  /* the dissipated power (frictional + plastic) and the u* leaving the contact (mean and
   * largest over the rows). At a held step's start the power at t is its left limit, for the
   * segment ending there as for the next one (whose first step, after IDA's restart, is
   * short): the state's rates after the jump are not known here. */
  rs_diag d;
  if ((status = rs_model_diagnostics(m, &r->w, r->started ? &before : &in, y, yp, &d, NULL, NULL,
                                     NULL)) != RS_OK)
    return rs_msg_set(&r->msg, status, "twin-disc: the dissipated power at t = %g s", t);
  const double power = d.frictional_power + d.plastic_power;
  double inlet[2] = {0.0, 0.0}, heat[2] = {0.0, 0.0}, T_max = -INFINITY;
  if (r->temp) {
    rs_temperature_run_eval(r->temp, m, &r->w, r->started ? &before : &in, y, &d);
    rs_thermal_inlet_temperature(&r->temp->th, in.velocity, inlet);
    heat[0] = d.heat_input_1;
    heat[1] = d.heat_input_2;
    if (isfinite(d.T_max)) T_max = d.T_max;
  }
  double ustar = 0.0, ustar_max = 0.0;
  for (int iy = 0; iy < ny; iy++) {
    ustar += exit_state[iy * (nc + 1) + nc] / ny;
    ustar_max = fmax(ustar_max, exit_state[iy * (nc + 1) + nc]);
  }
  if (!r->started) {
    r->started = 1;
    r->rev_ustar_max = ustar_max;
    r->rev_T_max = T_max;
  } else {
    const double t0 = r->t_prev, T = r->c->rig.revolution_time, t_end = r->c->end_time;
    while (r->rev < r->nrev) {
      const double a = r->rev * T, b = fmin((r->rev + 1) * T, t_end);
      r->rev_mu += overlap_integral(t0, r->mu_prev, t, mu, a, b);
      r->rev_slip += overlap_integral(t0, r->slip_prev, t, slip, a, b);
      r->rev_energy += overlap_integral(t0, r->power_prev, t, power, a, b);
      r->rev_ustar += overlap_integral(t0, r->ustar_prev, t, ustar, a, b);
      if (t > a) r->rev_ustar_max = fmax(r->rev_ustar_max, ustar_max);
      for (int disc = 0; r->temp && disc < 2; disc++) {
        r->rev_inlet[disc] += overlap_integral(t0, r->inlet_prev[disc], t, inlet[disc], a, b);
        r->rev_heat[disc] += overlap_integral(t0, r->heat_prev[disc], t, heat[disc], a, b);
      }
      if (t > a) r->rev_T_max = fmax(r->rev_T_max, T_max);
      if (t < b * (1.0 - 1e-12)) break;
      if (r->out && ((status = rs_output_put_revolution(r->out, r->rev, r->rev_mu / (b - a),
                                                        r->rev_slip / (b - a), &r->msg)) != RS_OK ||
                     (status = rs_output_put_revolution_energy(
                          r->out, r->rev, r->rev_energy, r->rev_ustar / (b - a), r->rev_ustar_max,
                          &r->msg)) != RS_OK))
        return status;
      if (r->temp && (status = revolution_heat(r, r->rev, b - a)) != RS_OK) return status;
      r->res->rig_revolutions = (double)(r->rev + 1);
      r->res->rig_rev_mu[r->rev] = r->rev_mu / (b - a);
      r->rev++;
      r->rev_mu = r->rev_slip = r->rev_energy = r->rev_ustar = 0.0;
      r->rev_ustar_max = ustar_max; /* the state at the boundary belongs to both */
      r->rev_T_max = T_max;
      r->rev_inlet[0] = r->rev_inlet[1] = r->rev_heat[0] = r->rev_heat[1] = 0.0;
    }
    while (r->step < r->c->rig.nsteps) {
      const size_t j = r->step;
      const double a = r->window_start[j], b = r->time_end[j];
      r->step_mu += overlap_integral(t0, r->mu_prev, t, mu, a, b);
      r->step_slip += overlap_integral(t0, r->slip_prev, t, slip, a, b);
      if (t < b * (1.0 - 1e-12)) break;
      r->res->rig_step_mu[j] = r->step_mu / (b - a);
      r->res->rig_step_slip[j] = r->step_slip / (b - a);
      if (r->out && (status = rs_output_put_step(r->out, j, r->res->rig_step_mu[j],
                                                 r->res->rig_step_slip[j], &r->msg)) != RS_OK)
        return status;
      r->step++;
      r->step_mu = r->step_slip = 0.0;
    }
  }
  r->t_prev = t;
  r->mu_prev = mu;
  r->slip_prev = slip_next;
  r->power_prev = power;
  r->ustar_prev = ustar;
  for (int b = 0; b < 2; b++) {
    r->inlet_prev[b] = inlet[b];
    r->heat_prev[b] = heat[b];
  }
  return RS_OK;
}
