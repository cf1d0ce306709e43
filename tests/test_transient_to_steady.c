/* Transient from rest at constant creepage approaches the steady solution of the
 * same grid (docs/verification.md 3): |F_x(t) - F_x,steady| / |F_x,steady| < 1e-4 after
 * enough rolling. In 2D the uniform-displacement term set by the reference length
 * L makes the build-up slow (docs/model.md §2): the rolled distance needed to come
 * within 1e-4 is printed for L = 20, 200 and 2000 mm and must grow with L.
 * Grid: the Carter case, dx = a/25 (52 cells over +-1.04a). */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

/* Returns the rolled distance (mm) after which the force stays within tol of the
 * steady one, or -1 on failure; *final_dev: relative deviation at the end. */
static double settle_distance(double L, double max_rolled, double tol, double *final_dev,
                              rs_stats *st_out)
{
  rs_case c;
  ts_carter_case(&c, 52);
  c.extent = 1.04;
  c.reference_length = L;
  c.mode = RS_MODE_TRANSIENT;
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return -1;
  }
  double *ys = calloc((size_t)m.lay.neq, sizeof(double)),
         *y = calloc((size_t)m.lay.neq, sizeof(double)),
         *yp = calloc((size_t)m.lay.neq, sizeof(double));
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_stats st = {0};
  double result = -1;
  if (rs_steady_create(&s, &m, NULL, &msg) || rs_steady_solve(s, 0.0, ys, &st, &msg)) {
    printf("FAIL steady: %s\n", msg.text);
    goto done;
  }
  double fx_steady = 0;
  for (int i = 0; i < m.grid.n; i++) fx_steady += ys[i] * m.grid.dx;
  /* rest: y = 0, consistent rates from the adhesion equations */
  if (ts_consistent_rates(&m, &w, 0.0, y, yp, &msg)) {
    printf("FAIL rates: %s\n", msg.text);
    goto done;
  }
  const double V = c.velocity.value, t_end = max_rolled / V;
  rs_transient_opts o = {.rtol = 1e-8,
                         .atol = 1e-6,
                         .max_order = 5,
                         .max_steps = 200000,
                         .max_newton = 10,
                         .t_stop = t_end};
  rs_transient *tr = NULL;
  if (rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg)) {
    printf("FAIL create: %s\n", msg.text);
    goto done;
  }
  const int nout = 400;
  double settled_at = -1, dev = 0;
  for (int k = 1; k <= nout; k++) {
    const double t = t_end * k / nout;
    if (rs_transient_advance(tr, t, y, yp, &msg)) {
      printf("FAIL advance: %s\n", msg.text);
      rs_transient_free(tr);
      goto done;
    }
    double fx = 0;
    for (int i = 0; i < m.grid.n; i++) fx += y[i] * m.grid.dx;
    dev = fabs(fx - fx_steady) / fabs(fx_steady);
    if (dev < tol && settled_at < 0) settled_at = V * t;
    if (dev >= tol) settled_at = -1;
  }
  rs_transient_get_stats(tr, st_out);
  rs_transient_free(tr);
  *final_dev = dev;
  result = settled_at;
done:
  rs_steady_free(s);
  rs_work_free(&w);
  free(ys);
  free(y);
  free(yp);
  rs_model_free(&m);
  return result;
}

int main(void)
{
  const double Ls[3] = {20.0, 200.0, 2000.0};
  const double rolled[3] = {40.0, 80.0, 160.0};
  double dist[3];
  for (int k = 0; k < 3; k++) {
    double dev = 1;
    rs_stats st = {0};
    dist[k] = settle_distance(Ls[k], rolled[k], 1e-4, &dev, &st);
    printf("L = %6.0f mm: within 1e-4 of steady after %.2f mm rolled (%.1f contact lengths); "
           "final deviation %.2e; IDA steps %ld, Newton iterations %ld, failed solves %ld, "
           "error-test fails %ld, Jacobians %ld, KLU analyses %ld\n",
           Ls[k], dist[k], dist[k] / 2.0, dev, st.steps, st.nonlin_iters, st.nonlin_fails,
           st.err_test_fails, st.jac_evals, st.klu_analyses);
    char what[96];
    snprintf(what, sizeof what, "L = %.0f mm: final deviation from steady below 1e-4", Ls[k]);
    ts_check(what, dev, 0.0, 1e-4);
  }
  ts_check_true("settling distance grows with L",
                dist[0] > 0 && dist[0] < dist[1] && dist[1] < dist[2]);
  return ts_failures ? 1 : 0;
}
