#define _POSIX_C_SOURCE 200809L
/* rs_run: one case end to end (see study/run.h). Records go to the netCDF file
 * as they are computed; the status attribute tells a reader how the run ended. */
#include "study/run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "study/errest.h"
#include "study/rig_protocol.h"
#include "base/util.h"
#include "physics/kalker.h"
#include "physics/normal3d.h"
#include "io/output.h"
#include "io/restart.h"
#include "study/sweep_fields.h"
#include "study/temperature.h"
#include "study/warnings.h"

typedef struct run_state {
  const rs_case *c;
  SUNContext ctx; /* the run's one SUNDIALS context */
  rs_model m;
  rs_work w;
  double *y, *yp, *slip, *tauc;
  double *mu; /* mu(|v_s|) per cell (NaN outside the contact), or the memory state */
  signed char *regime;
  rs_output *out;
  rs_fields *final;         /* copies of the last record's fields, or NULL */
  rs_temperature_run temp;  /* surface temperature (temp.on: the case has a temperature: block) */
  rs_diag est;              /* the error estimate of the steady record (its error fields) */
  rs_record_diags *collect; /* every record's quantities appended here, or NULL */
  const rs_record_diags *comp[2]; /* transient estimate: the companion runs' records, or NULL */
  double r21, r32;                /* their cell size ratios */
  size_t written;                 /* records written by write_record so far */
} run_state;

void rs_run_result_free(rs_run_result *res)
{
  free(res->rig_step_mu);
  free(res->rig_step_slip);
  free(res->rig_rev_mu);
  res->rig_step_mu = res->rig_step_slip = res->rig_rev_mu = NULL;
  res->rig_nrev = 0;
  res->rig_nsteps = 0;
}

/* Transient estimate: the record at t (the written-th) from the companion runs' records at
 * the same time, where both have one. */
static void transient_estimate(run_state *s, double t, rs_diag *d)
{
  const size_t i = s->written;
  const double tol = 1e-9 * s->c->output_interval;
  rs_errest_none(d);
  if (s->comp[0]->n > i && s->comp[1]->n > i && fabs(s->comp[0]->t[i] - t) <= tol &&
      fabs(s->comp[1]->t[i] - t) <= tol)
    rs_errest_diag(&s->m, s->r21, s->r32, &s->comp[0]->d[i], &s->comp[1]->d[i], d);
}

static int write_record(run_state *s, double t, rs_diag *d, rs_msg *msg)
{
  const rs_layout *L = &s->m.lay;
  rs_inputs in;
  rs_model_inputs_at(&s->m, t, &in);
  int status = rs_model_diagnostics(&s->m, &s->w, &in, s->y, s->yp, d, s->slip, s->tauc, s->regime);
  if (status != RS_OK) return rs_msg_set(msg, status, "%s", s->w.msg.text);
  rs_errest_copy(d, &s->est);
  if (s->comp[0]) transient_estimate(s, t, d);
  if (s->collect) {
    rs_record_diags *r = s->collect;
    if (r->n == r->cap) {
      const size_t cap = r->cap ? 2 * r->cap : 64;
      rs_diag *nd = realloc(r->d, cap * sizeof *nd);
      if (nd) r->d = nd;
      double *nt = realloc(r->t, cap * sizeof *nt);
      if (nt) r->t = nt;
      if (!nd || !nt) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the records");
      r->cap = cap;
    }
    r->d[r->n] = *d;
    r->t[r->n++] = t;
  }
  for (int i = 0; i < s->m.grid.n; i++) /* each cell's bound g = mu(|v_s|) p_n */
    s->mu[i] = s->w.pn[i] > 0.0 ? s->w.law[i].g / s->w.pn[i] : NAN;
  for (int i = 0; i < s->m.grid.n && L->memory; i++) /* friction memory: the state, everywhere */
    s->mu[i] = s->y[rs_at_mu(L, i)];
  if (s->final && L->ncomp == 1)
    rs_fields_copy(s->final, s->m.grid.n, s->y, s->w.pn, s->slip, s->tauc, s->regime, s->mu);
  /* from the modes of a transient, the steady march of the sources otherwise (§18) */
  rs_temperature_run_eval(&s->temp, &s->m, &s->w, &in, s->y, d);
  rs_record rec = {.time = t,
                   .Fx = d->Fx,
                   .Fn = d->Fn,
                   .creepage = d->creepage,
                   .Fy = d->Fy,
                   .Mz = d->Mz,
                   .lateral_creepage = d->lateral_creepage,
                   .spin = d->spin,
                   .velocity = d->velocity,
                   .n_exterior = d->count[RS_EXTERIOR],
                   .n_adhesion = d->count[RS_ADHESION],
                   .n_slip = d->count[RS_SLIP],
                   .n_plastic = d->count[RS_PLASTIC],
                   .frictional_power = d->frictional_power,
                   .plastic_power = d->plastic_power,
                   .elastic_energy = d->elastic_energy,
                   .px = s->y + rs_at_p(L, 0, 0),
                   .pn = s->w.pn,
                   .slip = s->slip,
                   .upl = s->y + rs_at_upl(L, 0, 0),
                   .ustar = s->y + rs_at_ustar(L, 0),
                   .tauc = s->tauc,
                   .regime = s->regime,
                   .mu = s->mu,
                   .T1 = s->temp.T1,
                   .T2 = s->temp.T2,
                   .T_max = d->T_max,
                   .heat_input_1 = d->heat_input_1,
                   .heat_input_2 = d->heat_input_2,
                   .Fx_error = d->Fx_error,
                   .Fy_error = d->Fy_error,
                   .Mz_error = d->Mz_error,
                   .Fx_extrapolated = d->Fx_extrapolated,
                   .Fy_extrapolated = d->Fy_extrapolated,
                   .Mz_extrapolated = d->Mz_extrapolated,
                   .error_reliable = d->error_state == RS_ERROR_RELIABLE     ? 1
                                     : d->error_state == RS_ERROR_UNRELIABLE ? 0
                                                                             : -1,
                   .temperature_modes = s->temp.modes ? s->y + L->neq : NULL};
  return s->out ? rs_output_write(s->out, &rec, msg) : RS_OK;
}

static void progress(double t, double t_end, long steps, double started)
{
  const int width = 30;
  const double frac = t_end > 0 ? fmin(1.0, t / t_end) : 1.0;
  const double elapsed = rs_wall_clock() - started;
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
  char bar[64];
  int k = (int)(frac * width);
  for (int i = 0; i < width; i++) bar[i] = i < k ? '#' : '.';
  bar[width] = '\0';
  fprintf(stderr, "\r[%s] t = %.4g / %.4g s  steps %ld  ETA %.0f s ", bar, t, t_end, steps, eta);
  fflush(stderr);
}

static void free_state(run_state *s)
{
  rs_work_free(&s->w);
  free(s->y);
  free(s->yp);
  free(s->slip);
  free(s->tauc);
  free(s->mu);
  free(s->regime);
  rs_temperature_run_free(&s->temp);
  if (s->m.grid.x) rs_model_free(&s->m);
  if (s->ctx) SUNContext_Free(&s->ctx);
}

/* The companion transient runs of the error estimate: the case on grids of a half and a
 * quarter of the cells along each axis, no output, every record collected. A companion that
 * fails keeps the records before its failure (the later ones get no estimate). */
static int transient_companions(const rs_case *c, const rs_run_opts *o, const rs_model *m,
                                rs_record_diags comp[2], double *r21, double *r32, rs_msg *msg)
{
  int n[3] = {m->grid.n, 0, 0};
  for (int k = 0; k < 2; k++) {
    rs_case cc = *c; /* shallow: rs_run reads the case only */
    cc.cells = m->grid.nx >> (k + 1);
    cc.cells_y = m->grid.ny > 1 ? (int)((long)m->grid.ny * cc.cells / m->grid.nx) : c->cells_y;
    cc.error_estimate = 0;
    cc.accuracy = 0.0;
    rs_run_opts co = {.no_output = 1, .records = &comp[k], .interrupt_flag = o->interrupt_flag};
    rs_model_params pc;
    if (o->params) { /* a wheel-rail patch: its grid's range on fewer cells, its own pressure */
      pc = *o->params;
      pc.cells = cc.cells;
      pc.cells_y = cc.cells_y;
      pc.normal_pressure = NULL;
      co.params = &pc;
    }
    rs_run_result rr;
    rs_msg cmsg = {{0}};
    const int status = rs_run(&cc, &co, &rr, &cmsg);
    rs_run_result_free(&rr);
    if (status == RS_ERR_INTERRUPTED || status == RS_ERR_INTERNAL)
      return rs_msg_set(msg, status, "%s", cmsg.text);
    n[k + 1] = cc.cells * (m->grid.ny > 1 ? cc.cells_y : 1);
  }
  const int three = m->grid.ny > 1;
  *r21 = three ? sqrt((double)n[0] / n[1]) : (double)n[0] / n[1];
  *r32 = three ? sqrt((double)n[1] / n[2]) : (double)n[1] / n[2];
  return RS_OK;
}

/* The error estimate of a steady solution (study/errest.h) on the companion grids. */
static int estimate_steady(run_state *s, rs_run_result *res, rs_msg *msg)
{
  rs_inputs in;
  rs_model_inputs_at(&s->m, 0.0, &in);
  int status = rs_model_diagnostics(&s->m, &s->w, &in, s->y, s->yp, &s->est, NULL, NULL, NULL);
  if (status != RS_OK) return rs_msg_set(msg, status, "%s", s->w.msg.text);
  const double started = rs_wall_clock();
  rs_errest e;
  status = rs_errest_create(&e, &s->m, s->ctx, msg);
  if (status == RS_OK) status = rs_errest_point(&e, &s->m, s->y, &s->est, msg);
  if (status == RS_OK && s->est.error_state == RS_ERROR_NONE)
    snprintf(res->error_note, sizeof res->error_note,
             "no error estimate: a coarser companion grid was not solved");
  rs_errest_free(&e);
  res->error_seconds = rs_wall_clock() - started;
  return status;
}

/* Solver loop for transient mode from t0 (0, or the time of a restart file's last
 * record): one record per output interval k*dt after t0, the last time always stored. */
static int run_transient(run_state *s, const rs_run_opts *o, rs_run_result *res, double t0,
                         double started, rs_rig_run *rig, rs_msg *msg)
{
  const rs_case *c = s->c;
  rs_transient_opts topts = {.rtol = res->rtol,
                             .atol = c->atol,
                             .max_order = c->max_order,
                             .max_steps = c->max_steps,
                             .max_newton = 10,
                             .t_stop = fmin(rs_model_next_breakpoint(&s->m, t0), c->end_time),
                             .interrupt = o->interrupt_flag,
                             .thermal = s->temp.modes ? &s->temp.th : NULL};
  /* mu(T), tau_c0(T): each step's contact and temperature solved together (transient.h) */
  const rs_transient_coupling coupling = {.mu_table = s->temp.mu_table,
                                          .tau_table = s->temp.tau_table,
                                          .mu_rest = s->temp.mu_rest,
                                          .tau_rest = s->temp.tau_rest,
                                          .mu_factor = s->temp.mu_factor,
                                          .yield_factor = s->temp.yield_factor,
                                          .T_used = s->temp.T_used,
                                          .fixed_point =
                                              s->temp.coupling == RS_COUPLING_FIXED_POINT};
  if (s->temp.modes && s->temp.T_used) topts.coupling = &coupling;
  if (rig) {
    topts.step_hook = rs_rig_run_step;
    topts.hook_ctx = rig;
    topts.max_step = rs_rig_memory_max_step(&rig->mem);
    int status = rs_rig_run_step(rig, t0, s->y, s->yp); /* the state at the start */
    if (status != RS_OK) return rs_msg_set(msg, status, "%s", rig->msg.text);
  }
  rs_transient *tr = NULL;
  int status = rs_transient_create(&tr, &s->m, s->ctx, t0, s->y, s->yp, &topts, msg);
  if (status != RS_OK) return status;
  /* Output times k*dt (the end time always stored), the same grid whether the run
   * started at 0 or was restarted at t0, so that the records of a restarted run fall on
   * those of the uninterrupted one; IDA stops at every breakpoint of an input history
   * and restarts from consistent rates there. */
  const double t_end = c->end_time;
  const long nrec = (long)ceil(t_end / c->output_interval - 1e-9);
  double t = t0, bp = topts.t_stop;
  rs_cost_watch cost;
  rs_cost_watch_init(&cost, c, s->m.grid.n, t0, started);
  long k = (long)floor(t0 / c->output_interval + 1e-9) + 1; /* first output time after t0 */
  while (status == RS_OK && k <= nrec) {
    const double t_out = k == nrec ? t_end : k * c->output_interval;
    /* A breakpoint that falls on an output time up to rounding is that output time: IDA
     * goes to the breakpoint itself (its stop time; asked for the output time an ulp away
     * it fails with IDA_ILL_INPUT) and the record there is stored at the output time. */
    const int on_output = fabs(bp - t_out) <= 1e-9 * c->output_interval;
    const double target = on_output ? bp : fmin(t_out, bp);
    status = rs_transient_advance(tr, target, s->y, s->yp, msg);
    if (status != RS_OK && rig && rig->msg.text[0]) rs_msg_set(msg, status, "%s", rig->msg.text);
    if (status != RS_OK) {
      rs_transient_get_stats(tr, &res->stats); /* the summary counts the failed attempt */
      break;
    }
    t = target;
    if (t == t_out || on_output) {
      rs_diag d;
      status = write_record(s, t_out, &d, msg);
      s->written++;
      if (status == RS_OK) { /* the summary describes the last record in the file */
        res->final = d;
        res->time = t_out;
        res->records++;
      }
      k++;
    }
    if (status == RS_OK && t == bp && t < t_end) {
      bp = fmin(rs_model_next_breakpoint(&s->m, t), t_end);
      rs_inputs in;
      rs_model_inputs_at(&s->m, t, &in);
      status = rs_model_project_state(&s->m, &s->w, &in, s->y, msg);
      if (status == RS_OK) status = rs_model_consistent_rates(&s->m, &s->w, &in, s->y, s->yp, msg);
      if (status == RS_OK)
        status = rs_temperature_run_rates(&s->temp, &s->m, &s->w, &in, s->y, s->yp, msg);
      if (status == RS_OK) status = rs_transient_restart(tr, t, s->y, s->yp, bp, msg);
    }
    rs_transient_get_stats(tr, &res->stats);
    if (o->cost_warning) rs_cost_watch_update(&cost, t, res->stats.steps, rs_wall_clock(), stderr);
    if (o->progress) progress(t, t_end, res->stats.steps, started);
    if (status == RS_OK && o->interrupt_flag && *o->interrupt_flag)
      status = rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted at t = %.6g s", t);
  }
  if (o->progress) fputc('\n', stderr);
  rs_transient_free(tr);
  res->rolled = rs_history_integral_abs(&c->velocity, t0, res->time); /* once, at the end */
  return status;
}

/* Restart: check the request and read the state at the old run's last record into s->y
 * (before the output file is created: an invalid restart writes nothing, exit 2). */
static int read_restart(run_state *s, const rs_run_opts *o, const char *out_path, double *t0,
                        rs_msg *msg)
{
  const rs_case *c = s->c;
  /* Writing the continuation over the file it starts from would destroy the old
   * records (the output file is created by renaming over its path). */
  struct stat st_old, st_new;
  if (!o->no_output && !o->append && stat(o->restart_path, &st_old) == 0 &&
      stat(out_path, &st_new) == 0 && st_old.st_dev == st_new.st_dev &&
      st_old.st_ino == st_new.st_ino)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "--restart %s: it is also the output file; choose another one with -o, "
                      "or add --append to continue in it",
                      o->restart_path);
  const rs_layout *L = &s->m.lay;
  const rs_restart_grid g = {.nx = (size_t)s->m.grid.nx,
                             .ny = (size_t)s->m.grid.ny,
                             .x = s->m.grid.x,
                             .y = s->m.grid.y,
                             .ncomp = L->ncomp,
                             .nextra = L->nextra,
                             .memory = L->memory};
  int status =
      rs_restart_read(o->restart_path, &g, t0, s->y + rs_at_p(L, 0, 0), s->y + rs_at_upl(L, 0, 0),
                      s->y + rs_at_ustar(L, 0), L->memory ? s->y + rs_at_mu(L, 0) : NULL,
                      L->nextra ? s->y + rs_at_extra(L, 0) : NULL, msg);
  if (status == RS_OK && s->temp.modes)
    status = rs_restart_read_modes(o->restart_path, &g, 2 * (s->temp.th.ker.nmodes + 1),
                                   s->y + L->neq, msg);
  if (status != RS_OK) return status;
  if (c->mode == RS_MODE_STEADY) { /* the stored state starts Newton at the case's inputs */
    *t0 = 0.0;
    return RS_OK;
  }
  if (*t0 >= c->end_time - 1e-9 * c->output_interval)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "--restart %s: nothing left to run: its last record is at t = %.9g s, "
                      "the case ends at t = %.9g s (raise simulation.rolled_distance or "
                      "simulation.end_time)",
                      o->restart_path, *t0, c->end_time);
  return RS_OK;
}

/* The history of a run that continues OLD.nc: OLD's history, then this command with
 * where it started and how OLD had ended (its status); for --append the line alone
 * (rs_output_open_append adds it to the file's history). */
static int restart_history(const rs_run_opts *o, const rs_case *c, double t0, char **history,
                           rs_msg *msg)
{
  char *old_history = NULL, *old_status = NULL;
  int status = rs_restart_read_provenance(o->restart_path, &old_history, &old_status, msg);
  if (status != RS_OK) return status;
  const char *base = o->history ? o->history : "";
  const size_t len =
      strlen(old_history) + strlen(base) + strlen(o->restart_path) + strlen(old_status) + 160;
  if (!(*history = malloc(len))) {
    free(old_history);
    free(old_status);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  const int keep_old = !o->append && c->mode == RS_MODE_TRANSIENT && *old_history;
  int k = snprintf(*history, len, "%s%s%s%s", keep_old ? old_history : "", keep_old ? "\n" : "",
                   base, *base ? " " : "");
  if (c->mode == RS_MODE_STEADY)
    snprintf(*history + k, len - (size_t)k, "(steady solve started from the last record of %s)",
             o->restart_path);
  else
    snprintf(*history + k, len - (size_t)k, "(%s %s at t = %.9g s; its status was '%s')",
             o->append ? "continued in" : "restart from", o->restart_path, t0, old_status);
  free(old_history);
  free(old_status);
  return RS_OK;
}

int rs_run(const rs_case *c, const rs_run_opts *o, rs_run_result *res, rs_msg *msg)
{
  const double started = rs_wall_clock();
  memset(res, 0, sizeof *res);
  run_state s = {.c = c};
  if (SUNContext_Create(NULL, &s.ctx) != 0)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
  s.est = (rs_diag){0};
  rs_errest_none(&s.est);
  int status = o->params ? rs_model_create(&s.m, o->params, msg) : rs_model_from_case(&s.m, c, msg);
  if (status != RS_OK) {
    free_state(&s);
    return status;
  }
  /* grid.accuracy: the grid refined until the estimate meets it (steady, no restart: the
   * case's keys say so), its solution Newton's start below and its estimate the record's. */
  /* transient runs (output.error_estimate: true given): companion runs, not after a restart */
  const int estimate = c->error_estimate && !c->rig.on &&
                       (c->mode == RS_MODE_STEADY || (!o->restart_path && !o->no_output));
  double *y_chosen = NULL;
  int accuracy_reached = 1;
  if (estimate && c->accuracy > 0.0) {
    if (o->restart_path) {
      free_state(&s);
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--restart %s: not with grid.accuracy (the grid is chosen by the run)",
                        o->restart_path);
    }
    status = rs_errest_refine(&s.m, s.ctx, c->accuracy, &y_chosen, &s.est, &accuracy_reached, msg);
    if (status != RS_OK) {
      free_state(&s);
      return status;
    }
    res->grid_chosen = 1;
    res->accuracy_met = accuracy_reached;
  }
  if ((status = rs_temperature_run_create(&s.temp, c, &s.m, msg)) != RS_OK) {
    free_state(&s);
    return status;
  }
  /* A transient carries the temperature modes as DAE state after the model's unknowns. */
  s.temp.modes = s.temp.on && c->mode == RS_MODE_TRANSIENT;
  if (s.temp.modes) { /* mu(T), tau_c0(T): the factors of the temperatures (those of T_used) */
    s.m.mu_factor = s.temp.mu_factor;
    s.m.yield_factor = s.temp.yield_factor;
  }
  const int n = s.m.grid.n, neq = rs_transient_neq(&s.m, s.temp.modes ? &s.temp.th : NULL);
  res->mu = s.m.par.friction.mu;
  res->dx = s.m.grid.dx;
  res->rtol = c->rtol > 0.0 ? c->rtol : rs_transient_auto_rtol(&s.m);
  s.y = calloc((size_t)neq, sizeof *s.y);
  s.yp = calloc((size_t)neq, sizeof *s.yp);
  s.slip = calloc((size_t)n * (size_t)s.m.lay.ncomp, sizeof *s.slip);
  s.tauc = calloc((size_t)n, sizeof *s.tauc);
  s.mu = calloc((size_t)n, sizeof *s.mu);
  s.regime = calloc((size_t)n, sizeof *s.regime);
  if (!s.y || !s.yp || !s.slip || !s.tauc || !s.mu || !s.regime ||
      rs_work_create(&s.w, &s.m) != RS_OK) {
    free(y_chosen);
    free_state(&s);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for %d cells", n);
  }
  rs_model_rest_state(&s.m, s.y);
  if (y_chosen) memcpy(s.y, y_chosen, (size_t)neq * sizeof *s.y);
  free(y_chosen);
  res->cells[0] = s.m.grid.nx;
  res->cells[1] = s.m.grid.ny;
  char why_none[256] = "";
  if (estimate && !res->grid_chosen && !rs_errest_admissible(&s.m, why_none, sizeof why_none))
    snprintf(res->error_note, sizeof res->error_note, "%s", why_none);
  if (c->error_estimate && c->mode == RS_MODE_TRANSIENT && o->restart_path)
    snprintf(res->error_note, sizeof res->error_note,
             "no error estimate after --restart (its companion runs would start from rest)");
  s.collect = o->records;
  rs_record_diags comp[2] = {{0}};
  if (estimate && c->mode == RS_MODE_TRANSIENT && !*res->error_note) {
    const double t_comp = rs_wall_clock();
    status = transient_companions(c, o, &s.m, comp, &s.r21, &s.r32, msg);
    res->error_seconds = rs_wall_clock() - t_comp;
    if (status != RS_OK) {
      for (int k = 0; k < 2; k++) {
        free(comp[k].d);
        free(comp[k].t);
      }
      free_state(&s);
      return status;
    }
    s.comp[0] = &comp[0];
    s.comp[1] = &comp[1];
  }
  const char *path = o->append && o->restart_path ? o->restart_path
                     : o->output_path             ? o->output_path
                                                  : c->output_file;
  snprintf(res->file, sizeof res->file, "%s", path);
  /* Twin-disc rig mode: the circumferential memory and the per-step results. */
  rs_rig_run rig_run, *rig = NULL;
  rs_output_rig rig_spec = {0};
  if (o->append && (!o->restart_path || c->mode != RS_MODE_TRANSIENT || o->no_output)) {
    free_state(&s);
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "--append continues a transient run in its file: give --restart OLD.nc "
                      "and simulation.mode: transient");
  }
  if (c->rig.on) {
    if (o->restart_path) {
      free_state(&s);
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--restart %s: a twin_disc: run cannot be restarted (the plastic state "
                        "around the discs is not stored in the output file); run it whole",
                        o->restart_path);
    }
    status = rs_rig_run_create(&rig_run, c, &s.m, res, msg);
    if (status != RS_OK) {
      free_state(&s);
      rs_run_result_free(res);
      return status;
    }
    if (s.temp.modes && (status = rs_rig_run_heat(&rig_run, &s.temp, msg)) != RS_OK) {
      rs_rig_run_free(&rig_run);
      free_state(&s);
      rs_run_result_free(res);
      return status;
    }
    rig = &rig_run;
    s.m.memory = &rig->mem;
    rig_spec = rs_rig_run_output(rig);
  }
  double t0 = 0.0;
  char *history = NULL; /* the history attribute, naming the restart file */
  if (o->restart_path) {
    status = read_restart(&s, o, path, &t0, msg);
    if (status == RS_OK) status = restart_history(o, c, t0, &history, msg);
    if (status != RS_OK) {
      free_state(&s);
      return status;
    }
  }
  /* The yield limit is infinite without plasticity: not written then. A transient file
   * always holds the state a restart needs (px, upl, ustar; the creepage is a scalar),
   * whatever output.fields asks for (twin-disc runs cannot be restarted). */
  const unsigned asked = c->has_plasticity ? c->fields : (c->fields & ~(unsigned)RS_FIELD_TAUC);
  const unsigned state = RS_FIELD_PX | RS_FIELD_UPL | RS_FIELD_USTAR;
  const unsigned fields =
      (c->mode == RS_MODE_TRANSIENT && !rig ? asked | state : asked) |
      (rs_friction_varies(&c->friction) || c->mu_table.n ? (unsigned)RS_FIELD_MU : 0u) |
      (c->temperature.on ? (unsigned)RS_FIELD_TEMPERATURE : 0u);
  rs_output_spec spec = {.path = path,
                         .title = c->title ? c->title : "",
                         .case_text = c->yaml_text ? c->yaml_text : "",
                         .history = history      ? history
                                    : o->history ? o->history
                                                 : "",
                         .patch = o->params ? o->patch : NULL,
                         .dimension = s.m.par.dimension,
                         .nx = (size_t)s.m.grid.nx,
                         .x = s.m.grid.x,
                         .ny = (size_t)s.m.grid.ny,
                         .y = s.m.grid.y,
                         .fields = fields,
                         .requested_fields = asked | (fields & RS_FIELD_MU),
                         .rig = rig ? &rig_spec : NULL,
                         .hertz_a = s.m.par.gap_at ? 0.0 : s.m.hertz_a, /* not Hertzian */
                         .hertz_b = s.m.hertz_b,
                         .hertz_load = s.m.normal_load,
                         .rtol = c->mode == RS_MODE_TRANSIENT ? res->rtol : 0.0,
                         .error_estimate = estimate,
                         .grid_chosen = res->grid_chosen,
                         .temperature_modes = s.temp.modes ? 2 * (s.temp.th.ker.nmodes + 1) : 0};
  if (o->no_output)
    status = RS_OK;
  else if (o->append)
    status = rs_output_open_append(&s.out, path, (size_t)s.m.grid.nx, s.m.grid.x,
                                   (size_t)s.m.grid.ny, s.m.grid.y, fields, history, msg);
  else
    status = rs_output_create(&s.out, &spec, msg);
  if (status == RS_OK && s.out && rs_output_backup(s.out))
    snprintf(res->backup, sizeof res->backup, "%s", rs_output_backup(s.out));
  free(history);
  s.final = o->final_fields && o->final_fields->n == n ? o->final_fields : NULL;
  if (status != RS_OK) {
    if (rig) rs_rig_run_free(rig);
    free_state(&s);
    return status;
  }

  /* Initial state: rest (no traction, fresh material), steady rolling, or the restart
   * file's last record (already in s.y; in steady mode, Newton's start). */
  if (c->mode == RS_MODE_STEADY || (!o->restart_path && c->initial_state == RS_START_STEADY)) {
    rs_steady *st = NULL;
    status = rs_steady_create(&st, &s.m, s.ctx, msg);
    if (status == RS_OK) status = rs_steady_solve(st, 0.0, s.y, &res->stats, msg);
    if (status == RS_OK) /* mu(T), tau_c0(T): the coupled steady state */
      status = rs_temperature_couple(&s.temp, &s.m, &s.w, st, s.y, &res->stats, msg);
    rs_steady_free(st);
  }
  if (status == RS_OK && estimate && !res->grid_chosen && !*res->error_note)
    status = estimate_steady(&s, res, msg);
  /* Rates at t0: zero in steady rolling at constant inputs, else consistent
   * (they set the regimes of the first record and start IDA). A restart recomputes them
   * from the stored state: the file holds no rates. */
  if (status == RS_OK && c->mode == RS_MODE_TRANSIENT) {
    rs_inputs in;
    rs_model_inputs_at(&s.m, t0, &in);
    if (o->restart_path || c->initial_state != RS_START_STEADY) /* mu(T), tau_c0(T) */
      rs_temperature_run_state_factors(&s.temp, &s.m, &in, s.y);
    status = rs_model_consistent_rates(&s.m, &s.w, &in, s.y, s.yp, msg);
    /* the modes: steady ones from a steady start, else those read by a restart or rest (0),
     * with their rates */
    if (status == RS_OK && !o->restart_path && c->initial_state == RS_START_STEADY)
      status = rs_temperature_run_steady_modes(&s.temp, &s.m, &s.w, &in, s.y, s.yp, msg);
    else if (status == RS_OK)
      status = rs_temperature_run_rates(&s.temp, &s.m, &s.w, &in, s.y, s.yp, msg);
  }
  if (status == RS_OK) {
    /* Appending: the file's last record already holds this state. */
    rs_output *file = s.out;
    if (o->append) s.out = NULL;
    status = write_record(&s, t0, &res->final, msg);
    s.written++;
    s.out = file;
    res->records = status == RS_OK && !o->append;
    res->time = t0;
  }
  if (status == RS_OK && !accuracy_reached)
    status = rs_msg_set(msg, RS_ERR_SOLVER,
                        "grid.accuracy %g not reached: the estimated error on the finest grid "
                        "allowed (%d cells, cap %ld) is %.3g (in mu F_n; M_z in mu F_n a); the "
                        "file holds that grid's result",
                        c->accuracy, s.m.grid.n,
                        s.m.grid.ny > 1 ? RS_ACCURACY_MAX_CELLS_3D : RS_ACCURACY_MAX_CELLS_2D,
                        rs_errest_worst(&s.m, &res->final));
  if (status == RS_OK && c->mode == RS_MODE_TRANSIENT) {
    if (rig) rig->out = s.out;
    status = run_transient(&s, o, res, t0, started, rig, msg);
  }

  char why[RS_FINAL_STATUS_LEN];
  rs_final_status(status, msg, why);
  rs_msg tmp;
  res->file_records = rs_output_records(s.out);
  int close_status;
  if (status == RS_ERR_OUTPUT) {
    close_status = rs_output_abandon(s.out, why, &tmp);
  } else {
    if (s.out) rs_output_set_status(s.out, why, &tmp);
    close_status = rs_output_close(s.out, status == RS_OK ? msg : &tmp);
  }
  if (status == RS_OK) status = close_status;
  res->wall_seconds = rs_wall_clock() - started;
  if (rig) rs_rig_run_free(rig);
  for (int k = 0; k < 2; k++) {
    free(comp[k].d);
    free(comp[k].t);
  }
  free_state(&s);
  return status;
}

/* rollsim check, 3D: Hertz, the grid and Kalker's linear-theory forces at t = 0. */
static int print_derived_3d(const rs_case *c, const rs_model *m, FILE *out, rs_msg *msg)
{
  int in_contact = 0;
  double fn = 0.0, pmax = 0.0;
  for (int i = 0; i < m->grid.n; i++) {
    in_contact += m->pn[i] > 0.0;
    fn += m->pn[i] * m->grid.area;
    pmax = fmax(pmax, m->pn[i]);
  }
  rs_hertz_ellipse hz;
  int status = rs_hertz3d(fn, 0.5 / c->radius, 0.5 / c->radius_y, c->shear_modulus,
                          c->poisson_ratio, &hz, msg);
  if (status != RS_OK) return status;
  fprintf(out, "hertz.semi_axes: [%.6g, %.6g]  # mm, a (along x), b (along y)\n", m->hertz_a,
          m->hertz_b);
  fprintf(out, "hertz.peak_pressure: %.6g  # N/mm^2, p0 = 3 F_n/(2 pi a b)\n", m->hertz_p0);
  fprintf(out, "hertz.approach: %.6g  # mm\n", hz.approach);
  fprintf(out, "grid.cell_size: [%.6g, %.6g]  # mm (a/%.4g, b/%.4g)\n", m->grid.dx, m->grid.dy,
          m->hertz_a / m->grid.dx, m->hertz_b / m->grid.dy);
  fprintf(out, "grid.potential_contact: [[%.6g, %.6g], [%.6g, %.6g]]  # mm, x and y\n",
          m->grid.x_lo, m->grid.x_hi, m->grid.y_lo, m->grid.y_hi);
  fprintf(out, "normal.cells_in_contact: %d  # of %d\n", in_contact, m->grid.n);
  fprintf(out, "normal.total_force: %.9g  # N\n", fn);
  fprintf(out, "normal.max_pressure: %.6g  # N/mm^2\n", pmax);
  rs_inputs in;
  rs_model_inputs_at(m, 0.0, &in);
  rs_kalker k;
  rs_msg kmsg = {{0}};
  if (rs_kalker_coefficients(m->hertz_a / m->hertz_b, c->poisson_ratio, &k, &kmsg) == RS_OK) {
    double fx, fy, mz;
    rs_kalker_forces(&k, c->shear_modulus, m->hertz_a, m->hertz_b, in.creepage, in.lateral_creepage,
                     in.spin, &fx, &fy, &mz);
    fx += 0.0; /* -0 prints as 0 */
    fy += 0.0;
    mz += 0.0;
    if (isnan(k.c33))
      fprintf(out,
              "kalker.coefficients: [%.5g, %.5g, %.5g, null]  # C11, C22, C23, C33 at a/b = %.4g, "
              "nu = %g (C33 tabulated for a <= b only)\n",
              k.c11, k.c22, k.c23, m->hertz_a / m->hertz_b, c->poisson_ratio);
    else
      fprintf(out,
              "kalker.coefficients: [%.5g, %.5g, %.5g, %.5g]  # C11, C22, C23, C33 at a/b = %.4g, "
              "nu = %g\n",
              k.c11, k.c22, k.c23, k.c33, m->hertz_a / m->hertz_b, c->poisson_ratio);
    fprintf(out,
            "kalker.linear_forces: [%.6g, %.6g]  # N, F_x and F_y of the linear theory at t = 0 "
            "(|F| <= mu F_n = %.6g N caps the real ones)\n",
            fx, fy, m->par.friction.mu * fn);
    if (isnan(mz))
      fprintf(out,
              "kalker.linear_moment: null  # N mm, M_z needs C33, tabulated for a <= b only\n");
    else
      fprintf(out, "kalker.linear_moment: %.6g  # N mm, M_z of the linear theory at t = 0\n", mz);
  } else {
    fprintf(out, "kalker.coefficients: null  # %s\n", kmsg.text);
  }
  fprintf(out, "solver.r_steady: %.6g  # N s/mm^3, semismooth scaling at t = 0\n",
          in.velocity > 0.0 ? rs_model_scaling(m, &in, 0.0) : 0.0);
  const double rolled = rs_history_integral_abs(&c->velocity, 0.0, c->end_time);
  if (rolled > 0.0 && c->mode == RS_MODE_TRANSIENT)
    fprintf(out, "simulation.rolled_distance_total: %.6g  # mm (%.4g contact lengths)\n", rolled,
            rolled / (2.0 * m->hertz_a));
  return RS_OK;
}

int rs_run_print_derived(const rs_case *c, FILE *out, rs_msg *msg)
{
  rs_model m;
  int status = rs_model_from_case(&m, c, msg);
  if (status != RS_OK) return status;
  int in_contact = 0;
  double fn = 0.0;
  for (int i = 0; i < m.grid.n; i++) {
    in_contact += m.pn[i] > 0.0;
    fn += m.pn[i] * m.grid.area;
  }
  fprintf(out, "# derived\n");
  if (m.lay.ncomp == 2) {
    status = print_derived_3d(c, &m, out, msg);
    if (status == RS_OK) status = rs_temperature_print_derived(c, &m, out, msg);
    rs_model_free(&m);
    return status;
  }
  fprintf(out, "hertz.half_width: %.6g  # mm, a = sqrt(4 q R (1-nu)/(pi G))\n", m.hertz_a);
  fprintf(out, "hertz.peak_pressure: %.6g  # N/mm^2, p0 = 2 q/(pi a)\n", m.hertz_p0);
  fprintf(out, "grid.dx: %.6g  # mm (a/%.4g)\n", m.grid.dx, m.hertz_a / m.grid.dx);
  fprintf(out, "grid.potential_contact: [%.6g, %.6g]  # mm\n", m.grid.x_lo, m.grid.x_hi);
  fprintf(out, "normal.cells_in_contact: %d\n", in_contact);
  fprintf(out, "normal.total_force: %.9g  # N/mm\n", fn);
  fprintf(out, "normal.max_pressure: %.6g  # N/mm^2\n", m.pn[m.grid.n / 2]);
  fprintf(out, "layer.flexibility: %.6g  # mm/(N/mm^2), h3/G3\n", m.layer_flex);
  rs_inputs in;
  rs_model_inputs_at(&m, 0.0, &in);
  const double V = in.velocity;
  fprintf(out, "solver.r_steady: %.6g  # N s/mm^3, semismooth scaling at t = 0\n",
          V > 0.0 ? rs_model_scaling(&m, &in, 0.0) : 0.0);
  const double rolled = rs_history_integral_abs(&c->velocity, 0.0, c->end_time);
  if (rolled > 0.0 && c->mode == RS_MODE_TRANSIENT)
    fprintf(out, "simulation.rolled_distance_total: %.6g  # mm (%.4g contact lengths)\n", rolled,
            rolled / (2.0 * m.hertz_a));
  if (c->rig.on)
    fprintf(out,
            "twin_disc.revolution_time: %.6g  # s, 2 pi R1/V (%.4g cells rolled per revolution)\n"
            "twin_disc.line_load: %.6g  # N/mm, normal_force/width\n",
            c->rig.revolution_time, c->rig.revolution_time * V / m.grid.dx,
            c->rig.normal_force / c->rig.width);
  status = rs_temperature_print_derived(c, &m, out, msg);
  rs_model_free(&m);
  return status;
}
