/* rollsim sweep on profiles (study/wheel_rail.h): a path of wheelset positions into one file
 * over (position, patch); the file's columns, which a moving wheelset's run writes over time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study/wheel_rail_internal.h"

#include "base/util.h"
#include "physics/elastic2d.h" /* RS_PI */

const rs_positions_column wr_position_cols[C_POSITION_COLS] = {
    {"lateral_displacement", "mm", "lateral displacement of the wheelset toward this rail", 0, 0},
    {"yaw", "rad", "yaw angle of the wheelset", 0, 0},
    {"wheel_angular_velocity", "rad/s", "angular velocity of the wheel about its axle", 0, 0},
    {"patches", "1", "contact patches found (loaded or open)", 0, 0},
    {"vertical_approach", "mm", "vertical approach of the wheel from first contact", 0, 0},
    {"Fx_track", "N", "force on the wheel along the track, summed over the patches", 0, 0},
    {"Fy_track", "N", "lateral force on the wheel toward the track centre, summed", 0, 0},
    {"Fz_track", "N", "vertical force on the wheel (up), summed", 0, 0},
    {"newton_iterations", "1", "Newton iterations of the tangential solves", 0, 0},
    {"converged", "1", "1: solved; 0: this position failed (its values NaN)", 0, 0},
};
const rs_positions_column wr_patch_cols[P_PATCH_COLS] = {
    {"rail_y", "mm", "contact point on the rail: y of the inclined rail profile", 1, 0},
    {"rail_z", "mm", "contact point on the rail: z (downward) of the inclined rail profile", 1, 0},
    {"wheel_y", "mm", "contact point on the wheel: y of the wheel profile", 1, 0},
    {"wheel_z", "mm", "contact point on the wheel: z of the wheel profile", 1, 0},
    {"contact_angle", "rad", "contact angle (positive toward the flange)", 1, 0},
    {"rolling_radius", "mm", "rolling radius of the wheel at the contact point", 1, 0},
    {"Fn", "N", "normal force on the patch", 1, 0},
    {"normal_approach", "mm", "normal approach of the patch", 1, 0},
    {"area", "mm2", "contact area (cells in contact)", 1, 0},
    {"max_pressure", "N/mm2", "maximum pressure", 1, 0},
    {"xi", "1", "longitudinal creepage of the wheel against the rail", 1, 0},
    {"eta", "1", "lateral creepage (along s)", 1, 0},
    {"phi", "1/mm", "spin creepage", 1, 0},
    {"Fx", "N", "tangential force on the wheel along the track", 1, 0},
    {"Fs", "N", "tangential force on the wheel along s (the profile's tangent)", 1, 0},
    {"Mn", "N mm", "spin moment on the wheel about the normal through the contact point", 1, 0},
};

void wr_position_store(const wr_position *pos, size_t i, double *pc, double *pp)
{
  double *row = pc + i * C_POSITION_COLS, *patch = pp + i * RS_WR_MAX_PATCHES * P_PATCH_COLS;
  row[C_NPATCH] = pos->geo.npatch;
  row[C_DZ] = pos->sol.dz;
  row[C_NEWTON] = (double)pos->newton;
  row[C_CONVERGED] = 1.0;
  double F[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < pos->geo.npatch; k++) {
    const rs_wr_patch *p = &pos->geo.patch[k];
    const rs_wr_patch_result *r = &pos->sol.patch[k];
    double *v = patch + (size_t)k * P_PATCH_COLS;
    v[P_RAIL_Y] = p->y;
    v[P_RAIL_Z] = p->z_rail;
    v[P_WHEEL_Y] = p->y_wheel;
    v[P_WHEEL_Z] = p->z_wheel;
    v[P_DELTA] = p->delta;
    v[P_RADIUS] = p->rolling_radius;
    v[P_FN] = r->loaded ? r->normal_force : 0.0;
    if (!r->loaded) continue;
    v[P_APPROACH] = r->approach;
    v[P_AREA] = r->area;
    v[P_PMAX] = r->p_max;
    /* the wheel's forces in the track frame (x along the track, y toward the track centre,
     * z up): s = (0, cos delta, -sin delta), n = (0, sin delta, cos delta) (docs/model.md §21) */
    const double cd = cos(p->delta), sd = sin(p->delta), fn = r->normal_force;
    double fx = 0.0, fs = 0.0;
    if (pos->tangential) {
      v[P_XI] = pos->cr[k].xi;
      v[P_ETA] = pos->cr[k].eta;
      v[P_PHI] = pos->cr[k].phi;
      v[P_FX] = fx = pos->d[k].Fx;
      v[P_FS] = fs = pos->d[k].Fy;
      v[P_MN] = pos->d[k].Mz;
    }
    F[0] += fx;
    F[1] += fs * cd + fn * sd;
    F[2] += -fs * sd + fn * cd;
  }
  row[C_FX_TRACK] = F[0];
  row[C_FY_TRACK] = F[1];
  row[C_FZ_TRACK] = F[2];
}

int rs_wheel_rail_sweep(const rs_case *c, const rs_sweep *sw, const rs_wr_sweep_opts *o,
                        rs_wr_sweep_result *res, rs_msg *msg)
{
  memset(res, 0, sizeof *res);
  const size_t n = sw->npoints;
  const int stride = RS_WR_MAX_PATCHES;
  double *pc = malloc(n * C_POSITION_COLS * sizeof *pc);
  double *pp = malloc(n * (size_t)stride * P_PATCH_COLS * sizeof *pp);
  double *cols = malloc(n * (C_POSITION_COLS + (size_t)stride * P_PATCH_COLS) * sizeof *cols);
  if (!pc || !pp || !cols) {
    free(pc);
    free(pp);
    free(cols);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the sweep's %zu positions", n);
  }
  for (size_t i = 0; i < n * C_POSITION_COLS; i++) pc[i] = NAN;
  for (size_t i = 0; i < n * (size_t)stride * P_PATCH_COLS; i++) pp[i] = NAN;
  const double t0 = rs_wall_clock();
  int npatch = 1, interrupted = 0;
  char first_error[512] = "";
  for (size_t i = 0; i < n; i++) {
    if (o->interrupt_flag && *o->interrupt_flag) {
      interrupted = 1;
      break;
    }
    rs_wheel_rail w = *c->profiles;
    rs_msg ignored = {{0}};
    for (int a = 0; a < sw->naxes; a++) /* values checked by rs_sweep_load */
      rs_wheel_rail_set(&w, sw->axes[a].key + 9, sw->axes[a].values[i], &ignored);
    double *row = pc + i * C_POSITION_COLS;
    row[C_Y] = w.lateral_displacement;
    row[C_YAW] = w.yaw;
    row[C_OMEGA] = w.wheel_angular_velocity > 0.0
                       ? w.wheel_angular_velocity
                       : rs_history_eval(&c->velocity, 0.0) / w.nominal_rolling_radius;
    wr_position pos;
    rs_msg pm = {{0}};
    if (wr_position_solve(c, &w, 0.0, 0.0, 0.0, &pos, &pm) != RS_OK) {
      row[C_CONVERGED] = 0.0;
      res->failed++;
      if (!*first_error)
        snprintf(first_error, sizeof first_error,
                 "position %zu (lateral displacement %g mm): %.400s", i + 1, w.lateral_displacement,
                 pm.text);
      if (o->table)
        fprintf(o->table, "%8g %9.4g  failed: %s\n", w.lateral_displacement, w.yaw, pm.text);
      continue;
    }
    wr_position_store(&pos, i, pc, pp);
    if (pos.geo.npatch > npatch) npatch = pos.geo.npatch;
    res->newton += pos.newton;
    res->done++;
    if (o->table) {
      fprintf(o->table, "%8g %9.4g", w.lateral_displacement, w.yaw);
      const double *v = pp + i * (size_t)stride * P_PATCH_COLS;
      for (int k = 0; k < pos.geo.npatch; k++, v += P_PATCH_COLS)
        fprintf(o->table, "  | %8.3f %7.2f %9.1f %8.1f %8.1f", v[P_RAIL_Y],
                v[P_DELTA] * 180.0 / RS_PI, v[P_FN], v[P_FX], v[P_FS]);
      fputc('\n', o->table);
    }
    wr_position_free(&pos);
  }
  res->wall_seconds = rs_wall_clock() - t0;
  /* the columns laid out for the writer: position columns [n], patch columns [n][stride] */
  rs_positions_column spec[C_POSITION_COLS + P_PATCH_COLS];
  for (int k = 0; k < C_POSITION_COLS; k++) {
    double *d = cols + (size_t)k * n;
    for (size_t i = 0; i < n; i++) d[i] = pc[i * C_POSITION_COLS + k];
    spec[k] = wr_position_cols[k];
    spec[k].data = d;
  }
  for (int k = 0; k < P_PATCH_COLS; k++) {
    double *d = cols + C_POSITION_COLS * n + (size_t)k * n * stride;
    for (size_t i = 0; i < n; i++)
      for (int j = 0; j < stride; j++) d[i * stride + j] = pp[(i * stride + j) * P_PATCH_COLS + k];
    spec[C_POSITION_COLS + k] = wr_patch_cols[k];
    spec[C_POSITION_COLS + k].data = d;
  }
  char status_text[700];
  if (interrupted)
    snprintf(status_text, sizeof status_text, "interrupted");

  else if (res->failed)
    snprintf(status_text, sizeof status_text, "failed: %zu of %zu positions; the first: %.500s",
             res->failed, n, first_error);
  else
    snprintf(status_text, sizeof status_text, "complete");
  const rs_positions_output out = {
      .path = o->output_path,
      .title = c->title ? c->title : "",
      .history = o->history,
      .case_text = o->case_text,
      .status = status_text,
      .frames = "per patch: x along the track, s along the profile's tangent (toward the track "
                "centre), n the normal into the wheel; *_track: x along the track, y toward the "
                "track centre, z up; forces on the wheel",
      .npos = n,
      .npatch = npatch,
      .stride = stride,
      .ncols = C_POSITION_COLS + P_PATCH_COLS,
      .cols = spec};
  int status = rs_positions_output_write(&out, res->backup, sizeof res->backup, msg);
  if (status == RS_OK) snprintf(res->file, sizeof res->file, "%s", o->output_path);
  if (status == RS_OK && interrupted)
    status = rs_msg_set(msg, RS_ERR_INTERRUPTED, "interrupted: %zu of %zu positions written",
                        res->done + res->failed, n);
  else if (status == RS_OK && res->failed)
    status = rs_msg_set(msg, RS_ERR_SOLVER, "%s", status_text + strlen("failed: "));
  free(pc);
  free(pp);
  free(cols);
  return status;
}
