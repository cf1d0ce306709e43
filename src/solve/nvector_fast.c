/* Optimised serial N_Vector kernels (see nvector_fast.h). */
#include "solve/nvector_fast.h"

#include <math.h>
#include <nvector/nvector_serial.h>

#include "base/status.h"

/* BLAS level 1 (Fortran interface). */
extern double ddot_(const int *n, const double *x, const int *incx, const double *y,
                    const int *incy);
extern void daxpy_(const int *n, const double *a, const double *x, const int *incx, double *y,
                   const int *incy);

static int len(N_Vector v) { return (int)NV_LENGTH_S(v); }
static double *data(N_Vector v) { return NV_DATA_S(v); }

static double dot(int n, const double *x, const double *y)
{
  static const int one = 1;
  return n > 0 ? ddot_(&n, x, &one, y, &one) : 0.0;
}

/* Sum of (x_i w_i)^2 over i with id_i > 0 (id NULL: all i); four partial sums so
 * that the additions do not wait on each other. */
static double wsqrsum(int n, const double *x, const double *w, const double *id)
{
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  int i = 0;
  if (!id) {
    for (; i + 4 <= n; i += 4)
      for (int k = 0; k < 4; k++) {
        const double t = x[i + k] * w[i + k];
        s[k] += t * t;
      }
  }
  for (; i < n; i++) {
    const double t = x[i] * w[i];
    if (!id || id[i] > 0.0) s[i & 3] += t * t;
  }
  return (s[0] + s[1]) + (s[2] + s[3]);
}

static void linearsum(double a, N_Vector x, double b, N_Vector y, N_Vector z)
{
  const double *xd = data(x), *yd = data(y);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = a * xd[i] + b * yd[i];
}

static void constant(double c, N_Vector z)
{
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = c;
}

static void prod(N_Vector x, N_Vector y, N_Vector z)
{
  const double *xd = data(x), *yd = data(y);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = xd[i] * yd[i];
}

static void divide(N_Vector x, N_Vector y, N_Vector z)
{
  const double *xd = data(x), *yd = data(y);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = xd[i] / yd[i];
}

static void scale(double c, N_Vector x, N_Vector z)
{
  const double *xd = data(x);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = c * xd[i];
}

static void absolute(N_Vector x, N_Vector z)
{
  const double *xd = data(x);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = fabs(xd[i]);
}

static void inverse(N_Vector x, N_Vector z)
{
  const double *xd = data(x);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = 1.0 / xd[i];
}

static void addconst(N_Vector x, double b, N_Vector z)
{
  const double *xd = data(x);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = xd[i] + b;
}

static double dotprod(N_Vector x, N_Vector y) { return dot(len(x), data(x), data(y)); }

/* max |x_i|, ignoring NaN as fmax would (SUNDIALS' serial kernel does the same). Four
 * running maxima with comparisons: fmax is a call into libm, and KINSOL takes this norm
 * at every residual and step. */
static double maxnorm(N_Vector x)
{
  const double *xd = data(x);
  const int n = len(x);
  double m[4] = {0.0, 0.0, 0.0, 0.0};
  int i = 0;
  for (; i + 4 <= n; i += 4)
    for (int k = 0; k < 4; k++) {
      const double a = fabs(xd[i + k]);
      m[k] = a > m[k] ? a : m[k];
    }
  for (; i < n; i++) {
    const double a = fabs(xd[i]);
    m[0] = a > m[0] ? a : m[0];
  }
  const double m01 = m[1] > m[0] ? m[1] : m[0], m23 = m[3] > m[2] ? m[3] : m[2];
  return m23 > m01 ? m23 : m01;
}

static double wrmsnorm(N_Vector x, N_Vector w)
{
  return sqrt(wsqrsum(len(x), data(x), data(w), NULL) / len(x));
}

static double wrmsnormmask(N_Vector x, N_Vector w, N_Vector id)
{
  return sqrt(wsqrsum(len(x), data(x), data(w), data(id)) / len(x));
}

static double minimum(N_Vector x)
{
  const double *xd = data(x);
  const int n = len(x);
  double mn = n > 0 ? xd[0] : 0.0;
  for (int i = 1; i < n; i++) mn = fmin(mn, xd[i]);
  return mn;
}

static double wl2norm(N_Vector x, N_Vector w)
{
  return sqrt(wsqrsum(len(x), data(x), data(w), NULL));
}

static double l1norm(N_Vector x)
{
  const double *xd = data(x);
  const int n = len(x);
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < n; i++) s[i & 3] += fabs(xd[i]);
  return (s[0] + s[1]) + (s[2] + s[3]);
}

static void compare(double c, N_Vector x, N_Vector z)
{
  const double *xd = data(x);
  double *zd = data(z);
  const int n = len(z);
  for (int i = 0; i < n; i++) zd[i] = fabs(xd[i]) >= c ? 1.0 : 0.0;
}

static double wsqrsumlocal(N_Vector x, N_Vector w)
{
  return wsqrsum(len(x), data(x), data(w), NULL);
}

static double wsqrsummasklocal(N_Vector x, N_Vector w, N_Vector id)
{
  return wsqrsum(len(x), data(x), data(w), data(id));
}

/* z = sum_j c_j X_j. Block by block through a buffer, so that z may be any of the
 * X_j (KINSOL and SPGMR pass z = X_0). */
enum { BLOCK = 256 };
static int linearcombination(int nvec, double *c, N_Vector *X, N_Vector z)
{
  static const int one = 1;
  const int n = len(z);
  double *zd = data(z);
  double buf[BLOCK];
  for (int b = 0; b < n; b += BLOCK) {
    const int m = n - b < BLOCK ? n - b : BLOCK;
    const double *x0 = data(X[0]) + b;
    for (int i = 0; i < m; i++) buf[i] = c[0] * x0[i];
    for (int j = 1; j < nvec; j++) daxpy_(&m, &c[j], data(X[j]) + b, &one, buf, &one);
    for (int i = 0; i < m; i++) zd[b + i] = buf[i];
  }
  return 0;
}

/* Z_j = a_j x + Y_j. */
static int scaleaddmulti(int nvec, double *a, N_Vector x, N_Vector *Y, N_Vector *Z)
{
  static const int one = 1;
  const int n = len(x);
  const double *xd = data(x);
  for (int j = 0; j < nvec; j++) {
    double *zd = data(Z[j]);
    const double *yd = data(Y[j]);
    if (zd == yd) {
      daxpy_(&n, &a[j], xd, &one, zd, &one);
    } else {
      for (int i = 0; i < n; i++) zd[i] = a[j] * xd[i] + yd[i];
    }
  }
  return 0;
}

/* d_j = x . Y_j */
static int dotprodmulti(int nvec, N_Vector x, N_Vector *Y, double *d)
{
  for (int j = 0; j < nvec; j++) d[j] = dot(len(x), data(x), data(Y[j]));
  return 0;
}

int rs_nvector_fast_ops(N_Vector v)
{
  if (!v || N_VGetVectorID(v) != SUNDIALS_NVEC_SERIAL) return RS_ERR_INTERNAL;
  N_Vector_Ops o = v->ops;
  o->nvlinearsum = linearsum;
  o->nvconst = constant;
  o->nvprod = prod;
  o->nvdiv = divide;
  o->nvscale = scale;
  o->nvabs = absolute;
  o->nvinv = inverse;
  o->nvaddconst = addconst;
  o->nvdotprod = dotprod;
  o->nvmaxnorm = maxnorm;
  o->nvwrmsnorm = wrmsnorm;
  o->nvwrmsnormmask = wrmsnormmask;
  o->nvmin = minimum;
  o->nvwl2norm = wl2norm;
  o->nvl1norm = l1norm;
  o->nvcompare = compare;
  o->nvlinearcombination = linearcombination;
  o->nvscaleaddmulti = scaleaddmulti;
  o->nvdotprodmulti = dotprodmulti;
  o->nvdotprodlocal = dotprod;
  o->nvmaxnormlocal = maxnorm;
  o->nvminlocal = minimum;
  o->nvl1normlocal = l1norm;
  o->nvwsqrsumlocal = wsqrsumlocal;
  o->nvwsqrsummasklocal = wsqrsummasklocal;
  return RS_OK;
}
