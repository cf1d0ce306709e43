/* Prescribed tangential force (issue 4 item 2, docs/model.md §6): the creepage is an
 * unknown with the equation sum p dx = F_x(t).
 *  - Steady: the force is held to 1e-8 relative (Newton tolerance 1e-10 on a mean
 *    traction), and the creepage found equals the creepage at which prescribed-
 *    creepage steady solves give that force (found here by the secant method on
 *    F_x(xi) to 1e-12 relative), to 1e-4 relative (the bound; the printed
 *    difference is at the solver tolerance since both solve the same discrete system).
 *    Carter elastic (mu = 0.3, F = 0.6 mu F_n) and with local plasticity (the paper's
 *    Fig. 7 case, tau_c0 = 35 N/mm^2, k_rel = 0.6, mu = 0.5, F = 0.5 mu F_n).
 *  - Transient from rest, the force ramped 0 -> F and held: every output time holds
 *    F_x(t) to rtol = 1e-6 of F, and after 15 contact lengths the creepage equals the
 *    steady one to 1e-5 (the force is imposed, so only the traction pattern relaxes, which
 *    takes a few contact lengths). */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

static double force_of(const rs_model *m, const double *y)
{
  double f = 0.0;
  for (int i = 0; i < m->grid.n; i++) f += y[i] * m->grid.dx;
  return f;
}

/* Steady solve of case c; *fx: total force, *xi: creepage. */
static int steady(const rs_case *c, double *fx, double *xi)
{
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  double *y = calloc((size_t)m.lay.neq, sizeof *y);
  rs_steady *s = NULL;
  rs_stats st = {0};
  int status = rs_steady_create(&s, &m, NULL, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, &st, &msg);
  if (status != RS_OK) printf("FAIL steady: %s\n", msg.text);
  *fx = force_of(&m, y);
  const rs_inputs in = ts_inputs(&m, 0.0);
  *xi = rs_model_creepage(&m, &in, y);
  rs_steady_free(s);
  free(y);
  rs_model_free(&m);
  return status != RS_OK;
}

static void check_steady(const char *label, rs_case *c, double target)
{
  rs_case cf = *c;
  cf.force_control = 1;
  cf.tangential_force.kind = RS_HISTORY_CONSTANT;
  cf.tangential_force.value = target;
  double fx, xi_f;
  if (steady(&cf, &fx, &xi_f)) {
    ts_failures++;
    return;
  }
  printf("%s: prescribed F_x = %.6g N/mm -> creepage %.10g\n", label, target, xi_f);
  ts_check("steady force held (rel)", fx / target, 1.0, 1e-8);

  /* The inverse by prescribed-creepage solves: secant on F_x(xi) - target. */
  double x0 = 0.5 * xi_f, x1 = 1.5 * xi_f, f0, f1, dummy;
  c->creepage.kind = RS_HISTORY_CONSTANT;
  c->creepage.value = x0;
  if (steady(c, &f0, &dummy)) return (void)ts_failures++;
  c->creepage.value = x1;
  if (steady(c, &f1, &dummy)) return (void)ts_failures++;
  int it = 0;
  while (fabs(f1 - target) > 1e-12 * fabs(target) && it++ < 60) {
    const double x2 = x1 - (f1 - target) * (x1 - x0) / (f1 - f0);
    x0 = x1;
    f0 = f1;
    x1 = x2;
    c->creepage.value = x1;
    if (steady(c, &f1, &dummy)) return (void)ts_failures++;
  }
  printf("%s: prescribed-creepage inverse after %d secant steps: creepage %.10g\n", label, it, x1);
  ts_check("creepage of the force run vs the inverse (rel)", xi_f / x1, 1.0, 1e-4);
}

static void check_transient(void)
{
  rs_case c;
  ts_carter_case(&c, 100);
  c.mode = RS_MODE_TRANSIENT;
  const double target = 0.6 * c.mu * 178.9, ramp = 2e-4;
  rs_case cs = c;
  cs.mode = RS_MODE_STEADY;
  cs.force_control = 1;
  cs.tangential_force.kind = RS_HISTORY_CONSTANT;
  cs.tangential_force.value = target;
  double fx_s, xi_s;
  if (steady(&cs, &fx_s, &xi_s)) return (void)ts_failures++;

  c.force_control = 1;
  c.tangential_force = (rs_history){
      .kind = RS_HISTORY_RAMP, .from = 0.0, .to = target, .start = 0.0, .duration = ramp};
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return (void)ts_failures++;
  }
  double *y = calloc((size_t)m.lay.neq, sizeof *y), *yp = calloc((size_t)m.lay.neq, sizeof *yp);
  rs_work w;
  rs_work_create(&w, &m);
  const double t_end = 15 * 2 * m.hertz_a / c.velocity.value;
  rs_transient_opts o = {.rtol = 1e-6,
                         .atol = 1e-6,
                         .max_order = 5,
                         .max_steps = 200000,
                         .max_newton = 10,
                         .t_stop = ramp};
  rs_transient *tr = NULL;
  double worst = 0.0;
  if (ts_consistent_rates(&m, &w, 0.0, y, yp, &msg) ||
      rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg)) {
    printf("FAIL setup: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  printf("transient: creepage at rest from the bordered rates: %.6g\n", y[3 * m.grid.n]);
  const int nout = 150;
  int restarted = 0;
  for (int k = 1; k <= nout; k++) {
    const double t = t_end * k / nout;
    if (!restarted && t > ramp) { /* stop at the end of the ramp, restart there */
      if (rs_transient_advance(tr, ramp, y, yp, &msg) ||
          ts_consistent_rates(&m, &w, ramp, y, yp, &msg) ||
          rs_transient_restart(tr, ramp, y, yp, t_end, &msg)) {
        printf("FAIL at the ramp end: %s\n", msg.text);
        ts_failures++;
        goto done;
      }
      restarted = 1;
    }
    if (rs_transient_advance(tr, t, y, yp, &msg)) {
      printf("FAIL advance: %s\n", msg.text);
      ts_failures++;
      goto done;
    }
    const double want = rs_history_eval(&m.par.force, t);
    worst = fmax(worst, fabs(force_of(&m, y) - want) / target);
  }
  printf("transient: %d records over %.3g s (15 contact lengths)\n", nout, t_end);
  ts_check("transient: max |F_x - F(t)| / F over the records", worst, 0.0, 1e-6);
  ts_check("transient: final creepage / steady creepage", y[3 * m.grid.n] / xi_s, 1.0, 1e-5);
done:
  rs_transient_free(tr);
  rs_work_free(&w);
  free(y);
  free(yp);
  rs_model_free(&m);
}

int main(void)
{
  rs_case c;
  ts_carter_case(&c, 100);
  check_steady("elastic Carter, 100 cells", &c, 0.6 * c.mu * 178.9);

  ts_carter_case(&c, 80);
  c.mu = 0.5;
  c.has_plasticity = 1;
  c.tau_c0 = 35.0;
  c.k_tau = c.shear_modulus * 0.6 / (1.0 - 0.6);
  c.tau_c_min = 3.5;
  check_steady("plastic Carter k_rel = 0.6, 80 cells", &c, 0.5 * c.mu * 178.9);

  check_transient();
  printf("%s\n", ts_failures ? "FAILED" : "all passed");
  return ts_failures != 0;
}
