/* The wheel-rail contact of a case's profiles: block (study/wheel_rail.h): the geometry and
 * the normal problem per patch (physics/wr_contact.h) for the block's position and load. */
#include "study/wheel_rail.h"

#include <math.h>
#include <stdlib.h>

#include "io/profile.h"
#include "physics/elastic2d.h" /* RS_PI */
#include "physics/history.h"
#include "physics/wr_contact.h"
#include "physics/wr_kinematics.h"
#include "solve/steady.h"
#include "study/run.h"

/* The creepages of a patch (docs/model.md §21) for the wheelset rolling along the track at V
 * (mm/s), yawed by psi, its wheel turning at omega about the axle: the profiles' frame taken as
 * a right wheel's, x along the track, y toward the track centre, z up; the contact point below
 * the axle by the patch's rolling radius, its tangent plane turned by the contact angle. */
static int patch_creepages(const rs_wr_patch *p, double V, double psi, double omega,
                           rs_creepages *cr, rs_msg *msg)
{
  const rs_wheelset_motion w = {.velocity = {V, 0.0, 0.0},
                                .omega = {-omega * sin(psi), omega * cos(psi), 0.0},
                                .centre = {0.0, 0.0, 0.0}};
  const double point[3] = {0.0, 0.0, -p->rolling_radius};
  rs_contact_frame f;
  /* the profiles' z grows downward: the rail's slope delta turns the tangent down toward +y */
  rs_wr_frame_from_angle(point, -p->delta, &f);
  return rs_wr_creepages(&w, &f, cr, msg);
}

/* The undeformed distance of a patch at (x, s) of its tangent plane (wr_contact.h). */
static double patch_gap_at(const void *ctx, double x, double s)
{
  const rs_wr_patch *p = ctx;
  return rs_wr_patch_h0(p, s) + x * x * cos(p->delta) / (2.0 * p->rolling_radius);
}

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

/* The steady tangential problem of a loaded patch on its grid, with the case's material,
 * friction and plasticity, the patch's normal force and its creepages: the forces on the
 * wheel in the patch's frame (F_x along the track, F_s along s, M_n about the normal through
 * the contact point) and the normal force of the model's own normal solution. */
static int patch_tangential(const rs_case *c, const rs_wr_patch *p, const rs_wr_patch_result *r,
                            double V, const rs_creepages *cr, rs_diag *d, rs_msg *msg)
{
  rs_model_params par;
  rs_model_params_from_case(c, &par);
  par.dimension = 3;
  par.cells = r->grid.nx;
  par.cells_y = r->grid.ny;
  par.grid_from_range = 1;
  par.x_range[0] = r->grid.x0;
  par.x_range[1] = r->grid.x0 + r->grid.nx * r->grid.dx;
  par.y_range[0] = r->grid.y0;
  par.y_range[1] = r->grid.y0 + r->grid.ny * r->grid.dy;
  par.radius = p->rolling_radius / cos(p->delta);
  par.radius_y = lateral_radius(p, r, par.radius);
  par.gap_at = patch_gap_at;
  par.gap_ctx = p;
  par.force_control = 0;
  par.load = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = r->normal_force};
  par.velocity = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = V};
  par.creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->xi};
  par.lateral_creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->eta};
  par.spin = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = cr->phi};
  rs_model m;
  int status = rs_model_create(&m, &par, msg);
  if (status != RS_OK) return status;
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_steady *s = NULL;
  rs_stats st = {0};
  status = y && yp ? rs_steady_create(&s, &m, NULL, msg)
                   : rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a patch's solution");
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, msg);
  rs_steady_free(s);
  if (status == RS_OK) {
    rs_work w;
    rs_inputs in;
    rs_model_inputs_at(&m, 0.0, &in);
    status = rs_work_create(&w, &m);
    if (status == RS_OK) {
      status = rs_model_diagnostics(&m, &w, &in, y, yp, d, NULL, NULL, NULL);
      rs_work_free(&w);
    }
  }
  free(y);
  free(yp);
  rs_model_free(&m);
  return status;
}

int rs_wheel_rail_given(const rs_case *c) { return c->profiles && c->profiles->vertical_load > 0; }

int rs_wheel_rail_print(const rs_case *c, FILE *out, rs_msg *msg)
{
  const rs_wheel_rail *w = c->profiles;
  if (!w || !(w->vertical_load > 0)) return RS_OK;
  rs_wr_input in;
  int status = rs_wheel_rail_input(w, &in, msg);
  if (status != RS_OK) return status;
  rs_wr_geometry geo;
  if ((status = rs_wr_geometry_build(&in, &geo, msg)) != RS_OK) return status;
  rs_wr_solution sol;
  status = rs_wr_normal_solve(&geo, w->vertical_load, c->shear_modulus, c->poisson_ratio,
                              w->grid_cells[0], w->grid_cells[1], &sol, msg);
  if (status != RS_OK) {
    rs_wr_geometry_free(&geo);
    return status;
  }
  const double deg = 180.0 / RS_PI, V = rs_history_eval(&c->velocity, 0.0);
  const double omega =
      w->wheel_angular_velocity > 0.0 ? w->wheel_angular_velocity : V / w->nominal_rolling_radius;
  fprintf(out,
          "# wheel-rail contact at lateral displacement %g mm under %g N (docs/model.md §20)\n",
          w->lateral_displacement, w->vertical_load);
  fprintf(out,
          "wheel_rail.wheel_shift: %.6f  # mm, y on the rail profile = y on the wheel's + this\n",
          in.wheel_shift);
  fprintf(out, "wheel_rail.patches: %d  # of %d gap minima, grouped by patch_separation %g mm\n",
          geo.npatch, geo.minima, w->patch_separation);
  fprintf(out, "wheel_rail.vertical_approach: %.6g  # mm, of the wheel from first contact\n",
          sol.dz);
  fprintf(out, "wheel_rail.vertical_force: %.9g  # N, sum of F_n cos(contact angle)\n",
          sol.vertical);
  fprintf(out,
          "wheel_rail.motion: [%.9g, %.9g, %.9g]  # V mm/s (rolling.velocity), yaw rad, the "
          "wheel's angular velocity rad/s%s\n",
          V, w->yaw, omega,
          w->wheel_angular_velocity > 0.0 ? "" : " (pure rolling of the nominal radius)");
  for (int k = 0; k < geo.npatch; k++) {
    const rs_wr_patch *p = &geo.patch[k];
    const rs_wr_patch_result *r = &sol.patch[k];
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
    rs_creepages cr;
    if (!(V > 0.0)) continue;
    if ((status = patch_creepages(p, V, w->yaw, omega, &cr, msg)) != RS_OK) break;
    fprintf(out,
            "wheel_rail.patch%d.creepages: [%.6g, %.6g, %.6g]  # xi, eta, phi (1/mm) of the "
            "wheel against the rail (docs/model.md §21)\n",
            k + 1, cr.xi, cr.eta, cr.phi);
    rs_diag d;
    if ((status = patch_tangential(c, p, r, V, &cr, &d, msg)) != RS_OK) break;
    fprintf(out,
            "wheel_rail.patch%d.tangential: [%.6g, %.6g, %.6g]  # F_x N, F_s N, M_n N mm on the "
            "wheel, steady rolling (F_n %.6g N on the patch's grid)\n",
            k + 1, d.Fx, d.Fy, d.Mz, d.Fn);
    fprintf(out,
            "wheel_rail.patch%d.grid: [[%.4f, %.4f], [%.4f, %.4f]]  # mm, x and s, %d x %d "
            "cells\n",
            k + 1, r->grid.x0, r->grid.x0 + r->grid.nx * r->grid.dx, r->grid.y0,
            r->grid.y0 + r->grid.ny * r->grid.dy, r->grid.nx, r->grid.ny);
  }
  fprintf(out,
          "# %d grid round(s), %d normal solves; the contact: block's Hertz contact is not used "
          "(nothing derived from it is printed)\n",
          sol.grid_rounds, sol.normal_solves);
  rs_wr_solution_free(&sol);
  rs_wr_geometry_free(&geo);
  return status;
}
