/* rollsim run on profiles (study/wheel_rail.h): every patch of a held wheelset into a run file
 * of its own, or a moving wheelset (a lateral-displacement or yaw history) followed through one
 * transient into one file over time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study/wheel_rail_internal.h"

#include <sundials/sundials_context.h>

#include "physics/elastic2d.h" /* RS_PI */
#include "physics/history.h"
#include "solve/transient.h"
#include "study/run.h"

/* One patch over one interval of a moving wheelset: its model at the interval's start, its
 * state carried from `from` (or rest), the transient to t1; the forces at t1 into d and the
 * model and state into keep. */
static int patch_interval(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                          double V, const rs_creepages *cr, const patch_state *from, double t0,
                          double t1, volatile sig_atomic_t *interrupt, SUNContext ctx, rs_diag *d,
                          rs_stats *stats, patch_state *keep, rs_msg *msg)
{
  rs_model m;
  rs_work w;
  double *y, *yp;
  int status = wr_patch_model(c, p, r, V, cr, &m, &w, &y, &yp, msg);
  if (status != RS_OK) return status;
  rs_inputs in;
  rs_model_inputs_at(&m, t0, &in);
  rs_model_rest_state(&m, y);
  if (from) status = wr_carry_state(from, p->y, p->delta, &m, &w, &in, y, msg);
  if (status == RS_OK) status = rs_model_project_state(&m, &w, &in, y, msg);
  if (status == RS_OK) status = rs_model_consistent_rates(&m, &w, &in, y, yp, msg);
  rs_transient *tr = NULL;
  const rs_transient_opts topts = {.rtol = c->rtol > 0.0 ? c->rtol : rs_transient_auto_rtol(&m),
                                   .atol = c->atol,
                                   .max_order = c->max_order,
                                   .max_steps = c->max_steps,
                                   .max_newton = 10,
                                   .t_stop = t1,
                                   .interrupt = interrupt};
  if (status == RS_OK) status = rs_transient_create(&tr, &m, ctx, t0, y, yp, &topts, msg);
  if (status == RS_OK) status = rs_transient_advance(tr, t1, y, yp, msg);
  if (tr) {
    rs_stats st;
    rs_transient_get_stats(tr, &st);
    stats->steps += st.steps;
    stats->nonlin_iters += st.nonlin_iters;
    rs_transient_free(tr);
  }
  if (status == RS_OK) {
    rs_model_inputs_at(&m, t1, &in);
    status = rs_model_diagnostics(&m, &w, &in, y, yp, d, NULL, NULL, NULL);
  }
  return wr_patch_finish(status, p, &m, &w, y, yp, keep);
}

/* rollsim run with the wheelset moving (profiles.lateral_displacement or yaw a history): at
 * the start of every output interval the patches, the load sharing and each patch's creepages
 * (with the lateral velocity and the yaw rate) for the position then, held over the interval,
 * each patch's transient continuing the nearest patch's state; one record per interval
 * (docs/model.md §20, "A moving wheelset"). */
static int path_run(const rs_case *c, const rs_run_opts *o, FILE *out, rs_wr_run_result *res,
                    rs_msg *msg)
{
  const rs_wheel_rail *w0 = c->profiles;
  const double T = c->end_time, dt = c->output_interval;
  const long nrec = (long)ceil(T / dt - 1e-9);
  if (!(rs_history_min(&c->velocity, 0.0, T) > 0.0))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "rolling.velocity: a moving wheelset needs it above 0 at all times (the "
                      "creepages are divided by it)");
  if (c->temperature.on)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "temperature: not with a moving wheelset yet (profiles.lateral_displacement "
                      "or profiles.yaw a history): run without the temperature: block or hold "
                      "the wheelset");
  for (long k = 0; k < nrec; k++) { /* every position placed before anything is solved */
    rs_wheel_rail wk = *w0;
    rs_msg m = {{0}};
    const double t = k * dt;
    if (rs_wheel_rail_set(&wk, "lateral_displacement", rs_history_eval(&w0->lateral_history, t),
                          &m) != RS_OK ||
        rs_wheel_rail_set(&wk, "yaw", rs_history_eval(&w0->yaw_history, t), &m) != RS_OK)
      return rs_msg_set(msg, RS_ERR_INPUT, "profiles.lateral_displacement at t = %g s: %s", t,
                        m.text);
  }
  const size_t n = (size_t)nrec;
  const int stride = RS_WR_MAX_PATCHES;
  double *times = malloc(n * sizeof *times), *pc = malloc(n * C_POSITION_COLS * sizeof *pc);
  double *pp = malloc(n * (size_t)stride * P_PATCH_COLS * sizeof *pp);
  double *cols = malloc(n * (C_POSITION_COLS + (size_t)stride * P_PATCH_COLS) * sizeof *cols);
  SUNContext ctx = NULL;
  int status =
      times && pc && pp && cols ? RS_OK : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  if (status == RS_OK && SUNContext_Create(NULL, &ctx) != 0)
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "could not create the SUNDIALS context");
  for (size_t i = 0; status == RS_OK && i < n * C_POSITION_COLS; i++) pc[i] = NAN;
  for (size_t i = 0; status == RS_OK && i < n * (size_t)stride * P_PATCH_COLS; i++) pp[i] = NAN;
  patch_state last[RS_WR_MAX_PATCHES] = {{0}};
  size_t done = 0;
  int npatch = 1, interrupted = 0;
  if (status == RS_OK && out)
    fprintf(out, "# t s, lateral displacement mm, yaw rad; per patch: y on the rail mm, contact "
                 "angle deg, F_n, F_x, F_s N (on the wheel)\n");
  for (long k = 0; status == RS_OK && k < nrec; k++) {
    if (o->interrupt_flag && *o->interrupt_flag) {
      interrupted = 1;
      break;
    }
    const double t0 = k * dt, t1 = k + 1 == nrec ? T : (k + 1) * dt;
    rs_wheel_rail wk = *w0;
    rs_msg ignored = {{0}};
    rs_wheel_rail_set(&wk, "lateral_displacement", rs_history_eval(&w0->lateral_history, t0),
                      &ignored);
    rs_wheel_rail_set(&wk, "yaw", rs_history_eval(&w0->yaw_history, t0), &ignored);
    /* the patches, their creepages with the wheelset's motion, and the loads of the steady
     * vertical balance at this position */
    wr_position pos;
    status = wr_position_solve(c, &wk, t0, -rs_history_rate(&w0->lateral_history, t0),
                               rs_history_rate(&w0->yaw_history, t0), &pos, msg);
    if (status != RS_OK) break;
    patch_state next[RS_WR_MAX_PATCHES] = {{0}};
    rs_stats st = {0};
    for (int j = 0; status == RS_OK && j < pos.geo.npatch; j++) {
      const rs_wr_patch *p = &pos.geo.patch[j];
      const rs_wr_patch_result *r = &pos.sol.patch[j];
      if (!r->loaded) continue;
      status = patch_interval(c, p, r, pos.V, &pos.cr[j], wr_nearest_patch(last, p), t0, t1,
                              o->interrupt_flag, ctx, &pos.d[j], &st, &next[j], msg);
    }
    for (int j = 0; j < RS_WR_MAX_PATCHES; j++) {
      wr_patch_state_free(&last[j]);
      last[j] = next[j];
    }
    res->newton += st.nonlin_iters;
    res->steps += st.steps;
    if (status == RS_OK) {
      pos.newton = st.nonlin_iters;
      times[k] = t1;
      wr_position_store(&pos, (size_t)k, pc, pp);
      double *row = pc + (size_t)k * C_POSITION_COLS;
      row[C_Y] = wk.lateral_displacement;
      row[C_YAW] = wk.yaw;
      row[C_OMEGA] = pos.omega;
      if (pos.geo.npatch > npatch) npatch = pos.geo.npatch;
      done++;
      if (out) {
        fprintf(out, "%9.5g %8.4g %9.4g", t1, wk.lateral_displacement, wk.yaw);
        const double *v = pp + (size_t)k * stride * P_PATCH_COLS;
        for (int j = 0; j < pos.geo.npatch; j++, v += P_PATCH_COLS)
          fprintf(out, "  | %8.3f %6.2f %9.1f %8.1f %8.1f", v[P_RAIL_Y], v[P_DELTA] * 180.0 / RS_PI,
                  v[P_FN], v[P_FX], v[P_FS]);
        fputc('\n', out);
      }
    }
    wr_position_free(&pos);
  }
  for (int j = 0; j < RS_WR_MAX_PATCHES; j++) wr_patch_state_free(&last[j]);
  if (ctx) SUNContext_Free(&ctx);
  if (status == RS_ERR_INTERRUPTED) interrupted = 1;
  int wstatus = RS_OK;
  if (times && pc && pp && cols && done > 0) {
    rs_positions_column spec[1 + C_POSITION_COLS + P_PATCH_COLS];
    spec[0] = (rs_positions_column){"time", "s", "time at the end of each interval", 0, times};
    for (int k = 0; k < C_POSITION_COLS; k++) {
      double *dcol = cols + (size_t)k * done;
      for (size_t i = 0; i < done; i++) dcol[i] = pc[i * C_POSITION_COLS + k];
      spec[1 + k] = wr_position_cols[k];
      spec[1 + k].data = dcol;
    }
    for (int k = 0; k < P_PATCH_COLS; k++) {
      double *dcol = cols + C_POSITION_COLS * done + (size_t)k * done * stride;
      for (size_t i = 0; i < done; i++)
        for (int j = 0; j < stride; j++)
          dcol[i * stride + j] = pp[(i * stride + j) * P_PATCH_COLS + k];
      spec[1 + C_POSITION_COLS + k] = wr_patch_cols[k];
      spec[1 + C_POSITION_COLS + k].data = dcol;
    }
    char status_text[700];
    if (interrupted)
      snprintf(status_text, sizeof status_text, "interrupted");
    else if (status != RS_OK)
      snprintf(status_text, sizeof status_text, "failed: %.600s", msg->text);
    else
      snprintf(status_text, sizeof status_text, "complete");
    const rs_positions_output po = {
        .path = o->output_path ? o->output_path : c->output_file,
        .title = c->title ? c->title : "",
        .history = o->history,
        .case_text = c->yaml_text ? c->yaml_text : "",
        .status = status_text,
        .frames = "per patch: x along the track, s along the profile's tangent (toward the track "
                  "centre), n the normal into the wheel; *_track: x along the track, y toward the "
                  "track centre, z up; forces on the wheel",
        .dim = "time",
        .npos = done,
        .npatch = npatch,
        .stride = stride,
        .ncols = 1 + C_POSITION_COLS + P_PATCH_COLS,
        .cols = spec};
    rs_msg wmsg = {{0}};
    wstatus = rs_positions_output_write(&po, res->backup, sizeof res->backup, &wmsg);
    if (wstatus == RS_OK)
      snprintf(res->file, sizeof res->file, "%s", po.path);
    else if (status == RS_OK)
      rs_msg_set(msg, wstatus, "%s", wmsg.text);
  }
  res->records = done;
  free(times);
  free(pc);
  free(pp);
  free(cols);
  if (status == RS_OK && wstatus != RS_OK) return wstatus;
  if (status == RS_OK && interrupted)
    return rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted: %zu of %zu intervals written", done,
                      n);
  return status;
}

/* OUT.nc -> OUT_patchK.nc (K from 1); a path without .nc gets _patchK.nc appended. */
static int patch_path(const char *base, int k, char *out, size_t len)
{
  size_t stem = strlen(base);
  if (stem > 3 && !strcmp(base + stem - 3, ".nc")) stem -= 3;
  return snprintf(out, len, "%.*s_patch%d.nc", (int)stem, base, k) < (int)len;
}

int rs_wheel_rail_run(const rs_case *c, const rs_run_opts *o, FILE *out, rs_wr_run_result *res,
                      rs_msg *msg)
{
  memset(res, 0, sizeof *res);
  const rs_wheel_rail *w = c->profiles;
  if (rs_wheel_rail_moving(c)) return path_run(c, o, out, res, msg);
  if (!(rs_history_eval(&c->velocity, 0.0) > 0.0))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "rolling.velocity: %g mm/s: a run on profiles needs the wheelset rolling "
                      "(the creepages are divided by its speed)",
                      rs_history_eval(&c->velocity, 0.0));
  /* the patches' loads and creepages of the steady vertical balance */
  wr_position pos;
  int status = wr_position_solve(c, w, 0.0, 0.0, 0.0, &pos, msg);
  if (status != RS_OK) return status;
  const char *base = o->output_path ? o->output_path : c->output_file;
  res->patches = pos.geo.npatch;
  for (int k = 0; k < pos.geo.npatch && status == RS_OK; k++) {
    const rs_wr_patch *p = &pos.geo.patch[k];
    const rs_wr_patch_result *r = &pos.sol.patch[k];
    if (!r->loaded) {
      if (out)
        fprintf(out, "patch %d: open (its gap exceeds the approach): nothing to run\n", k + 1);
      continue;
    }
    rs_creepages cr = pos.cr[k];
    if (!pos.tangential) {
      const wr_motion mo = {.V = pos.V, .psi = w->yaw, .omega = pos.omega};
      if ((status = wr_patch_creepages(p, &mo, &cr, msg)) != RS_OK) break;
    }
    rs_model_params par;
    double *pn = NULL;
    char path[1100];
    if (!patch_path(base, k + 1, path, sizeof path)) {
      status = rs_msg_set(msg, RS_ERR_INPUT, "output file %s: the name is too long", base);
      break;
    }
    if ((status = wr_patch_params(c, p, r, pos.V, &cr, &par, &pn, msg)) != RS_OK) break;
    char note[1400];
    snprintf(note, sizeof note,
             "patch %d of %d at lateral displacement %g mm, yaw %g rad: contact point y %.4f mm, "
             "z %.4f mm on the rail, contact angle %.6g rad, rolling radius %.4f mm, F_n %.9g N, "
             "creepages [%.9g, %.9g, %.9g]; x along the track, y along s (the profile's tangent "
             "toward the track centre, from the contact point), forces on the wheel",
             k + 1, pos.geo.npatch, w->lateral_displacement, w->yaw, p->y, p->z_rail, p->delta,
             p->rolling_radius, r->normal_force, cr.xi, cr.eta, cr.phi);
    rs_run_opts po = *o;
    po.output_path = path;
    po.params = &par;
    po.patch = note;
    rs_run_result rr;
    status = rs_run(c, &po, &rr, msg);
    free(pn);
    if (rr.records > 0) {
      res->runs++;
      res->newton += rr.stats.nonlin_iters;
      res->steps += rr.stats.steps;
      if (out)
        fprintf(out,
                "patch %d: contact angle %.2f deg, F_n %.6g N, creepages [%.6g, %.6g, %.6g]: F_x "
                "%.6g N, F_s %.6g N, M_n %.6g N mm at t = %g s (%zu records) -> %s%s%s%s\n",
                k + 1, p->delta * 180.0 / RS_PI, r->normal_force, cr.xi, cr.eta, cr.phi,
                rr.final.Fx, rr.final.Fy, rr.final.Mz, rr.time, rr.records, rr.file,
                *rr.backup ? " (the previous file kept as " : "", rr.backup, *rr.backup ? ")" : "");
    }
    rs_run_result_free(&rr);
  }
  wr_position_free(&pos);
  return status;
}
