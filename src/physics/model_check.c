/* Reported quantities (model.md §7) and the check of steady states (rollsim/model.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/model_internal.h"

int rs_model_diagnostics(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                         const double *yp, rs_diag *d, double *slip, double *tauc,
                         signed char *regime)
{
  const rs_layout *L = &m->lay;
  const int n = L->n;
  const double V = in->velocity, xi = rs_model_creepage(m, in, y), dA = m->grid.area;
  const double vrigid = V * xi + in->shift_velocity;
  /* Branches with the steady scaling (any r > 0 gives the same regimes at a solution). */
  const int status = rs_model_residual(m, w, in, y, yp, 0.0, NULL);
  if (status != RS_OK) return status;
  memset(d, 0, sizeof *d);
  d->creepage = xi;
  d->velocity = V;
  for (int i = 0; i < n; i++) {
    const double p = y[rs_at_p(L, 0, i)];
    rs_regime reg = RS_ADHESION;
    if (w->branch[i] & RS_BRANCH_EXTERIOR)
      reg = RS_EXTERIOR;
    else if (w->branch[i] & RS_BRANCH_SLIP)
      reg = RS_SLIP;
    else if (w->branch[i] & RS_BRANCH_YIELD)
      reg = RS_PLASTIC;
    d->count[reg]++;
    d->Fx += p * dA;
    d->Fn += w->pn[i] * dA;
    d->frictional_power -= p * w->vslip[i] * dA;
    d->plastic_power += p * w->dupl[i] * dA;
    d->elastic_energy += 0.5 * p * w->uel[i] * dA;
    d->rigid_slip_power -= p * vrigid * dA;
    if (slip) slip[i] = V > 0.0 ? w->vslip[i] / V : w->vslip[i];
    if (tauc) tauc[i] = rs_model_yield_limit(m, y[rs_at_ustar(L, i)]);
    if (regime) regime[i] = (signed char)reg;
  }
  return RS_OK;
}

/* Reason of the first failed condition, in the user's terms. */
static int refuse(rs_msg *msg, const rs_model *m, int i, const char *what, double p, double other,
                  const char *other_name, const char *unit)
{
  return rs_msg_set(msg, RS_ERR_SOLVER,
                    "steady solution refused: cell %d (x = %.4g mm): %s (p_x = %.6g N/mm^2, %s = "
                    "%.6g %s)",
                    i, m->grid.x[i % m->grid.nx], what, p, other_name, other, unit);
}

/* The paper's conditions (eqs. 7-10) cell by cell on the kinematics in w (of a steady
 * evaluation), rates in traction units through the steady scaling r. */
static int check_cells(const rs_model *m, const rs_work *w, const double *y, double tol,
                       rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n;
  const double r = w->r;
  for (int i = 0; i < n; i++) {
    const double p = y[rs_at_p(L, 0, i)], g = w->bound[i];
    const double tauc = rs_model_yield_limit(m, y[rs_at_ustar(L, i)]);
    const double vs = w->vslip[i], flow = w->dupl[i];
    if (!(w->pn[i] > 0.0)) {
      if (fabs(p) > tol)
        return refuse(msg, m, i, "traction outside the contact", p, w->pn[i], "p_n", "N/mm^2");
      if (r * fabs(flow) > tol)
        return refuse(msg, m, i, "plastic flow outside the contact", p, flow, "Du_pl/Dt", "mm/s");
      continue;
    }
    if (fabs(p) > g + tol)
      return refuse(msg, m, i, "traction above the bound g = mu p_n", p, g, "g", "N/mm^2");
    if (fabs(p) > tauc + tol)
      return refuse(msg, m, i, "traction above the yield limit", p, tauc, "tau_c", "N/mm^2");
    if (r * fabs(vs) > tol) { /* slipping: at the bound, the slip opposite to p */
      if (fabs(p) < g - tol)
        return refuse(msg, m, i, "slip below the traction bound", p, vs, "v_s", "mm/s");
      if (p * vs > 0.0)
        return refuse(msg, m, i, "slip along the traction (negative frictional power)", p, vs,
                      "v_s", "mm/s");
    }
    if (r * fabs(flow) > tol) { /* flowing: at the yield limit, the flow parallel to p */
      if (fabs(p) < tauc - tol)
        return refuse(msg, m, i, "plastic flow below the yield limit", p, flow, "Du_pl/Dt", "mm/s");
      if (p * flow < 0.0)
        return refuse(msg, m, i, "plastic flow opposite to the traction (negative plastic power)",
                      p, flow, "Du_pl/Dt", "mm/s");
    }
    if (r * fabs(w->dustar[i] - fabs(flow)) > tol)
      return refuse(msg, m, i, "u* does not grow with |Du_pl/Dt|", p, w->dustar[i], "Du*/Dt",
                    "mm/s");
  }
  return RS_OK;
}

int rs_model_check_steady(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                          rs_msg *msg)
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
  int status = rs_model_residual(m, w, in, y, yp, 0.0, NULL);
  double pref = 0.0;
  for (int i = 0; i < m->grid.n && status == RS_OK; i++) pref = fmax(pref, w->bound[i]);
  if (!(pref > 0.0)) pref = 1.0;
  const double tol = RS_STEADY_CHECK_TOL * pref;
  if (status != RS_OK)
    rs_msg_set(msg, status, "%s", w->msg.text);
  else
    status = check_cells(m, w, y, tol, msg);
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
