/* rollsim fit (study/fit.h): bounded nonlinear least squares over case keys.
 *
 * Minimises |r|^2, r_i = w_i (simulated_i - measured_i), by MINPACK's Levenberg-
 * Marquardt (lmder of cminpack; More, "The Levenberg-Marquardt algorithm: implementation
 * and theory", 1978) in unbounded variables u with the bounds of MINUIT's transform
 * p = lo + (hi - lo)(1 + sin u)/2 (James, MINUIT reference manual, §1.3). The Jacobian is
 * ours: forward differences of whole data sets in p (dr/du = dr/dp (hi - lo) cos(u)/2),
 * one column per parameter (independent: under MPI the columns go to the ranks,
 * study/fit_columns.c). Every evaluation solves each continuation line of the data in
 * memory as rollsim sweep does (study/sweep_lines.h), or a twin-disc protocol once.
 *
 * At the optimum: covariance C = s^2 (J^T J)^-1 with J = dr/dp and s^2 = |r|^2/(m - n)
 * (weights are relative precisions), standard errors sqrt(C_kk), correlations; notes for
 * a parameter at a bound, without effect on the simulated values, or correlated with
 * another (|rho| > 0.95; not identifiable together when J^T J is singular). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cminpack.h>

#include "io/case.h"
#include "study/fit.h"
#include "study/run.h"
#include "study/fit_internal.h"
#include "study/sweep_lines.h"
#include "base/util.h"

/* Stopping tolerances of lmder (relative reduction of |r|^2, relative step, cosine of
 * the residual with the Jacobian's columns). */
#define FIT_FTOL     1e-8
#define FIT_XTOL     1e-8
#define FIT_GTOL     1e-10
/* Correlations above this are reported (notes). */
#define FIT_RHO_NOTE 0.95

static double to_p(const rs_fit_param *q, double u)
{
  return q->lo + (q->hi - q->lo) * 0.5 * (1.0 + sin(u));
}

static double to_u(const rs_fit_param *q, double p)
{
  double s = 2.0 * (p - q->lo) / (q->hi - q->lo) - 1.0;
  s = s > 1 ? 1 : s < -1 ? -1 : s;
  return asin(s);
}

/* ---- the least-squares problem as lmder sees it ---- */

typedef struct fit_run {
  rs_fit_eval e;
  rs_fit_columns *cols; /* the Jacobian's columns (serial or over MPI ranks) */
  const rs_fit_spec *f;
  const rs_fit_opts *o;
  const rs_case *base;
  double *p, *sim, *w, *meas; /* scratch p, simulated, weights, measured */
  double *best_u, *best_p, *best_sim;
  double best_norm;
  int have_best;
  double started;
  int status;
  rs_msg msg;
  int written;
  char backup[1040];
  const char *path;
  const double *start; /* the file's start values: the case's, or the resumed file's */
  const char *history; /* the file's history attribute */
} fit_run;

static double residuals(const fit_run *r, const double *sim, double *fvec)
{
  double s = 0;
  for (size_t i = 0; i < r->f->npoints; i++) {
    fvec[i] = r->w[i] * (sim[i] - r->meas[i]);
    s += fvec[i] * fvec[i];
  }
  return sqrt(s);
}

static int write_file(fit_run *r, const char *status, const double *fitted, const double *se,
                      const double *cov, const double *sim, double norm, const char *notes,
                      rs_msg *msg)
{
  const rs_fit_output out = {.path = r->path,
                             .title = r->base->title,
                             .case_text = r->base->yaml_text,
                             .history = r->history,
                             .status = status,
                             .notes = notes,
                             .spec = r->f,
                             .start = r->start,
                             .fitted = fitted,
                             .std_error = se,
                             .covariance = cov,
                             .simulated = sim,
                             .residual_norm = norm,
                             .evaluations = r->e.evaluations,
                             .keep_old = !r->written,
                             .dimension = r->base->dimension};
  const int s = rs_fit_output_write(&out, r->backup, sizeof r->backup, msg);
  if (s == RS_OK) r->written = 1;
  return s;
}

/* A new best point: kept, and the file rewritten with it (status "running"). */
static int improve(fit_run *r, const double *u, const double *sim, double norm)
{
  const int n = r->f->nparams;
  r->have_best = 1;
  r->best_norm = norm;
  memcpy(r->best_u, u, (size_t)n * sizeof *u);
  for (int k = 0; k < n; k++) r->best_p[k] = to_p(&r->f->params[k], u[k]);
  memcpy(r->best_sim, sim, r->f->npoints * sizeof *sim);
  return write_file(r, "running", r->best_p, NULL, NULL, r->best_sim, norm, "", &r->msg);
}

static void progress(const fit_run *r, double norm)
{
  if (!r->o->progress) return;
  fprintf(stderr, "\rfit: %ld evaluations, residual %.6g (best %.6g), %.1f s ", r->e.evaluations,
          norm, r->best_norm, rs_wall_clock() - r->started);
  fflush(stderr);
}

static int lm_function(void *ctx, int m, int n, const double *u, double *fvec, double *fjac,
                       int ldfjac, int iflag)
{
  fit_run *r = ctx;
  (void)m;
  if (r->o->interrupt_flag && *r->o->interrupt_flag) {
    r->status = rs_msg_set(&r->msg, RS_ERR_INTERRUPTED, "interrupted");
    return -1;
  }
  if (iflag == 0) return 0;
  if (iflag == 1) {
    for (int k = 0; k < n; k++) r->p[k] = to_p(&r->f->params[k], u[k]);
    if ((r->status = rs_fit_eval_at(&r->e, r->p, r->sim, &r->msg)) != RS_OK) return -1;
    const double norm = residuals(r, r->sim, fvec);
    if ((!r->have_best || norm < r->best_norm) &&
        (r->status = improve(r, u, r->sim, norm)) != RS_OK)
      return -1;
    progress(r, norm);
    return 0;
  }
  /* iflag 2: the Jacobian at u (lmder's current point, the best so far, whose
   * simulated values are kept; otherwise evaluated here). */
  const double *sim0 = r->best_sim;
  if (!r->have_best || memcmp(u, r->best_u, (size_t)n * sizeof *u)) {
    for (int k = 0; k < n; k++) r->p[k] = to_p(&r->f->params[k], u[k]);
    if ((r->status = rs_fit_eval_at(&r->e, r->p, r->sim, &r->msg)) != RS_OK) return -1;
    sim0 = r->sim;
  }
  for (int k = 0; k < n; k++) r->p[k] = to_p(&r->f->params[k], u[k]);
  if ((r->status = rs_fit_columns_eval(r->cols, &r->e, r->p, sim0, r->w, fjac, ldfjac, &r->msg)) !=
      RS_OK)
    return -1;
  for (int k = 0; k < n; k++) { /* chain rule to u */
    const rs_fit_param *q = &r->f->params[k];
    const double dpdu = 0.5 * (q->hi - q->lo) * cos(u[k]);
    for (int i = 0; i < m; i++) fjac[(size_t)k * (size_t)ldfjac + (size_t)i] *= dpdu;
  }
  progress(r, r->best_norm);
  return 0;
}

static const char *stop_reason(int info)
{
  switch (info) {
  case 1: return "converged: relative reduction of the sum of squares below ftol";
  case 2: return "converged: relative change of the parameters below xtol";
  case 3: return "converged: sum of squares and parameters settled (ftol and xtol)";
  case 4: return "converged: residual orthogonal to the Jacobian's columns (gtol)";
  case 5: return "stopped: evaluation limit 100 (n + 1) reached";
  case 6: return "stopped: ftol too small, no further reduction possible";
  case 7: return "stopped: xtol too small, no further improvement of the parameters";
  case 8:
    return "stopped: gtol too small, residual orthogonal to the Jacobian to machine precision";
  default: return "stopped";
  }
}

/* Inverse of the symmetric positive definite n x n matrix a (in place, both triangles) by
 * LAPACK's Cholesky factorisation (dpotrf, dpotri); returns 0 when a squared pivot of the
 * factorisation falls below tol (singular to that tolerance: a has a unit diagonal here). */
static int invert_spd(double *a, int n, double tol)
{
  int info = 0;
  dpotrf_("L", &n, a, &n, &info);
  for (int k = 0; info == 0 && k < n; k++)
    if (a[k * n + k] * a[k * n + k] < tol) info = k + 1;
  if (info == 0) dpotri_("L", &n, a, &n, &info);
  if (info != 0) return 0;
  for (int c = 0; c < n; c++) /* column-major lower triangle -> the upper one */
    for (int r = c + 1; r < n; r++) a[r * n + c] = a[c * n + r];
  return 1;
}

static void note(char *notes, size_t len, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void note(char *notes, size_t len, const char *fmt, ...)
{
  const size_t used = strlen(notes);
  if (used + 1 >= len) return;
  char line[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  snprintf(notes + used, len - used, "%s%s", used ? "\n" : "", line);
}

/* A parameter this close to a bound (fraction of the bounds' span) is "at" it: the sine
 * transform approaches a bound only asymptotically. */
#define AT_BOUND 1e-4

/* Covariance, standard errors and notes at the best point (res->fitted). Parameters without
 * effect (a zero Jacobian column) get NaN; the others' covariance is that of the reduced
 * problem. */
static int analyse(fit_run *r, rs_fit_result *res)
{
  const rs_fit_spec *f = r->f;
  const int n = f->nparams;
  const size_t m = f->npoints;
  double *J = calloc(m * (size_t)n, sizeof *J);
  double *A = calloc((size_t)n * (size_t)n, sizeof *A);
  double *R = calloc((size_t)n * (size_t)n, sizeof *R);
  double *scale = calloc((size_t)n, sizeof *scale);
  int *act = calloc((size_t)n, sizeof *act);
  if (!J || !A || !R || !scale || !act) {
    free(J);
    free(A);
    free(R);
    free(scale);
    free(act);
    return rs_msg_set(&r->msg, RS_ERR_INTERNAL, "out of memory");
  }
  int status =
      rs_fit_columns_eval(r->cols, &r->e, res->fitted, r->best_sim, r->w, J, (int)m, &r->msg);
  double data_norm = 0;
  for (size_t i = 0; i < m; i++) data_norm += r->w[i] * r->meas[i] * r->w[i] * r->meas[i];
  data_norm = sqrt(data_norm);
  for (int a = 0; status == RS_OK && a < n; a++)
    for (int b = 0; b < n; b++) {
      double s = 0;
      for (size_t i = 0; i < m; i++) s += J[(size_t)a * m + i] * J[(size_t)b * m + i];
      A[a * n + b] = s;
    }
  const double s2 = res->residual_norm * res->residual_norm / (double)(m - (size_t)n);
  int na = 0; /* parameters with an effect */
  for (int k = 0; status == RS_OK && k < n; k++) {
    const rs_fit_param *q = &f->params[k];
    const double x = res->fitted[k], span = q->hi - q->lo;
    if (x - q->lo < AT_BOUND * span)
      note(res->notes, sizeof res->notes,
           "%s is at its lower bound %g: its standard error assumes it free (widen the bounds "
           "or fix it)",
           q->key, q->lo);
    else if (q->hi - x < AT_BOUND * span)
      note(res->notes, sizeof res->notes,
           "%s is at its upper bound %g: its standard error assumes it free (widen the bounds "
           "or fix it)",
           q->key, q->hi);
    /* no effect: moving it over its whole range would change the simulated values by less
     * than 1e-9 of the data */
    if (sqrt(A[k * n + k]) * span <= 1e-9 * data_norm) {
      note(res->notes, sizeof res->notes,
           "%s has no effect on the simulated values (not identifiable from these data: fix it "
           "or remove it)",
           q->key);
    } else {
      scale[k] = 1 / sqrt(A[k * n + k]);
      act[na++] = k;
    }
  }
  for (size_t k = 0; k < (size_t)n * (size_t)n; k++) res->covariance[k] = NAN;
  /* R: J^T J of the active parameters scaled to unit diagonal (cosines of J's columns) */
  for (int a = 0; a < na; a++)
    for (int b = 0; b < na; b++)
      R[a * na + b] = A[act[a] * n + act[b]] * scale[act[a]] * scale[act[b]];
  double *Rinv = malloc((size_t)(na > 0 ? na * na : 1) * sizeof *Rinv);
  if (!Rinv && status == RS_OK) status = rs_msg_set(&r->msg, RS_ERR_INTERNAL, "out of memory");
  if (status == RS_OK && na > 0) {
    memcpy(Rinv, R, (size_t)(na * na) * sizeof *R);
    if (invert_spd(Rinv, na, 1e-10)) {
      for (int a = 0; a < na; a++)
        for (int b = 0; b < na; b++)
          res->covariance[act[a] * n + act[b]] =
              s2 * Rinv[a * na + b] * scale[act[a]] * scale[act[b]];
    } else {
      int named = 0;
      for (int a = 0; a < na; a++)
        for (int b = a + 1; b < na; b++)
          if (fabs(R[a * na + b]) > 1 - 1e-8) {
            named = 1;
            note(res->notes, sizeof res->notes,
                 "%s and %s are not identifiable together (their effects on the data are "
                 "proportional, cosine %.10f): fix one of them",
                 f->params[act[a]].key, f->params[act[b]].key, R[a * na + b]);
          }
      if (!named)
        note(res->notes, sizeof res->notes,
             "J^T J is singular: the parameters are not identifiable together from these data");
    }
  }
  for (int k = 0; k < n; k++) res->std_error[k] = sqrt(res->covariance[k * n + k]);
  for (int a = 0; status == RS_OK && a < n; a++)
    for (int b = a + 1; b < n; b++) {
      const double rho = res->covariance[a * n + b] / (res->std_error[a] * res->std_error[b]);
      if (fabs(rho) > FIT_RHO_NOTE)
        note(res->notes, sizeof res->notes,
             "%s and %s are strongly correlated (rho = %+.4f): the data constrain a combination "
             "better than each",
             f->params[a].key, f->params[b].key, rho);
    }
  free(Rinv);
  free(J);
  free(A);
  free(R);
  free(scale);
  free(act);
  return status;
}

int rs_fit_serve(const rs_fit_spec *f, const rs_case *c, const rs_fit_opts *o, rs_msg *msg)
{
  rs_fit_eval e;
  rs_fit_columns *cols = NULL;
  int status = rs_fit_eval_init(&e, f, c, msg);
  if (status == RS_OK) status = rs_fit_columns_create(&cols, f, o->mpi_rank, o->mpi_size, msg);
  if (status == RS_OK) status = rs_fit_columns_serve(cols, &e);
  rs_fit_columns_free(cols);
  rs_fit_eval_free(&e);
  return status;
}

void rs_fit_result_free(rs_fit_result *res)
{
  free(res->fitted);
  free(res->std_error);
  free(res->covariance);
  free(res->simulated);
  memset(res, 0, sizeof *res);
}

int rs_fit_run(const rs_fit_spec *f, const rs_case *c, const rs_fit_opts *o, rs_fit_result *res,
               rs_msg *msg)
{
  memset(res, 0, sizeof *res);
  const int n = f->nparams, m = (int)f->npoints;
  fit_run r = {.f = f, .o = o, .started = rs_wall_clock()};
  int status = RS_OK;
  const char *case_path = c->source_path;
  r.base = c;
  r.path = o->output_path ? o->output_path : c->output_file;
  snprintf(res->file, sizeof res->file, "%s", r.path ? r.path : "");
  res->nparams = n;
  res->npoints = f->npoints;
  res->fitted = calloc((size_t)n, sizeof *res->fitted);
  res->std_error = calloc((size_t)n, sizeof *res->std_error);
  res->covariance = calloc((size_t)n * (size_t)n, sizeof *res->covariance);
  res->simulated = calloc((size_t)m, sizeof *res->simulated);
  r.p = calloc((size_t)n, sizeof *r.p);
  r.sim = calloc((size_t)m, sizeof *r.sim);
  r.w = calloc((size_t)m, sizeof *r.w);
  r.meas = calloc((size_t)m, sizeof *r.meas);
  r.best_u = calloc((size_t)n, sizeof *r.best_u);
  r.best_p = calloc((size_t)n, sizeof *r.best_p);
  r.best_sim = calloc((size_t)m, sizeof *r.best_sim);
  double *u = calloc((size_t)n, sizeof *u), *fvec = calloc((size_t)m, sizeof *fvec);
  double *fjac = calloc((size_t)m * (size_t)n, sizeof *fjac);
  double *diag = calloc((size_t)n, sizeof *diag), *qtf = calloc((size_t)n, sizeof *qtf);
  double *wa = calloc(3 * (size_t)n + (size_t)m, sizeof *wa);
  int *ipvt = calloc((size_t)n, sizeof *ipvt);
  double *start = calloc((size_t)n, sizeof *start);
  if (!r.path)
    status = rs_msg_set(msg, RS_ERR_INPUT, "%s: no output file (give -o FIT.nc)", case_path);
  else if (!res->fitted || !res->std_error || !res->covariance || !res->simulated || !r.p ||
           !r.sim || !r.w || !r.meas || !r.best_u || !r.best_p || !r.best_sim || !u || !fvec ||
           !fjac || !diag || !qtf || !wa || !ipvt || !start)
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  if (status == RS_OK) status = rs_fit_eval_init(&r.e, f, c, msg);
  if (status == RS_OK)
    status = rs_fit_columns_create(&r.cols, f, 0, o->mpi_size > 1 ? o->mpi_size : 1, msg);
  /* --resume: the file's best point is lmder's start, its evaluations are counted on; a file
   * that is not this fit's is refused before anything is run or written */
  rs_fit_previous prev = {0};
  char *history = NULL;
  if (status == RS_OK && o->resume &&
      (status = rs_fit_output_read_previous(r.path, f, c->yaml_text, &prev, msg)) == RS_OK) {
    res->already_complete = prev.complete;
    res->resumed = !prev.complete;
    res->evaluations_before = prev.evaluations;
    const size_t hl = strlen(prev.history) + strlen(o->history ? o->history : "") + 96;
    if (!(history = malloc(hl)))
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    else
      snprintf(history, hl, "%s%s%s (resumed from %ld evaluations, residual %.6g)", prev.history,
               *prev.history ? "\n" : "", o->history ? o->history : "", prev.evaluations,
               prev.residual_norm);
  }
  for (int k = 0; status == RS_OK && k < n; k++) {
    start[k] = o->resume ? prev.start[k] : f->params[k].start;
    res->fitted[k] = o->resume ? prev.fitted[k] : f->params[k].start;
  }
  res->residual_norm = prev.residual_norm;
  r.start = start;
  r.history = history ? history : o->history;
  r.e.evaluations = prev.evaluations;
  r.written = res->resumed; /* a resume rewrites its own file: no PATH~ */
  if (status == RS_OK && !res->already_complete) {
    for (int i = 0; i < m; i++) {
      const double *row = f->table + (size_t)i * (size_t)f->ncols;
      r.meas[i] = row[f->measured_col];
      r.w[i] = f->weight_col >= 0 ? row[f->weight_col] : 1.0;
    }
    for (int k = 0; k < n; k++) u[k] = to_u(&f->params[k], res->fitted[k]);
    int nfev = 0, njev = 0;
    const int info =
        lmder(lm_function, &r, m, n, u, fvec, fjac, m, FIT_FTOL, FIT_XTOL, FIT_GTOL, 100 * (n + 1),
              diag, 1, 100.0, 0, &nfev, &njev, ipvt, qtf, wa, wa + n, wa + 2 * n, wa + 3 * n);
    if (o->progress) fputc('\n', stderr);
    res->minpack_info = info;
    status = r.status;
    if (status == RS_OK && info == 0)
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "lmder: improper input parameters");
    snprintf(res->stop_reason, sizeof res->stop_reason, "%s",
             status == RS_ERR_INTERRUPTED ? "interrupted (best point so far kept)"
             : status != RS_OK            ? "failed"
                                          : stop_reason(info));
    if (status != RS_OK) snprintf(msg->text, sizeof msg->text, "%s", r.msg.text);
  }
  if (r.have_best) {
    memcpy(res->fitted, r.best_p, (size_t)n * sizeof *r.best_p);
    memcpy(res->simulated, r.best_sim, (size_t)m * sizeof *r.best_sim);
    res->residual_norm = r.best_norm;
  }
  if (status == RS_OK && !res->already_complete) {
    status = analyse(&r, res);
    if (status != RS_OK) snprintf(msg->text, sizeof msg->text, "%s", r.msg.text);
  }
  if (status != RS_OK && res->covariance && res->std_error) /* none short of convergence: NaN */
    for (int k = 0; k < n * n; k++) {
      res->covariance[k] = NAN;
      if (k < n) res->std_error[k] = NAN;
    }
  res->evaluations = res->already_complete ? prev.evaluations : r.e.evaluations;
  if (r.have_best) {
    char why[RS_FINAL_STATUS_LEN];
    rs_msg tmp;
    const int ws = write_file(&r, rs_final_status(status, msg, why), res->fitted,
                              status == RS_OK ? res->std_error : NULL,
                              status == RS_OK ? res->covariance : NULL, res->simulated,
                              res->residual_norm, res->notes, status == RS_OK ? msg : &tmp);
    if (status == RS_OK) status = ws;
  }
  snprintf(res->backup, sizeof res->backup, "%s", r.backup);
  res->wall_seconds = rs_wall_clock() - r.started;
  rs_fit_columns_free(r.cols);
  rs_fit_eval_free(&r.e);
  free(r.p);
  free(r.sim);
  free(r.w);
  free(r.meas);
  free(r.best_u);
  free(r.best_p);
  free(r.best_sim);
  free(u);
  free(fvec);
  free(fjac);
  free(diag);
  free(qtf);
  free(wa);
  free(ipvt);
  free(start);
  free(history);
  rs_fit_previous_free(&prev);
  return status;
}
