/* The Newton-Krylov set-up that reuses the residual's evaluation (rs_krylov_residual, then
 * rs_krylov_setup at the same point) against the set-up that evaluates the model itself,
 * on a plastic 3D ellipse (16 x 16 cells, partial slip and yield), steady (c_j = 0) and
 * with a transient c_j (V/dx) and rates.
 *
 * The two paths do the same floating-point operations in the same order, so the residual,
 * the products J v and the preconditioner's solves must agree bit for bit (tolerance 0).
 * A set-up at another point than the last residual's (another state, or the same state
 * with another c_j) must evaluate the model anew: its J v must equal the direct path's
 * there too, while J v at the other state differs (checked, so that the test of the guard
 * can fail). */
#include <stdlib.h>
#include <string.h>

#include "solve/linsys_krylov.h"
#include "test_krylov_support.h"

static double norm_max(const double *a, int n)
{
  double d = 0.0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i]));
  return d;
}

static double max_diff(const double *a, const double *b, int n)
{
  double d = 0.0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

/* J v and P^-1 v of a set-up at (y, yp, cj); before it, when ev is given, a residual
 * through the same Krylov object at (ev, yp, cj_ev). */
static int products(const rs_model *m, const rs_inputs *in, const double *y, const double *yp,
                    double cj, const double *ev, double cj_ev, const double *v, double *jv,
                    double *pv, double *F)
{
  rs_krylov k;
  if (rs_krylov_create(&k, m, RS_KRYLOV_BAND_3D, RS_KRYLOV_BAND_3D_Y) != RS_OK)
    return RS_ERR_INTERNAL;
  int status = ev ? rs_krylov_residual(&k, in, ev, yp, cj_ev, F) : RS_OK;
  if (status == RS_OK) status = rs_krylov_setup(&k, in, y, yp, cj);
  if (status == RS_OK) status = rs_krylov_times(&k, v, jv);
  memcpy(pv, v, (size_t)m->lay.neq * sizeof *pv);
  if (status == RS_OK) status = rs_krylov_psolve(&k, pv);
  rs_krylov_free(&k);
  return status;
}

int main(void)
{
  rs_model m;
  double *y = NULL;
  if (ts_plastic_ellipse_state(16, &m, &y)) return 1;
  const int neq = m.lay.neq;
  double *y2 = malloc((size_t)neq * sizeof *y2);
  double *yp = calloc((size_t)neq, sizeof *yp), *v = malloc((size_t)neq * sizeof *v);
  double *F1 = malloc((size_t)neq * sizeof *F1), *F2 = malloc((size_t)neq * sizeof *F2);
  double *jv[4], *pv[4];
  for (int k = 0; k < 4; k++) {
    jv[k] = malloc((size_t)neq * sizeof *jv[k]);
    pv[k] = malloc((size_t)neq * sizeof *pv[k]);
  }
  rs_work w;
  rs_work_create(&w, &m);
  unsigned long seed = 2026;
  for (int i = 0; i < neq; i++) {
    y[i] *= 1.0 + 0.01 * ts_random(&seed);
    y2[i] = y[i] * (1.0 + 0.01 * ts_random(&seed));
    v[i] = ts_random(&seed);
  }
  const rs_inputs in = ts_inputs(&m, 0.0);
  const double rate = in.velocity / m.grid.dx;
  for (int pass = 0; pass < 2; pass++) {
    const char *tag = NULL;
    const double cj = ts_krylov_pass(&m, pass, y, yp, &seed, &tag);
    /* 0: direct; 1: after the residual at the point; 2: after a residual elsewhere;
     * 3: after a residual at the point with another c_j */
    int ok = products(&m, &in, y, yp, cj, NULL, 0.0, v, jv[0], pv[0], NULL) == RS_OK &&
             products(&m, &in, y, yp, cj, y, cj, v, jv[1], pv[1], F1) == RS_OK &&
             products(&m, &in, y, yp, cj, y2, cj, v, jv[2], pv[2], F2) == RS_OK &&
             products(&m, &in, y, yp, cj, y, cj + 0.5 * rate, v, jv[3], pv[3], F2) == RS_OK &&
             rs_model_residual(&m, &w, &in, y, yp, cj, F2) == RS_OK;
    TS_CHECK(ok, "%s: an evaluation failed", tag);
    if (!ok) continue;
    printf("%s: max |J v| %.3e, max |P^-1 v| %.3e\n", tag, norm_max(jv[0], neq),
           norm_max(pv[0], neq));
    TS_CHECK(max_diff(F1, F2, neq) == 0.0, "%s: residual through the Krylov object differs by %.3e",
             tag, max_diff(F1, F2, neq));
    for (int k = 1; k < 4; k++) {
      TS_CHECK(max_diff(jv[k], jv[0], neq) == 0.0, "%s, path %d: J v differs by %.3e", tag, k,
               max_diff(jv[k], jv[0], neq));
      TS_CHECK(max_diff(pv[k], pv[0], neq) == 0.0, "%s, path %d: P^-1 v differs by %.3e", tag, k,
               max_diff(pv[k], pv[0], neq));
    }
    /* the other state linearises differently: the guard's test means something */
    double *jo = jv[2], *po = pv[2];
    products(&m, &in, y2, yp, cj, NULL, 0.0, v, jo, po, NULL);
    const double other = max_diff(jo, jv[0], neq);
    printf("%s: J v at the other state differs by %.3e\n", tag, other);
    TS_CHECK(other > 1e-6 * norm_max(jv[0], neq), "%s: the other state's J v is the same", tag);
  }
  rs_work_free(&w);
  rs_model_free(&m);
  for (int k = 0; k < 4; k++) {
    free(jv[k]);
    free(pv[k]);
  }
  free(y);
  free(y2);
  free(yp);
  free(v);
  free(F1);
  free(F2);
  printf("%s\n", ts_failures ? "FAILED" : "passed");
  return ts_failures ? 1 : 0;
}
