/* Discretisation error estimates (study/errest.h, docs/model.md "Discretisation error
 * estimates"). The scheme is first order in the cell size (upwind transport, piecewise
 * constant tractions), so a converged force behaves as F(h) = F + C h^p + ... with p near 1
 * once the grid resolves the contact; three grids give p and the error of the finest. */
#include "study/errest.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rs_errest_combine(double f1, double f2, double f3, double r21, double r32, double noise,
                      double *err)
{
  double extrap;
  return rs_errest_combine_extrapolate(f1, f2, f3, r21, r32, noise, err, &extrap);
}

int rs_errest_combine_extrapolate(double f1, double f2, double f3, double r21, double r32,
                                  double noise, double *err, double *extrap)
{
  const double e21 = f2 - f1, e32 = f3 - f2;
  *extrap = NAN;
  if (fabs(e21) <= noise && fabs(e32) <= noise) { /* converged to the solver's tolerance */
    *err = fmax(noise, fmax(fabs(e21), fabs(e32)));
    *extrap = f1;
    return 1;
  }
  /* Outside the asymptotic range the finer pair's difference can be small by chance (the
   * results cross, or stall for a refinement): the coarser pair's difference scaled to h1 as
   * if the error fell with h^2 (faster than the first-order scheme can) bounds it from below
   * too. */
  const double coarse = fabs(e32) / (r21 * r32);
  /* Oscillating (the two differences of opposite signs): no order; the formal order 1 with
   * the fallback's safety factor. */
  if (e21 == 0.0 || e32 / e21 <= 0.0) {
    *err = RS_ERREST_SAFETY_FALLBACK * fmax(fabs(e21) / (r21 - 1.0), coarse);
    return 0;
  }
  /* The observed order for unequal ratios (Celik et al. 2008): the fixed point of
   * p = (ln(e32/e21) + ln((r21^p - 1)/(r32^p - 1))) / ln r21 (q = 0 for equal ratios). */
  const double lr = log(r21), le = log(e32 / e21);
  double p = le / lr;
  for (int k = 0; k < 100 && isfinite(p) && p > 0.0; k++) {
    const double next = (le + log((pow(r21, p) - 1.0) / (pow(r32, p) - 1.0))) / lr;
    const int done = fabs(next - p) < 1e-12;
    p = next;
    if (done) break;
  }
  /* Within RS_ERREST_P_TOL of the formal order the three grids are in the asymptotic range:
   * the grid convergence index with the observed order; else (Roy's variant) the safety
   * factor of the fallback with the order taken in [0.5, 1], never above the formal one. */
  if (isfinite(p) && fabs(p - 1.0) <= RS_ERREST_P_TOL) {
    *err = RS_ERREST_SAFETY * fabs(e21) / (pow(r21, p) - 1.0);
    *extrap = f1 - e21 / (pow(r21, p) - 1.0); /* Richardson with the observed order */
    return 1;
  }
  const double pu = isfinite(p) ? fmin(fmax(p, RS_ERREST_P_MIN), 1.0) : RS_ERREST_P_MIN;
  *err = RS_ERREST_SAFETY_FALLBACK * fmax(fabs(e21) / (pow(r21, pu) - 1.0), coarse);
  return 0;
}

void rs_errest_none(rs_diag *d)
{
  d->error_state = RS_ERROR_NONE;
  d->Fx_error = d->Fy_error = d->Mz_error = NAN;
  d->Fx_extrapolated = d->Fy_extrapolated = d->Mz_extrapolated = NAN;
}

void rs_errest_copy(rs_diag *d, const rs_diag *e)
{
  d->Fx_error = e->Fx_error;
  d->Fy_error = e->Fy_error;
  d->Mz_error = e->Mz_error;
  d->Fx_extrapolated = e->Fx_extrapolated;
  d->Fy_extrapolated = e->Fy_extrapolated;
  d->Mz_extrapolated = e->Mz_extrapolated;
  d->error_state = e->error_state;
}

/* Cells along x of the companions: halved twice (integer division). */
static void companion_cells(int nx, int out[2])
{
  out[0] = nx / 2;
  out[1] = nx / 4;
}

double rs_errest_worst(const rs_model *m, const rs_diag *d)
{
  const double scale = m->par.friction.mu * fabs(d->Fn);
  if (m->grid.ny == 1) return d->Fx_error / scale;
  return fmax(fmax(d->Fx_error, d->Fy_error) / scale, d->Mz_error / (scale * m->hertz_a));
}

/* Cells across the Hertz contact along each axis (the fewer) on the grid of m with nx
 * cells along x (3D: ny in proportion, as rs_model_regrid makes them). */
static int cells_across(const rs_model *m, int nx)
{
  int across = (int)floor(2.0 * m->hertz_a * nx / (m->grid.x_hi - m->grid.x_lo) + 1e-9);
  if (m->grid.ny > 1) {
    const int ny = (int)((long)m->grid.ny * nx / m->grid.nx);
    const int ay = (int)floor(2.0 * m->hertz_b * ny / (m->grid.y_hi - m->grid.y_lo) + 1e-9);
    across = ay < across ? ay : across;
  }
  return across;
}

int rs_errest_admissible(const rs_model *m, char *why, size_t len)
{
  if (m->par.force_control) {
    snprintf(why, len, "no error estimate with a prescribed tangential force");
    return 0;
  }
  if (cells_across(m, m->grid.nx / 4) < RS_ERREST_MIN_CELLS) {
    int need = m->grid.nx;
    while (need < (1 << 20) && cells_across(m, need / 4) < RS_ERREST_MIN_CELLS) need++;
    snprintf(why, len,
             "no error estimate: the grid is too coarse (the estimate solves the point again on "
             "grids of a half and a quarter of the cells, whose coarsest needs at least %d cells "
             "across the contact; give at least %d along x%s)",
             RS_ERREST_MIN_CELLS, need, m->grid.ny > 1 ? ", y in proportion" : "");
    return 0;
  }
  return 1;
}

void rs_errest_free(rs_errest *e)
{
  for (int k = 0; k < 2; k++) {
    rs_steady_free(e->st[k]);
    rs_work_free(&e->w[k]);
    free(e->y[k]);
    free(e->yp[k]);
    if (e->m[k].grid.x) rs_model_free(&e->m[k]);
  }
  memset(e, 0, sizeof *e);
}

/* The cell size ratio of two grids (3D: of the square roots of the cell areas). */
static double ratio(const rs_model *fine, const rs_model *coarse)
{
  const double r = (double)fine->grid.n / (double)coarse->grid.n;
  return fine->grid.ny > 1 ? sqrt(r) : r;
}

int rs_errest_create(rs_errest *e, const rs_model *m, SUNContext ctx, rs_msg *msg)
{
  memset(e, 0, sizeof *e);
  int c[2];
  companion_cells(m->grid.nx, c);
  int status = RS_OK;
  for (int k = 0; k < 2 && status == RS_OK; k++) {
    status = rs_model_regrid(m, c[k], &e->m[k], msg);
    if (status != RS_OK) break;
    const size_t neq = (size_t)e->m[k].lay.neq;
    e->y[k] = calloc(neq, sizeof *e->y[k]);
    e->yp[k] = calloc(neq, sizeof *e->yp[k]);
    if (!e->y[k] || !e->yp[k] || rs_work_create(&e->w[k], &e->m[k]) != RS_OK)
      status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the error estimate's grids");
    if (status == RS_OK) status = rs_steady_create(&e->st[k], &e->m[k], ctx, msg);
    /* Where the companion's solve would have to roll the material from the finer solution
     * (thousands of Newton iterations), the point gets no estimate instead. */
    if (status == RS_OK) rs_steady_set_fail_fast(e->st[k], RS_FAIL_UNROLLED);
  }
  if (status != RS_OK) { /* a companion that cannot be built: no estimate, the point stands */
    rs_errest_free(e);
    return status == RS_ERR_INTERNAL ? status : RS_OK;
  }
  e->r21 = ratio(m, &e->m[0]);
  e->r32 = ratio(&e->m[0], &e->m[1]);
  e->on = 1;
  return RS_OK;
}

/* The companion takes the rolling inputs of the model (the chain of a sweep changes them
 * from point to point). */
static int copy_rolling(rs_model *dst, const rs_model *src)
{
  rs_history *d[] = {&dst->par.velocity, &dst->par.creepage,       &dst->par.lateral_creepage,
                     &dst->par.spin,     &dst->par.shift_velocity, &dst->par.force,
                     &dst->par.force_y};
  const rs_history *s[] = {&src->par.velocity, &src->par.creepage,       &src->par.lateral_creepage,
                           &src->par.spin,     &src->par.shift_velocity, &src->par.force,
                           &src->par.force_y};
  for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) {
    rs_history_free(d[k]);
    if (rs_history_copy(d[k], s[k]) != RS_OK) return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

int rs_errest_point(rs_errest *e, const rs_model *m, const double *y, rs_diag *d, rs_msg *msg)
{
  rs_errest_none(d);
  if (!e->on) return RS_OK;
  double f[3][3] = {{d->Fx, d->Fy, d->Mz}};
  const rs_model *from = m;
  const double *from_y = y;
  for (int k = 0; k < 2; k++) {
    rs_model *cm = &e->m[k];
    if (copy_rolling(cm, m) != RS_OK)
      return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the error estimate's inputs");
    rs_inputs in;
    rs_model_inputs_at(cm, 0.0, &in);
    rs_msg cmsg = {{0}};
    rs_stats st = {0};
    rs_diag dk;
    /* from the finer solution at the same inputs: the companion's differs by the
     * discretisation error only */
    int status = rs_model_interpolate_state(from, from_y, cm, &e->w[k], &in, e->y[k], &cmsg);
    if (status == RS_OK) status = rs_steady_solve(e->st[k], 0.0, e->y[k], &st, &cmsg);
    if (status == RS_OK)
      status = rs_model_diagnostics(cm, &e->w[k], &in, e->y[k], e->yp[k], &dk, NULL, NULL, NULL);
    if (status == RS_ERR_INTERNAL) return rs_msg_set(msg, status, "%s", cmsg.text);
    if (status != RS_OK) return RS_OK; /* a companion not solved: no estimate */
    f[k + 1][0] = dk.Fx;
    f[k + 1][1] = dk.Fy;
    f[k + 1][2] = dk.Mz;
    from = cm;
    from_y = e->y[k];
  }
  rs_diag d2 = {.Fx = f[1][0], .Fy = f[1][1], .Mz = f[1][2]};
  rs_diag d3 = {.Fx = f[2][0], .Fy = f[2][1], .Mz = f[2][2]};
  rs_errest_diag(m, e->r21, e->r32, &d2, &d3, d);
  return RS_OK;
}

void rs_errest_diag(const rs_model *m, double r21, double r32, const rs_diag *d2, const rs_diag *d3,
                    rs_diag *d)
{
  const int three = m->grid.ny > 1;
  const double force_scale = m->par.friction.mu * fabs(d->Fn);
  const double scale[3] = {force_scale, force_scale, force_scale * m->hertz_a};
  const double f[3][3] = {
      {d->Fx, d->Fy, d->Mz}, {d2->Fx, d2->Fy, d2->Mz}, {d3->Fx, d3->Fy, d3->Mz}};
  double err[3] = {NAN, NAN, NAN}, ext[3] = {NAN, NAN, NAN};
  int reliable = 1;
  for (int q = 0; q < (three ? 3 : 1); q++)
    reliable &= rs_errest_combine_extrapolate(f[0][q], f[1][q], f[2][q], r21, r32,
                                              RS_ERREST_NOISE * scale[q], &err[q], &ext[q]);
  d->Fx_error = err[0];
  d->Fy_error = err[1];
  d->Mz_error = err[2];
  /* The extrapolated values only where every quantity's grids are asymptotic (error_reliable) */
  d->Fx_extrapolated = reliable ? ext[0] : NAN;
  d->Fy_extrapolated = reliable ? ext[1] : NAN;
  d->Mz_extrapolated = reliable ? ext[2] : NAN;
  d->error_state = reliable ? RS_ERROR_RELIABLE : RS_ERROR_UNRELIABLE;
}

/* One grid of the refinement: the model of m's case with nx cells along x, solved from
 * yfrom (on `from`) interpolated, or from rest. */
static int refine_level(const rs_model *m, int nx, SUNContext ctx, const rs_model *from,
                        const double *yfrom, rs_model *g, double **y, rs_diag *d, rs_msg *msg)
{
  int status = rs_model_regrid(m, nx, g, msg);
  if (status != RS_OK) return status;
  const size_t neq = (size_t)g->lay.neq;
  *y = calloc(neq, sizeof **y);
  double *yp = calloc(neq, sizeof *yp);
  rs_work w = {0};
  if (!*y || !yp || rs_work_create(&w, g) != RS_OK)
    status = rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for a grid of %d cells", g->grid.n);
  rs_inputs in;
  rs_model_inputs_at(g, 0.0, &in);
  if (status == RS_OK && from)
    status = rs_model_interpolate_state(from, yfrom, g, &w, &in, *y, msg);
  else if (status == RS_OK)
    rs_model_rest_state(g, *y);
  rs_steady *st = NULL;
  rs_stats stats = {0};
  if (status == RS_OK) status = rs_steady_create(&st, g, ctx, msg);
  if (status == RS_OK) status = rs_steady_solve(st, 0.0, *y, &stats, msg);
  if (status == RS_OK) status = rs_model_diagnostics(g, &w, &in, *y, yp, d, NULL, NULL, NULL);
  if (status != RS_OK) {
    rs_msg why = *msg;
    rs_msg_set(msg, status, "grid.accuracy: the grid of %d cells: %s", g->grid.n, why.text);
  }
  rs_steady_free(st);
  rs_work_free(&w);
  free(yp);
  return status;
}

int rs_errest_refine(rs_model *m, SUNContext ctx, double accuracy, double **y, rs_diag *d,
                     int *reached, rs_msg *msg)
{
  *y = NULL;
  *reached = 0;
  const int n0 = m->grid.nx, three = m->grid.ny > 1;
  const long cap = three ? RS_ACCURACY_MAX_CELLS_3D : RS_ACCURACY_MAX_CELLS_2D;
  /* From the case's grid divided by 4 when that still resolves the contact: the case's own
   * grid then has its estimate at once; else from the case's grid up. */
  int level = n0 / 4 >= 1 && cells_across(m, n0 / 4) >= RS_ERREST_MIN_CELLS ? -2 : 0;
  int nx = level < 0 ? n0 >> -level : n0;
  rs_model cur = {0};
  double *ycur = NULL;
  double f[3][3] = {{NAN}}; /* the last three grids' Fx, Fy, Mz, the finest last */
  int cells[3] = {0, 0, 0}, solved = 0, status = RS_OK;
  for (;;) {
    rs_model g;
    double *yg = NULL;
    rs_diag dg;
    status = refine_level(m, nx, ctx, solved ? &cur : NULL, ycur, &g, &yg, &dg, msg);
    if (status != RS_OK) {
      free(yg);
      if (g.grid.x) rs_model_free(&g);
      break;
    }
    if (solved) rs_model_free(&cur);
    free(ycur);
    cur = g;
    ycur = yg;
    solved++;
    for (int k = 0; k < 2; k++) {
      memcpy(f[k], f[k + 1], sizeof f[k]);
      cells[k] = cells[k + 1];
    }
    f[2][0] = dg.Fx;
    f[2][1] = dg.Fy;
    f[2][2] = dg.Mz;
    cells[2] = cur.grid.n;
    *d = dg;
    rs_errest_none(d);
    if (solved >= 3 &&
        cells_across(m, level < 2 ? n0 >> (2 - level) : n0 << (level - 2)) >= RS_ERREST_MIN_CELLS) {
      const double r21 = three ? sqrt((double)cells[2] / cells[1]) : (double)cells[2] / cells[1];
      const double r32 = three ? sqrt((double)cells[1] / cells[0]) : (double)cells[1] / cells[0];
      const rs_diag d2 = {.Fx = f[1][0], .Fy = f[1][1], .Mz = f[1][2]};
      const rs_diag d3 = {.Fx = f[0][0], .Fy = f[0][1], .Mz = f[0][2]};
      rs_errest_diag(m, r21, r32, &d2, &d3, d);
      if (level >= 0 && rs_errest_worst(m, d) <= accuracy) {
        *reached = 1;
        break;
      }
    }
    level++;
    const long next = level < 0 ? n0 >> -level : (long)n0 << level;
    if (level > 0 && (three ? next * next * m->grid.ny / m->grid.nx : next) > cap) break;
    nx = (int)next;
  }
  if (status != RS_OK) {
    if (solved) rs_model_free(&cur);
    free(ycur);
    return status;
  }
  rs_model_free(m);
  *m = cur;
  *y = ycur;
  return RS_OK;
}
