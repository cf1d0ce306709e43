/* The three linear-algebra paths of the steady Newton iteration (KLU on the whole
 * Jacobian, the dense Schur complement, Newton-Krylov with FFT products) solve
 * the same discrete equations with the same Newton tolerance, so they must give
 * the same tractions and regimes. KINSOL stops at a scaled residual of 1e-10
 * relative to the largest traction bound g_max = mu p0, and every traction row has
 * unit diagonal (the scaling r), so each path's p is within about cond * 1e-10 *
 * mu p0 of the exact discrete solution; we allow max|dp| <= 1e-8 p0 (two orders of
 * magnitude of conditioning) and identical regime counts. Cases: Carter elastic at
 * 100 and 800 cells; the Figure 7 plastic case (k_rel = 0.6, hardening) at 100
 * cells, and with k_rel = 0.98 at 400 cells.
 *
 * The transient (IDA, KINSOL in every step) with KLU and with the dense Schur
 * complement, from rest: each Newton step agrees to roundoff, but a roundoff-sized
 * difference can move a regime switch to the other side of a step and IDA then
 * takes a different step sequence, so the two F_x(t) histories agree only to the
 * time-integration error, not to roundoff. The assertion: the paths differ by no
 * more than the KLU path's own global error, taken against a KLU run with
 * rtol 100 times smaller: max_t |F_dense - F_klu| <= max_t |F_klu - F_ref|; and that
 * error is below 100 rtol max|F_x| (a few rtol expected), so that a broken reference
 * cannot make room for a broken path. Cases: Carter elastic start-up, and the
 * Figure 7 plastic case (k_rel = 0.6), 100 cells, 6 contact lengths rolled. Both parts
 * also with friction memory (the memory rows dense in the contact). */
#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

#include <stdlib.h>

static int solve(const rs_model *m, rs_linear lin, double *y, rs_diag *d, rs_stats *st)
{
  rs_msg msg = {{0}};
  rs_steady *s = NULL;
  rs_model_rest_state(m, y);
  memset(st, 0, sizeof *st);
  int status = rs_steady_create_with(&s, m, NULL, lin, &msg);
  if (status == RS_OK) status = rs_steady_solve(s, 0.0, y, st, &msg);
  rs_steady_free(s);
  if (status != RS_OK) {
    printf("FAIL linear path %d: %s\n", (int)lin, msg.text);
    return 1;
  }
  double *yp = calloc((size_t)m->lay.neq, sizeof *yp);
  rs_work w;
  rs_work_create(&w, m);
  ts_diagnostics(m, &w, 0.0, y, yp, d, NULL, NULL, NULL);
  rs_work_free(&w);
  free(yp);
  return 0;
}

static int compare(const char *name, rs_case *c)
{
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL model %s: %s\n", name, msg.text);
    return 1;
  }
  const rs_linear paths[3] = {RS_LINEAR_KLU, RS_LINEAR_DENSE, RS_LINEAR_KRYLOV};
  const char *pname[3] = {"klu", "dense", "krylov"};
  double *y[3];
  rs_diag d[3];
  int fail = 0;
  for (int k = 0; k < 3; k++) {
    y[k] = calloc((size_t)m.lay.neq, sizeof *y[k]);
    rs_stats st;
    fail |= solve(&m, paths[k], y[k], &d[k], &st);
    printf("%s, %s: Fx/(mu Fn) = %.10f, E/H/S/P = %d/%d/%d/%d, Newton %ld, linear %ld\n", name,
           pname[k], d[k].Fx / (m.par.friction.mu * d[k].Fn), d[k].count[0], d[k].count[1],
           d[k].count[2], d[k].count[3], st.nonlin_iters, st.lin_solves);
  }
  if (!fail) {
    for (int k = 1; k < 3; k++) {
      double dp = 0.0;
      for (int i = 0; i < m.grid.n; i++) dp = fmax(dp, fabs(y[k][i] - y[0][i]));
      char what[160];
      snprintf(what, sizeof what, "%s: max|p_%s - p_klu| / p0", name, pname[k]);
      ts_check(what, dp / m.hertz_p0, 0.0, 1e-8);
      int same = 1;
      for (int r = 0; r < 4; r++) same &= d[k].count[r] == d[0].count[r];
      snprintf(what, sizeof what, "%s: regime counts of %s equal those of klu", name, pname[k]);
      ts_check_true(what, same);
    }
  }
  for (int k = 0; k < 3; k++) free(y[k]);
  rs_model_free(&m);
  return fail;
}

/* F_x at nout equally spaced times up to t_end, from rest (p = 0, consistent rates). */
static int transient_fx(const rs_model *m, rs_linear lin, double rtol, double t_end, int nout,
                        double *fx, rs_stats *st)
{
  rs_msg msg = {{0}};
  double *y = calloc((size_t)m->lay.neq, sizeof *y), *yp = calloc((size_t)m->lay.neq, sizeof *yp);
  rs_work w;
  int status = y && yp ? rs_work_create(&w, m) : RS_ERR_INTERNAL;
  if (status == RS_OK) rs_model_rest_state(m, y);
  if (status == RS_OK) status = ts_consistent_rates(m, &w, 0.0, y, yp, &msg);
  rs_transient_opts o = {.rtol = rtol,
                         .atol = 1e-9,
                         .max_order = 5,
                         .max_steps = 10000000,
                         .max_newton = 10,
                         .t_stop = t_end,
                         .linear = lin};
  rs_transient *tr = NULL;
  if (status == RS_OK) status = rs_transient_create(&tr, m, NULL, 0.0, y, yp, &o, &msg);
  for (int k = 1; status == RS_OK && k <= nout; k++) {
    status = rs_transient_advance(tr, t_end * k / nout, y, yp, &msg);
    fx[k - 1] = 0.0;
    for (int i = 0; i < m->grid.n; i++) fx[k - 1] += y[i] * m->grid.dx;
  }
  if (tr) rs_transient_get_stats(tr, st);
  if (status != RS_OK) printf("FAIL transient, linear path %d: %s\n", (int)lin, msg.text);
  rs_transient_free(tr);
  rs_work_free(&w);
  free(y);
  free(yp);
  return status != RS_OK;
}

static int compare_transient(const char *name, rs_case *c, double contact_lengths)
{
  rs_model m;
  rs_msg msg = {{0}};
  c->mode = RS_MODE_TRANSIENT;
  if (rs_model_from_case(&m, c, &msg) != RS_OK) {
    printf("FAIL model %s: %s\n", name, msg.text);
    return 1;
  }
  enum { NOUT = 100 };
  const double rtol = 1e-6;
  const double t_end = contact_lengths * 2.0 * m.hertz_a / c->velocity.value;
  double fx[3][NOUT];
  const rs_linear lin[3] = {RS_LINEAR_KLU, RS_LINEAR_DENSE, RS_LINEAR_KLU};
  const double tol[3] = {rtol, rtol, 1e-2 * rtol};
  const char *pname[3] = {"klu", "dense", "klu reference"};
  int fail = 0;
  for (int k = 0; k < 3 && !fail; k++) {
    rs_stats st = {0};
    fail |= transient_fx(&m, lin[k], tol[k], t_end, NOUT, fx[k], &st);
    printf("%s, %s (rtol %g): F_x(t_end) = %.10g N/mm, IDA steps %ld, Newton %ld, "
           "factorisations %ld\n",
           name, pname[k], tol[k], fx[k][NOUT - 1], st.steps, st.nonlin_iters, st.factorizations);
  }
  if (!fail) {
    double fx_max = 0.0, d_paths = 0.0, d_klu = 0.0;
    for (int j = 0; j < NOUT; j++) {
      fx_max = fmax(fx_max, fabs(fx[2][j]));
      d_paths = fmax(d_paths, fabs(fx[1][j] - fx[0][j]));
      d_klu = fmax(d_klu, fabs(fx[0][j] - fx[2][j]));
    }
    char what[200];
    snprintf(what, sizeof what, "%s: max|F_dense - F_klu| <= max|F_klu - F_ref| (%.3g N/mm)", name,
             d_klu);
    ts_check_true(what, d_paths <= d_klu);
    printf("     max|F_dense - F_klu| = %.3g N/mm = %.3g max|F_x|\n", d_paths, d_paths / fx_max);
    snprintf(what, sizeof what, "%s: max|F_klu - F_ref| / max|F_x|", name);
    ts_check(what, d_klu / fx_max, 0.0, 100.0 * rtol);
  }
  rs_model_free(&m);
  return fail;
}

int main(void)
{
  rs_case c;
  int fail = 0;
  ts_carter_case(&c, 100);
  fail |= compare("Carter elastic, 100 cells", &c);
  ts_carter_case(&c, 800);
  fail |= compare("Carter elastic, 800 cells", &c);
  ts_fig7_case(&c, 100, 0.6);
  fail |= compare("Carter plastic k_rel = 0.6, 100 cells", &c);
  ts_fig7_case(&c, 400, 0.98);
  fail |= compare("Carter plastic k_rel = 0.98, 400 cells", &c);
  ts_carter_case(&c, 100);
  fail |= compare_transient("Carter elastic start-up, 100 cells", &c, 6.0);
  ts_fig7_case(&c, 100, 0.6);
  fail |= compare_transient("Carter plastic k_rel = 0.6 start-up, 100 cells", &c, 6.0);
  /* Friction memory (docs/model.md §11): the memory rows are dense in the contact and the
   * Schur solver eliminates them on mu; the three steady paths and the two transient ones
   * must agree as above. Exponential law mu(0) = 0.3, mu_k = 0.2, v_h = 10 mm/s,
   * d_c = 0.05 mm (long enough that the weakening stays below the elastic stiffness). */
  const rs_friction memory = {.kind = RS_FRICTION_EXPONENTIAL,
                              .mu_kinetic = 0.2,
                              .terms = 1,
                              .mu_excess = {0.1},
                              .half_velocity = {10.0},
                              .memory_distance = 0.05,
                              .memory_velocity = 1.0};
  ts_carter_case(&c, 100);
  c.friction = memory;
  c.mu = 0.3;
  fail |= compare("Carter elastic, exponential friction with memory, 100 cells", &c);
  ts_carter_case(&c, 100);
  c.friction = memory;
  c.mu = 0.3;
  fail |= compare_transient("Carter elastic start-up, exponential friction with memory", &c, 6.0);
  if (fail) ts_failures++;
  printf("%s\n", ts_failures ? "FAILED" : "all passed");
  return ts_failures ? 1 : 0;
}
