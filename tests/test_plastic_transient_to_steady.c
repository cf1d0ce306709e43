/* A long transient from rest settles on the steady solution of the same grid
 * (docs/verification.md 3) with local plasticity, for each k_rel of the paper's
 * Figure 7 set: |F_x(t) - F_x,steady| / F_x,steady < 1e-4 at the end, and the
 * rolled distance after which it stays there is printed. Grid: 52 cells over
 * +-1.04a (dx = a/25), tau_c0 = 35 N/mm^2, mu = 0.5, xi = -4e-4, L = 200 mm. */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

int main(void)
{
  const double k_rels[4] = {0.98, 0.6, 0.0, -0.333};
  for (int k = 0; k < 4; k++) {
    rs_case c;
    ts_carter_case(&c, 52);
    c.extent = 1.04;
    c.mu = 0.5;
    c.creepage.value = -4e-4;
    c.has_plasticity = 1;
    c.tau_c0 = 35.0;
    c.k_tau = c.shear_modulus * k_rels[k] / (1.0 - k_rels[k]);
    c.tau_c_min = 3.5;
    rs_model m;
    rs_msg msg = {{0}};
    if (rs_model_from_case(&m, &c, &msg) != RS_OK) return 1;
    double *ys = calloc((size_t)m.lay.neq, sizeof(double)),
           *y = calloc((size_t)m.lay.neq, sizeof(double)),
           *yp = calloc((size_t)m.lay.neq, sizeof(double));
    rs_work w;
    rs_work_create(&w, &m);
    rs_steady *s = NULL;
    rs_stats st = {0};
    if (rs_steady_create(&s, &m, NULL, &msg) || rs_steady_solve(s, 0.0, ys, &st, &msg)) {
      printf("FAIL steady: %s\n", msg.text);
      return 1;
    }
    double fx_steady = 0;
    for (int i = 0; i < m.grid.n; i++) fx_steady += ys[i] * m.grid.dx;
    ts_consistent_rates(&m, &w, 0.0, y, yp, &msg);
    const double V = c.velocity.value, rolled = 70.0, t_end = rolled / V;
    rs_transient_opts o = {.rtol = 1e-8,
                           .atol = 1e-6,
                           .max_order = 5,
                           .max_steps = 1000000,
                           .max_newton = 10,
                           .t_stop = t_end};
    rs_transient *tr = NULL;
    if (rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg)) return 1;
    double settled = -1, dev = 1;
    const int nout = 140;
    for (int j = 1; j <= nout; j++) {
      const double t = t_end * j / nout;
      if (rs_transient_advance(tr, t, y, yp, &msg)) {
        printf("FAIL advance k_rel = %g: %s\n", k_rels[k], msg.text);
        return 1;
      }
      double fx = 0;
      for (int i = 0; i < m.grid.n; i++) fx += y[i] * m.grid.dx;
      dev = fabs(fx - fx_steady) / fabs(fx_steady);
      if (dev < 1e-4 && settled < 0) settled = V * t;
      if (dev >= 1e-4) settled = -1;
    }
    rs_stats ts;
    rs_transient_get_stats(tr, &ts);
    rs_diag d;
    ts_diagnostics(&m, &w, t_end, ys, yp, &d, NULL, NULL, NULL);
    printf("k_rel = %6.3f: steady F_x/(mu F_n) = %.6f (E/H/S/P %d/%d/%d/%d); transient within 1e-4 "
           "after %.1f mm rolled (%.1f contact lengths); final deviation %.2e; IDA steps %ld, "
           "Newton %ld, failed solves %ld\n",
           k_rels[k], fx_steady / (m.par.friction.mu * d.Fn), d.count[0], d.count[1], d.count[2],
           d.count[3], settled, settled / (2 * m.hertz_a), dev, ts.steps, ts.nonlin_iters,
           ts.nonlin_fails);
    char what[96];
    snprintf(what, sizeof what, "k_rel = %g: transient F_x within 1e-4 of steady", k_rels[k]);
    ts_check(what, dev, 0.0, 1e-4);
    rs_transient_free(tr);
    rs_steady_free(s);
    rs_work_free(&w);
    free(ys);
    free(y);
    free(yp);
    rs_model_free(&m);
  }
  return ts_failures ? 1 : 0;
}
