/* The normal problem on every wheel-rail patch under one vertical wheel load
 * (physics/wr_contact.h, docs/model.md §20): the wheel approaches the rail vertically by dz;
 * patch i closes by d_i = (dz - gap_i) cos(delta_i) along its normal; dz is found so that
 * sum F_n,i cos(delta_i) = F_z. */
#include "physics/wr_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/elastic2d.h" /* RS_PI */
#include "physics/elastic3d.h"

/* One patch's grid and elastic model while the load sharing is solved. */
typedef struct patch_solver {
  const rs_wr_patch *geo;
  int active; /* has a grid */
  rs_elastic3d el;
  rs_elastic3d_work work;
  rs_grid3d grid;
  double *h, *p, *start;
  int have_start;
  double h_min;
  double load, approach; /* of the last solve */
  int solves;
} patch_solver;

/* The patch's normal approach at the wheel's vertical approach dz. */
static double normal_approach(const rs_wr_patch *p, double dz)
{
  return (dz - p->gap) * cos(p->delta);
}

/* The interpenetration region of a patch at normal approach d: the s-range around the
 * contact point where h(0, s) < d (the end of the patch's table when it does not close),
 * and the x-range: |x| < the half-length where x^2 cos(delta)/(2r) < d; with yaw (p->xo)
 * where curv_x (x - xo(s))^2 / 2 < d - h(s) at some s of that s-range. */
static void region(const rs_wr_patch *p, double d, double s[2], double x[2])
{
  size_t k0 = 0;
  while (k0 + 1 < p->ns && p->s[k0 + 1] <= 0.0) k0++;
  s[0] = p->s[0];
  s[1] = p->s[p->ns - 1];
  for (size_t k = k0 + 1; k < p->ns; k++)
    if (p->h[k] >= d) {
      s[1] = p->s[k - 1] + (p->s[k] - p->s[k - 1]) * (d - p->h[k - 1]) / (p->h[k] - p->h[k - 1]);
      break;
    }
  for (size_t k = k0 + 1; k-- > 0;)
    if (p->h[k] >= d) {
      s[0] = p->s[k + 1] + (p->s[k] - p->s[k + 1]) * (d - p->h[k + 1]) / (p->h[k] - p->h[k + 1]);
      break;
    }
  if (!p->xo) {
    x[1] = sqrt(2.0 * p->rolling_radius * fmax(d, 0.0) / cos(p->delta));
    x[0] = -x[1];
    return;
  }
  double lo = 0.0, hi = 0.0;
  for (size_t k = 0; k < p->ns; k++)
    if (p->s[k] >= s[0] && p->s[k] <= s[1]) {
      const double half = sqrt(2.0 * fmax(d - p->h[k], 0.0) / p->curv_x);
      lo = fmin(lo, p->xo[k] - half);
      hi = fmax(hi, p->xo[k] + half);
    }
  x[0] = lo;
  x[1] = hi;
}

/* A start value for the grids only: the load of a patch at normal approach d estimated as
 * 0.532 E* d sqrt(A), A the area of its interpenetration region (the Hertz relation of a
 * circular contact, F = 4/3 E* R^(1/2) d^(3/2) with A = 2 pi R d, written without radii). */
static double load_estimate(const rs_wr_patch *p, double d, double estar)
{
  if (!(d > 0)) return 0.0;
  double area = 0.0;
  const double k = p->xo ? 2.0 / p->curv_x : 2.0 * p->rolling_radius / cos(p->delta);
  for (size_t j = 0; j + 1 < p->ns; j++) {
    const double a = fmax(d - p->h[j], 0.0), b = fmax(d - p->h[j + 1], 0.0);
    area += (p->s[j + 1] - p->s[j]) * (sqrt(k * a) + sqrt(k * b));
  }
  return 4.0 / (3.0 * sqrt(2.0 * RS_PI)) * estar * d * sqrt(area);
}

static double estimate_dz(const rs_wr_geometry *geo, double fz, double estar)
{
  double lo = 0.0, hi = 1e-3;
  for (int it = 0; it < 200; it++) {
    double f = 0.0;
    for (int i = 0; i < geo->npatch; i++)
      f += cos(geo->patch[i].delta) *
           load_estimate(&geo->patch[i], normal_approach(&geo->patch[i], hi), estar);
    if (f >= fz) break;
    lo = hi;
    hi *= 2.0;
  }
  for (int it = 0; it < 60; it++) {
    const double mid = 0.5 * (lo + hi);
    double f = 0.0;
    for (int i = 0; i < geo->npatch; i++)
      f += cos(geo->patch[i].delta) *
           load_estimate(&geo->patch[i], normal_approach(&geo->patch[i], mid), estar);
    if (f < fz)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

static void patch_solver_free(patch_solver *ps)
{
  if (ps->active) {
    rs_elastic3d_work_free(&ps->work);
    rs_elastic3d_free(&ps->el);
  }
  free(ps->h);
  free(ps->p);
  free(ps->start);
  ps->h = ps->p = ps->start = NULL;
  ps->active = 0;
}

/* The patch's grid from its interpenetration region at normal approach d, widened by
 * RS_WR_MARGIN of its length on each side (along s within the patch's table). */
static int patch_grid(patch_solver *ps, double d, int nx, int ns, double shear_modulus,
                      double poisson_ratio, rs_msg *msg)
{
  const rs_wr_patch *p = ps->geo;
  double s[2], x[2];
  region(p, d, s, x);
  const double ws = s[1] - s[0];
  const double s0 = fmax(s[0] - RS_WR_MARGIN * ws, p->s[0]);
  const double s1 = fmin(s[1] + RS_WR_MARGIN * ws, p->s[p->ns - 1]);
  if (p->xo) { /* the yawed wheel's region lies off x = 0 */
    const double wx = x[1] - x[0];
    ps->grid = (rs_grid3d){.nx = nx,
                           .ny = ns,
                           .x0 = x[0] - RS_WR_MARGIN * wx,
                           .y0 = s0,
                           .dx = (1.0 + 2.0 * RS_WR_MARGIN) * wx / nx,
                           .dy = (s1 - s0) / ns};
  } else {
    const double x0 = x[1] * (1.0 + 2.0 * RS_WR_MARGIN);
    ps->grid = (rs_grid3d){
        .nx = nx, .ny = ns, .x0 = -x0, .y0 = s0, .dx = 2.0 * x0 / nx, .dy = (s1 - s0) / ns};
  }
  const size_t n = (size_t)nx * ns;
  ps->h = malloc(n * sizeof *ps->h);
  ps->p = malloc(n * sizeof *ps->p);
  ps->start = malloc(n * sizeof *ps->start);
  if (!ps->h || !ps->p || !ps->start) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  rs_wr_patch_gap(p, &ps->grid, ps->h);
  ps->h_min = INFINITY;
  for (size_t k = 0; k < n; k++) ps->h_min = fmin(ps->h_min, ps->h[k]);
  int status = rs_elastic3d_create(&ps->el, nx, ns, ps->grid.dx, ps->grid.dy, shear_modulus,
                                   poisson_ratio, msg);
  if (status != RS_OK) return status;
  status = rs_elastic3d_work_create(&ps->work, &ps->el, msg);
  if (status != RS_OK) {
    rs_elastic3d_free(&ps->el);
    return status;
  }
  ps->active = 1;
  ps->have_start = 0;
  return RS_OK;
}

/* The patch's normal approach under load F (one normal solve, started from the last). */
static int approach_at(patch_solver *ps, double load, double *approach, rs_msg *msg)
{
  int status = rs_normal3d_solve(&ps->el, &ps->work, ps->h, load, ps->have_start ? ps->start : NULL,
                                 ps->p, approach, NULL, msg);
  if (status != RS_OK) return status;
  ps->solves++;
  ps->load = load;
  ps->approach = *approach;
  memcpy(ps->start, ps->p, (size_t)ps->el.nx * ps->el.ny * sizeof *ps->p);
  ps->have_start = 1;
  return RS_OK;
}

/* Root of f(t) = 0 bracketed by f(t0) < 0 < f(t1), by the Illinois variant of regula falsi
 * (Dowell & Jarratt 1971): superlinear and never leaves the bracket. Stops when |f| <= ftol
 * or the bracket is narrower than ttol. */
typedef int (*root_fn)(void *ctx, double t, double *f, rs_msg *msg);
static int illinois(root_fn fn, void *ctx, double t0, double f0, double t1, double f1, double ftol,
                    double ttol, double *t, rs_msg *msg)
{
  int side = 0;
  for (int it = 0; it < 200; it++) {
    double tc = t1 - f1 * (t1 - t0) / (f1 - f0);
    if (!(tc > fmin(t0, t1) && tc < fmax(t0, t1))) tc = 0.5 * (t0 + t1);
    double fc;
    int status = fn(ctx, tc, &fc, msg);
    if (status != RS_OK) return status;
    if (fabs(fc) <= ftol || fabs(t1 - t0) <= ttol) {
      *t = tc;
      return RS_OK;
    }
    if ((fc < 0) == (f0 < 0)) {
      t0 = tc, f0 = fc;
      if (side == -1) f1 *= 0.5;
      side = -1;
    } else {
      t1 = tc, f1 = fc;
      if (side == 1) f0 *= 0.5;
      side = 1;
    }
  }
  return rs_msg_set(msg, RS_ERR_SOLVER, "the wheel-rail load sharing did not converge");
}

/* Bracket a root of an increasing f from a start t: steps up or down, the first 2 |f(t)|
 * (f is a relative error and t a logarithm of a quantity ~ (the other)^(3/2)), doubling. */
static int bracket(root_fn fn, void *ctx, double t, double *t0, double *f0, double *t1, double *f1,
                   rs_msg *msg)
{
  double f;
  int status = fn(ctx, t, &f, msg);
  if (status != RS_OK) return status;
  if (f == 0.0) {
    *t0 = *t1 = t;
    *f0 = *f1 = 0.0;
    return RS_OK;
  }
  const double dir = f < 0 ? 1.0 : -1.0;
  double step = fmin(fmax(2.0 * fabs(f), 1e-9), 0.7);
  for (int it = 0; it < 60; it++, step *= 2.0) {
    const double tn = t + dir * step;
    double fn_;
    if ((status = fn(ctx, tn, &fn_, msg)) != RS_OK) return status;
    if ((fn_ < 0) != (f < 0) || fn_ == 0.0) {
      *t0 = dir > 0 ? t : tn, *f0 = dir > 0 ? f : fn_;
      *t1 = dir > 0 ? tn : t, *f1 = dir > 0 ? fn_ : f;
      return RS_OK;
    }
    t = tn, f = fn_;
  }
  return rs_msg_set(msg, RS_ERR_SOLVER, "the wheel-rail load sharing found no bracket");
}

/* Inner problem: the load F = exp(t) of one patch whose normal approach is `target`. */
typedef struct inner_ctx {
  patch_solver *ps;
  double target;
} inner_ctx;

static int inner_fn(void *ctx, double t, double *f, rs_msg *msg)
{
  inner_ctx *c = ctx;
  double a;
  int status = approach_at(c->ps, exp(t), &a, msg);
  *f = (a - c->target) / c->target;
  return status;
}

/* The load of a patch at normal approach d on its grid (0 when d does not reach h's
 * minimum on it); the pressure stays in ps->p. */
static int load_at(patch_solver *ps, double d, double estar, double *load, rs_msg *msg)
{
  if (!(d > ps->h_min)) {
    *load = 0.0;
    return RS_OK;
  }
  inner_ctx c = {ps, d};
  /* start from the last load scaled as d^(3/2), or from the estimate */
  double guess = ps->have_start && ps->approach > ps->h_min
                     ? ps->load * pow((d - ps->h_min) / (ps->approach - ps->h_min), 1.5)
                     : load_estimate(ps->geo, d, estar);
  if (!(guess > 0)) guess = 1.0;
  double t0 = 0, f0 = 0, t1 = 0, f1 = 0, t = 0;
  int status = bracket(inner_fn, &c, log(guess), &t0, &f0, &t1, &f1, msg);
  if (status == RS_OK && f0 == f1) {
    *load = exp(t0);
    return approach_at(ps, *load, &d, msg);
  }
  if (status == RS_OK)
    status = illinois(inner_fn, &c, t0, f0, t1, f1, RS_WR_APPROACH_TOL, 1e-14, &t, msg);
  if (status != RS_OK) return status;
  *load = exp(t);
  if (ps->load != *load) return approach_at(ps, *load, &d, msg);
  return RS_OK;
}

/* Outer problem: the vertical approach dz = exp(t) balancing the vertical load. */
typedef struct outer_ctx {
  const rs_wr_geometry *geo;
  patch_solver *ps;
  double fz, estar;
  double load[RS_WR_MAX_PATCHES];
} outer_ctx;

static int outer_fn(void *ctx, double t, double *f, rs_msg *msg)
{
  outer_ctx *c = ctx;
  const double dz = exp(t);
  double sum = 0.0;
  for (int i = 0; i < c->geo->npatch; i++) {
    c->load[i] = 0.0;
    if (!c->ps[i].active) continue;
    const rs_wr_patch *p = &c->geo->patch[i];
    int status = load_at(&c->ps[i], normal_approach(p, dz), c->estar, &c->load[i], msg);
    if (status != RS_OK) return status;
    sum += c->load[i] * cos(p->delta);
  }
  *f = (sum - c->fz) / c->fz;
  return RS_OK;
}

/* dz on the current grids. With one grid the patch's load is F_z / cos(delta) directly. */
static int balance(outer_ctx *c, double dz_guess, double *dz, rs_msg *msg)
{
  int active = 0, only = -1;
  for (int i = 0; i < c->geo->npatch; i++)
    if (c->ps[i].active) active++, only = i;
  if (active == 1) {
    const rs_wr_patch *p = &c->geo->patch[only];
    double a;
    const double load = c->fz / cos(p->delta);
    int status = approach_at(&c->ps[only], load, &a, msg);
    if (status != RS_OK) return status;
    for (int i = 0; i < c->geo->npatch; i++) c->load[i] = 0.0;
    c->load[only] = load;
    *dz = a / cos(p->delta) + p->gap;
    return RS_OK;
  }
  double t0 = 0, f0 = 0, t1 = 0, f1 = 0, t = 0;
  int status = bracket(outer_fn, c, log(dz_guess), &t0, &f0, &t1, &f1, msg);
  if (status == RS_OK && f0 == f1) {
    *dz = exp(t0);
    return RS_OK;
  }
  if (status == RS_OK)
    status = illinois(outer_fn, c, t0, f0, t1, f1, RS_WR_FORCE_TOL, 1e-14, &t, msg);
  if (status != RS_OK) return status;
  *dz = exp(t); /* the last evaluation: the loads and pressures are those at dz */
  return RS_OK;
}

void rs_wr_solution_free(rs_wr_solution *sol)
{
  for (int i = 0; i < RS_WR_MAX_PATCHES; i++) free(sol->patch[i].pn);
  memset(sol, 0, sizeof *sol);
}

int rs_wr_normal_solve(const rs_wr_geometry *geo, double vertical_load, double shear_modulus,
                       double poisson_ratio, int nx, int ns, rs_wr_solution *sol, rs_msg *msg)
{
  memset(sol, 0, sizeof *sol);
  sol->npatch = geo->npatch;
  const double estar = shear_modulus / (1.0 - poisson_ratio);
  patch_solver ps[RS_WR_MAX_PATCHES];
  memset(ps, 0, sizeof ps);
  for (int i = 0; i < geo->npatch; i++) ps[i].geo = &geo->patch[i];
  outer_ctx c = {.geo = geo, .ps = ps, .fz = vertical_load, .estar = estar};
  double dz = estimate_dz(geo, vertical_load, estar), dz_new = dz;
  int status = RS_OK, settled = 0;
  /* grids from the interpenetration regions at dz; again at the solved dz until the set of
   * loaded patches stays and dz moves by at most 5 % (the regions' lengths by ~2.5 %). The
   * first round, a scout, runs on a quarter of the cells along each axis (a sixteenth of the
   * work): its dz replaces the closed-form estimate, which can be off by more than 5 % for a
   * patch that is not Hertzian, so that the first round on the case's grid settles. */
  const int scout = nx >= 4 * RS_WR_SCOUT_CELLS && ns >= 4 * RS_WR_SCOUT_CELLS;
  for (int round = 0; round < 8 + scout && status == RS_OK && !settled; round++) {
    const int coarse = scout && round == 0;
    for (int i = 0; i < geo->npatch; i++) patch_solver_free(&ps[i]);
    for (int i = 0; i < geo->npatch && status == RS_OK; i++) {
      const double d = normal_approach(&geo->patch[i], dz);
      if (d > 0)
        status = patch_grid(&ps[i], d, coarse ? nx / 4 : nx, coarse ? ns / 4 : ns, shear_modulus,
                            poisson_ratio, msg);
    }
    if (status != RS_OK) break;
    sol->grid_rounds += !coarse;
    status = balance(&c, dz, &dz_new, msg);
    if (status != RS_OK) break;
    settled = !coarse && fabs(dz_new - dz) <= 0.05 * dz_new;
    for (int i = 0; i < geo->npatch; i++)
      if ((normal_approach(&geo->patch[i], dz_new) > 0) != ps[i].active) settled = 0;
    if (!settled) dz = dz_new;
  }
  if (status == RS_OK && !settled)
    status = rs_msg_set(msg, RS_ERR_SOLVER,
                        "the patches' grids did not settle (the loaded patches or the approach "
                        "changed in every round)");
  if (status == RS_OK) {
    sol->dz = dz_new;
    for (int i = 0; i < geo->npatch; i++) {
      rs_wr_patch_result *r = &sol->patch[i];
      const patch_solver *q = &ps[i];
      sol->normal_solves += q->solves;
      r->approach = normal_approach(&geo->patch[i], dz_new);
      if (!q->active || c.load[i] <= 0.0) continue;
      r->loaded = 1;
      r->normal_force = c.load[i];
      r->approach = q->approach;
      r->grid = q->grid;
      r->h_min = q->h_min;
      const size_t n = (size_t)q->grid.nx * q->grid.ny;
      if (!(r->pn = malloc(n * sizeof *r->pn))) {
        status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
        break;
      }
      memcpy(r->pn, q->p, n * sizeof *r->pn);
      r->x_extent[0] = r->s_extent[0] = INFINITY;
      r->x_extent[1] = r->s_extent[1] = -INFINITY;
      for (int js = 0; js < q->grid.ny; js++)
        for (int ix = 0; ix < q->grid.nx; ix++) {
          const double pv = r->pn[(size_t)js * q->grid.nx + ix];
          if (!(pv > 0)) continue;
          r->area += q->grid.dx * q->grid.dy;
          r->p_max = fmax(r->p_max, pv);
          r->x_extent[0] = fmin(r->x_extent[0], q->grid.x0 + ix * q->grid.dx);
          r->x_extent[1] = fmax(r->x_extent[1], q->grid.x0 + (ix + 1) * q->grid.dx);
          r->s_extent[0] = fmin(r->s_extent[0], q->grid.y0 + js * q->grid.dy);
          r->s_extent[1] = fmax(r->s_extent[1], q->grid.y0 + (js + 1) * q->grid.dy);
        }
      sol->vertical += r->normal_force * cos(geo->patch[i].delta);
    }
  } else {
    for (int i = 0; i < geo->npatch; i++) sol->normal_solves += ps[i].solves;
  }
  for (int i = 0; i < geo->npatch; i++) patch_solver_free(&ps[i]);
  if (status != RS_OK) rs_wr_solution_free(sol);
  return status;
}
