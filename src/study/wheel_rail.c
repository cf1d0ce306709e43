/* The wheel-rail contact of a case's profiles: block (study/wheel_rail.h): rollsim check's
 * patches and forces at the block's position (the sweep and the runs: wheel_rail_sweep.c,
 * wheel_rail_run.c). */
#include "study/wheel_rail.h"

#include <math.h>

#include "physics/elastic2d.h" /* RS_PI */
#include "physics/history.h"
#include "study/wheel_rail_internal.h"

int rs_wheel_rail_given(const rs_case *c) { return c->profiles && c->profiles->vertical_load > 0; }

int rs_wheel_rail_moving(const rs_case *c)
{
  return rs_wheel_rail_given(c) && c->mode == RS_MODE_TRANSIENT &&
         (!rs_history_is_constant(&c->profiles->lateral_history) ||
          !rs_history_is_constant(&c->profiles->yaw_history));
}

int rs_wheel_rail_print(const rs_case *c, FILE *out, rs_msg *msg)
{
  const rs_wheel_rail *w = c->profiles;
  if (!w || !(w->vertical_load > 0)) return RS_OK;
  wr_position pos;
  int status = wr_position_solve(c, w, 0.0, 0.0, 0.0, &pos, msg);
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
  wr_position_free(&pos);
  return RS_OK;
}
