/* The state the Newton-Krylov unit tests work on (test_krylov_evaluated, test_near_ylink). */
#ifndef ROLLSIM_TEST_KRYLOV_SUPPORT_H
#define ROLLSIM_TEST_KRYLOV_SUPPORT_H

#include <stdlib.h>

#include "solve/steady.h"
#include "test_support.h"

/* The plastic 3D ellipse (a/b = 1.6, xi = -1e-3, eta = 5e-4, phi = 1e-4 1/mm, tau_c0 = 150
 * N/mm^2, k_rel = 0.3) on n x n cells: its model into m and its steady state from rest into
 * *y (allocated, neq values), checked to have cells in adhesion, slip and yield (so that
 * every branch of the local laws is in the Jacobian). 0, or 1 with the failure printed. */
static inline int ts_plastic_ellipse_state(int n, rs_model *m, double **y)
{
  rs_case c;
  ts_ellipse_case(&c, n, 1.6, -1.0e-3, 5.0e-4, 1.0e-4);
  ts_plasticity(&c, 150.0, 0.3);
  rs_msg msg = {{0}};
  *y = NULL;
  if (rs_model_from_case(m, &c, &msg) != RS_OK) {
    printf("FAIL model: %s\n", msg.text);
    return 1;
  }
  const size_t neq = (size_t)m->lay.neq;
  double *yp = calloc(neq, sizeof *yp);
  *y = calloc(neq, sizeof **y);
  rs_steady *s = NULL;
  rs_stats st = {0};
  rs_work w;
  const int have_w = rs_work_create(&w, m) == RS_OK;
  int ok = yp && *y && have_w;
  if (ok && (rs_steady_create(&s, m, NULL, &msg) != RS_OK ||
             rs_steady_solve(s, 0.0, *y, &st, &msg) != RS_OK)) {
    printf("FAIL steady: %s\n", msg.text);
    ok = 0;
  }
  if (ok) {
    rs_diag d;
    ts_diagnostics(m, &w, 0.0, *y, yp, &d, NULL, NULL, NULL);
    ts_check_true("the state has cells in adhesion, slip and yield",
                  d.count[RS_ADHESION] > 0 && d.count[RS_SLIP] > 0 && d.count[RS_PLASTIC] > 0);
  }
  rs_steady_free(s);
  if (have_w) rs_work_free(&w);
  free(yp);
  return ok ? 0 : 1;
}

/* The two linearisations the tests check: pass 0 steady (c_j = 0, y' as given: zero), pass 1
 * with the transient's c_j = V/dx and random rates y' of size 1e-3 c_j y. Returns c_j. */
static inline double ts_krylov_pass(const rs_model *m, int pass, const double *y, double *yp,
                                    unsigned long *seed, const char **tag)
{
  const rs_inputs in = ts_inputs(m, 0.0);
  const double rate = in.velocity / m->grid.dx;
  *tag = pass == 0 ? "steady" : "c_j = V/dx";
  for (int i = 0; i < m->lay.neq && pass == 1; i++) yp[i] = 1e-3 * rate * ts_random(seed) * y[i];
  return pass == 0 ? 0.0 : rate;
}

#endif
