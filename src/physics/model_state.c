/* States of the model (physics/model.h): consistent rates, projection on the admissible
 * tractions, interpolation between grids. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "physics/model_internal.h"
#include "physics/normal.h"

/* |p| of cell I (2D: |p_x|). */
static double traction_norm(const rs_layout *L, const double *y, int I)
{
  double s = 0.0;
  for (int c = 0; c < L->ncomp; c++) s += y[rs_at_p(L, c, I)] * y[rs_at_p(L, c, I)];
  return L->ncomp == 1 ? fabs(y[rs_at_p(L, 0, I)]) : sqrt(s);
}

/* rs_contact_state with cell I's yield limit. */
static rs_state cell_state(const rs_model *m, int I, int in_contact, double p_norm, double g,
                           double ustar)
{
  rs_plasticity pl;
  return rs_contact_state(rs_model_cell_plasticity(m, I, &pl), in_contact, p_norm, g, ustar);
}

/* Conjugate gradients for (A + c3 I) x = b on the cells marked in `mask` (x, b zero
 * elsewhere; ncomp blocks of n): A is the elastic operator, symmetric positive definite,
 * products by FFT. Stops at |r| <= 1e-13 |b|. Scratch: 3 vectors of ncomp n. */
static int masked_cg(const rs_model *m, rs_work *w, const unsigned char *mask, const double *b,
                     double *x, double *r, double *d, double *q, rs_msg *msg)
{
  const int N = m->lay.ncomp * m->grid.n, n = m->grid.n;
  const double c3 = m->layer_flex;
  double bb = 0.0;
  for (int k = 0; k < N; k++) {
    x[k] = 0.0;
    r[k] = d[k] = mask[k % n] ? b[k] : 0.0;
    bb += r[k] * r[k];
  }
  double rr = bb;
  for (int it = 0; it < 10 * N + 100 && rr > 1e-26 * bb && rr > 0.0; it++) {
    rs_elastic_op_tang(&m->el, &w->ew, d, q, 0);
    double dq = 0.0;
    for (int k = 0; k < N; k++) {
      q[k] = mask[k % n] ? q[k] + c3 * d[k] : 0.0;
      dq += d[k] * q[k];
    }
    if (!(dq > 0.0)) break;
    const double alpha = rr / dq;
    double rr_new = 0.0;
    for (int k = 0; k < N; k++) {
      x[k] += alpha * d[k];
      r[k] -= alpha * q[k];
      rr_new += r[k] * r[k];
    }
    for (int k = 0; k < N; k++) d[k] = r[k] + rr_new / rr * d[k];
    rr = rr_new;
  }
  if (!(rr <= 1e-20 * bb) && rr > 0.0)
    return rs_msg_set(msg, RS_ERR_SOLVER,
                      "initial rates: the adhesion system did not converge (|r|/|b| = %.3g)",
                      sqrt(rr / bb));
  return RS_OK;
}

/* Adhesion rates of a 3D model: (A + c3 I) p'_H = -v_s(p'_H = 0) on the adhesion cells by
 * CG with FFT products; with force control bordered by dA sum p'_c = F_c'(t) - known_c,
 * which fixes the creepages (xi, eta): p' = P0 + xi P1 + eta P2 from three solves. */
static int adhesion_rates_3d(const rs_model *m, rs_work *w, const rs_inputs *in,
                             const unsigned char *adh, double *y, double *yp, rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, N = 2 * n, fc = m->par.force_control;
  const double V = in->velocity;
  double *buf = malloc((size_t)N * 9 * sizeof *buf);
  if (!buf) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory computing the initial rates");
  double *b = buf, *P0 = buf + N, *P1 = buf + 2 * N, *P2 = buf + 3 * N, *r = buf + 4 * N,
         *d = buf + 5 * N, *q = buf + 6 * N, *e = buf + 7 * N;
  const double xi = fc ? y[rs_at_extra(L, 0)] : 0.0, eta = fc ? y[rs_at_extra(L, 1)] : 0.0;
  for (int c = 0; c < 2; c++)
    for (int I = 0; I < n; I++) b[c * n + I] = -(w->vslip[c * n + I] - V * (c == 0 ? xi : eta));
  int status = masked_cg(m, w, adh, b, P0, r, d, q, msg);
  double xi_new = 0.0, eta_new = 0.0;
  if (status == RS_OK && fc) {
    for (int k = 0; k < N; k++) e[k] = k < n ? -V : 0.0;
    status = masked_cg(m, w, adh, e, P1, r, d, q, msg);
    for (int k = 0; k < N && status == RS_OK; k++) e[k] = k < n ? 0.0 : -V;
    if (status == RS_OK) status = masked_cg(m, w, adh, e, P2, r, d, q, msg);
    if (status == RS_OK) {
      /* dA sum (P0 + xi P1 + eta P2)_c = F_c' - known_c, c = x, y: a 2 x 2 system */
      double S[2][3] = {{0}}, rhs[2] = {in->force_rate, in->force_y_rate};
      for (int c = 0; c < 2; c++)
        for (int I = 0; I < n; I++) {
          const int k = c * n + I;
          if (!adh[I]) rhs[c] -= yp[rs_at_p(L, c, I)] * m->grid.area;
          S[c][0] += P0[k] * m->grid.area;
          S[c][1] += P1[k] * m->grid.area;
          S[c][2] += P2[k] * m->grid.area;
        }
      const double det = S[0][1] * S[1][2] - S[0][2] * S[1][1];
      if (!(fabs(det) > 0.0))
        status = rs_msg_set(msg, RS_ERR_SOLVER,
                            "initial rates: no contact cell in adhesion to "
                            "carry the prescribed force");
      else {
        const double r0 = rhs[0] - S[0][0], r1 = rhs[1] - S[1][0];
        xi_new = (r0 * S[1][2] - S[0][2] * r1) / det;
        eta_new = (S[0][1] * r1 - r0 * S[1][1]) / det;
      }
    }
  }
  if (status == RS_OK) {
    for (int c = 0; c < 2; c++)
      for (int I = 0; I < n; I++)
        if (adh[I]) {
          const int k = c * n + I;
          yp[rs_at_p(L, c, I)] = P0[k] + (fc ? xi_new * P1[k] + eta_new * P2[k] : 0.0);
        }
    if (fc) {
      y[rs_at_extra(L, 0)] = xi_new;
      y[rs_at_extra(L, 1)] = eta_new;
    }
  }
  free(buf);
  return status;
}

/* Adhesion rates of a 2D model: the dense system (A + c3 I) p'_H = -v_s(p'_H = 0) by
 * LAPACK, bordered by dx sum p' = F_x'(t) with force control (the creepage is its
 * unknown). adh: the adhesion cells in order, h of them. */
static int adhesion_rates_2d(const rs_model *m, rs_work *w, const rs_inputs *in, const int *adh,
                             int h, double *y, double *yp, rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, fc = m->par.force_control, hb = h + fc;
  const double V = in->velocity, xi = fc ? y[rs_at_extra(L, 0)] : 0.0, c3 = m->layer_flex;
  int *ipiv = malloc((size_t)hb * sizeof *ipiv);
  double *mat = malloc((size_t)hb * (size_t)hb * sizeof *mat);
  double *rhs = malloc((size_t)hb * sizeof *rhs);
  int status = RS_OK;
  if (!ipiv || !mat || !rhs) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory computing the initial rates");
    goto done;
  }
  /* Force control: v_s = V xi + ..., xi unknown, and dx sum p' = F_x'(t). */
  for (int c = 0; c < h; c++) {
    for (int r = 0; r < h; r++)
      mat[(size_t)c * hb + r] =
          rs_elastic_op_coef(&m->el, 0, 0, adh[r] - adh[c], 0) + (r == c ? c3 : 0.0);
    rhs[c] = -(w->vslip[adh[c]] - V * xi);
  }
  if (fc) {
    double known = 0.0; /* dx sum of the rates fixed above (cells on the bound) */
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
done:
  free(ipiv);
  free(mat);
  free(rhs);
  return status;
}

/* Friction memory: mu' from d_c Dmu/Dt = -max(|v_s|, s0) (mu - mu_law(|v_s|)) in the
 * contact, Dmu/Dt = 0 outside, Dmu/Dt = mu' - a (mu_up - mu) (fresh material at
 * mu_law(0)), on the kinematics in w. */
static void memory_rates(const rs_model *m, const rs_work *w, const rs_inputs *in, const double *y,
                         double *yp)
{
  const rs_layout *L = &m->lay;
  const rs_friction *f = &m->par.friction;
  const double a = in->velocity / m->grid.dx, mu_in = rs_friction_mu(f, 0.0);
  for (int i = 0; i < L->n; i++) {
    const int up = rs_grid_upstream(&m->grid, i);
    const double mu = y[rs_at_mu(L, i)], mu_next = up >= 0 ? y[rs_at_mu(L, up)] : mu_in;
    double dmu = 0.0;
    if (w->pn[i] > 0.0) {
      /* |v_s| (3D: the norm of both components) */
      const double speed =
          L->ncomp == 1 ? fabs(w->vslip[i]) : hypot(w->vslip[i], w->vslip[L->n + i]);
      dmu = -fmax(speed, f->memory_velocity) / f->memory_distance * (mu - rs_friction_mu(f, speed));
    }
    yp[rs_at_mu(L, i)] = dmu + a * (mu_next - mu);
  }
}

/* Friction memory: the rates of the cells at the bound (not in mask), p' = s g' with
 * s = p/|p| and g = mu p_n: mu' p_n, plus mu p_n' with a load history (pn_up: p_n at the load + h).
 */
static void bound_rates(const rs_model *m, const rs_work *w, const double *y,
                        const unsigned char *mask, const double *pn_up, const rs_inputs *in,
                        double *yp)
{
  const rs_layout *L = &m->lay;
  const double *us = y + rs_at_ustar(L, 0);
  for (int i = 0; i < L->n; i++) {
    if (mask[i] || cell_state(m, i, w->pn[i] > 0.0, traction_norm(L, y, i),
                              rs_model_bound(m, w, y, i), us[i]) != RS_STATE_AT_BOUND)
      continue;
    double gdot = yp[rs_at_mu(L, i)] * w->pn[i];
    if (in->load_rate != 0.0)
      gdot += y[rs_at_mu(L, i)] * (pn_up[i] - w->pn[i]) / (1e-6 * in->load) * in->load_rate;
    if (L->ncomp == 1) {
      yp[rs_at_p(L, 0, i)] = rs_sign_of(y[rs_at_p(L, 0, i)]) * gdot;
      continue;
    }
    const double pnorm = traction_norm(L, y, i); /* 3D: along the direction of p */
    for (int c = 0; c < L->ncomp; c++)
      yp[rs_at_p(L, c, i)] = pnorm > 0.0 ? y[rs_at_p(L, c, i)] / pnorm * gdot : 0.0;
  }
}

int rs_model_consistent_rates(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                              double *yp, rs_msg *msg)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  const double *us = y + rs_at_ustar(L, 0);
  const double a = in->velocity / m->grid.dx;
  memset(yp, 0, (size_t)L->neq * sizeof *yp);
  int status = rs_model_normal_at(m, w, in, msg);
  if (status != RS_OK) return status;
  int *adh = malloc((size_t)n * sizeof *adh);
  unsigned char *mask = calloc((size_t)n, 1);
  double *pn_up = malloc((size_t)n * sizeof *pn_up);
  if (!adh || !mask || !pn_up) {
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory computing the initial rates");
    goto done;
  }
  /* Cells at the traction bound follow it: p' = (p/|p|) g'(t) (a load history moves g;
   * g' by a difference quotient of the normal solution in the load). With friction memory
   * g = mu p_n also moves with mu' (memory_rates, below). */
  if (in->load_rate != 0.0) {
    const double h = 1e-6 * in->load, mu = rs_friction_mu(&m->par.friction, 0.0);
    status = rs_model_pressure(m, &w->ew, in->load + h, pn_up, NULL, msg);
    if (status != RS_OK) goto done;
    for (int i = 0; i < n; i++) {
      const double pnorm = traction_norm(L, y, i);
      if (cell_state(m, i, w->pn[i] > 0.0, pnorm, rs_model_bound(m, w, y, i), us[i]) !=
          RS_STATE_AT_BOUND)
        continue;
      const double mu_i = L->memory ? y[rs_at_mu(L, i)] : mu;
      const double gdot = mu_i * (pn_up[i] - w->pn[i]) / h * in->load_rate;
      for (int c = 0; c < nc; c++) {
        const double pc = y[rs_at_p(L, c, i)];
        yp[rs_at_p(L, c, i)] =
            nc == 1 ? rs_sign_of(pc) * gdot : (pnorm > 0.0 ? pc / pnorm : 0.0) * gdot;
      }
    }
  }
  int h = 0;
  for (int i = 0; i < n; i++)
    if (cell_state(m, i, w->pn[i] > 0.0, traction_norm(L, y, i), rs_model_bound(m, w, y, i),
                   us[i]) == RS_STATE_INSIDE) {
      adh[h++] = i;
      mask[i] = 1;
    }
  /* With friction memory the rates of cells at the bound, p' = s (mu' p_n + mu p_n'),
   * depend on the slip velocities through mu', and these on the adhesion rates: a few
   * fixed-point passes (from rest no cell is at the bound and one pass is exact). */
  const int passes = L->memory ? 4 : 1;
  for (int pass = 0; pass < passes; pass++) {
    if (pass > 0) {
      memory_rates(m, w, in, y, yp);
      bound_rates(m, w, y, mask, pn_up, in, yp);
      for (int k = 0; k < h; k++)
        for (int c = 0; c < nc; c++) yp[rs_at_p(L, c, adh[k])] = 0.0;
    }
    rs_model_kinematics(m, w, in, y, yp); /* with p' = 0 inside: v_s holds all but A p'_H */
    /* Adhesion: v_s = 0 with Du_pl/Dt = 0, i.e. (A + c3 I) p'_H = -v_s(p'_H = 0). */
    if (h > 0)
      status = nc == 1 ? adhesion_rates_2d(m, w, in, adh, h, y, yp, msg)
                       : adhesion_rates_3d(m, w, in, mask, y, yp, msg);
    if (status != RS_OK) goto done;
    rs_model_kinematics(m, w, in, y, yp);
  }
  if (L->memory) memory_rates(m, w, in, y, yp);
  rs_model_inflow(m, in, w->inflow);
  /* Transport of u_pl and u*: Du/Dt = 0, except plastic flow where |p| is at a yield
   * limit below the bound (flow takes up the slip velocity left over). */
  for (int i = 0; i < n; i++) {
    const int at_yield = cell_state(m, i, w->pn[i] > 0.0, traction_norm(L, y, i),
                                    rs_model_bound(m, w, y, i), us[i]) == RS_STATE_AT_YIELD;
    const int up = rs_grid_upstream(&m->grid, i);
    const double *in_row = w->inflow + rs_grid_row(&m->grid, i) * (nc + 1);
    double flow_norm2 = 0.0, flow1 = 0.0;
    for (int c = 0; c < nc; c++) {
      const double flow = at_yield ? -(w->vslip[c * n + i] - w->dupl[c * n + i]) : 0.0;
      flow_norm2 += flow * flow;
      flow1 = flow;
      const double upl_next = up >= 0 ? y[rs_at_upl(L, c, up)] : in_row[c];
      yp[rs_at_upl(L, c, i)] = flow + a * (upl_next - y[rs_at_upl(L, c, i)]);
    }
    const double us_next = up >= 0 ? us[up] : in_row[nc];
    yp[rs_at_ustar(L, i)] = (nc == 1 ? fabs(flow1) : sqrt(flow_norm2)) + a * (us_next - us[i]);
  }
done:
  free(adh);
  free(mask);
  free(pn_up);
  return status;
}

void rs_model_rest_state(const rs_model *m, double *y)
{
  const rs_layout *L = &m->lay;
  memset(y, 0, (size_t)L->neq * sizeof *y);
  const double mu0 = rs_friction_mu(&m->par.friction, 0.0);
  for (int i = 0; i < L->n && L->memory; i++) y[rs_at_mu(L, i)] = mu0;
}

int rs_model_project_state(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                           rs_msg *msg)
{
  const int status = rs_model_normal_at(m, w, in, msg);
  if (status != RS_OK) return status;
  const rs_layout *L = &m->lay;
  for (int i = 0; i < m->grid.n; i++) {
    const double g = w->pn[i] > 0.0 ? rs_model_bound(m, w, y, i) : 0.0;
    const double pnorm = traction_norm(L, y, i);
    if (!(pnorm > g)) continue;
    for (int c = 0; c < L->ncomp; c++) { /* onto the bound, keeping the direction */
      double *p = y + rs_at_p(L, c, i);
      *p = L->ncomp == 1 ? rs_sign_of(*p) * g : *p * (g / pnorm);
    }
  }
  return RS_OK;
}

/* Position of coordinate v among n centres c0 + k d: index j and weight f of j + 1,
 * constant beyond the outer centres. */
static void locate(double v, double c0, double d, int n, int *j, double *f)
{
  const double s = n > 1 ? (v - c0) / d : 0.0;
  *j = (int)floor(s);
  *f = s - *j;
  if (*j < 0) {
    *j = 0;
    *f = 0.0;
  } else if (*j >= n - 1) {
    *j = n - 1;
    *f = 0.0;
  }
}

int rs_model_interpolate_state(const rs_model *from, const double *y_from, const rs_model *to,
                               rs_work *w_to, const rs_inputs *in, double *y_to, rs_msg *msg)
{
  const rs_grid *gf = &from->grid, *gt = &to->grid;
  const int nf = gf->n, nt = gt->n;
  for (int iy = 0; iy < gt->ny; iy++) {
    int jy;
    double fy;
    locate(gt->y[iy], gf->y[0], gf->dy, gf->ny, &jy, &fy);
    for (int ix = 0; ix < gt->nx; ix++) {
      int jx;
      double fx;
      locate(gt->x[ix], gf->x[0], gf->dx, gf->nx, &jx, &fx);
      for (int b = 0; b < to->lay.ncell; b++) {
        const double *src = y_from + (size_t)b * nf;
        const double *row = src + (size_t)jy * gf->nx;
        double v = fx > 0.0 ? (1.0 - fx) * row[jx] + fx * row[jx + 1] : row[jx];
        if (fy > 0.0) { /* 3D: along y between rows jy and jy + 1 */
          const double *next = row + gf->nx;
          const double w1 = fx > 0.0 ? (1.0 - fx) * next[jx] + fx * next[jx + 1] : next[jx];
          v = (1.0 - fy) * v + fy * w1;
        }
        y_to[(size_t)b * nt + iy * gt->nx + ix] = v;
      }
    }
  }
  for (int k = 0; k < to->lay.nextra; k++)
    y_to[rs_at_extra(&to->lay, k)] =
        k < from->lay.nextra ? y_from[rs_at_extra(&from->lay, k)] : 0.0;
  return rs_model_project_state(to, w_to, in, y_to, msg);
}

/* Full sliding: the rigid slip over every contact cell at least this many times the largest
 * bound over G (the elastic slip across the contact is of the order of that ratio, so the
 * adhesion zone and the elastic part of the slip are a few per cent at most). */
#define SLIDE_FACTOR 10.0

int rs_model_sliding_state(const rs_model *m, rs_work *w, const rs_inputs *in, double *y)
{
  const rs_layout *L = &m->lay;
  const rs_grid *g = &m->grid;
  const rs_plasticity *pl0 = &m->par.plasticity;
  if (L->ncomp != 2 || !pl0->on || L->memory || L->nextra || m->par.force_control ||
      rs_friction_varies(&m->par.friction) || m->memory || !(in->velocity > 0.0))
    return RS_ERR_SOLVER;
  rs_msg msg = {{0}};
  if (rs_model_normal_at(m, w, in, &msg) != RS_OK) return RS_ERR_SOLVER;
  const int nx = g->nx, ny = g->ny;
  const double V = in->velocity;
  double gmax = 0.0, wmin = INFINITY;
  for (int iy = 0; iy < ny; iy++)
    for (int ix = 0; ix < nx; ix++) {
      const int I = iy * nx + ix;
      if (!(w->pn[I] > 0.0)) continue;
      const double wx = in->creepage - in->spin * g->y[iy] + in->shift_velocity / V;
      const double wy = in->lateral_creepage + in->spin * g->x[ix];
      gmax = fmax(gmax, rs_model_bound(m, w, y, I));
      wmin = fmin(wmin, hypot(wx, wy));
    }
  if (!(gmax > 0.0) || !(wmin >= SLIDE_FACTOR * gmax / m->par.shear_modulus)) return RS_ERR_SOLVER;
  rs_model_rest_state(m, y);
  for (int iy = 0; iy < ny; iy++) {
    double us = 0.0, upl[2] = {0.0, 0.0}; /* carried from the leading edge (fresh material) */
    for (int ix = nx - 1; ix >= 0; ix--) {
      const int I = iy * nx + ix;
      if (w->pn[I] > 0.0) {
        rs_plasticity buf;
        const rs_plasticity *pl = rs_model_cell_plasticity(m, I, &buf);
        const double wx = in->creepage - in->spin * g->y[iy] + in->shift_velocity / V;
        const double wy = in->lateral_creepage + in->spin * g->x[ix];
        const double wn = hypot(wx, wy), b = rs_model_bound(m, w, y, I),
                     tau_up = rs_yield_limit(pl, us);
        const double full = us + g->dx * wn; /* u* when the flow takes the whole slip */
        /* plastic (the flow takes the whole slip), hardening up to the bound within the cell
         * and then sliding, or sliding without flow (|p| = g, u* carried) */
        double t = b, us_new = us;
        if (tau_up < b && rs_yield_limit(pl, full) <= b) {
          t = rs_yield_limit(pl, full);
          us_new = full;
        } else if (tau_up < b && pl->k_tau > 0.0) {
          us_new = fmax(us, (b - pl->tau_c0) / pl->k_tau);
        }
        for (int c = 0; c < 2; c++) { /* flow and traction against the rigid slip */
          const double dir = (c == 0 ? wx : wy) / wn;
          upl[c] -= (us_new - us) * dir;
          y[rs_at_p(L, c, I)] = -t * dir;
        }
        us = us_new;
      }
      for (int c = 0; c < 2; c++) y[rs_at_upl(L, c, I)] = upl[c];
      y[rs_at_ustar(L, I)] = us;
    }
  }
  return RS_OK;
}
