/* The 3D Newton-Krylov GMRES (solve/gmres.h) on the systems it solves: the near-field
 * preconditioned Jacobian of the plastic 3D ellipse (16 x 16 cells, adhesion, slip and
 * yield), steady (c_j = 0) and with the transient's c_j, with scaling vectors that are not
 * uniform (s1 = s2, as KINSOL sets them).
 *
 * 1. Converged solves: the residual ||s (b - J x)||_2, computed here from J v, is at most
 *    the tolerance delta (plus 1e-12 of ||s b||, the roundoff of GMRES's own estimate),
 *    and agrees with the norm the solver reports; SUNDIALS' SPGMR on the same operator and
 *    preconditioner (the algorithm this one reorganises) takes the same number of
 *    iterations within one.
 * 2. Restarts (a basis of 3, so that the residual carried into each restart matters): the
 *    same tolerance is met, after more than 3 iterations.
 * 3. A non-zero initial guess: the residual is taken from b - J x0, and met.
 * 4. No convergence (a basis of 2, no restart, delta 1e-14): SUNLS_RES_REDUCED with a
 *    reported norm below ||s b|| that is the true residual of the returned x. */
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "solve/gmres.h"
#include "solve/linsys_krylov.h"
#include "test_krylov_support.h"

typedef struct {
  rs_krylov *k;
} op_data;

static int atimes(void *data, N_Vector v, N_Vector z)
{
  op_data *d = data;
  return rs_krylov_times(d->k, N_VGetArrayPointer(v), N_VGetArrayPointer(z)) == RS_OK ? 0 : -1;
}

static int psolve(void *data, N_Vector r, N_Vector z, double tol, int lr)
{
  (void)tol;
  (void)lr;
  op_data *d = data;
  N_VScale(1.0, r, z);
  return rs_krylov_psolve(d->k, N_VGetArrayPointer(z)) == RS_OK ? 0 : 1;
}

/* ||s (b - J x)||_2 from J v */
static double true_residual(rs_krylov *k, const double *s, const double *b, const double *x,
                            double *work, int n)
{
  rs_krylov_times(k, x, work);
  double ss = 0.0;
  for (int i = 0; i < n; i++) {
    const double r = s[i] * (b[i] - work[i]);
    ss += r * r;
  }
  return sqrt(ss);
}

int main(void)
{
  rs_model m;
  double *y = NULL;
  if (ts_plastic_ellipse_state(16, &m, &y)) return 1;
  const int neq = m.lay.neq;
  SUNContext ctx = NULL;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  N_Vector xv = N_VNew_Serial(neq, ctx), bv = N_VNew_Serial(neq, ctx);
  N_Vector sv = N_VNew_Serial(neq, ctx);
  double *yp = calloc((size_t)neq, sizeof *yp), *work = malloc((size_t)neq * sizeof *work);
  double *x0 = malloc((size_t)neq * sizeof *x0);
  double *b = N_VGetArrayPointer(bv), *x = N_VGetArrayPointer(xv), *s = N_VGetArrayPointer(sv);
  unsigned long seed = 7;
  for (int i = 0; i < neq; i++) {
    b[i] = ts_random(&seed);
    s[i] = 1.0 / (1.0 + (double)(i % 7)); /* not uniform */
    x0[i] = 1e-3 * ts_random(&seed);
  }
  double sb = 0.0;
  for (int i = 0; i < neq; i++) sb += s[i] * b[i] * s[i] * b[i];
  sb = sqrt(sb);
  const double delta = 1e-8 * sb;
  const rs_inputs in = ts_inputs(&m, 0.0);
  for (int pass = 0; pass < 2; pass++) {
    const char *tag = NULL;
    const double cj = ts_krylov_pass(&m, pass, y, yp, &seed, &tag);
    rs_krylov k;
    if (rs_krylov_create(&k, &m, RS_KRYLOV_BAND_3D, RS_KRYLOV_BAND_3D_Y) != RS_OK ||
        rs_krylov_setup(&k, &in, y, yp, cj) != RS_OK) {
      printf("FAIL %s: set-up\n", tag);
      return 1;
    }
    op_data od = {&k};

    /* 1. against SPGMR */
    SUNLinearSolver ours = rs_gmres_create(&k, xv, 60, 4, ctx);
    SUNLinSolSetScalingVectors(ours, sv, sv);
    SUNLinSolSetZeroGuess(ours, 1);
    N_VConst(0.0, xv);
    int flag = SUNLinSolSolve(ours, NULL, xv, bv, delta);
    const int iters = SUNLinSolNumIters(ours);
    const double reported = SUNLinSolResNorm(ours);
    const double res = true_residual(&k, s, b, x, work, neq);
    printf("%s: %d iterations, residual %.3e (reported %.3e), delta %.3e\n", tag, iters, res,
           reported, delta);
    TS_CHECK(flag == SUNLS_SUCCESS, "%s: flag %d", tag, flag);
    TS_CHECK(res <= delta + 1e-12 * sb, "%s: residual %.3e above delta %.3e", tag, res, delta);
    TS_CHECK(fabs(res - reported) <= 1e-12 * sb, "%s: reported %.3e, true %.3e", tag, reported,
             res);
    SUNLinearSolver ref = SUNLinSol_SPGMR(xv, SUN_PREC_RIGHT, 60, ctx);
    SUNLinSol_SPGMRSetGSType(ref, SUN_CLASSICAL_GS);
    SUNLinSol_SPGMRSetMaxRestarts(ref, 4);
    SUNLinSolSetATimes(ref, &od, atimes);
    SUNLinSolSetPreconditioner(ref, &od, NULL, psolve);
    SUNLinSolSetScalingVectors(ref, sv, sv);
    SUNLinSolInitialize(ref);
    SUNLinSolSetZeroGuess(ref, 1);
    N_VConst(0.0, xv);
    const int ref_flag = SUNLinSolSolve(ref, NULL, xv, bv, delta);
    const int ref_iters = SUNLinSolNumIters(ref);
    printf("%s: SPGMR %d iterations (flag %d)\n", tag, ref_iters, ref_flag);
    TS_CHECK(abs(iters - ref_iters) <= 1, "%s: %d iterations against SPGMR's %d", tag, iters,
             ref_iters);
    SUNLinSolFree(ref);
    SUNLinSolFree(ours);

    /* 2. restarts */
    SUNLinearSolver small = rs_gmres_create(&k, xv, 3, 200, ctx);
    SUNLinSolSetScalingVectors(small, sv, sv);
    SUNLinSolSetZeroGuess(small, 1);
    N_VConst(0.0, xv);
    flag = SUNLinSolSolve(small, NULL, xv, bv, delta);
    const double res2 = true_residual(&k, s, b, x, work, neq);
    printf("%s: basis 3 with restarts: %d iterations, residual %.3e\n", tag,
           SUNLinSolNumIters(small), res2);
    TS_CHECK(flag == SUNLS_SUCCESS && SUNLinSolNumIters(small) > 3, "%s: restarts (flag %d)", tag,
             flag);
    TS_CHECK(res2 <= delta + 1e-12 * sb, "%s: restarted residual %.3e", tag, res2);

    /* 3. from x0 */
    memcpy(x, x0, (size_t)neq * sizeof *x);
    SUNLinSolSetZeroGuess(small, 0);
    flag = SUNLinSolSolve(small, NULL, xv, bv, delta);
    const double res3 = true_residual(&k, s, b, x, work, neq);
    printf("%s: from a non-zero guess: residual %.3e\n", tag, res3);
    TS_CHECK(flag == SUNLS_SUCCESS && res3 <= delta + 1e-12 * sb, "%s: from x0: flag %d, %.3e", tag,
             flag, res3);
    SUNLinSolFree(small);

    /* 4. no convergence */
    SUNLinearSolver tiny = rs_gmres_create(&k, xv, 2, 0, ctx);
    SUNLinSolSetScalingVectors(tiny, sv, sv);
    SUNLinSolSetZeroGuess(tiny, 1);
    N_VConst(0.0, xv);
    flag = SUNLinSolSolve(tiny, NULL, xv, bv, 1e-14 * sb);
    const double res4 = true_residual(&k, s, b, x, work, neq), rep4 = SUNLinSolResNorm(tiny);
    printf("%s: basis 2, no restart: flag %d, residual %.3e (reported %.3e) of %.3e\n", tag, flag,
           res4, rep4, sb);
    TS_CHECK(flag == SUNLS_RES_REDUCED && rep4 < sb, "%s: not converged: flag %d", tag, flag);
    TS_CHECK(fabs(res4 - rep4) <= 1e-12 * sb, "%s: reported %.3e, true %.3e", tag, rep4, res4);
    SUNLinSolFree(tiny);
    rs_krylov_free(&k);
  }
  N_VDestroy(xv);
  N_VDestroy(bv);
  N_VDestroy(sv);
  SUNContext_Free(&ctx);
  rs_model_free(&m);
  free(y);
  free(yp);
  free(work);
  free(x0);
  printf("%s\n", ts_failures ? "FAILED" : "passed");
  return ts_failures ? 1 : 0;
}
