/* Velocity-dependent friction in steady rolling (docs/model.md §11, docs/verification.md 14), on
 * Carter's contact (cases/carter2d.yaml: q = 178.9 N/mm, R = 500 mm, 100 cells, V =
 * 30000 mm/s, p0 = 113.9 N/mm^2):
 *
 * 1. Coulomb limit. An exponential law with half velocity 1e9 mm/s is Coulomb with mu =
 *    mu_k + mu_excess = 0.3 to within mu_excess ln2 |v_s| / v_h ~ 5e-10 at the slip speeds
 *    of xi = -2.4e-4 (|v_s| <= V|xi| = 7.2 mm/s), i.e. tractions within 5e-10 p_n <=
 *    6e-8 N/mm^2 = 5e-10 p0, plus the Newton tolerance (a residual below 1e-9 of the
 *    bound's scale): the tractions must agree with the Coulomb solution to 1e-8 p0.
 * 2. Full sliding. At xi = -1 % (rigid slip 300 mm/s, no adhesion), every contact cell
 *    carries |p| = mu(|v_s|) p_n with v_s opposite to p, where v_s = V xi + D u_el/Dt is
 *    recomputed here from the tractions with the influence coefficients A(k) (u_el =
 *    sum A(i - j) p_j, D/Dt = -V (u(i+1) - u(i))/dx, the upwind difference of the model),
 *    not taken from the model's kinematics. Tolerance 1e-8 p0 (Newton tolerance and the
 *    roundoff of the sums). The law is exponential with v_h = 100 mm/s: mu(300 mm/s) =
 *    0.2125, between mu_k and mu(0), so the check sees the law, not a constant.
 * 3. For every law, the summary quantity F_x/F_n in full sliding lies between mu at the
 *    largest and at the smallest slip speed of the patch.
 * 4. Uniqueness where the creep curve falls (exponential, v_h = 20 mm/s, xi = -0.8 permil,
 *    past the curve's maximum): Newton started from three different states - the
 *    continuation from rest, the Coulomb solution with mu = mu(0), and full sliding at
 *    mu_k (p = mu_k p_n) - reaches the same tractions to 1e-8 p0 (the Newton tolerance). */
#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

static int solve(rs_case *c, rs_model *m, double **y)
{
  rs_msg msg = {{0}};
  if (rs_model_from_case(m, c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return ts_failures++, 1;
  }
  *y = calloc((size_t)m->lay.neq, sizeof **y);
  rs_steady *s = NULL;
  rs_stats st = {0};
  const int status = rs_steady_create(&s, m, NULL, &msg) == RS_OK
                         ? rs_steady_solve(s, 0.0, *y, &st, &msg)
                         : RS_ERR_SOLVER;
  rs_steady_free(s);
  if (status != RS_OK) {
    printf("FAIL steady: %s\n", msg.text);
    return ts_failures++, 1;
  }
  return 0;
}

static void set_exponential(rs_case *c, double v_h)
{
  rs_friction f = {.kind = RS_FRICTION_EXPONENTIAL, .mu_kinetic = 0.2, .terms = 1};
  f.mu_excess[0] = 0.1;
  f.half_velocity[0] = v_h;
  c->friction = f;
  c->mu = rs_friction_mu(&f, 0.0);
}

static void coulomb_limit(void)
{
  rs_case c;
  rs_model mc, mf;
  double *yc = NULL, *yf = NULL;
  ts_carter_case(&c, 100);
  if (solve(&c, &mc, &yc)) return;
  set_exponential(&c, 1e9);
  if (solve(&c, &mf, &yf)) return;
  double worst = 0.0;
  for (int i = 0; i < mc.grid.n; i++) worst = fmax(worst, fabs(yf[i] - yc[i]));
  ts_check("Coulomb limit (v_h = 1e9 mm/s): max |p - p_Coulomb| / p0", worst / mc.hertz_p0, 0.0,
           1e-8);
  free(yc);
  free(yf);
  rs_model_free(&mc);
  rs_model_free(&mf);
}

/* Full sliding at xi = -1 %: |p| = mu(|v_s|) p_n cell by cell; F_x/F_n inside the range
 * of mu over the patch. */
static void full_sliding(rs_friction_kind kind, const char *name)
{
  rs_case c;
  rs_model m;
  double *y = NULL;
  ts_carter_case(&c, 100);
  c.creepage.value = -0.01;
  set_exponential(&c, 100.0);
  c.friction.kind = kind;
  if (kind == RS_FRICTION_LINEAR) /* its kink at 2 v_h = 400 mm/s above every slip speed */
    c.friction.half_velocity[0] = 200.0;
  if (kind == RS_FRICTION_RATIONAL) {
    c.friction.terms = 2;
    c.friction.mu_excess[0] = c.friction.mu_excess[1] = 0.05;
    c.friction.half_velocity[1] = 300.0;
  }
  if (kind == RS_FRICTION_POLACH) {
    c.friction.mu_static = 0.3;
    c.friction.polach_a = 0.4;
    c.friction.polach_b = 0.003; /* s/mm */
  }
  c.mu = rs_friction_mu(&c.friction, 0.0);
  if (solve(&c, &m, &y)) return;
  const int n = m.grid.n;
  const double V = c.velocity.value, xi = c.creepage.value, dx = m.grid.dx;
  double *u = malloc((size_t)(n + 1) * sizeof *u);
  for (int i = 0; i <= n; i++) { /* u_el(i) = sum_j A(i - j) p_j, and one cell upstream */
    double sum = 0.0;
    for (int j = 0; j < n; j++) sum += rs_elastic_op_coef(&m.el, 0, 0, i - j, 0) * y[j];
    u[i] = sum;
  }
  double worst = 0.0, mu_lo = INFINITY, mu_hi = 0.0, Fx = 0.0, Fn = 0.0;
  int slipping = 0, contact = 0, wrong_direction = 0;
  for (int i = 0; i < n; i++) {
    if (!(m.pn[i] > 0.0)) continue;
    contact++;
    const double vs = V * xi - V * (u[i + 1] - u[i]) / dx;
    const double mu = rs_friction_mu(&c.friction, fabs(vs));
    worst = fmax(worst, fabs(fabs(y[i]) - mu * m.pn[i]));
    wrong_direction += y[i] * vs > 0.0;
    slipping += fabs(vs) > 1.0; /* mm/s */
    mu_lo = fmin(mu_lo, mu);
    mu_hi = fmax(mu_hi, mu);
    Fx += y[i] * m.grid.area;
    Fn += m.pn[i] * m.grid.area;
  }
  char what[160];
  snprintf(what, sizeof what, "%s, full sliding: every contact cell slips (%d of %d)", name,
           slipping, contact);
  ts_check_true(what, slipping == contact && contact > 0);
  snprintf(what, sizeof what, "%s, full sliding: v_s opposite to p in every cell", name);
  ts_check_true(what, wrong_direction == 0);
  snprintf(what, sizeof what, "%s, full sliding: max ||p| - mu(|v_s|) p_n| / p0", name);
  ts_check(what, worst / m.hertz_p0, 0.0, 1e-8);
  snprintf(what, sizeof what,
           "%s, full sliding: |F_x|/F_n = %.5f within mu over the patch [%.5f, %.5f]", name,
           fabs(Fx) / Fn, mu_lo, mu_hi);
  ts_check_true(what, fabs(Fx) / Fn >= mu_lo - 1e-12 && fabs(Fx) / Fn <= mu_hi + 1e-12 &&
                          mu_hi < rs_friction_mu(&c.friction, 0.0));
  free(u);
  free(y);
  rs_model_free(&m);
}

/* Steady Newton of model m from the start y (not from rest: no continuation). */
static int solve_from(rs_model *m, double *y)
{
  rs_msg msg = {{0}};
  rs_steady *s = NULL;
  rs_stats st = {0};
  const int status = rs_steady_create(&s, m, NULL, &msg) == RS_OK
                         ? rs_steady_solve(s, 0.0, y, &st, &msg)
                         : RS_ERR_SOLVER;
  rs_steady_free(s);
  if (status != RS_OK) printf("     (steady from a given start: %s)\n", msg.text);
  return status;
}

static void uniqueness(void)
{
  rs_case c;
  rs_model mc, mf;
  double *yc = NULL, *yf = NULL;
  ts_carter_case(&c, 100);
  c.creepage.value = -8e-4;
  if (solve(&c, &mc, &yc)) return; /* Coulomb, mu = 0.3 */
  set_exponential(&c, 20.0);
  if (solve(&c, &mf, &yf)) return; /* continuation from rest */
  const int n = mf.grid.n, neq = mf.lay.neq;
  double *y = calloc((size_t)neq, sizeof *y);
  const char *names[2] = {"the Coulomb solution", "full sliding at mu_k"};
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i < neq; i++) y[i] = k == 0 ? yc[i] : 0.0;
    if (k == 1)
      for (int i = 0; i < n; i++) y[i] = c.friction.mu_kinetic * mf.pn[i];
    double worst = INFINITY;
    if (solve_from(&mf, y) == RS_OK) {
      worst = 0.0;
      for (int i = 0; i < n; i++) worst = fmax(worst, fabs(y[i] - yf[i]));
    }
    char what[160];
    snprintf(what, sizeof what,
             "falling part (xi = -0.8 permil): Newton from %s = continuation from rest, "
             "max |dp| / p0",
             names[k]);
    ts_check(what, worst / mf.hertz_p0, 0.0, 1e-8);
  }
  free(y);
  free(yc);
  free(yf);
  rs_model_free(&mc);
  rs_model_free(&mf);
}

int main(void)
{
  coulomb_limit();
  uniqueness();
  full_sliding(RS_FRICTION_EXPONENTIAL, "exponential");
  full_sliding(RS_FRICTION_LINEAR, "linear");
  full_sliding(RS_FRICTION_RATIONAL, "rational");
  full_sliding(RS_FRICTION_POLACH, "polach");
  return ts_failures ? 1 : 0;
}
