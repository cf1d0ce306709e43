/* Reported quantities (docs/model.md §7) and the check of steady states (physics/model.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "physics/model_internal.h"

int rs_model_diagnostics(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                         const double *yp, rs_diag *d, double *slip, double *tauc,
                         signed char *regime)
{
  /* Branches with the steady scaling (any r > 0 gives the same regimes at a solution). */
  const int status = rs_model_residual(m, w, in, y, yp, 0.0, NULL);
  if (status != RS_OK) return status;
  rs_model_diagnostics_of(m, w, in, y, d, slip, tauc, regime);
  return RS_OK;
}

void rs_model_diagnostics_of(const rs_model *m, const rs_work *w, const rs_inputs *in,
                             const double *y, rs_diag *d, double *slip, double *tauc,
                             signed char *regime)
{
  const rs_layout *L = &m->lay;
  const rs_grid *g = &m->grid;
  const int n = L->n, nc = L->ncomp, px = g->nx + 1;
  const double V = in->velocity, xi = rs_model_creepage(m, in, y), dA = g->area;
  const double eta = rs_model_lateral_creepage(m, in, y), phi = nc > 1 ? in->spin : 0.0;
  memset(d, 0, sizeof *d);
  d->creepage = xi;
  d->lateral_creepage = eta;
  d->spin = phi;
  d->velocity = V;
  if (nc > 1 && m->normal_load > 0.0 && in->load > 0.0) {
    /* at fixed curvatures and materials a and b grow as F^(1/3) (the ellipse's shape does
     * not depend on the load): from the model's semi-axes at its largest load */
    const double s = in->load == m->normal_load ? 1.0 : cbrt(in->load / m->normal_load);
    d->hertz_a = m->hertz_a * s;
    d->hertz_b = m->hertz_b * s;
  }
  for (int i = 0; i < n; i++) {
    const int ix = i % g->nx, iy = i / g->nx;
    rs_regime reg = RS_ADHESION;
    if (w->branch[i] & RS_BRANCH_EXTERIOR)
      reg = RS_EXTERIOR;
    else if (w->branch[i] & RS_BRANCH_SLIP)
      reg = RS_SLIP;
    else if (w->branch[i] & RS_BRANCH_YIELD)
      reg = RS_PLASTIC;
    d->count[reg]++;
    d->Fn += w->pn[i] * dA;
    for (int c = 0; c < nc; c++) {
      const double p = y[rs_at_p(L, c, i)];
      /* rigid slip V w = V (xi - phi y, eta + phi x) (+ the shift along x) */
      const double vrigid =
          c == 0 ? V * (xi - phi * g->y[iy]) + in->shift_velocity : V * (eta + phi * g->x[ix]);
      if (c == 0)
        d->Fx += p * dA;
      else
        d->Fy += p * dA;
      d->frictional_power -= p * w->vslip[c * n + i] * dA;
      d->plastic_power += p * w->dupl[c * n + i] * dA;
      d->elastic_energy += 0.5 * p * w->uel[(size_t)c * px * g->ny + iy * px + ix] * dA;
      d->rigid_slip_power -= p * vrigid * dA;
      if (slip) slip[c * n + i] = V > 0.0 ? w->vslip[c * n + i] / V : w->vslip[c * n + i];
    }
    if (nc > 1) d->Mz += (g->x[ix] * y[rs_at_p(L, 1, i)] - g->y[iy] * y[rs_at_p(L, 0, i)]) * dA;
    if (tauc) tauc[i] = rs_model_yield_limit(m, i, y[rs_at_ustar(L, i)]);
    if (regime) regime[i] = (signed char)reg;
  }
}

void rs_model_power_densities(const rs_model *m, const rs_work *w, const double *y,
                              double *frictional, double *plastic)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  for (int i = 0; i < n; i++) {
    double pf = 0.0, pp = 0.0;
    for (int c = 0; c < nc; c++) {
      const double p = y[rs_at_p(L, c, i)];
      pf -= p * w->vslip[c * n + i];
      pp += p * w->dupl[c * n + i];
    }
    frictional[i] = pf;
    plastic[i] = pp;
  }
}

void rs_model_power_jv(const rs_model *m, const rs_work *w, rs_work *wlin, const rs_inputs *in,
                       double cj, const double *y, const double *v, const double *vp,
                       double *dfrictional, double *dplastic)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  rs_inputs lin = *in;
  lin.linear = 1; /* the rates' linear part: no rigid slip, no inflow */
  rs_model_kinematics_scaled(m, wlin, &lin, v, vp, cj);
  for (int i = 0; i < n; i++) {
    double pf = 0.0, pp = 0.0;
    for (int c = 0; c < nc; c++) {
      const double p = y[rs_at_p(L, c, i)], dp = v[rs_at_p(L, c, i)];
      pf -= dp * w->vslip[c * n + i] + p * wlin->vslip[c * n + i];
      pp += dp * w->dupl[c * n + i] + p * wlin->dupl[c * n + i];
    }
    dfrictional[i] = pf;
    dplastic[i] = pp;
  }
}

/* Reason of the first failed condition, in the user's terms. */
static int refuse(rs_msg *msg, const rs_model *m, int i, const char *what, double p, double other,
                  const char *other_name, const char *unit)
{
  char where[64] = "";
  if (m->lay.ncomp > 1) snprintf(where, sizeof where, ", y = %.4g mm", m->grid.y[i / m->grid.nx]);
  return rs_msg_set(msg, RS_ERR_SOLVER,
                    "steady solution refused: cell %d (x = %.4g mm%s): %s (p_x = %.6g N/mm^2, %s "
                    "= %.6g %s)",
                    i, m->grid.x[i % m->grid.nx], where, what, p, other_name, other, unit);
}

/* The paper's conditions (eqs. 7-10) cell by cell on the kinematics in w (of a steady
 * evaluation), rates in traction units through the steady scaling r. Directions (3D):
 * slip opposite to p and flow along p to an angle of 1e-6 (a converged solution has
 * them exact up to the Newton tolerance). */
static int check_cells(const rs_model *m, const rs_work *w, const double *y, double tol,
                       rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  const double r = w->r;
  for (int i = 0; i < n; i++) {
    double p[RS_MAX_COMP], vs[RS_MAX_COMP], flow[RS_MAX_COMP];
    double pn2 = 0.0, vs2 = 0.0, fl2 = 0.0, pv = 0.0, pf = 0.0;
    for (int c = 0; c < nc; c++) {
      p[c] = y[rs_at_p(L, c, i)];
      vs[c] = w->vslip[c * n + i];
      flow[c] = w->dupl[c * n + i];
      pn2 += p[c] * p[c];
      vs2 += vs[c] * vs[c];
      fl2 += flow[c] * flow[c];
      pv += p[c] * vs[c];
      pf += p[c] * flow[c];
    }
    /* each cell's own bound: mu(|v_s|) p_n with velocity-dependent friction */
    const double pa = sqrt(pn2), va = sqrt(vs2), fa = sqrt(fl2), g = w->law[i].g;
    const double tauc = rs_model_yield_limit(m, i, y[rs_at_ustar(L, i)]);
    const double px = p[0], cos_tol = nc > 1 ? 1e-6 : 0.0;
    if (!(w->pn[i] > 0.0)) {
      if (pa > tol)
        return refuse(msg, m, i, "traction outside the contact", px, w->pn[i], "p_n", "N/mm^2");
      if (r * fa > tol)
        return refuse(msg, m, i, "plastic flow outside the contact", px, flow[0], "Du_pl/Dt",
                      "mm/s");
      continue;
    }
    if (pa > g + tol)
      return refuse(msg, m, i, "traction above the bound g = mu p_n", px, g, "g", "N/mm^2");
    if (pa > tauc + tol)
      return refuse(msg, m, i, "traction above the yield limit", px, tauc, "tau_c", "N/mm^2");
    if (r * va > tol) { /* slipping: at the bound, the slip opposite to p */
      if (pa < g - tol)
        return refuse(msg, m, i, "slip below the traction bound", px, vs[0], "v_s", "mm/s");
      if (pv > -(1.0 - cos_tol) * pa * va)
        return refuse(msg, m, i,
                      nc == 1 ? "slip along the traction (negative frictional power)"
                              : "slip not opposite to the traction",
                      px, vs[0], "v_s", "mm/s");
    }
    if (r * fa > tol) { /* flowing: at the yield limit, the flow parallel to p */
      if (pa < tauc - tol)
        return refuse(msg, m, i, "plastic flow below the yield limit", px, flow[0], "Du_pl/Dt",
                      "mm/s");
      if (pf < (1.0 - cos_tol) * pa * fa)
        return refuse(msg, m, i,
                      nc == 1 ? "plastic flow opposite to the traction (negative plastic power)"
                              : "plastic flow not along the traction",
                      px, flow[0], "Du_pl/Dt", "mm/s");
    }
    if (r * fabs(w->dustar[i] - fa) > tol)
      return refuse(msg, m, i, "u* does not grow with |Du_pl/Dt|", px, w->dustar[i], "Du*/Dt",
                    "mm/s");
    /* Softening: a flowing cell whose upstream neighbour does not flow and whose bound lies
     * below the yield limit of the material entering it. That material slides before it
     * can yield; the cell yields only because its own flow, through the jump of u* across
     * one cell of the upwind difference, lowers tau_c below g. A zero of the discrete
     * equations (the cell keeps itself soft) that no transient from fresh material reaches
     * and that has no continuum counterpart (u* is continuous along the material path). */
    if (m->par.plasticity.k_tau < 0.0 && r * fa > tol) {
      const int up = rs_grid_upstream(&m->grid, i);
      const int iy = i / m->grid.nx;
      double up_flow = 0.0;
      for (int c = 0; c < nc && up >= 0; c++) up_flow += w->dupl[c * n + up] * w->dupl[c * n + up];
      const double us_up = up >= 0 ? y[rs_at_ustar(L, up)] : w->inflow[iy * (nc + 1) + nc];
      const double tauc_up = rs_model_yield_limit(m, i, us_up);
      if (!(r * sqrt(up_flow) > tol) && g < tauc_up - tol)
        return refuse(msg, m, i,
                      "plastic flow where the material entering the cell slides before it "
                      "yields (softening within one cell)",
                      px, tauc_up, "tau_c upstream", "N/mm^2");
    }
  }
  return RS_OK;
}

int rs_model_check_steady(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                          rs_msg *msg)
{
  return rs_model_check_steady_with(m, NULL, w, in, y, msg);
}

int rs_model_check_steady_with(const rs_model *m, const rs_work *ws, rs_work *w,
                               const rs_inputs *in, const double *y, rs_msg *msg)
{
  const int neq = m->lay.neq;
  double *F = malloc((size_t)neq * sizeof *F), *yp = calloc((size_t)neq, sizeof *yp);
  if (!F || !yp) {
    free(F);
    free(yp);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory checking the steady solution");
  }
  /* Kinematics of the steady state: y' = 0 gives the same v_s, Du_pl/Dt and Dustar/Dt
   * for every c_j. */
  int status = RS_OK;
  if (!ws) {
    status = rs_model_residual(m, w, in, y, yp, 0.0, NULL);
    ws = w;
  }
  double pref = 0.0;
  for (int i = 0; i < m->grid.n && status == RS_OK; i++) pref = fmax(pref, ws->bound[i]);
  if (!(pref > 0.0)) pref = 1.0;
  const double tol = RS_STEADY_CHECK_TOL * pref;
  if (status != RS_OK)
    rs_msg_set(msg, status, "%s", w->msg.text);
  else
    status = check_cells(m, ws, y, tol, msg);
  /* The residual of the transient at y' = 0, with the scaling of a time step of one
   * cell passage (c_j = V/dx): another r, the same zero set. */
  if (status == RS_OK) {
    status =
        rs_model_residual(m, w, in, y, yp, in->velocity > 0.0 ? in->velocity / m->grid.dx : 0.0, F);
    if (status != RS_OK) rs_msg_set(msg, status, "%s", w->msg.text);
  }
  if (status == RS_OK) {
    int worst = 0;
    for (int i = 1; i < neq; i++)
      if (fabs(F[i]) > fabs(F[worst])) worst = i;
    if (!(fabs(F[worst]) <= tol))
      status = rs_msg_set(msg, RS_ERR_SOLVER,
                          "steady solution refused: the transient residual there is %.3g N/mm^2 "
                          "(row %d, allowed %.3g): not a steady state of the DAE",
                          fabs(F[worst]), worst, tol);
  }
  free(F);
  free(yp);
  return status;
}
