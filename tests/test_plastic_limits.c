/* Limits of the local-plasticity model (docs/verification.md 5, 6), steady rolling
 * on the Carter grid with mu = 0.5 (the paper's Figure 7 case):
 *  - tau_c0 -> infinity reproduces the elastic solution of the same grid (to the
 *    Newton tolerance: 1e-9 relative in every traction);
 *  - k_tau = 0 at full sliding: F_x = sum min(mu p_n, tau_c0) dx, to 1e-8 relative;
 *  - frictional and plastic power are never negative, and in steady rolling the
 *    power of the rigid slip equals the dissipation up to O(dx): the gap halves
 *    (ratio 2 +- 0.5) when dx halves (dx = a/25, a/50, a/100). */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

typedef struct result {
  double *p;
  int n;
  rs_diag d;
  double sum_min_bound; /* sum min(mu p_n, tau_c0) dx */
} result;

static int steady(rs_case *c, result *r)
{
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  if (status != RS_OK) {
    printf("FAIL steady: %s\n", msg.text);
    return 1;
  }
  ts_diagnostics(&m, &w, 0.0, y, yp, &r->d, NULL, NULL, NULL);
  r->n = m.grid.n;
  r->p = y;
  r->sum_min_bound = 0;
  for (int i = 0; i < m.grid.n; i++)
    r->sum_min_bound += fmin(m.bound[i], c->has_plasticity ? c->tau_c0 : INFINITY) * m.grid.dx;
  rs_steady_free(s);
  rs_work_free(&w);
  free(yp);
  rs_model_free(&m);
  return 0;
}

static void fig7_case(rs_case *c, int cells, double k_rel)
{
  ts_fig7_case(c, cells, k_rel);
  c->extent = 1.04;
}

int main(void)
{
  /* 1. tau_c0 -> infinity */
  rs_case c;
  result el, pl;
  ts_carter_case(&c, 104);
  c.extent = 1.04;
  c.mu = 0.5;
  c.creepage.value = -4e-4;
  if (steady(&c, &el)) return 1;
  fig7_case(&c, 104, 0.6);
  c.tau_c0 = 1e9;
  c.tau_c_min = 1e8;
  if (steady(&c, &pl)) return 1;
  double dmax = 0, pmax = 0;
  for (int i = 0; i < el.n; i++) {
    dmax = fmax(dmax, fabs(el.p[i] - pl.p[i]));
    pmax = fmax(pmax, fabs(el.p[i]));
  }
  ts_check("tau_c0 = 1e9: max |p - p_elastic| / max |p|", dmax / pmax, 0.0, 1e-9);
  ts_check("tau_c0 = 1e9: plastic cells", pl.d.count[RS_PLASTIC], 0, 0);
  free(el.p);
  free(pl.p);

  /* 2. k_tau = 0 at full sliding (|xi| = 0.01 is 10x the elastic saturation mu a/R) */
  fig7_case(&c, 104, 0.0);
  c.creepage.value = -0.01;
  if (steady(&c, &pl)) return 1;
  ts_check("k_tau = 0, full sliding: F_x / sum min(mu p_n, tau_c0) dx", pl.d.Fx / pl.sum_min_bound,
           1.0, 1e-8);
  ts_check("k_tau = 0, full sliding: no adhesion cells", pl.d.count[RS_ADHESION], 0, 0);
  free(pl.p);

  /* 3. Powers on three grids, k_rel = 0.6 */
  const int cells[3] = {52, 104, 208};
  double gap[3];
  for (int k = 0; k < 3; k++) {
    fig7_case(&c, cells[k], 0.6);
    if (steady(&c, &pl)) return 1;
    const rs_diag *d = &pl.d;
    const double diss = d->frictional_power + d->plastic_power;
    gap[k] = fabs(d->rigid_slip_power - diss) / d->rigid_slip_power;
    printf("cells %d: rigid-slip power %.6g, frictional %.6g, plastic %.6g N mm/s/mm, gap %.3e; "
           "E/H/S/P %d/%d/%d/%d\n",
           cells[k], d->rigid_slip_power, d->frictional_power, d->plastic_power, gap[k],
           d->count[0], d->count[1], d->count[2], d->count[3]);
    char what[96];
    snprintf(what, sizeof what, "cells %d: frictional power >= 0", cells[k]);
    ts_check_true(what, d->frictional_power >= 0);
    snprintf(what, sizeof what, "cells %d: plastic power > 0 (plastic cells present)", cells[k]);
    ts_check_true(what, d->plastic_power > 0 && d->count[RS_PLASTIC] > 0);
    free(pl.p);
  }
  ts_check("power gap ratio dx = a/25 -> a/50 (first order: 2)", gap[0] / gap[1], 2.0, 0.5);
  ts_check("power gap ratio dx = a/50 -> a/100 (first order: 2)", gap[1] / gap[2], 2.0, 0.5);
  return ts_failures ? 1 : 0;
}
