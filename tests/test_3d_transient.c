/* 3D elliptic contact, transient (docs/verification.md 3, 13): IDA with the KINSOL nonlinear
 * solver and Newton-Krylov, from rest, at constant inputs (xi, eta and spin together),
 * settles on the steady solution of the same grid: |F(t) - F_steady| / |F_steady| < 1e-4
 * for F_x, F_y and M_z at the end of 15 contact lengths of rolling (the 3D kernel decays
 * like 1/r: the traction settles after the material has crossed the patch a few times,
 * unlike 2D's slow logarithmic tail), elastic and plastic (tau_c0 = 60 N/mm^2, k_rel =
 * 0.3). Also: frictional and plastic power never negative at any output time (to 1e-9
 * of the rigid-slip power's scale), and the transient ends inside the friction limit. */
#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

static void run(int plastic)
{
  rs_case c;
  ts_carter_case(&c, 16);
  c.dimension = 3;
  c.radius = 100.0;
  c.radius_y = 200.0;
  c.cells_y = 16;
  c.extent = c.extent_y = 1.1;
  c.normal_load.value = 1000.0;
  c.mu = 0.3;
  c.creepage.value = -8e-4;
  c.lateral_creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 3e-4};
  c.spin = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 2e-4};
  c.tangential_force_y = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 0.0};
  if (plastic) ts_plasticity(&c, 60.0, 0.3);
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    ts_failures++;
    return;
  }
  const int neq = m.lay.neq;
  double *ys = calloc((size_t)neq, sizeof *ys), *y = calloc((size_t)neq, sizeof *y);
  double *yp = calloc((size_t)neq, sizeof *yp), *yps = calloc((size_t)neq, sizeof *yps);
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_stats st = {0};
  rs_diag ds, d;
  if (rs_steady_create(&s, &m, NULL, &msg) != RS_OK ||
      rs_steady_solve(s, 0.0, ys, &st, &msg) != RS_OK) {
    printf("FAIL steady: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  ts_diagnostics(&m, &w, 0.0, ys, yps, &ds, NULL, NULL, NULL);
  const double V = c.velocity.value, lengths = 15.0, t_end = lengths * 2.0 * m.hertz_a / V;
  rs_transient_opts o = {.rtol = 1e-7,
                         .atol = 1e-6,
                         .max_order = 5,
                         .max_steps = 1000000,
                         .max_newton = 10,
                         .t_stop = t_end};
  rs_transient *tr = NULL;
  if (ts_consistent_rates(&m, &w, 0.0, y, yp, &msg) != RS_OK ||
      rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg) != RS_OK) {
    printf("FAIL transient set-up: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  double min_power = 0.0, scale = 0.0;
  const int nout = 30;
  for (int k = 1; k <= nout; k++) {
    if (rs_transient_advance(tr, t_end * k / nout, y, yp, &msg) != RS_OK) {
      printf("FAIL advance: %s\n", msg.text);
      ts_failures++;
      break;
    }
    ts_diagnostics(&m, &w, t_end * k / nout, y, yp, &d, NULL, NULL, NULL);
    min_power = fmin(min_power, fmin(d.frictional_power, d.plastic_power));
    scale = fmax(scale, fabs(d.rigid_slip_power));
  }
  rs_stats ts;
  rs_transient_get_stats(tr, &ts);
  rs_transient_free(tr);
  printf("%s: steady F = (%.6g, %.6g) N, M_z %.6g N mm (E/H/S/P %d/%d/%d/%d); transient after "
         "%.0f contact lengths F = (%.6g, %.6g), M_z %.6g; %ld IDA steps (%.2f per cell "
         "passage)\n",
         plastic ? "plastic" : "elastic", ds.Fx, ds.Fy, ds.Mz, ds.count[0], ds.count[1],
         ds.count[2], ds.count[3], lengths, d.Fx, d.Fy, d.Mz, ts.steps,
         ts.steps / (lengths * 2.0 * m.hertz_a / m.grid.dx));
  char what[120];
  snprintf(what, sizeof what, "%s: transient F_x / steady F_x", plastic ? "plastic" : "elastic");
  ts_check(what, d.Fx / ds.Fx, 1.0, 1e-4);
  snprintf(what, sizeof what, "%s: transient F_y / steady F_y", plastic ? "plastic" : "elastic");
  ts_check(what, d.Fy / ds.Fy, 1.0, 1e-4);
  snprintf(what, sizeof what, "%s: transient M_z / steady M_z", plastic ? "plastic" : "elastic");
  ts_check(what, d.Mz / ds.Mz, 1.0, 1e-4);
  snprintf(what, sizeof what, "%s: min(frictional, plastic power) / max rigid-slip power",
           plastic ? "plastic" : "elastic");
  ts_check(what, fmin(min_power, 0.0) / scale, 0.0, 1e-9);
  if (plastic) ts_check_true("plastic: cells in plastic flow", ds.count[RS_PLASTIC] > 0);
done:
  rs_steady_free(s);
  rs_work_free(&w);
  free(ys);
  free(y);
  free(yp);
  free(yps);
  rs_model_free(&m);
}

int main(void)
{
  run(0);
  run(1);
  return ts_failures ? 1 : 0;
}
