/* The semi-discrete 2D rolling-contact DAE with local plasticity (model.md §4-5):
 * residual, generalized Jacobian, consistent rates and reported quantities.
 *
 * Per contact cell I, with D f/Dt = f' - V (f_{I+1} - f_I)/dx (first-order upwind,
 * material enters at the high-x edge) and v_s = V xi + v_shift + Du_el/Dt + Du_pl/Dt:
 *   R_f  = p - proj_[-g, g](p - r v_s)
 *   R_pl = p - proj_[-tau_c, tau_c](p + r Du_pl/Dt)
 *   R_*  = r (Dustar/Dt - |Du_pl/Dt|)
 * Exterior cells (p_n = 0): p = 0, Du_pl/Dt = 0 (scaled by r), R_* as above. */
#include "rollsim/model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rollsim/normal.h"
#include "rollsim/rig.h"
#include "base/util.h"


static double sign_of(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }


/* Pressure for a load: the discrete normal solution or the Hertz pressure. */
static int solve_normal(const rs_model *m, double load, double *pn, double *approach, rs_msg *msg)
{
  if (m->normal_solution == RS_NORMAL_HERTZ) {
    double a, p0;
    rs_hertz2d(load, m->radius, m->shear_modulus, m->poisson_ratio, &a, &p0);
    rs_normal2d_hertz(m->x, m->n, a, p0, pn);
    if (approach) *approach = 0.0;
    return RS_OK;
  }
  return rs_normal2d_solve(&m->el, m->x, m->radius, load, pn, approach, NULL, msg);
}

/* Grid of n cells over [-half, half], its influence coefficients, the normal
 * solution at the load of t = 0 and the traction bound; needs the material, radius,
 * reference length, mu and the load history of m. On failure the caller frees m. */
static int build_grid(rs_model *m, int n, double half, rs_msg *msg)
{
  m->n = n;
  m->neq = 3 * n + (m->force_control ? 1 : 0);
  m->dx = 2.0 * half / n;
  m->x = malloc((size_t)n * sizeof *m->x);
  m->pn = malloc((size_t)n * sizeof *m->pn);
  m->bound = malloc((size_t)n * sizeof *m->bound);
  if (!m->x || !m->pn || !m->bound)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a grid of %d cells", n);
  for (int i = 0; i < n; i++) m->x[i] = -half + (i + 0.5) * m->dx;
  int status = rs_elastic2d_create(&m->el, n, m->dx, m->shear_modulus, m->poisson_ratio,
                                   m->reference_length, msg);
  if (status == RS_OK)
    status = solve_normal(m, rs_history_eval(&m->load, 0.0), m->pn, &m->approach, msg);
  if (status != RS_OK) return status;
  for (int i = 0; i < n; i++) m->bound[i] = m->mu * m->pn[i];
  return RS_OK;
}

int rs_model_create(rs_model *m, const rs_case *c, rs_msg *msg)
{
  memset(m, 0, sizeof *m);
  m->force_control = c->force_control;
  /* The grid is sized on the largest load of the run: with a normal-load history the
   * contact grows and shrinks inside it (cells enter and leave the contact). */
  m->load_varies = !rs_history_is_constant(&c->normal_load);
  m->normal_load = m->load_varies ? rs_history_max_abs(&c->normal_load, 0.0, c->end_time)
                                  : rs_history_eval(&c->normal_load, 0.0);
  m->radius = c->radius;
  m->shear_modulus = c->shear_modulus;
  m->poisson_ratio = c->poisson_ratio;
  m->normal_solution = c->normal_solution;
  m->reference_length = c->reference_length;
  m->mu = c->mu;
  rs_hertz2d(m->normal_load, c->radius, c->shear_modulus, c->poisson_ratio, &m->hertz_a,
             &m->hertz_p0);
  m->layer_flex = c->layer_thickness > 0.0 ? c->layer_thickness / c->layer_shear_modulus : 0.0;
  m->has_plasticity = c->has_plasticity;
  m->tau_c0 = c->tau_c0;
  m->k_tau = c->k_tau;
  m->tau_c_min = c->tau_c_min;
  m->scaling = c->scaling;
  m->time_scale = c->output_interval;
  if (rs_history_copy(&m->load, &c->normal_load) != RS_OK ||
      rs_history_copy(&m->velocity, &c->velocity) != RS_OK ||
      rs_history_copy(&m->creepage, &c->creepage) != RS_OK ||
      rs_history_copy(&m->shift, &c->shift_velocity) != RS_OK ||
      rs_history_copy(&m->force, &c->tangential_force) != RS_OK) {
    rs_model_free(m);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory copying input histories");
  }
  const int status = build_grid(m, c->cells, c->extent * m->hertz_a, msg);
  if (status != RS_OK) rs_model_free(m);
  return status;
}

void rs_model_free(rs_model *m)
{
  free(m->x);
  free(m->pn);
  free(m->bound);
  rs_elastic2d_free(&m->el);
  rs_history_free(&m->velocity);
  rs_history_free(&m->creepage);
  rs_history_free(&m->shift);
  rs_history_free(&m->load);
  rs_history_free(&m->force);
  memset(m, 0, sizeof *m);
}

int rs_model_regrid(const rs_model *m, int n, rs_model *out, rs_msg *msg)
{
  *out = *m; /* scalars and the memory pointer; arrays and histories replaced below */
  out->x = out->pn = out->bound = NULL;
  out->el = (rs_elastic2d){0};
  out->velocity = out->creepage = out->shift = out->load = out->force = (rs_history){0};
  if (rs_history_copy(&out->velocity, &m->velocity) != RS_OK ||
      rs_history_copy(&out->creepage, &m->creepage) != RS_OK ||
      rs_history_copy(&out->shift, &m->shift) != RS_OK ||
      rs_history_copy(&out->load, &m->load) != RS_OK ||
      rs_history_copy(&out->force, &m->force) != RS_OK) {
    rs_model_free(out);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory copying input histories");
  }
  const int status = build_grid(out, n, 0.5 * m->n * m->dx, msg);
  if (status != RS_OK) rs_model_free(out);
  return status;
}

int rs_model_interpolate_state(const rs_model *from, const double *y_from, const rs_model *to,
                               rs_work *w_to, double t, double *y_to, rs_msg *msg)
{
  const int nf = from->n, nt = to->n;
  for (int i = 0; i < nt; i++) {
    /* position of cell i of `to` in cell-centre units of `from` */
    const double s = (to->x[i] - from->x[0]) / from->dx;
    int j = (int)floor(s);
    double f = s - j;
    if (j < 0) {
      j = 0;
      f = 0.0;
    } else if (j >= nf - 1) {
      j = nf - 1;
      f = 0.0;
    }
    for (int b = 0; b < 3; b++) {
      const double *src = y_from + (size_t)b * nf;
      y_to[(size_t)b * nt + i] = f > 0.0 ? (1.0 - f) * src[j] + f * src[j + 1] : src[j];
    }
  }
  if (to->force_control) y_to[3 * nt] = from->force_control ? y_from[3 * nf] : 0.0;
  return rs_model_project_state(to, w_to, t, y_to, msg);
}

int rs_work_create(rs_work *w, int n)
{
  w->uel = calloc((size_t)n + 1, sizeof *w->uel);
  w->ueldot = calloc((size_t)n, sizeof *w->ueldot);
  w->vslip = calloc((size_t)n, sizeof *w->vslip);
  w->dupl = calloc((size_t)n, sizeof *w->dupl);
  w->dustar = calloc((size_t)n, sizeof *w->dustar);
  w->branch = calloc((size_t)n, sizeof *w->branch);
  w->pn_buf = calloc((size_t)n, sizeof *w->pn_buf);
  w->bound_buf = calloc((size_t)n, sizeof *w->bound_buf);
  w->load_cached = NAN;
  if (!w->uel || !w->ueldot || !w->vslip || !w->dupl || !w->dustar || !w->branch || !w->pn_buf ||
      !w->bound_buf) {
    rs_work_free(w);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

void rs_work_free(rs_work *w)
{
  free(w->uel);
  free(w->ueldot);
  free(w->vslip);
  free(w->dupl);
  free(w->dustar);
  free(w->branch);
  free(w->pn_buf);
  free(w->bound_buf);
  memset(w, 0, sizeof *w);
}

int rs_model_normal_at(const rs_model *m, rs_work *w, double t, rs_msg *msg)
{
  if (!m->load_varies) {
    w->pn = m->pn;
    w->bound = m->bound;
    return RS_OK;
  }
  w->pn = w->pn_buf;
  w->bound = w->bound_buf;
  const double load = rs_history_eval(&m->load, t);
  if (load == w->load_cached) return RS_OK;
  w->load_cached = NAN;
  const int status = solve_normal(m, load, w->pn_buf, NULL, msg);
  if (status != RS_OK) return status;
  for (int i = 0; i < m->n; i++) w->bound_buf[i] = m->mu * w->pn_buf[i];
  w->load_cached = load;
  return RS_OK;
}

int64_t rs_model_jac_capacity(const rs_model *m)
{
  return (int64_t)m->n * (m->n + 2) + 8 * (int64_t)m->n + (m->force_control ? 2 * m->n + 2 : 0);
}

double rs_model_creepage(const rs_model *m, double t, const double *y)
{
  return m->force_control ? y[3 * m->n] : rs_history_eval(&m->creepage, t);
}

double rs_model_next_breakpoint(const rs_model *m, double t)
{
  return fmin(fmin(rs_history_next_breakpoint(&m->velocity, t),
                   rs_history_next_breakpoint(&m->creepage, t)),
              fmin(fmin(rs_history_next_breakpoint(&m->shift, t),
                        rs_history_next_breakpoint(&m->load, t)),
                   m->force_control ? rs_history_next_breakpoint(&m->force, t) : INFINITY));
}

/* The yield limit sees u* >= 0 only: u* never decreases along the material path and
 * enters at >= 0, so a solution has u* >= 0 everywhere, but a Newton iterate can
 * have u* < 0 (the linearised |Du_pl/Dt| with the wrong sign). Without the clamp such
 * an iterate lowers tau_c towards the floor, every slipping cell then "yields", and
 * the active set jumps wildly (measured: Carter k_rel = 0.1, 50 cells, u* down to
 * -1e-2 mm and |F| ~ 1e4 N/mm^2 over 25 iterations without convergence). */
double rs_model_yield_limit(const rs_model *m, double ustar)
{
  if (!m->has_plasticity) return INFINITY;
  return fmax(m->tau_c_min, m->tau_c0 + m->k_tau * fmax(ustar, 0.0));
}

/* d tau_c / d u*: k_tau above the floor and for u* >= 0, 0 otherwise. */
static double yield_slope(const rs_model *m, double ustar)
{
  return (ustar >= 0.0 && m->tau_c0 + m->k_tau * ustar > m->tau_c_min) ? m->k_tau : 0.0;
}

double rs_model_scaling(const rs_model *m, double t, double cj)
{
  const double self = rs_elastic2d_tang(&m->el, 0) + m->layer_flex;
  rs_scaling choice = m->scaling;
  if (choice == RS_SCALING_AUTO) choice = m->has_plasticity ? RS_SCALING_SELF : RS_SCALING_DIFFERENCE;
  const double shift = choice == RS_SCALING_SELF
                           ? self
                           : self - rs_elastic2d_tang(&m->el, 1);
  const double V = rs_history_eval(&m->velocity, t);
  double denom = cj * self + V * shift / m->dx;
  if (!(denom > 0.0)) denom = self / m->time_scale; /* no rolling, no time step: a time scale */
  return 1.0 / denom;
}

/* Transport terms shared by residual, rates and diagnostics: u_el on the padded
 * grid, its rate, and the material derivatives of u_el, u_pl, u*. */
static void inflow(const rs_model *m, double t, double *upl, double *ustar)
{
  if (m->memory)
    rs_rig_memory_inflow(m->memory, t, upl, ustar);
  else
    *upl = *ustar = 0.0;
}

static void kinematics(const rs_model *m, rs_work *w, double t, const double *y, const double *yp)
{
  double upl_in, us_in;
  inflow(m, t, &upl_in, &us_in);
  const int n = m->n;
  const double *p = y, *upl = y + n, *us = y + 2 * n;
  const double c3 = m->layer_flex, a = rs_history_eval(&m->velocity, t) / m->dx;
  const double vrigid = rs_history_eval(&m->velocity, t) * rs_model_creepage(m, t, y) +
                        rs_history_eval(&m->shift, t);
  rs_elastic2d_apply(&m->el, m->el.tang, p, w->uel, n + 1);
  rs_elastic2d_apply(&m->el, m->el.tang, yp, w->ueldot, n);
  for (int i = 0; i < n; i++) {
    w->uel[i] += c3 * p[i];
    w->ueldot[i] += c3 * yp[i];
  }
  for (int i = 0; i < n; i++) {
    const double upl_next = i + 1 < n ? upl[i + 1] : upl_in;
    const double us_next = i + 1 < n ? us[i + 1] : us_in;
    const double duel = w->ueldot[i] - a * (w->uel[i + 1] - w->uel[i]);
    w->dupl[i] = yp[n + i] - a * (upl_next - upl[i]);
    w->dustar[i] = yp[2 * n + i] - a * (us_next - us[i]);
    w->vslip[i] = vrigid + duel + w->dupl[i];
  }
}

/* Append an entry to the current row of a CSR matrix. */
static void csr_put(rs_csr *J, int64_t col, double val)
{
  const int64_t k = J->rowptr[J->nrows + 1]++; /* rowptr[nrows + 1]: end of the open row */
  J->col[k] = col;
  J->val[k] = val;
}

static void csr_next_row(rs_csr *J)
{
  J->nrows++;
  if (J->nrows < J->cap_rows) J->rowptr[J->nrows + 1] = J->rowptr[J->nrows];
}

int rs_model_eval(const rs_model *m, rs_work *w, double t, const double *y, const double *yp,
                  double cj, double *F, rs_csr *jac)
{
  const int n = m->n;
  const double *p = y, *us = y + 2 * n;
  const double r = rs_model_scaling(m, t, cj);
  const double a = rs_history_eval(&m->velocity, t) / m->dx, c3 = m->layer_flex;
  rs_msg msg;
  const int status = rs_model_normal_at(m, w, t, &msg);
  if (status != RS_OK) return status;
  kinematics(m, w, t, y, yp);

  for (int i = 0; i < n; i++) {
    unsigned char br = 0;
    const double g = w->bound[i], tauc = rs_model_yield_limit(m, us[i]);
    const double mpl = w->dupl[i];
    double Fp, Fupl;
    if (!(w->pn[i] > 0.0)) {
      br = RS_BRANCH_EXTERIOR;
      Fp = p[i];
      Fupl = r * mpl;
    } else {
      /* Both projections active at once: slip and flow with |p| = g = tau_c. With
       * hardening (or softening) the yield row fixes u* and the flow follows from
       * the u* row: a legitimate state (a cell that has just hardened up to g).
       * Without it (k_tau = 0, or on the floor tau_c_min) the split between slip
       * and flow is undetermined (singular Jacobian): the lower bound decides,
       * slip where g <= tau_c, flow where tau_c < g. On the boundary of that region
       * the choice agrees with the plain projections, so F stays continuous there. */
      const double arg_f = p[i] - r * w->vslip[i], arg_pl = p[i] + r * mpl;
      int slip = fabs(arg_f) > g, yield = fabs(arg_pl) > tauc;
      if (slip && yield && !(yield_slope(m, us[i]) > 0.0 && g > m->tau_c0)) {
        if (g <= tauc)
          yield = 0;
        else
          slip = 0;
      }
      if (slip) {
        br |= RS_BRANCH_SLIP;
        Fp = p[i] - g * sign_of(arg_f);
      } else {
        Fp = r * w->vslip[i];
      }
      if (yield) {
        br |= RS_BRANCH_YIELD;
        /* The plain projection, also when the cell slips as well (hardened up to the
         * bound): p = tau_c sign(p + r Du_pl/Dt) is what makes the flow parallel to p
         * (lambda >= 0). Taking the slip's direction here instead admitted spurious
         * zeros with p = -g and the flow opposite to p (negative plastic power) next
         * to the trailing edge: steady states the transient never reaches (the
         * Table-1 contact at xi = -1 %: F_x/F_n 0.1385 instead of 0.1350). */
        Fupl = p[i] - tauc * sign_of(arg_pl);
      } else {
        Fupl = -r * mpl;
      }
    }
    w->branch[i] = br;
    if (F) {
      F[i] = Fp;
      F[n + i] = Fupl;
      F[2 * n + i] = r * (w->dustar[i] - fabs(mpl));
    }
  }
  /* Force row, scaled to a mean traction over the contact width 2a. */
  const double force_row = m->dx / (2.0 * m->hertz_a);
  if (F && m->force_control) {
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += p[i];
    F[3 * n] = force_row * sum - rs_history_eval(&m->force, t) / (2.0 * m->hertz_a);
  }
  if (!jac) return RS_OK;

  /* Generalized Jacobian dF/dy + cj dF/dy', row by row (CSR, sorted columns). */
  jac->nrows = 0;
  jac->cap_rows = m->neq;
  jac->rowptr[0] = jac->rowptr[1] = 0;
  const double *coef = m->el.tang + n; /* coef[k] = A(k) */
  for (int i = 0; i < n; i++) {
    const unsigned char br = w->branch[i];
    if (br & (RS_BRANCH_EXTERIOR | RS_BRANCH_SLIP)) {
      csr_put(jac, i, 1.0);
    } else {
      /* r dv_s/dp_j = r [cj A(i-j) - a (A(i+1-j) - A(i-j))] (+ layer on the diagonal) */
      const int j0 = jac->band > 0 && i > jac->band ? i - (int)jac->band : 0;
      const int j1 = jac->band > 0 && i + jac->band < n ? i + (int)jac->band + 1 : n;
      for (int j = j0; j < j1; j++) {
        double v = cj * coef[i - j] - a * (coef[i + 1 - j] - coef[i - j]);
        if (j == i) v += (cj + a) * c3;
        if (j == i + 1) v -= a * c3;
        csr_put(jac, j, r * v);
      }
      csr_put(jac, n + i, r * (cj + a));
      if (i + 1 < n) csr_put(jac, n + i + 1, -r * a);
      if (m->force_control) csr_put(jac, 3 * n, r * rs_history_eval(&m->velocity, t));
    }
    csr_next_row(jac);
  }
  for (int i = 0; i < n; i++) {
    const unsigned char br = w->branch[i];
    if (br & RS_BRANCH_YIELD) {
      const double arg_pl = p[i] + r * w->dupl[i];
      csr_put(jac, i, 1.0);
      csr_put(jac, 2 * n + i, -sign_of(arg_pl) * yield_slope(m, us[i]));
    } else {
      const double s = (br & RS_BRANCH_EXTERIOR) ? r : -r;
      csr_put(jac, n + i, s * (cj + a));
      if (i + 1 < n) csr_put(jac, n + i + 1, -s * a);
    }
    csr_next_row(jac);
  }
  for (int i = 0; i < n; i++) {
    /* d|m|/dm: sign of m, or the direction of p where m = 0 (model.md §9). */
    const double sig = w->dupl[i] != 0.0 ? sign_of(w->dupl[i]) : sign_of(p[i]);
    csr_put(jac, n + i, -r * sig * (cj + a));
    if (i + 1 < n) csr_put(jac, n + i + 1, r * sig * a);
    csr_put(jac, 2 * n + i, r * (cj + a));
    if (i + 1 < n) csr_put(jac, 2 * n + i + 1, -r * a);
    csr_next_row(jac);
  }
  if (m->force_control) {
    for (int j = 0; j < n; j++) csr_put(jac, j, force_row);
    csr_put(jac, 3 * n, 0.0); /* structural: keeps the pattern of the bordered system */
    csr_next_row(jac);
  }
  return RS_OK;
}

int rs_model_consistent_rates(const rs_model *m, rs_work *w, double t, double *y, double *yp,
                              rs_msg *msg)
{
  const int n = m->n;
  const double *p = y, *us = y + 2 * n;
  const double a = rs_history_eval(&m->velocity, t) / m->dx, c3 = m->layer_flex;
  memset(yp, 0, (size_t)m->neq * sizeof *yp);
  int status = rs_model_normal_at(m, w, t, msg);
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
  const double dload = m->load_varies ? rs_history_rate(&m->load, t) : 0.0;
  if (dload != 0.0) {
    const double load = rs_history_eval(&m->load, t), h = 1e-6 * load;
    status = solve_normal(m, load + h, rhs, NULL, msg);
    if (status != RS_OK) goto done;
    for (int i = 0; i < n; i++)
      if (w->pn[i] > 0.0 && w->bound[i] <= rs_model_yield_limit(m, us[i]) &&
          fabs(p[i]) >= w->bound[i] * (1.0 - 1e-12))
        yp[i] = sign_of(p[i]) * m->mu * (rhs[i] - w->pn[i]) / h * dload;
  }
  kinematics(m, w, t, y, yp); /* with p' = 0 off the bound: v_s holds everything but A p'_H */
  int h = 0;
  for (int i = 0; i < n; i++) {
    const double lim = fmin(w->bound[i], rs_model_yield_limit(m, us[i]));
    if (w->pn[i] > 0.0 && fabs(p[i]) < lim * (1.0 - 1e-12)) adh[h++] = i;
  }
  if (h > 0) {
    /* Adhesion: v_s = 0 with Du_pl/Dt = 0, i.e. (A + c3 I) p'_H = -v_s(p'_H = 0).
     * Force control: v_s = V xi + ..., xi unknown, and dx sum p' = F_x'(t). */
    const int fc = m->force_control, hb = h + fc;
    const double V = rs_history_eval(&m->velocity, t), xi = fc ? y[3 * n] : 0.0;
    for (int c = 0; c < h; c++) {
      for (int r = 0; r < h; r++)
        mat[(size_t)c * hb + r] = rs_elastic2d_tang(&m->el, adh[r] - adh[c]) + (r == c ? c3 : 0.0);
      rhs[c] = -(w->vslip[adh[c]] - V * xi);
    }
    if (fc) {
      double known = 0.0; /* dx sum of the rates fixed above (cells on the bound) */
      for (int i = 0; i < n; i++) known += yp[i] * m->dx;
      for (int r = 0; r < h; r++) mat[(size_t)h * hb + r] = V; /* column of xi */
      for (int c = 0; c < h; c++) mat[(size_t)c * hb + h] = m->dx;
      mat[(size_t)h * hb + h] = 0.0;
      rhs[h] = rs_history_rate(&m->force, t) - known;
    }
    int one = 1, info = 0;
    dgesv_(&hb, &one, mat, &hb, ipiv, rhs, &hb, &info);
    if (info != 0) {
      status = rs_msg_set(msg, RS_ERR_SOLVER, "initial rates: singular adhesion system (info %d)", info);
      goto done;
    }
    for (int c = 0; c < h; c++) yp[adh[c]] = rhs[c];
    if (fc) y[3 * n] = rhs[h];
  }
  kinematics(m, w, t, y, yp);
  double upl_in, us_in;
  inflow(m, t, &upl_in, &us_in);
  /* Transport of u_pl and u*: Du/Dt = 0, except plastic flow where |p| is at a
   * yield limit below the bound (flow takes up the slip velocity left over). */
  for (int i = 0; i < n; i++) {
    const double tauc = rs_model_yield_limit(m, us[i]);
    double flow = 0.0;
    if (w->pn[i] > 0.0 && tauc < w->bound[i] && fabs(p[i]) >= tauc * (1.0 - 1e-12))
      flow = -(w->vslip[i] - w->dupl[i]);
    const double upl_next = i + 1 < n ? y[n + i + 1] : upl_in;
    const double us_next = i + 1 < n ? us[i + 1] : us_in;
    yp[n + i] = flow + a * (upl_next - y[n + i]);
    yp[2 * n + i] = fabs(flow) + a * (us_next - us[i]);
  }
done:
  free(adh);
  free(ipiv);
  free(mat);
  free(rhs);
  return status;
}

int rs_model_project_state(const rs_model *m, rs_work *w, double t, double *y, rs_msg *msg)
{
  const int status = rs_model_normal_at(m, w, t, msg);
  if (status != RS_OK) return status;
  for (int i = 0; i < m->n; i++) {
    const double g = w->pn[i] > 0.0 ? w->bound[i] : 0.0;
    if (fabs(y[i]) > g) y[i] = sign_of(y[i]) * g;
  }
  return RS_OK;
}

int rs_model_diagnostics(const rs_model *m, rs_work *w, double t, const double *y,
                         const double *yp, rs_diag *d, double *slip, double *tauc,
                         signed char *regime)
{
  const int n = m->n;
  const double V = rs_history_eval(&m->velocity, t);
  const double xi = rs_model_creepage(m, t, y);
  const double vrigid = V * xi + rs_history_eval(&m->shift, t);
  /* Branches with the steady scaling (any r > 0 gives the same regimes at a solution). */
  rs_msg msg;
  const int status = rs_model_eval(m, w, t, y, yp, 0.0, NULL, NULL);
  if (status != RS_OK) return rs_msg_set(&msg, status, "normal problem failed at t = %g s", t);
  memset(d, 0, sizeof *d);
  d->creepage = xi;
  d->velocity = V;
  for (int i = 0; i < n; i++) {
    const double p = y[i];
    rs_regime reg = RS_ADHESION;
    if (w->branch[i] & RS_BRANCH_EXTERIOR)
      reg = RS_EXTERIOR;
    else if (w->branch[i] & RS_BRANCH_SLIP)
      reg = RS_SLIP;
    else if (w->branch[i] & RS_BRANCH_YIELD)
      reg = RS_PLASTIC;
    d->count[reg]++;
    d->Fx += p * m->dx;
    d->Fn += w->pn[i] * m->dx;
    d->frictional_power -= p * w->vslip[i] * m->dx;
    d->plastic_power += p * w->dupl[i] * m->dx;
    d->elastic_energy += 0.5 * p * w->uel[i] * m->dx;
    d->rigid_slip_power -= p * vrigid * m->dx;
    if (slip) slip[i] = V > 0.0 ? w->vslip[i] / V : w->vslip[i];
    if (tauc) tauc[i] = rs_model_yield_limit(m, y[2 * n + i]);
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
                    i, m->x[i], what, p, other_name, other, unit);
}

/* The paper's conditions (eqs. 7-10) cell by cell on the kinematics in w (of a steady
 * evaluation), rates in traction units through the steady scaling r. */
static int check_cells(const rs_model *m, const rs_work *w, double t, const double *y, double tol,
                       rs_msg *msg)
{
  const int n = m->n;
  const double r = rs_model_scaling(m, t, 0.0);
  for (int i = 0; i < n; i++) {
    const double p = y[i], g = w->bound[i], tauc = rs_model_yield_limit(m, y[2 * n + i]);
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

int rs_model_check_steady(const rs_model *m, rs_work *w, double t, const double *y, rs_msg *msg)
{
  double *F = malloc((size_t)m->neq * sizeof *F), *yp = calloc((size_t)m->neq, sizeof *yp);
  if (!F || !yp) {
    free(F);
    free(yp);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory checking the steady solution");
  }
  /* Kinematics of the steady state: y' = 0 gives the same v_s, Du_pl/Dt and Dustar/Dt
   * for every c_j. */
  int status = rs_model_eval(m, w, t, y, yp, 0.0, NULL, NULL);
  double pref = 0.0;
  for (int i = 0; i < m->n; i++) pref = fmax(pref, w->bound[i]);
  if (!(pref > 0.0)) pref = 1.0;
  const double tol = RS_STEADY_CHECK_TOL * pref;
  if (status != RS_OK)
    status = rs_msg_set(msg, status, "normal problem failed at t = %g s", t);
  else
    status = check_cells(m, w, t, y, tol, msg);
  /* The residual of the transient at y' = 0, with the scaling of a time step of one
   * cell passage (c_j = V/dx): another r, the same zero set. */
  const double V = rs_history_eval(&m->velocity, t);
  if (status == RS_OK) status = rs_model_eval(m, w, t, y, yp, V > 0.0 ? V / m->dx : 0.0, F, NULL);
  if (status == RS_OK) {
    int worst = 0;
    for (int i = 1; i < m->neq; i++)
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
