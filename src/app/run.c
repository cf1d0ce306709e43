#define _POSIX_C_SOURCE 200809L
/* rs_run: one case end to end (see rollsim/run.h). Records go to the netCDF file
 * as they are computed; the status attribute tells a reader how the run ended. */
#include "rollsim/run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "rollsim/output.h"
#include "rollsim/restart.h"
#include "rollsim/rig.h"
#include "base/util.h"

typedef struct run_state {
  const rs_case *c;
  rs_model m;
  rs_work w;
  double *y, *yp, *slip, *tauc;
  signed char *regime;
  rs_output *out;
} run_state;

/* Twin-disc bookkeeping, updated after every accepted time step: the memory of the
 * state leaving the contact, and the time integrals of F_x/F_n and of the slip over
 * each revolution and each step's averaging window (trapezoidal between steps). */
typedef struct rig_state {
  const rs_case *c;
  const rs_model *m;
  rs_rig_memory mem;
  rs_output *out;
  rs_run_result *res;
  double *window_start, *slip_start, *slip_end, *time_start, *time_end; /* per step */
  size_t nrev, rev, step;          /* revolutions, current revolution, current step */
  double t_prev, mu_prev, slip_prev;
  double rev_mu, rev_slip, step_mu, step_slip; /* integrals so far */
  int started;
  rs_msg msg;
} rig_state;

static void rig_free(rig_state *r)
{
  rs_rig_memory_free(&r->mem);
  free(r->window_start);
  free(r->slip_start);
  free(r->slip_end);
  free(r->time_start);
  free(r->time_end);
}

static int rig_create(rig_state *r, const rs_case *c, const rs_model *m, rs_msg *msg)
{
  memset(r, 0, sizeof *r);
  r->c = c;
  r->m = m;
  const rs_twin_disc *rig = &c->rig;
  const double V = rs_history_eval(&m->velocity, 0.0), L = m->n * m->dx;
  const double two_pi = 2.0 * RS_PI;
  int status = rs_rig_memory_create(&r->mem, (two_pi * rig->radius_1 - L) / V,
                                    (two_pi * rig->radius_2 - L) / V, rig->recovery, msg);
  if (status != RS_OK) return status;
  const size_t ns = rig->nsteps;
  r->window_start = malloc(ns * sizeof(double));
  r->slip_start = malloc(ns * sizeof(double));
  r->slip_end = malloc(ns * sizeof(double));
  r->time_start = malloc(ns * sizeof(double));
  r->time_end = malloc(ns * sizeof(double));
  if (!r->window_start || !r->slip_start || !r->slip_end || !r->time_start || !r->time_end) {
    rig_free(r);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory (twin-disc protocol)");
  }
  double revs = 0.0;
  for (size_t j = 0; j < ns; j++) {
    r->time_start[j] = revs * rig->revolution_time;
    revs += rig->steps[j].revolutions;
    r->time_end[j] = j + 1 == ns ? c->end_time : revs * rig->revolution_time;
    r->window_start[j] =
        r->time_end[j] - rig->average_window * (r->time_end[j] - r->time_start[j]);
    r->slip_start[j] = rig->steps[j].slip_start;
    r->slip_end[j] = rig->steps[j].slip_end;
  }
  r->nrev = (size_t)ceil(revs - 1e-9);
  return RS_OK;
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

static int rig_step_hook(void *ctx, double t, const double *y)
{
  rig_state *r = ctx;
  const rs_model *m = r->m;
  const int n = m->n;
  int status = rs_rig_memory_record(&r->mem, t, y[n], y[2 * n], &r->msg);
  if (status != RS_OK) return status;
  double fx = 0.0;
  for (int i = 0; i < n; i++) fx += y[i] * m->dx;
  /* The slip jumps where a held step starts: the segment ending at t takes its left
   * limit, the next one starts from the value at t. */
  const double mu = fx / m->normal_load, slip_next = -rs_model_creepage(m, t, y);
  const double slip = r->started ? -rs_model_creepage(m, nextafter(t, -INFINITY), y) : slip_next;
  if (!r->started) {
    r->started = 1;
  } else {
    const double t0 = r->t_prev, T = r->c->rig.revolution_time, t_end = r->c->end_time;
    while (r->rev < r->nrev) {
      const double a = r->rev * T, b = fmin((r->rev + 1) * T, t_end);
      r->rev_mu += overlap_integral(t0, r->mu_prev, t, mu, a, b);
      r->rev_slip += overlap_integral(t0, r->slip_prev, t, slip, a, b);
      if (t < b * (1.0 - 1e-12)) break;
      if (r->out &&
          (status = rs_output_put_revolution(r->out, r->rev, r->rev_mu / (b - a),
                                             r->rev_slip / (b - a), &r->msg)) != RS_OK)
        return status;
      r->res->rig_revolutions = (double)(r->rev + 1);
      r->rev++;
      r->rev_mu = r->rev_slip = 0.0;
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
  return RS_OK;
}

void rs_run_result_free(rs_run_result *res)
{
  free(res->rig_step_mu);
  free(res->rig_step_slip);
  res->rig_step_mu = res->rig_step_slip = NULL;
  res->rig_nsteps = 0;
}

static int write_record(run_state *s, double t, rs_diag *d, rs_msg *msg)
{
  const int n = s->m.n;
  rs_model_diagnostics(&s->m, &s->w, t, s->y, s->yp, d, s->slip, s->tauc, s->regime);
  rs_record rec = {.time = t,
                   .Fx = d->Fx,
                   .Fn = d->Fn,
                   .creepage = d->creepage,
                   .velocity = d->velocity,
                   .n_exterior = d->count[RS_EXTERIOR],
                   .n_adhesion = d->count[RS_ADHESION],
                   .n_slip = d->count[RS_SLIP],
                   .n_plastic = d->count[RS_PLASTIC],
                   .frictional_power = d->frictional_power,
                   .plastic_power = d->plastic_power,
                   .elastic_energy = d->elastic_energy,
                   .px = s->y,
                   .pn = s->w.pn,
                   .slip = s->slip,
                   .upl = s->y + n,
                   .ustar = s->y + 2 * n,
                   .tauc = s->tauc,
                   .regime = s->regime};
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
  free(s->regime);
  if (s->m.x) rs_model_free(&s->m);
}

/* Solver loop for transient mode from t0 (0, or the time of a restart file's last
 * record): one record per output interval k*dt after t0, the last time always stored. */
static int run_transient(run_state *s, const rs_run_opts *o, rs_run_result *res, double t0,
                         double started, rig_state *rig, rs_msg *msg)
{
  const rs_case *c = s->c;
  rs_transient_opts topts = {.rtol = c->rtol,
                             .atol = c->atol,
                             .max_order = c->max_order,
                             .max_steps = c->max_steps,
                             .max_newton = 10,
                             .t_stop = fmin(rs_model_next_breakpoint(&s->m, t0), c->end_time),
                             .interrupt = o->interrupt_flag};
  if (rig) {
    topts.step_hook = rig_step_hook;
    topts.hook_ctx = rig;
    topts.max_step = rs_rig_memory_max_step(&rig->mem);
    int status = rig_step_hook(rig, t0, s->y); /* the state at the start */
    if (status != RS_OK) return rs_msg_set(msg, status, "%s", rig->msg.text);
  }
  rs_transient *tr = NULL;
  int status = rs_transient_create(&tr, &s->m, t0, s->y, s->yp, &topts, msg);
  if (status != RS_OK) return status;
  /* Output times k*dt (the end time always stored), the same grid whether the run
   * started at 0 or was restarted at t0, so that the records of a restarted run fall on
   * those of the uninterrupted one; IDA stops at every breakpoint of an input history
   * and restarts from consistent rates there. */
  const double t_end = c->end_time;
  const long nrec = (long)ceil(t_end / c->output_interval - 1e-9);
  double t = t0, bp = topts.t_stop;
  long k = (long)floor(t0 / c->output_interval + 1e-9) + 1; /* first output time after t0 */
  while (status == RS_OK && k <= nrec) {
    const double t_out = k == nrec ? t_end : k * c->output_interval;
    /* A breakpoint that falls on an output time up to rounding is that output time
     * (else IDA would be asked to restart a rounding error away from its stop). */
    if (fabs(bp - t_out) <= 1e-9 * c->output_interval) bp = t_out;
    const double target = fmin(t_out, bp);
    status = rs_transient_advance(tr, target, s->y, s->yp, msg);
    if (status != RS_OK && rig && rig->msg.text[0]) rs_msg_set(msg, status, "%s", rig->msg.text);
    if (status != RS_OK) {
      rs_transient_get_stats(tr, &res->stats); /* the summary counts the failed attempt */
      break;
    }
    t = target;
    if (t == t_out) {
      rs_diag d;
      status = write_record(s, t, &d, msg);
      if (status == RS_OK) { /* the summary describes the last record in the file */
        res->final = d;
        res->time = t;
        res->records++;
      }
      k++;
    }
    if (status == RS_OK && t == bp && t < t_end) {
      bp = fmin(rs_model_next_breakpoint(&s->m, t), t_end);
      status = rs_model_project_state(&s->m, &s->w, t, s->y, msg);
      if (status == RS_OK) status = rs_model_consistent_rates(&s->m, &s->w, t, s->y, s->yp, msg);
      if (status == RS_OK) status = rs_transient_restart(tr, t, s->y, s->yp, bp, msg);
    }
    rs_transient_get_stats(tr, &res->stats);
    if (o->progress) progress(t, t_end, res->stats.steps, started);
    if (status == RS_OK && o->interrupt_flag && *o->interrupt_flag)
      status = rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted at t = %.6g s", t);
  }
  if (o->progress) fputc('\n', stderr);
  rs_transient_free(tr);
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
  if (!o->no_output && stat(o->restart_path, &st_old) == 0 && stat(out_path, &st_new) == 0 &&
      st_old.st_dev == st_new.st_dev && st_old.st_ino == st_new.st_ino)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "--restart %s: it is also the output file; choose another one with -o",
                      o->restart_path);
  int status = rs_restart_read(o->restart_path, (size_t)s->m.n, s->m.x, t0, s->y,
                               s->m.force_control ? s->y + 3 * s->m.n : NULL, msg);
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

int rs_run(const rs_case *c, const rs_run_opts *o, rs_run_result *res, rs_msg *msg)
{
  const double started = rs_wall_clock();
  memset(res, 0, sizeof *res);
  run_state s = {.c = c};
  int status = rs_model_create(&s.m, c, msg);
  if (status != RS_OK) return status;
  const int n = s.m.n;
  res->mu = s.m.mu;
  res->dx = s.m.dx;
  s.y = calloc((size_t)s.m.neq, sizeof *s.y);
  s.yp = calloc((size_t)s.m.neq, sizeof *s.yp);
  s.slip = calloc((size_t)n, sizeof *s.slip);
  s.tauc = calloc((size_t)n, sizeof *s.tauc);
  s.regime = calloc((size_t)n, sizeof *s.regime);
  if (!s.y || !s.yp || !s.slip || !s.tauc || !s.regime || rs_work_create(&s.w, n) != RS_OK) {
    free_state(&s);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for %d cells", n);
  }
  const char *path = o->output_path ? o->output_path : c->output_file;
  snprintf(res->file, sizeof res->file, "%s", path);
  /* Twin-disc rig mode: the circumferential memory and the per-step results. */
  rig_state rig_mem, *rig = NULL;
  rs_output_rig rig_spec = {0};
  if (c->rig.on) {
    if (o->restart_path) {
      free_state(&s);
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--restart %s: a twin_disc: run cannot be restarted (the plastic state "
                        "around the discs is not stored in the output file); run it whole",
                        o->restart_path);
    }
    status = rig_create(&rig_mem, c, &s.m, msg);
    if (status != RS_OK) {
      free_state(&s);
      return status;
    }
    rig = &rig_mem;
    rig->res = res;
    res->rig_nsteps = c->rig.nsteps;
    res->rig_step_mu = malloc(c->rig.nsteps * sizeof(double));
    res->rig_step_slip = malloc(c->rig.nsteps * sizeof(double));
    if (!res->rig_step_mu || !res->rig_step_slip) {
      rig_free(rig);
      free_state(&s);
      rs_run_result_free(res);
      return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    }
    for (size_t j = 0; j < c->rig.nsteps; j++) res->rig_step_mu[j] = res->rig_step_slip[j] = NAN;
    s.m.memory = &rig->mem;
    rig_spec = (rs_output_rig){.nsteps = c->rig.nsteps,
                               .nrevolutions = rig->nrev,
                               .slip_start = rig->slip_start,
                               .slip_end = rig->slip_end,
                               .time_start = rig->time_start,
                               .time_end = rig->time_end,
                               .window_start = rig->window_start,
                               .revolution_time = c->rig.revolution_time,
                               .recovery = c->rig.recovery};
  }
  double t0 = 0.0;
  char *history = NULL; /* the history attribute, naming the restart file */
  if (o->restart_path) {
    status = read_restart(&s, o, path, &t0, msg);
    const char *base = o->history ? o->history : "";
    const size_t len = strlen(base) + strlen(o->restart_path) + 96;
    if (status == RS_OK && !(history = malloc(len)))
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    if (status != RS_OK) {
      if (rig) rig_free(rig);
      free_state(&s);
      return status;
    }
    if (c->mode == RS_MODE_STEADY)
      snprintf(history, len, "%s%s(steady solve started from the last record of %s)", base,
               *base ? " " : "", o->restart_path);
    else
      snprintf(history, len, "%s%s(restart from %s at t = %.9g s)", base, *base ? " " : "",
               o->restart_path, t0);
  }
  /* The yield limit is infinite without plasticity: not written then. */
  const unsigned fields = c->has_plasticity ? c->fields : (c->fields & ~(unsigned)RS_FIELD_TAUC);
  rs_output_spec spec = {.path = path,
                         .title = c->title ? c->title : "",
                         .case_text = c->yaml_text ? c->yaml_text : "",
                         .history = history ? history : o->history ? o->history : "",
                         .dimension = c->dimension,
                         .nx = (size_t)n,
                         .x = s.m.x,
                         .fields = fields,
                         .rig = rig ? &rig_spec : NULL};
  status = o->no_output ? RS_OK : rs_output_create(&s.out, &spec, msg);
  free(history);
  if (status != RS_OK) {
    if (rig) rig_free(rig);
    free_state(&s);
    return status;
  }

  /* Initial state: rest (no traction, fresh material), steady rolling, or the restart
   * file's last record (already in s.y; in steady mode, Newton's start). */
  if (c->mode == RS_MODE_STEADY || (!o->restart_path && c->initial_state == RS_START_STEADY)) {
    rs_steady *st = NULL;
    status = rs_steady_create(&st, &s.m, msg);
    if (status == RS_OK) status = rs_steady_solve(st, 0.0, s.y, &res->stats, msg);
    rs_steady_free(st);
  }
  /* Rates at t0: zero in steady rolling at constant inputs, else consistent
   * (they set the regimes of the first record and start IDA). A restart recomputes them
   * from the stored state: the file holds no rates. */
  if (status == RS_OK && c->mode == RS_MODE_TRANSIENT)
    status = rs_model_consistent_rates(&s.m, &s.w, t0, s.y, s.yp, msg);
  if (status == RS_OK) {
    status = write_record(&s, t0, &res->final, msg);
    res->records = status == RS_OK;
    res->time = t0;
  }
  if (status == RS_OK && c->mode == RS_MODE_TRANSIENT) {
    if (rig) rig->out = s.out;
    status = run_transient(&s, o, res, t0, started, rig, msg);
  }

  char why[RS_MSG_LEN + 16];
  if (status == RS_OK)
    snprintf(why, sizeof why, "complete");
  else if (status == RS_ERR_INTERRUPTED)
    snprintf(why, sizeof why, "interrupted");
  else
    snprintf(why, sizeof why, "failed: %s", msg->text);
  rs_msg tmp;
  if (s.out && status != RS_ERR_OUTPUT) rs_output_set_status(s.out, why, &tmp);
  int close_status = rs_output_close(s.out, status == RS_OK ? msg : &tmp);
  if (status == RS_OK) status = close_status;
  res->wall_seconds = rs_wall_clock() - started;
  if (rig) rig_free(rig);
  free_state(&s);
  return status;
}

int rs_run_print_derived(const rs_case *c, FILE *out, rs_msg *msg)
{
  rs_model m;
  int status = rs_model_create(&m, c, msg);
  if (status != RS_OK) return status;
  int in_contact = 0;
  double fn = 0.0;
  for (int i = 0; i < m.n; i++) {
    in_contact += m.pn[i] > 0.0;
    fn += m.pn[i] * m.dx;
  }
  fprintf(out, "# derived\n");
  fprintf(out, "hertz.half_width: %.6g  # mm, a = sqrt(4 q R (1-nu)/(pi G))\n", m.hertz_a);
  fprintf(out, "hertz.peak_pressure: %.6g  # N/mm^2, p0 = 2 q/(pi a)\n", m.hertz_p0);
  fprintf(out, "grid.dx: %.6g  # mm (a/%.4g)\n", m.dx, m.hertz_a / m.dx);
  fprintf(out, "grid.potential_contact: [%.6g, %.6g]  # mm\n", m.x[0] - 0.5 * m.dx,
          m.x[m.n - 1] + 0.5 * m.dx);
  fprintf(out, "normal.cells_in_contact: %d\n", in_contact);
  fprintf(out, "normal.total_force: %.9g  # N/mm\n", fn);
  fprintf(out, "normal.max_pressure: %.6g  # N/mm^2\n", m.pn[m.n / 2]);
  fprintf(out, "layer.flexibility: %.6g  # mm/(N/mm^2), h3/G3\n", m.layer_flex);
  fprintf(out, "solver.r_steady: %.6g  # N s/mm^3, semismooth scaling at t = 0\n",
          rs_history_eval(&m.velocity, 0.0) > 0.0 ? rs_model_scaling(&m, 0.0, 0.0) : 0.0);
  const double V = rs_history_eval(&m.velocity, 0.0);
  if (V > 0.0)
    fprintf(out, "simulation.rolled_distance_total: %.6g  # mm (%.4g contact lengths)\n",
            V * c->end_time, V * c->end_time / (2.0 * m.hertz_a));
  if (c->rig.on)
    fprintf(out,
            "twin_disc.revolution_time: %.6g  # s, 2 pi R1/V (%.4g cells rolled per revolution)\n"
            "twin_disc.line_load: %.6g  # N/mm, normal_force/width\n",
            c->rig.revolution_time, c->rig.revolution_time * V / m.dx,
            c->rig.normal_force / c->rig.width);
  rs_model_free(&m);
  return RS_OK;
}
