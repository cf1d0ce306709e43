/* Hou's rheometer (docs/verification.md 4): one cell with prescribed pressure under a
 * pure shift (V = 0). With c = A(0) + h3/G3 the self-compliance and s(t) the
 * prescribed shift, the traction q = -p follows the piecewise-linear law
 *   elastic        dq/ds = 1/c             while |q| < min(tau_c, g)
 *   plastic        d|q|/d|s| = k/(1 + c k) while |q| = tau_c < g, dustar/d|s| = 1/(1 + c k)
 *   slip           |q| = g                 (after hardening up to g)
 * with tau_c = max(tau_c_min, tau_c0 + k u*); unloading is elastic, and reloading
 * elastic up to the current tau_c. The expected traction is that law integrated
 * exactly over the shift path (an independent path through the physics); the DAE
 * solution must match it to 10 rtol (relative to tau_c0) at every probe time. */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

typedef struct hou_state {
  double q, ustar; /* q = -p: traction against the shift direction; u* */
} hou_state;

typedef struct hou_law {
  double c, g, tau_c0, k, tau_min;
} hou_law;

static double hou_tauc(const hou_law *L, double ustar)
{
  return fmax(L->tau_min, L->tau_c0 + L->k * ustar);
}

/* Exact update over a shift increment ds (one direction), by sub-segments. */
static void hou_advance(const hou_law *L, hou_state *s, double ds)
{
  const double dir = ds > 0 ? 1.0 : -1.0;
  double rem = fabs(ds);
  while (rem > 0.0) {
    const double tauc = hou_tauc(L, s->ustar), lim = fmin(tauc, L->g);
    const double to_limit = (lim - dir * s->q) * L->c; /* elastic shift to reach the limit */
    if (to_limit > 1e-15) {
      const double step = fmin(rem, to_limit);
      s->q += dir * step / L->c;
      rem -= step;
      continue;
    }
    if (L->g <= tauc) { /* slip: traction held at g */
      s->q = dir * L->g;
      return;
    }
    /* plastic flow at tau_c < g: hardening / softening slope until g or the floor */
    const double k_eff = (L->tau_c0 + L->k * s->ustar > L->tau_min) ? L->k : 0.0;
    double step = rem;
    if (k_eff > 0) step = fmin(step, (L->g - tauc) * (1 + L->c * k_eff) / k_eff);
    if (k_eff < 0) step = fmin(step, (tauc - L->tau_min) * (1 + L->c * k_eff) / (-k_eff));
    s->ustar += step / (1 + L->c * k_eff);
    s->q = dir * hou_tauc(L, s->ustar);
    rem -= step;
    if (step <= 1e-18) rem = 0.0;
  }
}

static int run_variant(const char *name, double k, double layer_h3, double layer_g3)
{
  rs_case c;
  ts_carter_case(&c, 1);
  c.extent = 1.0;
  c.mu = 0.5;
  c.mode = RS_MODE_TRANSIENT;
  c.velocity.value = 0.0;
  c.creepage.value = 0.0;
  c.has_plasticity = 1;
  c.tau_c0 = 20.0;
  c.k_tau = k;
  c.tau_c_min = 2.0;
  c.layer_thickness = layer_h3;
  c.layer_shear_modulus = layer_g3;
  /* shift velocity (mm/s): load, unload past the other yield, reload, load to slip */
  double st[4] = {0.0, 3e-3, 9e-3, 15e-3}, sv[4] = {1.0, -1.0, 1.0, 1.0};
  c.shift_velocity.kind = RS_HISTORY_STEPS;
  c.shift_velocity.n = 4;
  c.shift_velocity.t = st;
  c.shift_velocity.v = sv;
  c.output_interval = 1e-4;
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  hou_law L = {.c = rs_elastic2d_tang(&m.el.line, 0) + m.layer_flex,
               .g = m.bound[0],
               .tau_c0 = c.tau_c0,
               .k = k,
               .tau_min = c.tau_c_min};
  const double rtol = 1e-7;
  rs_transient_opts o = {.rtol = rtol,
                         .atol = 1e-9,
                         .max_order = 5,
                         .max_steps = 100000,
                         .max_newton = 10,
                         .t_stop = st[1]};
  double y[3] = {0, 0, 0}, yp[3];
  rs_work w;
  rs_work_create(&w, &m);
  ts_consistent_rates(&m, &w, 0.0, y, yp, &msg);
  rs_transient *tr = NULL;
  if (rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg)) {
    printf("FAIL create: %s\n", msg.text);
    return 1;
  }
  hou_state hs = {0, 0};
  double t = 0.0, max_err = 0.0, s_total = 0.0;
  int seg = 1, regimes_seen[4] = {0};
  const double t_end = 19e-3, dt = 1e-4;
  while (t < t_end - 1e-12) {
    const double bp = seg < 4 ? st[seg] : t_end;
    const double t_next = fmin(t + dt, bp);
    if (rs_transient_advance(tr, t_next, y, yp, &msg)) {
      printf("FAIL advance (%s): %s\n", name, msg.text);
      return 1;
    }
    const double v = rs_history_eval(&c.shift_velocity, 0.5 * (t + t_next));
    hou_advance(&L, &hs, v * (t_next - t));
    s_total += v * (t_next - t);
    t = t_next;
    max_err = fmax(max_err, fabs(-y[0] - hs.q));
    rs_diag d;
    signed char reg;
    ts_diagnostics(&m, &w, t, y, yp, &d, NULL, NULL, &reg);
    regimes_seen[(int)reg] = 1;
    if (t == bp && seg < 4) { /* breakpoint of the shift history: restart */
      seg++;
      ts_consistent_rates(&m, &w, t, y, yp, &msg);
      rs_transient_restart(tr, t, y, yp, seg < 4 ? st[seg] : t_end, &msg);
    }
  }
  rs_stats stt;
  rs_transient_get_stats(tr, &stt);
  printf("%s: k = %g N/mm^3, c = %.4e mm^3/N, g = %.3f, final q = %.6f (exact %.6f), u* = %.4e "
         "(exact %.4e), regimes H/S/P seen %d/%d/%d, steps %ld\n",
         name, k, L.c, L.g, -y[0], hs.q, y[2], hs.ustar, regimes_seen[1], regimes_seen[2],
         regimes_seen[3], stt.steps);
  char what[128];
  snprintf(what, sizeof what, "%s: max traction error / tau_c0 below 10 rtol", name);
  ts_check(what, max_err / c.tau_c0, 0.0, 10 * rtol);
  snprintf(what, sizeof what, "%s: accumulated plastic deformation u* (mm)", name);
  ts_check(what, y[2], hs.ustar, 10 * rtol * c.tau_c0 * L.c);
  ts_check_true("  passed through plastic flow", regimes_seen[RS_PLASTIC]);
  rs_transient_free(tr);
  rs_work_free(&w);
  c.shift_velocity.kind = RS_HISTORY_CONSTANT; /* the arrays are on the stack */
  rs_model_free(&m);
  return 0;
}

int main(void)
{
  if (run_variant("hardening", 1e5, 0.0, 1.0)) return 1;
  if (run_variant("perfectly plastic", 0.0, 0.0, 1.0)) return 1;
  if (run_variant("softening, third-body layer", -5000.0, 0.01, 1000.0)) return 1;
  return ts_failures ? 1 : 0;
}
