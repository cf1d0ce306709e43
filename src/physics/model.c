/* The semi-discrete rolling-contact DAE with local plasticity (docs/model.md §4-5): creation
 * from plain parameters, the inputs at a time, the normal pressure, the kinematics and
 * the residual. Per contact cell I, with D f/Dt = f' - V (f_up - f_I)/dx (first-order
 * upwind, material enters at the high-x edge) and v_s = V xi + v_shift + Du_el/Dt +
 * Du_pl/Dt, the rows are those of the contact law (physics/contact_law.h). With force
 * control the last row is (dA sum p - F_x(t)) / (2 a) (a mean traction). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/model_internal.h"
#include "physics/normal.h"
#include "physics/normal3d.h"
#include "physics/rig.h"

int rs_model_pressure(const rs_model *m, rs_elastic_work *ew, double load, double *pn,
                      double *approach, rs_msg *msg)
{
  if (m->par.normal_solution == RS_NORMAL_HERTZ && m->par.dimension == 3) {
    rs_hertz_ellipse hz;
    const int status = rs_hertz3d(load, 0.5 / m->par.radius, 0.5 / m->par.radius_y,
                                  m->par.shear_modulus, m->par.poisson_ratio, &hz, msg);
    if (status != RS_OK) return status;
    const rs_grid3d g = {.nx = m->grid.nx,
                         .ny = m->grid.ny,
                         .x0 = m->grid.x_lo,
                         .y0 = m->grid.y_lo,
                         .dx = m->grid.dx,
                         .dy = m->grid.dy};
    rs_hertz3d_pressure(&hz, &g, pn);
    if (approach) *approach = hz.approach;
    return RS_OK;
  }
  if (m->par.normal_solution == RS_NORMAL_HERTZ) {
    double a, p0;
    rs_hertz2d(load, m->par.radius, m->par.shear_modulus, m->par.poisson_ratio, &a, &p0);
    rs_normal2d_hertz(m->grid.x, m->grid.n, a, p0, pn);
    if (approach) *approach = 0.0;
    return RS_OK;
  }
  return rs_normal_solve(&m->el, ew, m->gap, load, pn, approach, msg);
}

/* Grid of cells over [x_lo, x_hi] x [y_lo, y_hi] (2D: ny = 1, y_lo = y_hi = 0), the elastic
 * operator, the gap, the normal solution at the load of t = 0 and the traction bound. On
 * failure the caller frees m. */
static int build_grid(rs_model *m, int nx, double x_lo, double x_hi, int ny, double y_lo,
                      double y_hi, rs_msg *msg)
{
  int status = rs_grid_create(&m->grid, nx, x_lo, x_hi, ny, y_lo, y_hi, msg);
  if (status != RS_OK) return status;
  const int n = m->grid.n, ncomp = m->par.dimension == 3 ? 2 : 1;
  m->lay = rs_layout_make(n, ncomp, m->par.force_control ? ncomp : 0,
                          rs_friction_has_memory(&m->par.friction));
  m->gap = malloc((size_t)n * sizeof *m->gap);
  m->pn = malloc((size_t)n * sizeof *m->pn);
  m->bound = malloc((size_t)n * sizeof *m->bound);
  if (!m->gap || !m->pn || !m->bound)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a grid of %d cells", n);
  if (m->par.dimension == 3 && m->par.gap_at) {
    for (int j = 0; j < m->grid.ny; j++)
      for (int i = 0; i < m->grid.nx; i++)
        m->gap[j * m->grid.nx + i] = m->par.gap_at(m->par.gap_ctx, m->grid.x[i], m->grid.y[j]);
  } else if (m->par.dimension == 3) { /* h = x^2/(2 Rx) + y^2/(2 Ry) */
    for (int j = 0; j < m->grid.ny; j++)
      for (int i = 0; i < m->grid.nx; i++)
        m->gap[j * m->grid.nx + i] = m->grid.x[i] * m->grid.x[i] / (2.0 * m->par.radius) +
                                     m->grid.y[j] * m->grid.y[j] / (2.0 * m->par.radius_y);
  } else {
    rs_normal2d_profile(m->grid.x, n, m->par.radius, m->gap);
  }
  status = rs_elastic_op_create(&m->el, &m->grid, m->par.shear_modulus, m->par.poisson_ratio,
                                m->par.reference_length, msg);
  rs_elastic_work ew = {0};
  if (status == RS_OK && rs_elastic_work_create(&ew, &m->el) != RS_OK)
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the elastic products");
  if (status == RS_OK && m->par.normal_pressure && m->par.gap_at && !m->load_varies) {
    memcpy(m->pn, m->par.normal_pressure, (size_t)n * sizeof *m->pn);
    m->approach = m->par.normal_approach;
  } else if (status == RS_OK) {
    status =
        rs_model_pressure(m, &ew, rs_history_eval(&m->par.load, 0.0), m->pn, &m->approach, msg);
  }
  rs_elastic_work_free(&ew);
  if (status != RS_OK) return status;
  const double mu = rs_friction_mu(&m->par.friction, 0.0);
  for (int i = 0; i < n; i++) m->bound[i] = mu * m->pn[i];
  return RS_OK;
}

/* Deep copies of the parameters' histories into m->par (the rest is plain values). */
static int copy_params(rs_model *m, const rs_model_params *par, rs_msg *msg)
{
  m->par = *par;
  m->par.load = m->par.velocity = m->par.creepage = m->par.shift_velocity = m->par.force =
      m->par.lateral_creepage = m->par.spin = m->par.force_y = (rs_history){0};
  if (rs_history_copy(&m->par.load, &par->load) != RS_OK ||
      rs_history_copy(&m->par.velocity, &par->velocity) != RS_OK ||
      rs_history_copy(&m->par.creepage, &par->creepage) != RS_OK ||
      rs_history_copy(&m->par.lateral_creepage, &par->lateral_creepage) != RS_OK ||
      rs_history_copy(&m->par.spin, &par->spin) != RS_OK ||
      rs_history_copy(&m->par.shift_velocity, &par->shift_velocity) != RS_OK ||
      rs_history_copy(&m->par.force, &par->force) != RS_OK ||
      rs_history_copy(&m->par.force_y, &par->force_y) != RS_OK)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory copying input histories");
  return RS_OK;
}

int rs_model_create(rs_model *m, const rs_model_params *par, rs_msg *msg)
{
  memset(m, 0, sizeof *m);
  int status = copy_params(m, par, msg);
  if (status != RS_OK) {
    rs_model_free(m);
    return status;
  }
  /* The grid is sized on the largest load of the run: with a normal-load history the
   * contact grows and shrinks inside it (cells enter and leave the contact). */
  m->load_varies = !rs_history_is_constant(&par->load);
  m->normal_load = m->load_varies ? rs_history_max_abs(&par->load, 0.0, par->end_time)
                                  : rs_history_eval(&par->load, 0.0);
  m->layer_flex =
      par->layer_thickness > 0.0 ? par->layer_thickness / par->layer_shear_modulus : 0.0;
  if (par->dimension == 3) {
    rs_hertz_ellipse hz;
    status = rs_hertz3d(m->normal_load, 0.5 / par->radius, 0.5 / par->radius_y, par->shear_modulus,
                        par->poisson_ratio, &hz, msg);
    if (status != RS_OK) {
      rs_model_free(m);
      return status;
    }
    m->hertz_a = hz.a;
    m->hertz_b = hz.b;
    m->hertz_p0 = hz.p0;
    m->contact_measure = RS_PI * hz.a * hz.b;
    const double hx = par->extent * hz.a, hy = par->extent_y * hz.b;
    status = par->grid_from_range ? build_grid(m, par->cells, par->x_range[0], par->x_range[1],
                                               par->cells_y, par->y_range[0], par->y_range[1], msg)
                                  : build_grid(m, par->cells, -hx, hx, par->cells_y, -hy, hy, msg);
  } else {
    rs_hertz2d(m->normal_load, par->radius, par->shear_modulus, par->poisson_ratio, &m->hertz_a,
               &m->hertz_p0);
    m->contact_measure = 2.0 * m->hertz_a;
    const double half = par->extent * m->hertz_a;
    status = par->grid_from_range
                 ? build_grid(m, par->cells, par->x_range[0], par->x_range[1], 1, 0.0, 0.0, msg)
                 : build_grid(m, par->cells, -half, half, 1, 0.0, 0.0, msg);
  }
  m->par.normal_pressure = NULL; /* read here only: a regridded model solves its own */
  if (status != RS_OK) rs_model_free(m);
  return status;
}

void rs_model_free(rs_model *m)
{
  free(m->gap);
  free(m->pn);
  free(m->bound);
  rs_elastic_op_free(&m->el);
  rs_grid_free(&m->grid);
  rs_history_free(&m->par.velocity);
  rs_history_free(&m->par.creepage);
  rs_history_free(&m->par.lateral_creepage);
  rs_history_free(&m->par.spin);
  rs_history_free(&m->par.shift_velocity);
  rs_history_free(&m->par.load);
  rs_history_free(&m->par.force);
  rs_history_free(&m->par.force_y);
  memset(m, 0, sizeof *m);
}

int rs_model_regrid(const rs_model *m, int cells, rs_model *out, rs_msg *msg)
{
  memset(out, 0, sizeof *out);
  int status = copy_params(out, &m->par, msg);
  out->load_varies = m->load_varies;
  out->normal_load = m->normal_load;
  out->hertz_a = m->hertz_a;
  out->hertz_b = m->hertz_b;
  out->hertz_p0 = m->hertz_p0;
  out->contact_measure = m->contact_measure;
  out->layer_flex = m->layer_flex;
  out->memory = m->memory;
  /* 3D: the cells along y in the same proportion */
  const int cells_y = m->grid.ny == 1 ? 1
                                      : (int)((long)m->grid.ny * cells / m->grid.nx > 0
                                                  ? (long)m->grid.ny * cells / m->grid.nx
                                                  : 1);
  if (status == RS_OK)
    status = build_grid(out, cells, m->grid.x_lo, m->grid.x_hi, cells_y, m->grid.y_lo, m->grid.y_hi,
                        msg);
  if (status != RS_OK) rs_model_free(out);
  return status;
}

void rs_model_inputs_at(const rs_model *m, double t, rs_inputs *in)
{
  const rs_model_params *p = &m->par;
  const int fc = p->force_control, three = p->dimension == 3;
  *in = (rs_inputs){.t = t,
                    .velocity = rs_history_eval(&p->velocity, t),
                    .creepage = rs_history_eval(&p->creepage, t),
                    .lateral_creepage = three ? rs_history_eval(&p->lateral_creepage, t) : 0.0,
                    .spin = three ? rs_history_eval(&p->spin, t) : 0.0,
                    .shift_velocity = rs_history_eval(&p->shift_velocity, t),
                    .load = rs_history_eval(&p->load, t),
                    .force = fc ? rs_history_eval(&p->force, t) : 0.0,
                    .force_y = fc && three ? rs_history_eval(&p->force_y, t) : 0.0,
                    .load_rate = m->load_varies ? rs_history_rate(&p->load, t) : 0.0,
                    .force_rate = fc ? rs_history_rate(&p->force, t) : 0.0,
                    .force_y_rate = fc && three ? rs_history_rate(&p->force_y, t) : 0.0};
}

void rs_inputs_freeze(rs_inputs *in) { in->load_rate = in->force_rate = in->force_y_rate = 0.0; }

double rs_model_next_breakpoint(const rs_model *m, double t)
{
  const rs_model_params *p = &m->par;
  double next = fmin(fmin(rs_history_next_breakpoint(&p->velocity, t),
                          rs_history_next_breakpoint(&p->creepage, t)),
                     fmin(fmin(rs_history_next_breakpoint(&p->shift_velocity, t),
                               rs_history_next_breakpoint(&p->load, t)),
                          p->force_control ? rs_history_next_breakpoint(&p->force, t) : INFINITY));
  if (p->dimension == 3) {
    next = fmin(next, fmin(rs_history_next_breakpoint(&p->lateral_creepage, t),
                           rs_history_next_breakpoint(&p->spin, t)));
    if (p->force_control) next = fmin(next, rs_history_next_breakpoint(&p->force_y, t));
  }
  return next;
}

static int work_create(rs_work *w, const rs_model *m, int laws)
{
  memset(w, 0, sizeof *w);
  const size_t n = (size_t)m->grid.n, nc = (size_t)m->lay.ncomp;
  const size_t padded = nc * (size_t)(m->grid.nx + 1) * (size_t)m->grid.ny;
  w->uel = calloc(padded, sizeof *w->uel);
  w->ueldot = calloc(nc * n, sizeof *w->ueldot);
  w->vslip = calloc(nc * n, sizeof *w->vslip);
  w->dupl = calloc(nc * n, sizeof *w->dupl);
  w->dustar = calloc(n, sizeof *w->dustar);
  w->branch = calloc(n, sizeof *w->branch);
  const size_t neq = (size_t)m->lay.neq;
  if (laws) {
    w->law = calloc(n, sizeof *w->law);
    w->dense = calloc(neq, sizeof *w->dense);
    w->pivot = calloc(neq, sizeof *w->pivot);
  }
  if (m->lay.memory && !(w->dmu = calloc(n, sizeof *w->dmu))) {
    rs_work_free(w);
    return RS_ERR_INTERNAL;
  }
  w->pn_buf = calloc(n, sizeof *w->pn_buf);
  w->bound_buf = calloc(n, sizeof *w->bound_buf);
  w->inflow = calloc((nc + 1) * (size_t)m->grid.ny, sizeof *w->inflow);
  w->load_cached = NAN;
  if (!w->uel || !w->ueldot || !w->vslip || !w->dupl || !w->dustar || !w->branch ||
      (laws && (!w->law || !w->dense || !w->pivot)) || !w->pn_buf || !w->bound_buf || !w->inflow ||
      rs_elastic_work_create(&w->ew, &m->el) != RS_OK) {
    rs_work_free(w);
    return RS_ERR_INTERNAL;
  }
  if (m->el.dim == 3) w->ew.surf.threads = m->par.threads;
  return RS_OK;
}

int rs_work_create(rs_work *w, const rs_model *m) { return work_create(w, m, 1); }

int rs_work_create_kinematics(rs_work *w, const rs_model *m) { return work_create(w, m, 0); }

void rs_work_free(rs_work *w)
{
  rs_elastic_work_free(&w->ew);
  free(w->uel);
  free(w->ueldot);
  free(w->vslip);
  free(w->dupl);
  free(w->dustar);
  free(w->dmu);
  free(w->branch);
  free(w->law);
  free(w->dense);
  free(w->pivot);
  free(w->jv_start);
  free(w->jv_idx);
  free(w->jv_val);
  free(w->pn_buf);
  free(w->bound_buf);
  free(w->inflow);
  memset(w, 0, sizeof *w);
}

int rs_model_normal_at(const rs_model *m, rs_work *w, const rs_inputs *in, rs_msg *msg)
{
  if (!m->load_varies) {
    w->pn = m->pn;
    w->bound = m->bound;
    return RS_OK;
  }
  w->pn = w->pn_buf;
  w->bound = w->bound_buf;
  if (in->load == w->load_cached) return RS_OK;
  w->load_cached = NAN;
  const int status = rs_model_pressure(m, &w->ew, in->load, w->pn_buf, NULL, msg);
  if (status != RS_OK) return status;
  const double mu = rs_friction_mu(&m->par.friction, 0.0);
  for (int i = 0; i < m->grid.n; i++) w->bound_buf[i] = mu * w->pn_buf[i];
  w->load_cached = in->load;
  return RS_OK;
}

double rs_model_creepage(const rs_model *m, const rs_inputs *in, const double *y)
{
  return m->par.force_control ? y[rs_at_extra(&m->lay, 0)] : in->creepage;
}

double rs_model_lateral_creepage(const rs_model *m, const rs_inputs *in, const double *y)
{
  if (m->lay.ncomp < 2) return 0.0;
  return m->par.force_control ? y[rs_at_extra(&m->lay, 1)] : in->lateral_creepage;
}

double rs_model_scaling(const rs_model *m, const rs_inputs *in, double cj)
{
  const double self = rs_elastic_op_coef(&m->el, 0, 0, 0, 0) + m->layer_flex;
  rs_scaling choice = m->par.scaling;
  if (choice == RS_SCALING_AUTO)
    choice = m->par.plasticity.on ? RS_SCALING_SELF : RS_SCALING_DIFFERENCE;
  const double shift =
      choice == RS_SCALING_SELF ? self : self - rs_elastic_op_coef(&m->el, 0, 0, 1, 0);
  double denom = cj * self + in->velocity * shift / m->grid.dx;
  if (!(denom > 0.0)) denom = self / m->par.time_scale; /* no rolling, no time step */
  return 1.0 / denom;
}

void rs_model_inflow(const rs_model *m, const rs_inputs *in, double *state)
{
  const int width = (m->lay.ncomp + 1) * m->grid.ny;
  if (m->memory && !in->linear) {
    rs_rig_memory_inflow(m->memory, in->t, state);
  } else {
    for (int k = 0; k < width; k++) state[k] = 0.0;
  }
}

void rs_model_kinematics(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                         const double *yp)
{
  rs_model_kinematics_scaled(m, w, in, y, yp, -1.0);
}

void rs_model_kinematics_scaled(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                                const double *yp, double rate)
{
  const rs_layout *L = &m->lay;
  const rs_grid *g = &m->grid;
  const int n = L->n, nc = L->ncomp, nx = g->nx, ny = g->ny, px = nx + 1; /* padded row */
  rs_model_inflow(m, in, w->inflow);
  const double c3 = m->layer_flex, V = in->velocity, a = V / g->dx;
  const double xi =
      in->linear ? (L->nextra ? y[rs_at_extra(L, 0)] : 0.0) : rs_model_creepage(m, in, y);
  const double eta = nc < 2       ? 0.0
                     : in->linear ? (L->nextra ? y[rs_at_extra(L, 1)] : 0.0)
                                  : rs_model_lateral_creepage(m, in, y);
  const double phi = in->linear ? 0.0 : in->spin, shift = in->linear ? 0.0 : in->shift_velocity;
  const double *p = y + rs_at_p(L, 0, 0), *us = y + rs_at_ustar(L, 0);
  rs_elastic_op_tang(&m->el, &w->ew, p, w->uel, 1);
  if (rate >= 0.0) { /* p' = rate p: A p' from A p on the grid, one product fewer */
    for (int c = 0; c < nc; c++)
      for (int iy = 0; iy < ny; iy++)
        for (int ix = 0; ix < nx; ix++)
          w->ueldot[c * n + iy * nx + ix] = rate * w->uel[(size_t)c * px * ny + iy * px + ix];
  } else {
    rs_elastic_op_tang(&m->el, &w->ew, yp + rs_at_p(L, 0, 0), w->ueldot, 0);
  }
  for (int c = 0; c < nc; c++)
    for (int iy = 0; iy < ny; iy++)
      for (int ix = 0; ix < nx; ix++) {
        const int I = iy * nx + ix;
        w->uel[(size_t)c * px * ny + iy * px + ix] += c3 * p[c * n + I];
        w->ueldot[c * n + I] += c3 * yp[rs_at_p(L, c, I)];
      }
  /* friction memory: fresh material enters at mu_law(0) (nothing in the linear part) */
  const double *mu = L->memory ? y + rs_at_mu(L, 0) : NULL;
  const double mu_in = in->linear ? 0.0 : rs_friction_mu(&m->par.friction, 0.0);
  for (int iy = 0; iy < ny; iy++) {
    const double *in_row = w->inflow + iy * (nc + 1); /* u_pl components, then u* */
    for (int ix = 0; ix < nx; ix++) {
      const int I = iy * nx + ix, up = rs_grid_upstream(g, I);
      const double us_next = up >= 0 ? us[up] : in_row[nc];
      w->dustar[I] = yp[rs_at_ustar(L, I)] - a * (us_next - us[I]);
      if (mu) w->dmu[I] = yp[rs_at_mu(L, I)] - a * ((up >= 0 ? mu[up] : mu_in) - mu[I]);
      for (int c = 0; c < nc; c++) {
        const double *upl = y + rs_at_upl(L, c, 0);
        const double *u = w->uel + (size_t)c * px * ny + iy * px;
        /* rigid slip V w = V (xi - phi y, eta + phi x), docs/model.md §1 */
        const double vrigid =
            c == 0 ? V * (xi - phi * g->y[iy]) + shift : V * (eta + phi * g->x[ix]);
        const double upl_next = up >= 0 ? upl[up] : in_row[c];
        const double duel = w->ueldot[c * n + I] - a * (u[ix + 1] - u[ix]);
        w->dupl[c * n + I] = yp[rs_at_upl(L, c, I)] - a * (upl_next - upl[I]);
        w->vslip[c * n + I] = vrigid + duel + w->dupl[c * n + I];
      }
    }
  }
}

void rs_model_cell_law(const rs_model *m, const rs_work *w, const double *y, int I, int jac,
                       rs_law_out *out)
{
  const rs_layout *L = &m->lay;
  rs_law_in in = {.ncomp = L->ncomp,
                  .in_contact = w->pn[I] > 0.0,
                  .dustar = w->dustar[I],
                  .ustar = y[rs_at_ustar(L, I)],
                  .g = w->bound[I],
                  .r = w->r,
                  .r_yield = w->r_yield,
                  .friction = &m->par.friction,
                  .pn = w->pn[I],
                  .memory = L->memory,
                  .mu = L->memory ? y[rs_at_mu(L, I)] : 0.0,
                  .dmu = L->memory ? w->dmu[I] : 0.0};
  for (int c = 0; c < L->ncomp; c++) {
    in.p[c] = y[rs_at_p(L, c, I)];
    in.vs[c] = w->vslip[c * L->n + I];
    in.flow[c] = w->dupl[c * L->n + I];
  }
  if (m->mu_factor) { /* mu(T): the bound's factor, through p_n in every law's g = mu p_n */
    in.g *= m->mu_factor[I];
    in.pn *= m->mu_factor[I];
  }
  rs_plasticity pl; /* tau_c0(T): the cell's yield limit */
  rs_contact_law(rs_model_cell_plasticity(m, I, &pl), &in, jac, out);
}

int rs_model_cell_rows(const rs_model *m, const rs_work *w, const double *y, int I, int *row,
                       double *R)
{
  const rs_layout *L = &m->lay;
  rs_law_out o;
  rs_model_cell_law(m, w, y, I, 0, &o);
  int k = 0;
  for (int c = 0; c < L->ncomp; c++) {
    row[k] = rs_at_p(L, c, I);
    R[k++] = o.R[rs_law_row_f(c)];
    row[k] = rs_at_upl(L, c, I);
    R[k++] = o.R[rs_law_row_pl(L->ncomp, c)];
  }
  row[k] = rs_at_ustar(L, I);
  R[k++] = o.R[rs_law_row_star(L->ncomp)];
  if (L->memory) {
    row[k] = rs_at_mu(L, I);
    R[k++] = o.R[rs_law_row_mu(L->ncomp)];
  }
  return k;
}

int rs_model_residual(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, double *F)
{
  return rs_model_evaluate(m, w, in, y, yp, cj, F, 0);
}

/* What J v and the assembly need beyond the local laws: each row's dense flag and pivot,
 * and the local Jacobians' present entries in a compact list (rs_work). The products then
 * skip the entries that are not present, exact zeros (rs_contact_law): the same sums in
 * the same order, bit for bit the same results, in about half the time.
 * rs_model_evaluate takes each cell's right after its law (rs_model_cell_flags), while the
 * law's output is still in the first-level cache; a pass over all the cells' outputs after
 * the laws read them back from memory on fine grids (at 128 x 128 cells 10 MB). */
int rs_model_flags_alloc(const rs_model *m, rs_work *w)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  const int nrow = 2 * nc + 1 + L->memory, nvar = 3 * nc + 2 + 2 * L->memory;
  if (w->jv_start) return RS_OK;
  const size_t entries = (size_t)n * (size_t)(nrow * nvar);
  w->jv_start = malloc(((size_t)n + 1) * sizeof *w->jv_start);
  w->jv_idx = malloc(entries * sizeof *w->jv_idx);
  w->jv_val = malloc(entries * sizeof *w->jv_val);
  if (!w->jv_start || !w->jv_idx || !w->jv_val) {
    free(w->jv_start);
    free(w->jv_idx);
    free(w->jv_val);
    w->jv_start = NULL;
    w->jv_idx = NULL;
    w->jv_val = NULL;
    return rs_msg_set(&w->msg, RS_ERR_INTERNAL, "out of memory (local Jacobians)");
  }
  return RS_OK;
}

void rs_model_cell_flags(const rs_model *m, rs_work *w, int i, int *e)
{
  const rs_layout *L = &m->lay;
  const int nc = L->ncomp;
  const int nrow = 2 * nc + 1 + L->memory, nvar = 3 * nc + 2 + 2 * L->memory;
  const rs_law_out *o = &w->law[i];
  int k = *e;
  w->jv_start[i] = k;
  for (int lr = 0; lr < nrow; lr++)
    for (int q = 0; q < nvar; q++)
      if (o->present[lr][q]) {
        w->jv_idx[k] = (unsigned char)(16 * lr + q);
        w->jv_val[k++] = o->jac[lr][q];
      }
  *e = k;
  for (int c = 0; c < nc; c++) {
    const int row = rs_law_row_f(c), r = rs_at_p(L, c, i);
    w->dense[r] = 0;
    for (int b = 0; b < nc; b++) w->dense[r] |= o->present[row][rs_law_var_vs(nc, b)];
    w->pivot[r] = o->pins_p ? rs_at_upl(L, c, i) : r;
  }
  if (L->memory) { /* a memory row in the contact involves v_s: eliminated on mu */
    const int r = rs_at_mu(L, i);
    w->dense[r] = 0;
    for (int b = 0; b < nc; b++) w->dense[r] |= o->present[rs_law_row_mu(nc)][rs_law_var_vs(nc, b)];
    w->pivot[r] = r;
  }
}

/* The friction projections' weight of the slip velocity in steady Newton's evaluations of
 * a 3D hardening model, in units of r (rs_model_evaluate). */
#define FRICTION_WEIGHT           0.7
#define FRICTION_WEIGHT_PER_K_REL 10.0
#define TAU_C_FLOOR               0.1

int rs_model_evaluate(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, double *F, int jac)
{
  const rs_layout *L = &m->lay;
  const int n = L->n;
  const double r0 = rs_model_scaling(m, in, cj);
  /* Steady Newton's evaluations (in->newton) of a 3D hardening model (k_tau > 0, Coulomb
   * friction, no friction memory) weigh the slip velocity in the friction projections with
   * 0.7 r; other evaluations (the regimes reported of transient states, which depend on the
   * weight where cells are not at a steady state) keep r. Any r gives the same zeros; with
   * hardening, cells harden up to the friction bound and then slip, a front that the
   * continuation predictor misses by many cells, and the smaller weight lets Newton move them
   * in fewer iterations. Perfect plasticity, softening and elastic models keep r (no gain, or
   * another of several steady states). The steady check (rs_model_check_steady) measures
   * rates through the same weight. */
  const int hardening = in->newton && cj == 0.0 && m->el.dim == 3 && m->par.plasticity.on &&
                        m->par.plasticity.k_tau > 0.0 && !rs_friction_varies(&m->par.friction) &&
                        !L->memory;
  /* Weak hardening (10 k_rel tau_c0/g_max below 0.7, with g_max the largest bound mu p_n):
   * the weight falls with k_rel and tau_c0, to FRICTION_WEIGHT_PER_K_REL k_rel
   * tau_c0/g_max r. A cell that hardened up to the friction bound slips and flows at once,
   * its u* pinned by tau_c(u*) = mu p_n, so a change of its traction moves u* by that change
   * over k_tau, and the flow and u* of every cell downstream with it. With the slip velocity
   * weighed by 0.7 r the slip test of such cells flipped with these moves and Newton cycled
   * between the slip + yield and the yield-only branch; a weight in proportion to k_rel keeps
   * the test on the traction. A low tau_c0 makes the hardened zone longer (from tau_c0 up to
   * mu p_n) and asks for a smaller weight still (bench/RESULTS.md, issue 42). The factor
   * tau_c0/g_max is kept above TAU_C_FLOOR: r must stay positive. */
  const double k_tau = m->par.plasticity.k_tau, k_rel = k_tau / (m->par.shear_modulus + k_tau);
  double g_max = 0.0;
  for (int i = 0; i < n && hardening; i++) g_max = fmax(g_max, m->bound[i]);
  double tau_c0 = m->par.plasticity.tau_c0, lowest = INFINITY; /* tau_c0(T): the lowest cell's */
  for (int i = 0; i < n && hardening && m->yield_factor; i++)
    if (m->bound[i] > 0.0) lowest = fmin(lowest, tau_c0 * m->yield_factor[i]);
  if (lowest < INFINITY) tau_c0 = lowest;
  const double margin = g_max > 0.0 ? fmax(tau_c0 / g_max, TAU_C_FLOOR) : 1.0;
  w->r = hardening ? fmin(FRICTION_WEIGHT, FRICTION_WEIGHT_PER_K_REL * k_rel * margin) * r0 : r0;
  /* The yield projections of steady evaluations (cj = 0) weigh the flow with a fraction of
   * r. Any r > 0 gives the same zeros (a projection is exact for every r); r sets how
   * Newton's linearisation weighs the flow against the traction, and a smaller weight lets
   * steady Newton move cells into and out of yield with fewer line-search steps (0.2 r: the
   * fewest iterations on the bench's plastic creep curves). Transients keep r (more Newton
   * iterations with 0.2 r), and so does 2D (the interval law). */
  w->r_yield = cj == 0.0 ? 0.2 * r0 : r0;
  int status = rs_model_normal_at(m, w, in, &w->msg);
  if (status != RS_OK) return status;
  if (jac && (status = rs_model_flags_alloc(m, w)) != RS_OK) return status;
  rs_model_kinematics(m, w, in, y, yp);
  if (w->before_laws && (status = w->before_laws(w->before_laws_ctx, w, in, y)) != RS_OK)
    return status;
  int e = 0;
  for (int i = 0; i < n; i++) {
    rs_law_out *o = &w->law[i];
    rs_model_cell_law(m, w, y, i, jac, o);
    if (jac) rs_model_cell_flags(m, w, i, &e);
    w->branch[i] = o->branch;
    if (!F) continue;
    for (int c = 0; c < L->ncomp; c++) {
      F[rs_at_p(L, c, i)] = o->R[rs_law_row_f(c)];
      F[rs_at_upl(L, c, i)] = o->R[rs_law_row_pl(L->ncomp, c)];
    }
    F[rs_at_ustar(L, i)] = o->R[rs_law_row_star(L->ncomp)];
    if (L->memory) F[rs_at_mu(L, i)] = o->R[rs_law_row_mu(L->ncomp)];
  }
  if (jac) w->jv_start[n] = e;
  /* Force rows, scaled to a mean traction over the contact (2a in 2D, pi a b in 3D). */
  for (int k = 0; F && k < L->nextra; k++) {
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += y[rs_at_p(L, k, i)];
    F[rs_at_extra(L, k)] = m->grid.area / m->contact_measure * sum -
                           (k == 0 ? in->force : in->force_y) / m->contact_measure;
  }
  return RS_OK;
}
