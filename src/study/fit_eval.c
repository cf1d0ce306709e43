/* The model of a fit evaluated on its data set (study/fit_internal.h): the data rows grouped
 * into continuation lines, each solved in memory as rollsim sweep solves a line
 * (study/sweep_lines.h), or a twin-disc protocol run once; and the finite-difference step of
 * a parameter. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case.h"
#include "study/fit.h"
#include "study/fit_internal.h"
#include "study/run.h"
#include "study/sweep_lines.h"

#define FIT_RTOL 1e-6

/* Relative forward-difference step in p: about the square root of the accuracy of a
 * steady solution (Newton converged to ~1e-12 relative), times the parameter's scale. */
#define FD_STEP 1e-6

/* Group the data rows into continuation lines: consecutive rows that agree in every
 * input column but the last one. */
static int make_lines(rs_fit_eval *e, rs_msg *msg)
{
  const rs_fit_spec *f = e->f;
  e->key_col = -1;
  for (int j = 0; j < f->ncols; j++)
    if (f->input_keys[j]) e->key_col = j;
  e->line_start = calloc(f->npoints + 1, sizeof *e->line_start);
  if (!e->line_start) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  e->nlines = 0;
  for (size_t i = 0; i < f->npoints; i++) {
    int same = i > 0;
    for (int j = 0; same && j < f->ncols; j++)
      if (f->input_keys[j] && j != e->key_col &&
          f->table[i * (size_t)f->ncols + (size_t)j] !=
              f->table[(i - 1) * (size_t)f->ncols + (size_t)j])
        same = 0;
    if (!same) e->line_start[e->nlines++] = i;
  }
  e->line_start[e->nlines] = f->npoints;
  return RS_OK;
}

int rs_fit_eval_init(rs_fit_eval *e, const rs_fit_spec *f, const rs_case *base, rs_msg *msg)
{
  memset(e, 0, sizeof *e);
  e->f = f;
  e->base = base;
  e->ov = calloc((size_t)(1 + f->nparams + f->ncols), sizeof *e->ov);
  /* Forward differences need the time integration's error far below a parameter step's
   * effect: a transient case's solver.rtol auto (3D: up to 3e-3) becomes FIT_RTOL. */
  e->rtol_key =
      base->mode == RS_MODE_TRANSIENT && base->rtol == 0.0 ? rs_case_key_index("solver.rtol") : -1;
  e->param_key = calloc((size_t)f->nparams, sizeof *e->param_key);
  e->input_key = calloc((size_t)f->ncols, sizeof *e->input_key);
  e->xs = calloc(f->npoints, sizeof *e->xs);
  e->diag = calloc(f->npoints, sizeof *e->diag);
  e->ok = calloc(f->npoints, sizeof *e->ok);
  if (!e->ov || !e->param_key || !e->input_key || !e->xs || !e->diag || !e->ok)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (int k = 0; k < f->nparams; k++) e->param_key[k] = rs_case_key_index(f->params[k].key);
  for (int j = 0; j < f->ncols; j++)
    e->input_key[j] = f->input_keys && f->input_keys[j] ? rs_case_key_index(f->input_keys[j]) : -1;
  if (f->kind != RS_FIT_STEADY) return RS_OK;
  int status = make_lines(e, msg);
  for (size_t i = 0; i < f->npoints; i++)
    e->xs[i] = f->table[i * (size_t)f->ncols + (size_t)e->key_col];
  return status;
}

void rs_fit_eval_free(rs_fit_eval *e)
{
  free(e->ov);
  free(e->param_key);
  free(e->input_key);
  free(e->xs);
  free(e->diag);
  free(e->ok);
  free(e->line_start);
  memset(e, 0, sizeof *e);
}

/* The simulated output of a point. */
static double output_of(const rs_fit_spec *f, const rs_diag *d)
{
  return !strcmp(f->measured, "Fx") ? d->Fx : d->Fx / d->Fn;
}

/* Protocol step (0-based) of a data row of a twin-disc fit. */
static size_t rig_step_of(const rs_fit_spec *f, const rs_case *c, size_t row)
{
  int col = 0;
  for (int j = 0; j < f->ncols; j++)
    if (f->roles[j] == RS_FIT_COL_INPUT) col = j;
  const double v = f->table[row * (size_t)f->ncols + (size_t)col];
  if (f->kind == RS_FIT_RIG_STEP || f->kind == RS_FIT_RIG_REV) return (size_t)v - 1;
  for (size_t k = 0; k < c->rig.nsteps; k++)
    if (c->rig.steps[k].slip_start == v && c->rig.steps[k].slip_end == v) return k;
  return 0; /* not reached: rs_fit_load checked the rows */
}

static int store_point(void *ctx, size_t j, int status, const rs_diag *d, long newton,
                       const char *why)
{
  rs_fit_eval *e = ctx;
  (void)newton;
  (void)why;
  e->ok[e->line0 + j] = status == RS_OK;
  e->diag[e->line0 + j] = *d;
  return RS_OK;
}

int rs_fit_eval_at(rs_fit_eval *e, const double *p, double *sim, rs_msg *msg)
{
  const rs_fit_spec *f = e->f;
  int n = 0;
  for (int k = 0; k < f->nparams; k++) e->ov[n++] = (rs_case_override){e->param_key[k], p[k]};
  if (e->rtol_key >= 0) e->ov[n++] = (rs_case_override){e->rtol_key, FIT_RTOL};
  int status = RS_OK;
  if (f->kind == RS_FIT_STEADY) {
    for (size_t l = 0; l < e->nlines && status == RS_OK; l++) {
      const size_t i0 = e->line_start[l], len = e->line_start[l + 1] - i0;
      int nl = n;
      for (int j = 0; j < f->ncols; j++)
        if (f->input_keys[j] && j != e->key_col)
          e->ov[nl++] =
              (rs_case_override){e->input_key[j], f->table[i0 * (size_t)f->ncols + (size_t)j]};
      e->line0 = i0;
      const rs_sweep_line line = {.base = e->base,
                                  .fixed = e->ov,
                                  .nfixed = nl,
                                  .key = e->input_key[e->key_col],
                                  .values = e->xs + i0,
                                  .n = len,
                                  .first_point = -1,
                                  .point_done = store_point,
                                  .ctx = e};
      status = rs_sweep_line_eval(&line, msg);
      for (size_t i = i0; status == RS_OK && i < i0 + len; i++) {
        if (!e->ok[i])
          status = rs_msg_set(msg, RS_ERR_SOLVER, "data row %zu did not converge", i + 1);
        else
          sim[i] = output_of(f, &e->diag[i]);
      }
    }
  } else {
    rs_case c;
    status = rs_case_derive(e->base, e->ov, n, &c, msg);
    if (status == RS_OK) {
      const rs_run_opts po = {.no_output = 1};
      rs_run_result rr;
      status = rs_run(&c, &po, &rr, msg);
      for (size_t i = 0; status == RS_OK && i < f->npoints; i++) {
        const size_t k = rig_step_of(f, &c, i);
        const int rev = f->kind == RS_FIT_RIG_REV;
        sim[i] = rev ? (k < rr.rig_nrev ? rr.rig_rev_mu[k] : NAN)
                     : (k < rr.rig_nsteps ? rr.rig_step_mu[k] : NAN);
        if (!isfinite(sim[i]))
          status = rs_msg_set(msg, RS_ERR_SOLVER, "%s %zu has no traction coefficient",
                              rev ? "revolution" : "protocol step", k + 1);
      }
      rs_run_result_free(&rr);
      rs_case_free(&c);
    }
  }
  if (status != RS_OK) {
    char ps[512] = "";
    size_t len = 0;
    for (int k = 0; k < f->nparams && len < sizeof ps; k++)
      len += (size_t)snprintf(ps + len, sizeof ps - len, "%s%s = %.10g", k ? ", " : "",
                              f->params[k].key, p[k]);
    char inner[RS_MSG_LEN];
    snprintf(inner, sizeof inner, "%s", msg->text);
    rs_msg_set(msg, status, "at %s: %s", ps, inner);
  }
  e->evaluations++;
  return status;
}

/* Forward-difference step of parameter k at p (inside the bounds). */
double rs_fit_fd_step(const rs_fit_param *q, double p)
{
  double h = FD_STEP * fmax(fabs(p), 1e-3 * (q->hi - q->lo));
  if (p + h > q->hi) h = -h;
  return h;
}
