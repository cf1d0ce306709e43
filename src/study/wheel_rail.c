/* The wheel-rail contact of a case's profiles: block (study/wheel_rail.h): the geometry and
 * the normal problem per patch (physics/wr_contact.h) for the block's position and load. */
#include "study/wheel_rail.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "io/output.h"
#include "io/profile.h"
#include "physics/elastic2d.h" /* RS_PI */
#include "physics/history.h"
#include "physics/wr_contact.h"
#include "physics/wr_kinematics.h"
#include "solve/steady.h"
#include "study/run.h"

/* The wheelset's motion at one time: forward speed V (mm/s), yaw psi (rad), the wheel's
 * angular velocity omega about the axle (rad/s); moving wheelsets also the lateral velocity
 * toward the track centre (mm/s), the yaw rate (rad/s) and the distance from the contact's
 * lateral position to the wheelset's centre line (mm, toward the track centre). */
typedef struct wr_motion {
  double V, psi, omega;
  double v_lateral, yaw_rate, to_centre;
} wr_motion;

/* The creepages of a patch (docs/model.md §21) for the wheelset rolling along the track: the
 * profiles' frame taken as a right wheel's, x along the track, y toward the track centre, z up;
 * the contact point below the axle by its axle height (the rolling radius without yaw) and
 * ahead by its lead x, its tangent plane turned by the contact angle. The yaw rate about the
 * wheelset's centre moves the axle point above the contact along x by -yaw_rate times its
 * lateral offset from the centre. */
static int patch_creepages(const rs_wr_patch *p, const wr_motion *mo, rs_creepages *cr, rs_msg *msg)
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
static int patch_params(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                        double V, const rs_creepages *cr, rs_model_params *par, double **pn_out,
                        rs_msg *msg)
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

/* A patch's solution kept for the next round of the vertical balance or the next interval of a
 * moving wheelset: its model (only its grid and layout are read later) and state. */
typedef struct patch_state {
  int valid;
  rs_model m;
  double *y;
  double rail_y, delta; /* the contact point on the rail (mm) and the contact angle (rad) */
} patch_state;

static void patch_state_free(patch_state *k)
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
#define CARRY_DISTANCE 2.0
#define CARRY_ANGLE    0.05
static const patch_state *nearest_patch(const patch_state *last, const rs_wr_patch *p)
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
static int carry_state(const patch_state *from, double rail_y, double delta, const rs_model *m,
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

/* The steady tangential problem of a loaded patch (patch_params): the forces on the wheel in
 * the patch's frame (F_x along the track, F_s along s, M_n about the normal through the
 * contact point) and the normal force of the model's pressure. With `from` (the same patch in
 * the last round of the vertical balance) Newton starts from its solution carried over, and
 * from rest if that fails; with `keep` the model and solution are kept. */
static int patch_tangential(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                            double V, const rs_creepages *cr, rs_diag *d, long *newton,
                            const patch_state *from, patch_state *keep, rs_msg *msg)
{
  rs_model_params par;
  double *pn = NULL;
  int status = patch_params(c, p, r, V, cr, &par, &pn, msg);
  if (status != RS_OK) return status;
  rs_model m;
  status = rs_model_create(&m, &par, msg);
  free(pn);
  if (status != RS_OK) return status;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_steady *s = NULL;
  rs_stats st = {0};
  rs_work w;
  int have_work = 0;
  rs_inputs in;
  rs_model_inputs_at(&m, 0.0, &in);
  status = y && yp ? rs_steady_create(&s, &m, NULL, msg)
                   : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a patch's solution");
  if (status == RS_OK) {
    status = rs_work_create(&w, &m);
    have_work = status == RS_OK;
  }
  if (status == RS_OK && from) {
    rs_msg ignored = {{0}};
    if (carry_state(from, p->y, p->delta, &m, &w, &in, y, &ignored) != RS_OK ||
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
  if (have_work) rs_work_free(&w);
  free(yp);
  if (status == RS_OK && keep) {
    *keep = (patch_state){.valid = 1, .m = m, .y = y, .rail_y = p->y, .delta = p->delta};
    return RS_OK;
  }
  free(y);
  rs_model_free(&m);
  return status;
}

int rs_wheel_rail_given(const rs_case *c) { return c->profiles && c->profiles->vertical_load > 0; }

int rs_wheel_rail_moving(const rs_case *c)
{
  return rs_wheel_rail_given(c) && c->mode == RS_MODE_TRANSIENT &&
         (!rs_history_is_constant(&c->profiles->lateral_history) ||
          !rs_history_is_constant(&c->profiles->yaw_history));
}

/* Everything at one wheelset position: the patches, the load sharing and, rolling, each
 * loaded patch's creepages and steady tangential solution. */
typedef struct wr_position {
  rs_wr_geometry geo;
  rs_wr_solution sol;
  double V, omega; /* mm/s, rad/s */
  int tangential;  /* 1: V > 0, cr and d of the loaded patches filled */
  rs_creepages cr[RS_WR_MAX_PATCHES];
  rs_diag d[RS_WR_MAX_PATCHES];
  long newton;                /* Newton iterations of the tangential solves */
  double v_lateral, yaw_rate; /* a moving wheelset's (mm/s toward the track centre, rad/s) */
  double centre;              /* the wheelset's centre line, y on the rail profile (mm) */
  double normal_load;         /* N: sum F_n cos(delta), the load the normal problem balanced */
  double vertical;    /* N: the wheel's vertical force sum (F_n cos(delta) - F_s sin(delta)) */
  int balance_rounds; /* normal and tangential solves of the vertical balance */
} wr_position;

/* The wheel's vertical force (up) of a solved position: each loaded patch's normal force and,
 * rolling, its tangential force along s, turned by the contact angle. */
static double vertical_force(const wr_position *pos)
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

static void position_free(wr_position *pos)
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
    status = patch_creepages(p, &mo, &pos->cr[k], msg);
    if (status == RS_OK)
      status = patch_tangential(c, p, r, pos->V, &pos->cr[k], &pos->d[k], &pos->newton,
                                last ? nearest_patch(last, p) : NULL, last ? &kept[k] : NULL, msg);
  }
  for (int k = 0; last && k < RS_WR_MAX_PATCHES; k++) { /* the next round starts from these */
    patch_state_free(&last[k]);
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
static int position_solve(const rs_case *c, const rs_wheel_rail *w, double t, double v_lateral,
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
    pos->vertical = vertical_force(pos);
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
  for (int k = 0; k < RS_WR_MAX_PATCHES; k++) patch_state_free(&last[k]);
  if (status != RS_OK) position_free(pos);
  return status;
}

int rs_wheel_rail_print(const rs_case *c, FILE *out, rs_msg *msg)
{
  const rs_wheel_rail *w = c->profiles;
  if (!w || !(w->vertical_load > 0)) return RS_OK;
  wr_position pos;
  int status = position_solve(c, w, 0.0, 0.0, 0.0, &pos, msg);
  if (status != RS_OK) return status;
  const rs_wr_geometry *geo = &pos.geo;
  const rs_wr_solution *sol = &pos.sol;
  rs_wr_input in;
  rs_wheel_rail_input(w, &in, msg);
  const double deg = 180.0 / RS_PI, V = pos.V, omega = pos.omega;
  fprintf(out,
          "# wheel-rail contact at lateral displacement %g mm under %g N (docs/model.md §20)\n",
          w->lateral_displacement, w->vertical_load);
  fprintf(out,
          "wheel_rail.wheel_shift: %.6f  # mm, y on the rail profile = y on the wheel's + this\n",
          in.wheel_shift);
  fprintf(out, "wheel_rail.patches: %d  # of %d gap minima, grouped by patch_separation %g mm\n",
          geo->npatch, geo->minima, w->patch_separation);
  fprintf(out, "wheel_rail.vertical_approach: %.6g  # mm, of the wheel from first contact\n",
          sol->dz);
  fprintf(out,
          "wheel_rail.vertical_force: %.9g  # N, the wheel's, sum of F_n cos(contact angle) %s\n",
          pos.tangential ? pos.vertical : sol->vertical,
          pos.tangential ? "- F_s sin(contact angle) (rolling)" : "(not rolling)");
  if (pos.tangential)
    fprintf(out,
            "wheel_rail.normal_share: %.9g  # N, sum of F_n cos(contact angle), %d round(s) of "
            "the vertical balance\n",
            sol->vertical, pos.balance_rounds);
  fprintf(out,
          "wheel_rail.motion: [%.9g, %.9g, %.9g]  # V mm/s (rolling.velocity), yaw rad, the "
          "wheel's angular velocity rad/s%s\n",
          V, w->yaw, omega,
          w->wheel_angular_velocity > 0.0 ? "" : " (pure rolling of the nominal radius)");
  for (int k = 0; k < geo->npatch; k++) {
    const rs_wr_patch *p = &geo->patch[k];
    const rs_wr_patch_result *r = &sol->patch[k];
    fprintf(out, "wheel_rail.patch%d.rail_point: [%.4f, %.4f]  # mm, y z on the rail (inclined)\n",
            k + 1, p->y, p->z_rail);
    fprintf(out, "wheel_rail.patch%d.wheel_point: [%.4f, %.4f]  # mm, y z on the wheel profile\n",
            k + 1, p->y_wheel, p->z_wheel);
    fprintf(out, "wheel_rail.patch%d.contact_angle: %.4f  # deg\n", k + 1, p->delta * deg);
    fprintf(out, "wheel_rail.patch%d.rolling_radius: %.4f  # mm\n", k + 1, p->rolling_radius);
    fprintf(out, "wheel_rail.patch%d.gap: %.6f  # mm, vertical, with the wheel at first contact\n",
            k + 1, p->gap);
    if (!r->loaded) {
      fprintf(out, "wheel_rail.patch%d.normal_force: 0  # N, open: its gap exceeds the approach\n",
              k + 1);
      continue;
    }
    fprintf(out, "wheel_rail.patch%d.normal_force: %.6g  # N\n", k + 1, r->normal_force);
    fprintf(out, "wheel_rail.patch%d.normal_approach: %.6g  # mm\n", k + 1, r->approach);
    fprintf(out, "wheel_rail.patch%d.area: %.5g  # mm^2, cells in contact\n", k + 1, r->area);
    fprintf(out, "wheel_rail.patch%d.extent_x: [%.4f, %.4f]  # mm, along the track\n", k + 1,
            r->x_extent[0], r->x_extent[1]);
    fprintf(out,
            "wheel_rail.patch%d.extent_s: [%.4f, %.4f]  # mm, along the profile from the "
            "contact point\n",
            k + 1, r->s_extent[0], r->s_extent[1]);
    fprintf(out, "wheel_rail.patch%d.max_pressure: %.6g  # N/mm^2\n", k + 1, r->p_max);
    if (!pos.tangential) continue;
    const rs_creepages *cr = &pos.cr[k];
    fprintf(out,
            "wheel_rail.patch%d.creepages: [%.6g, %.6g, %.6g]  # xi, eta, phi (1/mm) of the "
            "wheel against the rail (docs/model.md §21)\n",
            k + 1, cr->xi, cr->eta, cr->phi);
    const rs_diag *d = &pos.d[k];
    fprintf(out,
            "wheel_rail.patch%d.tangential: [%.6g, %.6g, %.6g]  # F_x N, F_s N, M_n N mm on the "
            "wheel, steady rolling (F_n %.6g N on the patch's grid)\n",
            k + 1, d->Fx, d->Fy, d->Mz, d->Fn);
    fprintf(out,
            "wheel_rail.patch%d.grid: [[%.4f, %.4f], [%.4f, %.4f]]  # mm, x and s, %d x %d "
            "cells\n",
            k + 1, r->grid.x0, r->grid.x0 + r->grid.nx * r->grid.dx, r->grid.y0,
            r->grid.y0 + r->grid.ny * r->grid.dy, r->grid.nx, r->grid.ny);
  }
  fprintf(out,
          "# %d grid round(s), %d normal solves; the contact: block's Hertz contact is not used "
          "(nothing derived from it is printed)\n",
          sol->grid_rounds, sol->normal_solves);
  position_free(&pos);
  return RS_OK;
}

/* The columns of a sweep file on profiles (docs/file-format.md "Wheel-rail sweep files"). */
enum {
  C_Y,
  C_YAW,
  C_OMEGA,
  C_NPATCH,
  C_DZ,
  C_FX_TRACK,
  C_FY_TRACK,
  C_FZ_TRACK,
  C_NEWTON,
  C_CONVERGED,
  C_POSITION_COLS
};
enum {
  P_RAIL_Y,
  P_RAIL_Z,
  P_WHEEL_Y,
  P_WHEEL_Z,
  P_DELTA,
  P_RADIUS,
  P_FN,
  P_APPROACH,
  P_AREA,
  P_PMAX,
  P_XI,
  P_ETA,
  P_PHI,
  P_FX,
  P_FS,
  P_MN,
  P_PATCH_COLS
};
static const rs_positions_column position_cols[C_POSITION_COLS] = {
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
static const rs_positions_column patch_cols[P_PATCH_COLS] = {
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

static void position_store(const wr_position *pos, const rs_wheel_rail *w, size_t i, double *pc,
                           double *pp)
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
  (void)w;
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
    if (position_solve(c, &w, 0.0, 0.0, 0.0, &pos, &pm) != RS_OK) {
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
    position_store(&pos, &w, i, pc, pp);
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
    position_free(&pos);
  }
  res->wall_seconds = rs_wall_clock() - t0;
  /* the columns laid out for the writer: position columns [n], patch columns [n][stride] */
  rs_positions_column spec[C_POSITION_COLS + P_PATCH_COLS];
  for (int k = 0; k < C_POSITION_COLS; k++) {
    double *d = cols + (size_t)k * n;
    for (size_t i = 0; i < n; i++) d[i] = pc[i * C_POSITION_COLS + k];
    spec[k] = position_cols[k];
    spec[k].data = d;
  }
  for (int k = 0; k < P_PATCH_COLS; k++) {
    double *d = cols + C_POSITION_COLS * n + (size_t)k * n * stride;
    for (size_t i = 0; i < n; i++)
      for (int j = 0; j < stride; j++) d[i * stride + j] = pp[(i * stride + j) * P_PATCH_COLS + k];
    spec[C_POSITION_COLS + k] = patch_cols[k];
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

/* One patch over one interval of a moving wheelset: its model at the interval's start, its
 * state carried from `from` (or rest), the transient to t1; the forces at t1 into d and the
 * model and state into keep. */
static int patch_interval(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                          double V, const rs_creepages *cr, const patch_state *from, double t0,
                          double t1, volatile sig_atomic_t *interrupt, SUNContext ctx, rs_diag *d,
                          rs_stats *stats, patch_state *keep, rs_msg *msg)
{
  rs_model_params par;
  double *pn = NULL;
  int status = patch_params(c, p, r, V, cr, &par, &pn, msg);
  if (status != RS_OK) return status;
  rs_model m;
  status = rs_model_create(&m, &par, msg);
  free(pn);
  if (status != RS_OK) return status;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_work w;
  int have_work = 0;
  rs_inputs in;
  rs_model_inputs_at(&m, t0, &in);
  status = y && yp ? rs_work_create(&w, &m) : RS_ERR_INTERNAL;
  if (status != RS_OK) status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a patch");
  have_work = status == RS_OK;
  if (status == RS_OK) {
    rs_model_rest_state(&m, y);
    if (from) status = carry_state(from, p->y, p->delta, &m, &w, &in, y, msg);
  }
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
  if (have_work) rs_work_free(&w);
  free(yp);
  if (status == RS_OK) {
    *keep = (patch_state){.valid = 1, .m = m, .y = y, .rail_y = p->y, .delta = p->delta};
    return RS_OK;
  }
  free(y);
  rs_model_free(&m);
  return status;
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
    status = position_solve(c, &wk, t0, -rs_history_rate(&w0->lateral_history, t0),
                            rs_history_rate(&w0->yaw_history, t0), &pos, msg);
    if (status != RS_OK) break;
    patch_state next[RS_WR_MAX_PATCHES] = {{0}};
    rs_stats st = {0};
    for (int j = 0; status == RS_OK && j < pos.geo.npatch; j++) {
      const rs_wr_patch *p = &pos.geo.patch[j];
      const rs_wr_patch_result *r = &pos.sol.patch[j];
      if (!r->loaded) continue;
      status = patch_interval(c, p, r, pos.V, &pos.cr[j], nearest_patch(last, p), t0, t1,
                              o->interrupt_flag, ctx, &pos.d[j], &st, &next[j], msg);
    }
    for (int j = 0; j < RS_WR_MAX_PATCHES; j++) {
      patch_state_free(&last[j]);
      last[j] = next[j];
    }
    res->newton += st.nonlin_iters;
    res->steps += st.steps;
    if (status == RS_OK) {
      pos.newton = st.nonlin_iters;
      times[k] = t1;
      position_store(&pos, &wk, (size_t)k, pc, pp);
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
    position_free(&pos);
  }
  for (int j = 0; j < RS_WR_MAX_PATCHES; j++) patch_state_free(&last[j]);
  if (ctx) SUNContext_Free(&ctx);
  if (status == RS_ERR_INTERRUPTED) interrupted = 1;
  int wstatus = RS_OK;
  if (times && pc && pp && cols && done > 0) {
    rs_positions_column spec[1 + C_POSITION_COLS + P_PATCH_COLS];
    spec[0] = (rs_positions_column){"time", "s", "time at the end of each interval", 0, times};
    for (int k = 0; k < C_POSITION_COLS; k++) {
      double *dcol = cols + (size_t)k * done;
      for (size_t i = 0; i < done; i++) dcol[i] = pc[i * C_POSITION_COLS + k];
      spec[1 + k] = position_cols[k];
      spec[1 + k].data = dcol;
    }
    for (int k = 0; k < P_PATCH_COLS; k++) {
      double *dcol = cols + C_POSITION_COLS * done + (size_t)k * done * stride;
      for (size_t i = 0; i < done; i++)
        for (int j = 0; j < stride; j++)
          dcol[i * stride + j] = pp[(i * stride + j) * P_PATCH_COLS + k];
      spec[1 + C_POSITION_COLS + k] = patch_cols[k];
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
  /* the patches' loads and creepages of the steady vertical balance */
  wr_position pos;
  int status = position_solve(c, w, 0.0, 0.0, 0.0, &pos, msg);
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
      if ((status = patch_creepages(p, &mo, &cr, msg)) != RS_OK) break;
    }
    rs_model_params par;
    double *pn = NULL;
    char path[1100];
    if (!patch_path(base, k + 1, path, sizeof path)) {
      status = rs_msg_set(msg, RS_ERR_INPUT, "output file %s: the name is too long", base);
      break;
    }
    if ((status = patch_params(c, p, r, pos.V, &cr, &par, &pn, msg)) != RS_OK) break;
    char note[400];
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
  position_free(&pos);
  return status;
}
