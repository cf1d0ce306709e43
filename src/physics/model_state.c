/* States of the model (rollsim/model.h): consistent rates, projection on the admissible
 * tractions, interpolation between grids. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "physics/model_internal.h"
#include "rollsim/normal.h"

int rs_model_consistent_rates(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                              double *yp, rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n;
  const double *us = y + rs_at_ustar(L, 0);
  const double a = in->velocity / m->grid.dx, c3 = m->layer_flex;
  memset(yp, 0, (size_t)L->neq * sizeof *yp);
  int status = rs_model_normal_at(m, w, in, msg);
  if (status != RS_OK) return status;

  /* One more row and column with force control: the border. */
  const int nb = n + 1;
  int *adh = malloc((size_t)n * sizeof *adh);
  int *ipiv = malloc((size_t)nb * sizeof *ipiv);
  double *mat = malloc((size_t)nb * (size_t)nb * sizeof *mat);
  double *rhs = malloc((size_t)nb * sizeof *rhs);
  if (!adh || !ipiv || !mat || !rhs) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory computing the initial rates");
    goto done;
  }
  /* Cells at the traction bound follow it: p' = sign(p) g'(t) (a load history moves g;
   * g' by a difference quotient of the normal solution in the load). */
  if (in->load_rate != 0.0) {
    const double h = 1e-6 * in->load, mu = rs_friction_mu(&m->par.friction, 0.0);
    status = rs_model_pressure(m, &w->ew, in->load + h, rhs, NULL, msg);
    if (status != RS_OK) goto done;
    for (int i = 0; i < n; i++) {
      const double p = y[rs_at_p(L, 0, i)];
      if (rs_contact_state(&m->par.plasticity, w->pn[i] > 0.0, fabs(p), w->bound[i], us[i]) ==
          RS_STATE_AT_BOUND)
        yp[rs_at_p(L, 0, i)] = rs_sign_of(p) * mu * (rhs[i] - w->pn[i]) / h * in->load_rate;
    }
  }
  rs_model_kinematics(m, w, in, y, yp); /* with p' = 0 inside: v_s holds all but A p'_H */
  int h = 0;
  for (int i = 0; i < n; i++)
    if (rs_contact_state(&m->par.plasticity, w->pn[i] > 0.0, fabs(y[rs_at_p(L, 0, i)]), w->bound[i],
                         us[i]) == RS_STATE_INSIDE)
      adh[h++] = i;
  if (h > 0) {
    /* Adhesion: v_s = 0 with Du_pl/Dt = 0, i.e. (A + c3 I) p'_H = -v_s(p'_H = 0).
     * Force control: v_s = V xi + ..., xi unknown, and dA sum p' = F_x'(t). */
    const int fc = m->par.force_control, hb = h + fc;
    const double V = in->velocity, xi = fc ? y[rs_at_extra(L, 0)] : 0.0;
    for (int c = 0; c < h; c++) {
      for (int r = 0; r < h; r++)
        mat[(size_t)c * hb + r] =
            rs_elastic_op_coef(&m->el, 0, 0, adh[r] - adh[c], 0) + (r == c ? c3 : 0.0);
      rhs[c] = -(w->vslip[adh[c]] - V * xi);
    }
    if (fc) {
      double known = 0.0; /* dA sum of the rates fixed above (cells on the bound) */
      for (int i = 0; i < n; i++) known += yp[rs_at_p(L, 0, i)] * m->grid.area;
      for (int r = 0; r < h; r++) mat[(size_t)h * hb + r] = V; /* column of xi */
      for (int c = 0; c < h; c++) mat[(size_t)c * hb + h] = m->grid.area;
      mat[(size_t)h * hb + h] = 0.0;
      rhs[h] = in->force_rate - known;
    }
    int one = 1, info = 0;
    dgesv_(&hb, &one, mat, &hb, ipiv, rhs, &hb, &info);
    if (info != 0) {
      status =
          rs_msg_set(msg, RS_ERR_SOLVER, "initial rates: singular adhesion system (info %d)", info);
      goto done;
    }
    for (int c = 0; c < h; c++) yp[rs_at_p(L, 0, adh[c])] = rhs[c];
    if (fc) y[rs_at_extra(L, 0)] = rhs[h];
  }
  rs_model_kinematics(m, w, in, y, yp);
  double upl_in, us_in;
  rs_model_inflow(m, in, &upl_in, &us_in);
  /* Transport of u_pl and u*: Du/Dt = 0, except plastic flow where |p| is at a yield
   * limit below the bound (flow takes up the slip velocity left over). */
  for (int i = 0; i < n; i++) {
    double flow = 0.0;
    if (rs_contact_state(&m->par.plasticity, w->pn[i] > 0.0, fabs(y[rs_at_p(L, 0, i)]), w->bound[i],
                         us[i]) == RS_STATE_AT_YIELD)
      flow = -(w->vslip[i] - w->dupl[i]);
    const int up = rs_grid_upstream(&m->grid, i);
    const double upl_next = up >= 0 ? y[rs_at_upl(L, 0, up)] : upl_in;
    const double us_next = up >= 0 ? us[up] : us_in;
    yp[rs_at_upl(L, 0, i)] = flow + a * (upl_next - y[rs_at_upl(L, 0, i)]);
    yp[rs_at_ustar(L, i)] = fabs(flow) + a * (us_next - us[i]);
  }
done:
  free(adh);
  free(ipiv);
  free(mat);
  free(rhs);
  return status;
}

int rs_model_project_state(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                           rs_msg *msg)
{
  const int status = rs_model_normal_at(m, w, in, msg);
  if (status != RS_OK) return status;
  for (int i = 0; i < m->grid.n; i++) {
    double *p = y + rs_at_p(&m->lay, 0, i);
    const double g = w->pn[i] > 0.0 ? w->bound[i] : 0.0;
    if (fabs(*p) > g) *p = rs_sign_of(*p) * g;
  }
  return RS_OK;
}

int rs_model_interpolate_state(const rs_model *from, const double *y_from, const rs_model *to,
                               rs_work *w_to, const rs_inputs *in, double *y_to, rs_msg *msg)
{
  const int nf = from->grid.n, nt = to->grid.n;
  for (int i = 0; i < nt; i++) {
    /* position of cell i of `to` in cell-centre units of `from` */
    const double s = (to->grid.x[i] - from->grid.x[0]) / from->grid.dx;
    int j = (int)floor(s);
    double f = s - j;
    if (j < 0) {
      j = 0;
      f = 0.0;
    } else if (j >= nf - 1) {
      j = nf - 1;
      f = 0.0;
    }
    for (int b = 0; b < to->lay.ncell; b++) {
      const double *src = y_from + (size_t)b * nf;
      y_to[(size_t)b * nt + i] = f > 0.0 ? (1.0 - f) * src[j] + f * src[j + 1] : src[j];
    }
  }
  for (int k = 0; k < to->lay.nextra; k++)
    y_to[rs_at_extra(&to->lay, k)] =
        k < from->lay.nextra ? y_from[rs_at_extra(&from->lay, k)] : 0.0;
  return rs_model_project_state(to, w_to, in, y_to, msg);
}
