/* The transient's modified Newton (docs/model.md §9): the main job's case (cases/default.yaml:
 * Carter 2D from rest, 100 cells on +-1.05a, 40 mm rolled), here at rtol 1e-6, atol 1e-6 N/mm^2
 * integrated to the end, then its counts and its final force.
 *   - Jacobian evaluations per IDA step at most 0.5: a factorisation is kept while every
 *     cell stays in its regime and c_j within a factor 4, so fresh ones follow the slip
 *     front's moves during the build-up and the larger changes of the step size, not the
 *     steps (exact Newton evaluates at every iteration, at least once a step);
 *   - Newton iterations per step at most 3: a kept factorisation is refreshed when an
 *     iteration reduces the residual by less than a factor 5, and from a predictor within
 *     IDA's tolerance the test at 1/100 of it then takes at most 3 (5^3 > 100);
 *   - the final F_x equals the steady solution of the same grid within 1e-4, the bound of
 *     test_transient_to_steady (after 20 contact lengths the build-up is within it). */
#include <stdlib.h>

#include "physics/model.h"
#include "solve/steady.h"
#include "test_support.h"

int main(void)
{
  rs_case c;
  ts_carter_case(&c, 100);
  c.mode = RS_MODE_TRANSIENT;
  rs_model m;
  rs_msg msg = {{0}};
  if (rs_model_from_case(&m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  const int neq = m.lay.neq;
  double *ys = calloc((size_t)neq, sizeof(double)), *y = calloc((size_t)neq, sizeof(double)),
         *yp = calloc((size_t)neq, sizeof(double));
  rs_work w;
  rs_work_create(&w, &m);
  rs_steady *s = NULL;
  rs_transient *tr = NULL;
  rs_stats st = {0};
  if (rs_steady_create(&s, &m, NULL, &msg) || rs_steady_solve(s, 0.0, ys, &st, &msg)) {
    printf("FAIL steady: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  double fx_steady = 0.0, fx = 0.0;
  for (int i = 0; i < m.grid.n; i++) fx_steady += ys[i] * m.grid.dx;
  if (ts_consistent_rates(&m, &w, 0.0, y, yp, &msg)) {
    printf("FAIL rates: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  const double t_end = 40.0 / c.velocity.value;
  const rs_transient_opts o = {.rtol = 1e-6,
                               .atol = 1e-6,
                               .max_order = 5,
                               .max_steps = 100000,
                               .max_newton = 10,
                               .t_stop = t_end};
  if (rs_transient_create(&tr, &m, NULL, 0.0, y, yp, &o, &msg) ||
      rs_transient_advance(tr, t_end, y, yp, &msg)) {
    printf("FAIL transient: %s\n", msg.text);
    ts_failures++;
    goto done;
  }
  rs_transient_get_stats(tr, &st);
  for (int i = 0; i < m.grid.n; i++) fx += y[i] * m.grid.dx;
  printf("IDA steps %ld, Newton iterations %ld, Jacobian evaluations %ld, factorisations %ld, "
         "error-test fails %ld, failed solves %ld; F_x %.8g, steady %.8g\n",
         st.steps, st.nonlin_iters, st.jac_evals, st.factorizations, st.err_test_fails,
         st.nonlin_fails, fx, fx_steady);
  ts_check("Jacobian evaluations per step (at most 0.5)", (double)st.jac_evals / st.steps, 0.25,
           0.25);
  ts_check("Newton iterations per step (1 to 3)", (double)st.nonlin_iters / st.steps, 2.0, 1.0);
  ts_check("final F_x against the steady solution (relative)", (fx - fx_steady) / fx_steady, 0.0,
           1e-4);
done:
  rs_transient_free(tr);
  rs_steady_free(s);
  rs_work_free(&w);
  free(ys);
  free(y);
  free(yp);
  rs_model_free(&m);
  return ts_failures ? 1 : 0;
}
