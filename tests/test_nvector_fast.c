/* The optimised serial N_Vector kernels (src/nvector_fast.c) through SUNDIALS'
 * generic N_V* calls, on vectors whose results are known in closed form: entries
 * are small integers (or their reciprocals chosen so that products are 1), so
 * sums, products and combinations are exact in double precision and are compared
 * exactly; results through a square root are allowed 2 ulp. Lengths 1, 3, 7, 256,
 * 257 and 2550 cover the unrolled loops' remainders and the block size of the
 * linear combination. Clones must inherit the kernels (KINSOL and IDA work on
 * clones of the vectors rollsim creates). */
#include <nvector/nvector_serial.h>

#include "solve/nvector_fast.h"
#include "base/status.h"
#include "test_support.h"

static int fails = 0;
#define EXPECT(cond, ...)                                                                          \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      printf("FAIL n=%d: ", n);                                                                    \
      printf(__VA_ARGS__);                                                                         \
      printf("\n");                                                                                \
      fails++;                                                                                     \
    }                                                                                              \
  } while (0)

static int close_ulp(double a, double b) { return fabs(a - b) <= 4.5e-16 * fabs(b); }

static void check_length(int n, SUNContext ctx)
{
  N_Vector x = N_VNew_Serial(n, ctx);
  if (rs_nvector_fast_ops(x) != RS_OK) {
    printf("FAIL: serial vector refused\n");
    fails++;
    return;
  }
  N_Vector y = N_VClone(x), z = N_VClone(x), w = N_VClone(x), id = N_VClone(x);
  EXPECT(y->ops->nvdotprod == x->ops->nvdotprod && y->ops->nvlinearcombination != NULL,
         "a clone does not inherit the kernels");
  double *xd = N_VGetArrayPointer(x), *yd = N_VGetArrayPointer(y), *zd = N_VGetArrayPointer(z),
         *wd = N_VGetArrayPointer(w), *idd = N_VGetArrayPointer(id);
  for (int i = 0; i < n; i++) {
    xd[i] = i + 1.0;
    yd[i] = 1.0;
    wd[i] = 1.0 / (i + 1.0); /* not exact, but x_i w_i rounds to 1 for these i */
    idd[i] = i % 2 == 0 ? 1.0 : 0.0;
  }
  const double tri = 0.5 * n * (n + 1.0);
  EXPECT(N_VDotProd(x, y) == tri, "dot %g, expected %g", N_VDotProd(x, y), tri);
  EXPECT(close_ulp(N_VWrmsNorm(x, w), 1.0), "wrms %.17g, expected 1", N_VWrmsNorm(x, w));
  const double evens = (n + 1) / 2;
  EXPECT(close_ulp(N_VWrmsNormMask(x, w, id), sqrt(evens / n)), "wrms mask %.17g",
         N_VWrmsNormMask(x, w, id));
  EXPECT(close_ulp(N_VWL2Norm(x, w), sqrt((double)n)), "wl2 %.17g", N_VWL2Norm(x, w));

  N_VLinearSum(2.0, x, -1.0, y, z); /* z = 2 x - 1 */
  int ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == 2.0 * (i + 1) - 1.0;
  EXPECT(ok, "linear sum");
  N_VScale(-1.0, x, z); /* z = -x */
  EXPECT(N_VL1Norm(z) == tri, "l1 %g", N_VL1Norm(z));
  EXPECT(N_VMaxNorm(z) == n, "max norm %g", N_VMaxNorm(z));
  EXPECT(N_VMin(z) == -n, "min %g", N_VMin(z));
  N_VAbs(z, z);
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == i + 1.0;
  EXPECT(ok, "abs");
  N_VProd(x, x, z);
  N_VDiv(z, x, z); /* x^2 / x = x */
  N_VAddConst(z, -1.0, z);
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == i;
  EXPECT(ok, "prod, div, add const");
  N_VConst(4.0, z);
  N_VInv(z, z);
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == 0.25;
  EXPECT(ok, "const, inv");
  N_VCompare(2.5, x, z); /* |x_i| >= 2.5 from i = 2 on */
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == (i >= 2 ? 1.0 : 0.0);
  EXPECT(ok, "compare");

  /* Fused operations, with the result aliasing an input as KINSOL and SPGMR do. */
  N_Vector X[3] = {z, x, y};
  N_VScale(3.0, x, z); /* X0 = 3 x */
  double c[3] = {2.0, -1.0, 5.0};
  N_VLinearCombination(3, c, X, z); /* z = 6 x - x + 5 = 5 x + 5 */
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == 5.0 * (i + 1) + 5.0;
  EXPECT(ok, "linear combination (z = X[0])");
  N_Vector Y[2] = {z, y}, Z[2] = {z, w};
  double a[2] = {-5.0, 2.0};
  N_VScaleAddMulti(2, a, x, Y, Z); /* z = -5 x + z = 5; w = 2 x + 1 */
  ok = 1;
  for (int i = 0; i < n; i++) ok &= zd[i] == 5.0 && wd[i] == 2.0 * (i + 1) + 1.0;
  EXPECT(ok, "scale add multi");
  double d[3];
  N_Vector V[3] = {y, z, w};
  N_VDotProdMulti(3, x, V, d); /* x.1, x.5, x.(2x + 1) */
  const double sq = n * (n + 1.0) * (2.0 * n + 1.0) / 6.0;
  EXPECT(d[0] == tri && d[1] == 5.0 * tri && d[2] == 2.0 * sq + tri, "dot multi %g %g %g", d[0],
         d[1], d[2]);
  N_VDestroy(x);
  N_VDestroy(y);
  N_VDestroy(z);
  N_VDestroy(w);
  N_VDestroy(id);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  const int lengths[] = {1, 3, 7, 256, 257, 2550};
  for (int k = 0; k < 6; k++) check_length(lengths[k], ctx);
  const int n = 0;
  EXPECT(rs_nvector_fast_ops(NULL) == RS_ERR_INTERNAL, "a NULL vector is accepted");
  SUNContext_Free(&ctx);
  if (fails) return 1;
  printf("optimised N_Vector kernels: all operations exact on lengths 1..2550\n");
  return 0;
}
