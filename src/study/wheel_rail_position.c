/* One wheelset position of a case's profiles: block (study/wheel_rail_internal.h): the patches'
 * creepages and steady tangential problems, the vertical balance with the tangential forces. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study/wheel_rail_internal.h"

#include "physics/history.h"
#include "solve/steady.h"
#include "study/run.h"

/* The creepages of a patch (docs/model.md §21) for the wheelset rolling along the track: the
 * profiles' frame taken as a right wheel's, x along the track, y toward the track centre, z up;
 * the contact point below the axle by its axle height (the rolling radius without yaw) and
 * ahead by its lead x, its tangent plane turned by the contact angle. The yaw rate about the
 * wheelset's centre moves the axle point above the contact along x by -yaw_rate times its
 * lateral offset from the centre. */
int wr_patch_creepages(const rs_wr_patch *p, const wr_motion *mo, rs_creepages *cr, rs_msg *msg)
{
  const rs_wheelset_motion w = {
      .velocity = {mo->V + mo->yaw_rate * mo->to_centre, mo->v_lateral, 0.0},
      .omega = {-mo->omega * sin(mo->psi), mo->omega * cos(mo->psi), mo->yaw_rate},
      .centre = {0.0, 0.0, 0.0}};
  const double point[3] = {p->x, 0.0, -p->axle_height};
  rs_contact_frame f;
  /* the profiles' z grows downward: the rail's slope delta turns the tangent down toward +y */
  rs_wr_frame_from_angle(point, -p->delta, &f);
  return rs_wr_creepages(&w, &f, cr, msg);
}

/* The undeformed distance of a patch at (x, s) of its tangent plane (wr_contact.h). */
static double patch_gap_at(const void *ctx, double x, double s) { return rs_wr_patch_h(ctx, x, s); }

/* Curvature radius of h(0, s) over the loaded part of the patch, from its ends: the Hertz
 * scale of the lateral direction (the solvers' weights). A flat or conformal patch (no
 * positive curvature) gets 1000 times the longitudinal radius. */
static double lateral_radius(const rs_wr_patch *p, const rs_wr_patch_result *r, double rx)
{
  const double lo = r->s_extent[0], hi = r->s_extent[1];
  const double rise = rs_wr_patch_h0(p, lo) + rs_wr_patch_h0(p, hi) - 2.0 * rs_wr_patch_h0(p, 0.0);
  const double ry = rise > 0.0 ? (lo * lo + hi * hi) / (2.0 * rise) : 1e3 * rx;
  return fmin(fmax(ry, 1e-3 * rx), 1e3 * rx);
}

/* The model of a loaded patch's tangential problem: the case's material, friction and
 * plasticity, the patch's gap, normal force and pressure, its creepages. Its grid is the
 * patch's cut to its contact cells and TANGENTIAL_MARGIN cells around them: the cells outside
 * carry no traction, and the margin keeps every contact cell's upstream neighbour, the same
 * problem on fewer cells. *pn_out (the pressure on that grid, which par points to) is the
 * caller's to free once the model is created. */
#define TANGENTIAL_MARGIN 1
int wr_patch_params(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r, double V,
                    const rs_creepages *cr, rs_model_params *par, double **pn_out, rs_msg *msg)
{
  const rs_grid3d *g = &r->grid;
  int lo[2] = {g->nx, g->ny}, hi[2] = {-1, -1};
  for (int j = 0; j < g->ny; j++)
    for (int i = 0; i < g->nx; i++)
      if (r->pn[(size_t)j * g->nx + i] > 0.0) {
        lo[0] = i < lo[0] ? i : lo[0];
        hi[0] = i > hi[0] ? i : hi[0];
        lo[1] = j < lo[1] ? j : lo[1];
        hi[1] = j > hi[1] ? j : hi[1];
      }
  for (int a = 0; a < 2; a++) {
    const int n = a ? g->ny : g->nx;
    lo[a] = lo[a] - TANGENTIAL_MARGIN > 0 ? lo[a] - TANGENTIAL_MARGIN : 0;
    hi[a] = hi[a] + TANGENTIAL_MARGIN < n - 1 ? hi[a] + TANGENTIAL_MARGIN : n - 1;
  }
  const int nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1;
  if (nx < 1 || ny < 1) return rs_msg_set(msg, RS_ERR_INTERNAL, "a loaded patch without pressure");
  double *pn = *pn_out = malloc((size_t)nx * ny * sizeof *pn);
  if (!pn) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a patch's solution");
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      pn[(size_t)j * nx + i] = r->pn[(size_t)(j + lo[1]) * g->nx + i + lo[0]];
  rs_model_params_from_case(c, par);
  par->dimension = 3;
  par->cells = nx;
  par->cells_y = ny;
  par->grid_from_range = 1;
  par->x_range[0] = g->x0 + lo[0] * g->dx;
  par->x_range[1] = g->x0 + (hi[0] + 1) * g->dx;
  par->y_range[0] = g->y0 + lo[1] * g->dy;
  par->y_range[1] = g->y0 + (hi[1] + 1) * g->dy;
  par->radius = p->rolling_radius / cos(p->delta);
  par->radius_y = lateral_radius(p, r, par->radius);
  par->gap_at = patch_gap_at;
  par->gap_ctx = p;
  par->normal_pressure = pn; /* the load sharing's solution on this grid */
  par->normal_approach = r->approach;
  par->force_control = 0;
  par->load = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = r->normal_force};
  par->velocity = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = V};
  par->creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->xi};
  par->lateral_creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->eta};
  par->spin = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->phi};
  return RS_OK;
}

void wr_patch_state_free(patch_state *k)
{
  if (k->valid) {
    rs_model_free(&k->m);
    free(k->y);
  }
  memset(k, 0, sizeof *k);
}

/* The patch of the last round or interval a patch continues: the nearest on the rail, within
 * CARRY_DISTANCE mm and CARRY_ANGLE rad of contact angle (else it starts from rest: a new
 * patch, or a jump from the tread to the flange). */
const patch_state *wr_nearest_patch(const patch_state *last, const rs_wr_patch *p)
{
  const patch_state *best = NULL;
  for (int j = 0; j < RS_WR_MAX_PATCHES; j++)
    if (last[j].valid && fabs(last[j].rail_y - p->y) <= CARRY_DISTANCE &&
        fabs(last[j].delta - p->delta) <= CARRY_ANGLE &&
        (!best || fabs(last[j].rail_y - p->y) < fabs(best->rail_y - p->y)))
      best = &last[j];
  return best;
}

/* The state of `from` carried onto the model m of the patch now at rail_y: interpolated in
 * (x, s) with s shifted by the contact point's move along the profile, (rail_y - from's) /
 * cos(delta), so that a point of the surface keeps its place on the rail. */
int wr_carry_state(const patch_state *from, double rail_y, double delta, const rs_model *m,
                   rs_work *w, const rs_inputs *in, double *y, rs_msg *msg)
{
  const double ds = (rail_y - from->rail_y) / cos(delta);
  const int ny = from->m.grid.ny;
  double *ys = malloc((size_t)ny * sizeof *ys);
  if (!ys) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (int j = 0; j < ny; j++) ys[j] = from->m.grid.y[j] - ds;
  rs_model shifted = from->m; /* shallow: only its grid and layout are read */
  shifted.grid.y = ys;
  const int status = rs_model_interpolate_state(&shifted, from->y, m, w, in, y, msg);
  free(ys);
  return status;
}

int wr_patch_model(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r, double V,
                   const rs_creepages *cr, rs_model *m, rs_work *w, double **y, double **yp,
                   rs_msg *msg)
{
  rs_model_params par;
  double *pn = NULL;
  int status = wr_patch_params(c, p, r, V, cr, &par, &pn, msg);
  if (status != RS_OK) return status;
  status = rs_model_create(m, &par, msg);
  free(pn);
  if (status != RS_OK) return status;
  *y = calloc((size_t)m->lay.neq, sizeof **y);
  *yp = calloc((size_t)m->lay.neq, sizeof **yp);
  if (*y && *yp && rs_work_create(w, m) == RS_OK) return RS_OK;
  free(*y);
  free(*yp);
  rs_model_free(m);
  return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a patch's solution");
}

int wr_patch_finish(int status, const rs_wr_patch *p, rs_model *m, rs_work *w, double *y,
                    double *yp, patch_state *keep)
{
  rs_work_free(w);
  free(yp);
  if (status == RS_OK && keep) {
    *keep = (patch_state){.valid = 1, .m = *m, .y = y, .rail_y = p->y, .delta = p->delta};
    return RS_OK;
  }
  free(y);
  rs_model_free(m);
  return status;
}

/* The steady tangential problem of a loaded patch (wr_patch_params): the forces on the wheel in
 * the patch's frame (F_x along the track, F_s along s, M_n about the normal through the
 * contact point) and the normal force of the model's pressure. With `from` (the same patch in
 * the last round of the vertical balance) Newton starts from its solution carried over, and
 * from rest if that fails; with `keep` the model and solution are kept. */
int wr_patch_tangential(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                        double V, const rs_creepages *cr, rs_diag *d, long *newton,
                        const patch_state *from, patch_state *keep, rs_msg *msg)
{
  rs_model m;
  rs_work w;
  double *y, *yp;
  int status = wr_patch_model(c, p, r, V, cr, &m, &w, &y, &yp, msg);
  if (status != RS_OK) return status;
  rs_steady *s = NULL;
  rs_stats st = {0};
  rs_inputs in;
  rs_model_inputs_at(&m, 0.0, &in);
  status = rs_steady_create(&s, &m, NULL, msg);
  if (status == RS_OK && from) {
    rs_msg ignored = {{0}};
    if (wr_carry_state(from, p->y, p->delta, &m, &w, &in, y, &ignored) != RS_OK ||
        rs_steady_solve(s, 0.0, y, &st, &ignored) != RS_OK) {
      memset(y, 0, (size_t)m.lay.neq * sizeof *y);
      status = rs_steady_solve(s, 0.0, y, &st, msg);
    }
  } else if (status == RS_OK) {
    status = rs_steady_solve(s, 0.0, y, &st, msg);
  }
  *newton += st.nonlin_iters;
  rs_steady_free(s);
  if (status == RS_OK) status = rs_model_diagnostics(&m, &w, &in, y, yp, d, NULL, NULL, NULL);
  return wr_patch_finish(status, p, &m, &w, y, yp, keep);
}

/* The wheel's vertical force (up) of a solved position: each loaded patch's normal force and,
 * rolling, its tangential force along s, turned by the contact angle. */
double wr_vertical_force(const wr_position *pos)
{
  double fz = 0.0;
  for (int k = 0; k < pos->geo.npatch; k++) {
    const rs_wr_patch_result *r = &pos->sol.patch[k];
    if (!r->loaded) continue;
    const double delta = pos->geo.patch[k].delta;
    fz += r->normal_force * cos(delta) - (pos->tangential ? pos->d[k].Fy * sin(delta) : 0.0);
  }
  return fz;
}

void wr_position_free(wr_position *pos)
{
  rs_wr_solution_free(&pos->sol);
  rs_wr_geometry_free(&pos->geo);
}

/* Solve the position of w (the case's block or a sweep's copy of it). On failure nothing is
 * left to free. */
/* Tolerance and most rounds of the vertical balance with the tangential forces. */
#define BALANCE_TOL 1e-6
#define BALANCE_MAX 30

/* The patches' normal problems balancing `load` (sum F_n cos(delta)) and, rolling, each loaded
 * patch's creepages and steady tangential solution. */
static int position_round(const rs_case *c, const rs_wheel_rail *w, double load, wr_position *pos,
                          patch_state *last, rs_msg *msg)
{
  patch_state kept[RS_WR_MAX_PATCHES] = {{0}};
  int status = rs_wr_normal_solve(&pos->geo, load, c->shear_modulus, c->poisson_ratio,
                                  w->grid_cells[0], w->grid_cells[1], &pos->sol, msg);
  for (int k = 0; status == RS_OK && pos->tangential && k < pos->geo.npatch; k++) {
    const rs_wr_patch *p = &pos->geo.patch[k];
    const rs_wr_patch_result *r = &pos->sol.patch[k];
    if (!r->loaded) continue;
    const wr_motion mo = {.V = pos->V,
                          .psi = w->yaw,
                          .omega = pos->omega,
                          .v_lateral = pos->v_lateral,
                          .yaw_rate = pos->yaw_rate,
                          .to_centre = pos->centre - p->y};
    status = wr_patch_creepages(p, &mo, &pos->cr[k], msg);
    if (status == RS_OK)
      status =
          wr_patch_tangential(c, p, r, pos->V, &pos->cr[k], &pos->d[k], &pos->newton,
                              last ? wr_nearest_patch(last, p) : NULL, last ? &kept[k] : NULL, msg);
  }
  for (int k = 0; last && k < RS_WR_MAX_PATCHES; k++) { /* the next round starts from these */
    wr_patch_state_free(&last[k]);
    last[k] = kept[k];
  }
  pos->normal_load = load;
  pos->balance_rounds++;
  return status;
}

/* Everything at the position of w: the patches, and the load the normal problems balance
 * found by the secant method so that the wheel's whole vertical force, tangential forces
 * included, is the wheel load to BALANCE_TOL (docs/model.md §20, "Vertical balance"). On
 * failure nothing is left to free. */
int wr_position_solve(const rs_case *c, const rs_wheel_rail *w, double t, double v_lateral,
                      double yaw_rate, wr_position *pos, rs_msg *msg)
{
  memset(pos, 0, sizeof *pos);
  rs_wr_input in;
  int status = rs_wheel_rail_input(w, &in, msg);
  if (status != RS_OK) return status;
  if ((status = rs_wr_geometry_build(&in, &pos->geo, msg)) != RS_OK) return status;
  pos->v_lateral = v_lateral;
  pos->yaw_rate = yaw_rate;
  /* the track centre line is at y = gauge/2 + y_gauge on the rail profile (io/profile.h), the
   * wheelset's centre line there less the lateral displacement */
  pos->centre = in.wheel_shift + 0.5 * w->flange_back_distance + w->flange_back_position;
  pos->V = rs_history_eval(&c->velocity, t);
  pos->omega = w->wheel_angular_velocity > 0.0 ? w->wheel_angular_velocity
                                               : pos->V / w->nominal_rolling_radius;
  pos->tangential = pos->V > 0.0;
  const double fz = w->vertical_load;
  double load = fz, load_last = 0.0, miss_last = 0.0, miss = 0.0;
  patch_state last[RS_WR_MAX_PATCHES] = {{0}};
  for (int round = 0; status == RS_OK; round++) {
    if (round > 0) rs_wr_solution_free(&pos->sol);
    status = position_round(c, w, load, pos, last, msg);
    if (status != RS_OK) break;
    pos->vertical = wr_vertical_force(pos);
    miss = pos->vertical - fz;
    if (!pos->tangential || fabs(miss) <= BALANCE_TOL * fz) break;
    if (round + 1 == BALANCE_MAX) {
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "the wheel's vertical force with the tangential forces did not balance "
                          "the wheel load in %d rounds: %.9g N against %.9g N",
                          BALANCE_MAX, pos->vertical, fz);
      break;
    }
    /* the first step as if the tangential forces grew in proportion to the normal ones (as
     * at full slip), then secant steps */
    const double next = round == 0 || miss == miss_last
                            ? load * fz / pos->vertical
                            : load - miss * (load - load_last) / (miss - miss_last);
    load_last = load;
    miss_last = miss;
    load = next > 0.0 ? next : 0.5 * load;
  }
  for (int k = 0; k < RS_WR_MAX_PATCHES; k++) wr_patch_state_free(&last[k]);
  if (status != RS_OK) wr_position_free(pos);
  return status;
}
