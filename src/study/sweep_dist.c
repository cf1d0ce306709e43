/* The sweep driver (study/sweep.h, study/sweep_dist.h): a task farm over the sweep's
 * continuation lines (the points that differ only in the last key; each starts from rest,
 * so lines are independent), each solved by rs_sweep_line_eval:
 *  - serial: the farm of one rank, which computes every line in order;
 *  - under MPI: rank 0 hands out lines, in line order, to ranks that ask, computes lines
 *    itself between requests and writes every point as it arrives (with the rank that
 *    computed it);
 *  - rollsim sweep --part K/N: the lines l with l mod N = K - 1, into a file of the full
 *    sweep's shape (points of other parts left unwritten), joined by rollsim merge.
 *  - --resume (any of the above): the lines complete in the existing file are kept, the
 *    others computed again from their first point, into that file.
 * A point's numbers do not depend on which process computed it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output.h"
#include "study/sweep.h"
#include "study/sweep_fields.h"
#include "study/sweep_dist.h"
#include "study/sweep_lines.h"
#include "base/util.h"

enum { TAG_REQUEST = 1, TAG_POINT = 2, TAG_LINE = 3 };
/* A point message: line, j, status, 11 scalars, newton, has_fields, then 7 nx values. */
/* m[16..21]: F_y, M_z, eta, phi, Hertz a, b (3D; 0 in 2D); m[22..24]: T_max, heat inputs;
 * m[25..28]: the errors of F_x, F_y, M_z and error_reliable; m[29..31]: F_x, F_y, M_z
 * extrapolated */
enum { PT_HEAD = 32 };

typedef struct dist_run {
  const rs_sweep *s;
  const rs_case *c; /* the loaded case */
  const rs_run_opts *o;
  const rs_sweep_dist *dist;
  rs_sweep_result *res;
  size_t nlast, nlines;
  rs_case_override *fixed; /* [naxes - 1] the other axes' values of the line */
  rs_sweep_output *out;    /* rank 0 / the part's file */
  rs_fields buf;           /* this rank's fields of a point (when the file stores them) */
  int with_fields;
  size_t nx;
  double *msgbuf; /* a point message */
  int msglen;
  size_t line;         /* the line being computed by this rank */
  size_t next_line;    /* rank 0: next line to hand out */
  unsigned char *done; /* --resume: [nlines] 1 for a line complete in the file, else NULL */
  int stopped;         /* rank 0: workers told to stop */
  int interrupted;
  rs_stats stats;
  long refined;
  long midpoints;
  long in_two;
  double started;
  int estimate; /* steady sweeps: error estimates per point */
  rs_msg msg;
} dist_run;

/* The rows of a point message <-> the sweep file's point. */
static void pack(dist_run *r, size_t line, size_t j, int status, const rs_diag *d, long newton)
{
  double *m = r->msgbuf;
  const int ok = status == RS_OK;
  m[0] = (double)line;
  m[1] = (double)j;
  m[2] = status;
  const double v[] = {d->Fx,
                      d->Fn,
                      d->creepage,
                      d->velocity,
                      d->count[RS_EXTERIOR],
                      d->count[RS_ADHESION],
                      d->count[RS_SLIP],
                      d->count[RS_PLASTIC],
                      d->frictional_power,
                      d->plastic_power,
                      d->elastic_energy};
  for (int k = 0; k < 11; k++) m[3 + k] = ok ? v[k] : NAN;
  m[14] = (double)newton;
  m[15] = ok && r->with_fields;
  const double v3[6] = {d->Fy, d->Mz, d->lateral_creepage, d->spin, d->hertz_a, d->hertz_b};
  for (int k = 0; k < 6; k++) m[16 + k] = ok ? v3[k] : NAN;
  const double vt[3] = {d->T_max, d->heat_input_1, d->heat_input_2};
  for (int k = 0; k < 3; k++) m[22 + k] = ok ? vt[k] : NAN;
  const int est = ok && d->error_state != RS_ERROR_NONE;
  m[25] = est ? d->Fx_error : NAN;
  m[26] = est ? d->Fy_error : NAN;
  m[27] = est ? d->Mz_error : NAN;
  m[28] = !est ? -1 : d->error_state == RS_ERROR_RELIABLE ? 1 : 0;
  m[29] = est ? d->Fx_extrapolated : NAN;
  m[30] = est ? d->Fy_extrapolated : NAN;
  m[31] = est ? d->Mz_extrapolated : NAN;
  if (ok && r->with_fields) {
    const double *rows[6] = {r->buf.px,  r->buf.pn,    r->buf.slip,
                             r->buf.upl, r->buf.ustar, r->buf.tauc};
    for (int f = 0; f < 6; f++) memcpy(m + PT_HEAD + (size_t)f * r->nx, rows[f], r->nx * sizeof *m);
    for (size_t i = 0; i < r->nx; i++) m[PT_HEAD + 6 * r->nx + i] = r->buf.regime[i];
    memcpy(m + PT_HEAD + 7 * r->nx, r->buf.mu, r->nx * sizeof *m); /* mu(|v_s|) per cell */
  }
}

/* Write the point of a message (as the serial sweep writes it) computed by `rank`. */
static int write_point(dist_run *r, const double *m, int rank)
{
  const size_t line = (size_t)m[0], j = (size_t)m[1], p = line * r->nlast + j;
  const int status = (int)m[2];
  rs_sweep_point pt;
  memset(&pt, 0, sizeof pt);
  signed char *regime = NULL;
  if (status == RS_OK) {
    pt.Fx = m[3];
    pt.Fn = m[4];
    pt.creepage = m[5];
    pt.velocity = m[6];
    pt.n_exterior = (int)m[7];
    pt.n_adhesion = (int)m[8];
    pt.n_slip = (int)m[9];
    pt.n_plastic = (int)m[10];
    pt.frictional_power = m[11];
    pt.plastic_power = m[12];
    pt.elastic_energy = m[13];
    pt.Fy = m[16];
    pt.Mz = m[17];
    pt.lateral_creepage = m[18];
    pt.spin = m[19];
    pt.hertz_a = m[20];
    pt.hertz_b = m[21];
    pt.T_max = m[22];
    pt.heat_input_1 = m[23];
    pt.heat_input_2 = m[24];
    pt.Fx_error = m[25];
    pt.Fy_error = m[26];
    pt.Mz_error = m[27];
    pt.error_reliable = (int)m[28];
    pt.Fx_extrapolated = m[29];
    pt.Fy_extrapolated = m[30];
    pt.Mz_extrapolated = m[31];
    pt.converged = 1;
    if (pt.error_reliable >= 0) {
      r->res->points_estimated++;
      r->res->points_reliable += pt.error_reliable == 1;
      if (pt.Fn != 0.0 && fabs(pt.Fx_error / pt.Fn) > r->res->max_mu_error)
        r->res->max_mu_error = fabs(pt.Fx_error / pt.Fn);
    }
    if (m[15] != 0) {
      const double *f = m + PT_HEAD;
      pt.px = f;
      pt.pn = f + r->nx;
      pt.slip = f + 2 * r->nx;
      pt.upl = f + 3 * r->nx;
      pt.ustar = f + 4 * r->nx;
      pt.tauc = f + 5 * r->nx;
      pt.mu = f + 7 * r->nx;
      regime = malloc(r->nx);
      if (!regime) return rs_msg_set(&r->msg, RS_ERR_INTERNAL, "out of memory");
      for (size_t i = 0; i < r->nx; i++) regime[i] = (signed char)f[6 * r->nx + i];
      pt.regime = regime;
    }
    r->res->points_done++;
  } else {
    pt.Fx = pt.Fn = pt.creepage = pt.velocity = NAN;
    pt.Fy = pt.Mz = pt.lateral_creepage = pt.spin = pt.hertz_a = pt.hertz_b = NAN;
    pt.frictional_power = pt.plastic_power = pt.elastic_energy = NAN;
    pt.T_max = pt.heat_input_1 = pt.heat_input_2 = NAN;
    pt.n_exterior = pt.n_adhesion = pt.n_slip = pt.n_plastic = -1;
    pt.Fx_error = pt.Fy_error = pt.Mz_error = NAN;
    pt.Fx_extrapolated = pt.Fy_extrapolated = pt.Mz_extrapolated = NAN;
    pt.error_reliable = -1;
    r->res->points_failed++;
  }
  r->res->newton_iters += (long)m[14];
  pt.rank = rank;
  const int ws = rs_sweep_output_write(r->out, p, &pt, &r->msg);
  free(regime);
  if (r->dist->progress)
    r->dist->progress(r->dist->progress_ctx, r->res->points_done + r->res->points_failed,
                      r->s->npoints);
  if (r->o->progress) {
    fprintf(stderr, "\rsweep: %zu/%zu points, %zu failed, %.1f s ",
            r->res->points_done + r->res->points_failed, r->s->npoints, r->res->points_failed,
            rs_wall_clock() - r->started);
    fflush(stderr);
  }
  return ws;
}

/* The values of the axes other than the last for a line. */
static void line_sets(dist_run *r, size_t line)
{
  const rs_sweep *s = r->s;
  size_t rest = line;
  for (int a = s->naxes - 2; a >= 0; a--) {
    const int k = (int)(rest % (size_t)s->axes[a].n);
    rest /= (size_t)s->axes[a].n;
    r->fixed[a] = (rs_case_override){s->axes[a].key_index, s->axes[a].values[k]};
  }
}

static int serve(dist_run *r, int block);

/* Rank 0: next_line past the lines kept from the file (--resume). */
static void next_pending(dist_run *r)
{
  while (r->done && r->next_line < r->nlines && r->done[r->next_line]) r->next_line++;
}

/* After each point of this rank: write it (rank 0, parts) or send it (workers). */
static int point_done(void *ctx, size_t j, int status, const rs_diag *d, long newton,
                      const char *why)
{
  dist_run *r = ctx;
  const rs_sweep *s = r->s;
  if (status != RS_OK)
    fprintf(stderr, "rollsim sweep: point %zu (%s=%.17g): %s\n", r->line * r->nlast + j,
            s->axes[s->naxes - 1].key, s->axes[s->naxes - 1].values[j], why);
  pack(r, r->line, j, status, d, newton);
  int st;
  if (r->dist->mpi && r->dist->mpi->rank > 0) {
    st = rs_mpi_send_doubles(r->msgbuf, r->msglen, 0, TAG_POINT) == 0
             ? RS_OK
             : rs_msg_set(&r->msg, RS_ERR_INTERNAL, "MPI_Send failed");
  } else {
    st = write_point(r, r->msgbuf, 0);
    if (st == RS_OK && r->dist->mpi && r->dist->mpi->size > 1) st = serve(r, 0);
  }
  if (st == RS_OK && r->o->interrupt_flag && *r->o->interrupt_flag) {
    r->interrupted = 1;
    st = RS_ERR_INTERRUPTED;
  }
  return st;
}

static int compute_line(dist_run *r, size_t line)
{
  const rs_sweep *s = r->s;
  const rs_sweep_axis *last = &s->axes[s->naxes - 1];
  r->line = line;
  line_sets(r, line);
  const rs_sweep_line L = {.base = r->c,
                           .fixed = r->fixed,
                           .nfixed = s->naxes - 1,
                           .key = last->key_index,
                           .values = last->values,
                           .n = (size_t)last->n,
                           .first_point = (long)(line * r->nlast),
                           .fields = r->with_fields ? &r->buf : NULL,
                           .point_done = point_done,
                           .ctx = r,
                           .interrupt_flag = r->o->interrupt_flag,
                           .stats = &r->stats,
                           .refined = &r->refined,
                           .midpoints = &r->midpoints,
                           .in_two = &r->in_two,
                           .estimate = r->estimate};
  rs_msg m = {{0}};
  const int st = rs_sweep_line_eval(&L, &m);
  if (st == RS_ERR_INTERRUPTED) r->interrupted = 1; /* also inside a transient point */
  if (st != RS_OK && st != RS_ERR_INTERRUPTED && !r->msg.text[0])
    snprintf(r->msg.text, sizeof r->msg.text, "%s", m.text);
  return st;
}

/* Rank 0: answer the messages waiting (block: wait for one first). A request gets the
 * next line, or "stop" (-1) when none is left or the sweep was interrupted. */
static int serve(dist_run *r, int block)
{
  int src, tag, status = RS_OK;
  while (status == RS_OK && (block ? rs_mpi_wait(&src, &tag) == 0 : rs_mpi_probe(&src, &tag))) {
    block = 0;
    if (tag == TAG_REQUEST) {
      char text[RS_MSG_LEN + 32];
      rs_mpi_recv_text(text, sizeof text, src, TAG_REQUEST, NULL);
      const int ws = atoi(text); /* the worker's last line: status and message */
      if (ws != RS_OK && ws != RS_ERR_INTERRUPTED && status == RS_OK) {
        const char *why = strchr(text, ' ');
        status = rs_msg_set(&r->msg, ws, "rank %d: %s", src, why ? why + 1 : "");
      }
      if (ws == RS_ERR_INTERRUPTED) r->interrupted = 1;
      double next = -1;
      next_pending(r);
      if (!r->interrupted && status == RS_OK && r->next_line < r->nlines)
        next = (double)r->next_line++;
      if (next < 0) r->stopped++;
      rs_mpi_send_doubles(&next, 1, src, TAG_LINE);
    } else if (tag == TAG_POINT) {
      int n = 0;
      rs_mpi_recv_doubles(r->msgbuf, r->msglen, src, TAG_POINT, NULL, NULL, &n);
      status = write_point(r, r->msgbuf, src);
    } else {
      status = rs_msg_set(&r->msg, RS_ERR_INTERNAL, "unexpected MPI message (tag %d)", tag);
    }
  }
  return status;
}

/* Workers: ask for lines until told to stop. */
static int worker(dist_run *r)
{
  int last = RS_OK;
  for (;;) {
    char text[RS_MSG_LEN + 32];
    snprintf(text, sizeof text, "%d %s", last, last == RS_OK ? "" : r->msg.text);
    if (rs_mpi_send_text(text, 0, TAG_REQUEST) != 0)
      return rs_msg_set(&r->msg, RS_ERR_INTERNAL, "MPI_Send failed");
    double line = -1;
    if (rs_mpi_recv_doubles(&line, 1, 0, TAG_LINE, NULL, NULL, NULL) != 0)
      return rs_msg_set(&r->msg, RS_ERR_INTERNAL, "MPI_Recv failed");
    if (line < 0) return last == RS_ERR_INTERRUPTED ? RS_ERR_INTERRUPTED : RS_OK;
    if (last == RS_OK) last = compute_line(r, (size_t)line);
  }
}

/* --resume: reopen the file (refused, untouched, unless it is this sweep's) and mark the
 * lines complete in it, counting their points as done or failed. */
static int resume_open(dist_run *r, const rs_sweep_output_spec *spec, rs_msg *msg)
{
  int *conv = malloc(r->s->npoints * sizeof *conv);
  r->done = calloc(r->nlines, 1);
  if (!conv || !r->done) {
    free(conv);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  size_t written = 0;
  const int status = rs_sweep_output_resume(&r->out, spec, conv, &written, msg);
  for (size_t l = 0; l < r->nlines && status == RS_OK; l++) {
    size_t ok = 0, failed = 0;
    for (size_t j = 0; j < r->nlast; j++) {
      ok += conv[l * r->nlast + j] == 1;
      failed += conv[l * r->nlast + j] == 0;
    }
    if (ok + failed < r->nlast) continue;
    r->done[l] = 1;
    r->res->points_done += ok;
    r->res->points_failed += failed;
    r->res->points_kept += r->nlast;
  }
  free(conv);
  return status;
}

int rs_sweep_run(const rs_sweep *s, const rs_case *c, const rs_run_opts *o, rs_sweep_result *res,
                 rs_msg *msg)
{
  const rs_sweep_dist serial = {0};
  return rs_sweep_run_dist(s, c, o, &serial, res, msg);
}

int rs_sweep_run_dist(const rs_sweep *s, const rs_case *c, const rs_run_opts *o,
                      const rs_sweep_dist *dist, rs_sweep_result *res, rs_msg *msg)
{
  dist_run r = {.s = s, .c = c, .o = o, .dist = dist, .res = res, .started = rs_wall_clock()};
  memset(res, 0, sizeof *res);
  const int rank = dist->mpi ? dist->mpi->rank : 0, size = dist->mpi ? dist->mpi->size : 1;
  int status = RS_OK;
  const char *path = o->output_path ? o->output_path : c->output_file;
  snprintf(res->file, sizeof res->file, "%s", path);
  r.nlast = (size_t)s->axes[s->naxes - 1].n;
  r.nlines = s->npoints / r.nlast;
  double *grid_x = NULL;
  int grid_n = 0;
  const char **keys = calloc((size_t)s->naxes, sizeof *keys);
  int *sizes = calloc((size_t)s->naxes, sizeof *sizes);
  const double **values = calloc((size_t)s->naxes, sizeof *values);
  r.fixed = calloc((size_t)s->naxes, sizeof *r.fixed);
  if (!keys || !sizes || !values || !r.fixed) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    goto done;
  }
  for (int a = 0; a < s->naxes; a++) {
    keys[a] = s->axes[a].key;
    sizes[a] = s->axes[a].n;
    values[a] = s->axes[a].values;
  }
  /* Profiles (output.fields) when every point has the loaded case's grid. */
  const unsigned fields = rs_sweep_profile_fields(c, rank == 0);
  if (fields) {
    char why[512];
    int common = 0;
    status = rs_sweep_common_grid(s, c, &common, &grid_x, &grid_n, why, sizeof why, msg);
    if (status != RS_OK) goto done;
    if (!common && rank == 0)
      fprintf(stderr,
              "rollsim sweep: warning: output.fields not stored: %s, and the profiles "
              "of a sweep file share one x axis (output.fields: [] silences this)\n",
              why);
    else if (common && rs_fields_alloc(&r.buf, grid_n) != RS_OK) {
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
      goto done;
    }
  }
  r.estimate = c->mode == RS_MODE_STEADY && c->error_estimate && !c->rig.on;
  res->error_estimate = r.estimate;
  r.with_fields = grid_x != NULL;
  r.nx = r.with_fields ? (size_t)grid_n : 0;
  r.msglen = PT_HEAD + 8 * (int)r.nx;
  r.msgbuf = calloc((size_t)r.msglen, sizeof *r.msgbuf);
  if (!r.msgbuf) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
    goto done;
  }
  if (rank == 0) {
    const rs_sweep_output_spec spec = {.path = path,
                                       .fields = grid_x ? fields : 0,
                                       .nx = (size_t)grid_n,
                                       .x = grid_x,
                                       .title = c->title,
                                       .case_text = c->yaml_text,
                                       .history = o->history,
                                       .dimension = c->dimension,
                                       .naxes = s->naxes,
                                       .keys = keys,
                                       .sizes = sizes,
                                       .values = values,
                                       .ranks = dist->mpi && size > 1 ? size : 0,
                                       .part = dist->part,
                                       .parts = dist->parts,
                                       .temperature = c->temperature.on,
                                       .error_estimate = r.estimate};
    if (dist->resume)
      status = resume_open(&r, &spec, msg);
    else
      status = rs_sweep_output_create(&r.out, &spec, msg);
    if (status != RS_OK) {
      res->file[0] = '\0'; /* none written, or the resumed one left as it was */
      /* the workers are waiting for lines: tell them to stop */
      r.next_line = r.nlines;
      while (r.stopped < size - 1 && serve(&r, 1) == RS_OK) {
      }
      goto done;
    }
    if (rs_sweep_output_backup(r.out))
      snprintf(res->backup, sizeof res->backup, "%s", rs_sweep_output_backup(r.out));
  }
  if (rank > 0) {
    status = worker(&r);
    if (status != RS_OK && status != RS_ERR_INTERRUPTED)
      snprintf(msg->text, sizeof msg->text, "%s", r.msg.text);
    goto done;
  }
  /* This process's lines: a part's share, or (rank 0 of a farm) the queue. Every line of
   * a sweep has the same number of points; the queue is in line order (longest first
   * among equals). */
  if (dist->parts > 0) {
    for (size_t l = (size_t)(dist->part - 1); l < r.nlines && status == RS_OK;
         l += (size_t)dist->parts)
      if (!r.done || !r.done[l]) status = compute_line(&r, l);
  } else {
    next_pending(&r);
    while (status == RS_OK && !r.interrupted && r.next_line < r.nlines) {
      status = compute_line(&r, r.next_line++);
      next_pending(&r);
    }
    /* the workers' last lines, and stop them */
    if (status == RS_ERR_INTERRUPTED) status = RS_OK;
    while (status == RS_OK && r.stopped < size - 1) status = serve(&r, 1);
    if (status != RS_OK && r.stopped < size - 1) {
      fprintf(stderr, "rollsim sweep: %s\n", r.msg.text);
      rs_sweep_output_close(r.out, "failed: see the messages of rank 0", msg);
      rs_mpi_abort(dist->mpi, 1);
    }
  }
  if (r.interrupted && (status == RS_OK || status == RS_ERR_INTERRUPTED))
    status = rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted after %zu of %zu points",
                        res->points_done + res->points_failed, s->npoints);
  else if (status != RS_OK)
    snprintf(msg->text, sizeof msg->text, "%s", r.msg.text);
  if (o->progress) fputc('\n', stderr);
  if (status == RS_OK && res->points_failed > 0)
    status =
        rs_msg_set(msg, RS_ERR_SOLVER, "%zu of %zu sweep points did not converge (NaN in the file)",
                   res->points_failed, s->npoints);
  {
    char why[RS_FINAL_STATUS_LEN];
    rs_msg tmp;
    const int cs = rs_sweep_output_close(r.out, rs_final_status(status, msg, why),
                                         status == RS_OK ? msg : &tmp);
    if (status == RS_OK) status = cs;
  }
done:
  /* newton_iters: the points' own counts (write_point), every rank's, steady ones too */
  res->lin_solves = r.stats.lin_solves;
  res->jac_evals = r.stats.jac_evals;
  res->refused = r.stats.refused;
  res->couplings = r.stats.couplings;
  res->coupling_newton = r.stats.coupling_newton;
  res->coupling_products = r.stats.coupling_products;
  res->refined = r.refined;
  res->midpoints = r.midpoints;
  res->lines_in_two = r.in_two;
  res->wall_seconds = rs_wall_clock() - r.started;
  free(grid_x);
  rs_fields_free(&r.buf);
  free(r.msgbuf);
  free(keys);
  free(sizes);
  free(values);
  free(r.fixed);
  free(r.done);
  return status;
}
