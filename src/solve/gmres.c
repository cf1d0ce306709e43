/* Restarted GMRES with fused vector work (see gmres.h). */
#include "solve/gmres.h"

#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdlib.h>
#include <string.h>

#include "base/status.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RS_GMRES_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RS_GMRES_CLONES
#endif

/* Four partial sums in one vector; loads from any double's address. Each lane's additions
 * come in a fixed order (whatever the instruction set), so the sums do not depend on it. */
typedef double v4 __attribute__((vector_size(4 * sizeof(double)), aligned(sizeof(double))));

/* the vectors' work goes in pieces that stay in the first-level cache */
enum { PIECE = 512, FACTOR = 1000 };

typedef struct {
  rs_krylov *kry;
  int n, maxl, maxrs;
  double **V;  /* maxl + 1 basis vectors */
  double *z;   /* the preconditioner's vector */
  double *H;   /* (maxl + 1) x maxl Hessenberg, by columns, then its triangular factor */
  double *raw; /* each new vector's norm before the rotations */
  double *cs, *sn, *g, *y, *dots;
  const double *s1, *s2; /* scaling vectors (NULL: ones) */
  void *pdata;
  SUNPSetupFn pset;
  int zeroguess, numiters, last_flag;
  double resnorm;
} gmres;

#define CONTENT(S) ((gmres *)(S)->content)

/* (Vectors by address: a function that takes or returns one by value has another calling
 * convention with 256-bit registers than without.) */
static double sum4(const v4 *a) { return ((*a)[0] + (*a)[1]) + ((*a)[2] + (*a)[3]); }

/* The partial dot product of one piece, added to acc: four vectors of partial sums (their
 * chains of additions side by side), then the tail in lane 0. */
static inline __attribute__((always_inline)) void dot_piece(v4 *acc, const double *x,
                                                            const double *y, int len)
{
  v4 p[4] = {{0.0}};
  int i = 0;
  for (; i + 16 <= len; i += 16)
    for (int q = 0; q < 4; q++) {
      v4 a, b;
      memcpy(&a, x + i + 4 * q, sizeof a);
      memcpy(&b, y + i + 4 * q, sizeof b);
      p[q] += a * b;
    }
  for (; i + 4 <= len; i += 4) {
    v4 a, b;
    memcpy(&a, x + i, sizeof a);
    memcpy(&b, y + i, sizeof b);
    p[0] += a * b;
  }
  *acc += (p[0] + p[1]) + (p[2] + p[3]);
  for (; i < len; i++) (*acc)[0] += x[i] * y[i];
}

/* dot_piece for two vectors x0, x1 against the same y (acc[0], acc[1]): each sum's additions
 * in dot_piece's order, y read once for both. */
static inline __attribute__((always_inline)) void
dot_piece2(v4 *acc, const double *x0, const double *x1, const double *y, int len)
{
  v4 p[4] = {{0.0}}, q[4] = {{0.0}};
  int i = 0;
  for (; i + 16 <= len; i += 16)
    for (int k = 0; k < 4; k++) {
      v4 a, b, c;
      memcpy(&a, x0 + i + 4 * k, sizeof a);
      memcpy(&b, x1 + i + 4 * k, sizeof b);
      memcpy(&c, y + i + 4 * k, sizeof c);
      p[k] += a * c;
      q[k] += b * c;
    }
  for (; i + 4 <= len; i += 4) {
    v4 a, b, c;
    memcpy(&a, x0 + i, sizeof a);
    memcpy(&b, x1 + i, sizeof b);
    memcpy(&c, y + i, sizeof c);
    p[0] += a * c;
    q[0] += b * c;
  }
  acc[0] += (p[0] + p[1]) + (p[2] + p[3]);
  acc[1] += (q[0] + q[1]) + (q[2] + q[3]);
  for (; i < len; i++) {
    acc[0][0] += x0[i] * y[i];
    acc[1][0] += x1[i] * y[i];
  }
}

/* w <- s2 w (s2 NULL: w), and the dot products of w with V[0..m-1] into d, |w|^2 into *ww. */
RS_GMRES_CLONES static void scale_and_dots(int n, const double *s2, double *w, double *const *V,
                                           int m, double *d, double *ww)
{
  v4 acc[64 + 1];
  const v4 zero = {0.0, 0.0, 0.0, 0.0};
  for (int j = 0; j <= m; j++) acc[j] = zero;
  for (int i0 = 0; i0 < n; i0 += PIECE) {
    const int len = n - i0 < PIECE ? n - i0 : PIECE;
    double *wp = w + i0;
    if (s2)
      for (int i = 0; i < len; i++) wp[i] *= s2[i0 + i];
    dot_piece(&acc[m], wp, wp, len);
    int j = 0;
    for (; j + 2 <= m; j += 2) dot_piece2(&acc[j], V[j] + i0, V[j + 1] + i0, wp, len);
    if (j < m) dot_piece(&acc[j], V[j] + i0, wp, len);
  }
  for (int j = 0; j < m; j++) d[j] = sum4(&acc[j]);
  *ww = sum4(&acc[m]);
}

/* w <- w - sum_j d[j] V[j], j < m; returns |w|^2. */
RS_GMRES_CLONES static double subtract(int n, double *w, double *const *V, int m, const double *d)
{
  v4 acc = {0.0, 0.0, 0.0, 0.0};
  for (int i0 = 0; i0 < n; i0 += PIECE) {
    const int len = n - i0 < PIECE ? n - i0 : PIECE;
    double *wp = w + i0;
    int j = 0;
    for (; j + 4 <= m; j += 4) { /* four at a time, each element's subtractions in order */
      const double d0 = d[j], d1 = d[j + 1], d2 = d[j + 2], d3 = d[j + 3];
      const double *v0 = V[j] + i0, *v1 = V[j + 1] + i0, *v2 = V[j + 2] + i0, *v3 = V[j + 3] + i0;
      for (int i = 0; i < len; i++) {
        double t = wp[i];
        t -= d0 * v0[i];
        t -= d1 * v1[i];
        t -= d2 * v2[i];
        t -= d3 * v3[i];
        wp[i] = t;
      }
    }
    for (; j < m; j++) {
      const double dj = d[j], *vp = V[j] + i0;
      for (int i = 0; i < len; i++) wp[i] -= dj * vp[i];
    }
    dot_piece(&acc, wp, wp, len);
  }
  return sum4(&acc);
}

/* v <- c v, and z <- v / s1 (s1 NULL: z <- v), in one pass. */
RS_GMRES_CLONES static void normalise_into(int n, double c, double *v, const double *s1, double *z)
{
  if (s1)
    for (int i = 0; i < n; i++) {
      v[i] *= c;
      z[i] = v[i] / s1[i];
    }
  else
    for (int i = 0; i < n; i++) z[i] = v[i] *= c;
}

/* z <- (sum_j c[j] V[j], j < m) / s1 */
RS_GMRES_CLONES static void combine(int n, double *const *V, int m, const double *c,
                                    const double *s1, double *z)
{
  for (int i0 = 0; i0 < n; i0 += PIECE) {
    const int len = n - i0 < PIECE ? n - i0 : PIECE;
    double *zp = z + i0;
    for (int i = 0; i < len; i++) zp[i] = 0.0;
    for (int j = 0; j < m; j++) {
      const double cj = c[j], *vp = V[j] + i0;
      for (int i = 0; i < len; i++) zp[i] += cj * vp[i];
    }
    if (s1)
      for (int i = 0; i < len; i++) zp[i] /= s1[i0 + i];
  }
}

static SUNLinearSolver_Type gettype(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_ITERATIVE;
}

static SUNLinearSolver_ID getid(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_CUSTOM;
}

static int setatimes(SUNLinearSolver S, void *data, SUNATimesFn fn)
{
  (void)S; /* the products are rs_krylov_times */
  (void)data;
  (void)fn;
  return SUNLS_SUCCESS;
}

static int setpreconditioner(SUNLinearSolver S, void *data, SUNPSetupFn pset, SUNPSolveFn psol)
{
  (void)psol; /* the solves are rs_krylov_psolve */
  CONTENT(S)->pdata = data;
  CONTENT(S)->pset = pset;
  return SUNLS_SUCCESS;
}

static int setscalingvectors(SUNLinearSolver S, N_Vector s1, N_Vector s2)
{
  CONTENT(S)->s1 = s1 ? N_VGetArrayPointer(s1) : NULL;
  CONTENT(S)->s2 = s2 ? N_VGetArrayPointer(s2) : NULL;
  return SUNLS_SUCCESS;
}

static int setzeroguess(SUNLinearSolver S, sunbooleantype on)
{
  CONTENT(S)->zeroguess = on;
  return SUNLS_SUCCESS;
}

static int initialize(SUNLinearSolver S)
{
  CONTENT(S)->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

static int setup(SUNLinearSolver S, SUNMatrix A)
{
  (void)A;
  gmres *c = CONTENT(S);
  const int status = c->pset ? c->pset(c->pdata) : 0;
  c->last_flag = status == 0  ? SUNLS_SUCCESS
                 : status > 0 ? SUNLS_PSET_FAIL_REC
                              : SUNLS_PSET_FAIL_UNREC;
  return c->last_flag;
}

/* x <- x + P^-1 ((sum_j y_j V[j]) / s1), j < k: the correction's combination written into
 * z, P^-1 in place there (into x itself from a zero guess). */
static int add_correction(gmres *c, double *x, int k)
{
  double *t = c->zeroguess ? x : c->z;
  combine(c->n, c->V, k, c->y, c->s1, t);
  if (rs_krylov_psolve(c->kry, t) != RS_OK) return SUNLS_PSOLVE_FAIL_REC;
  if (!c->zeroguess)
    for (int i = 0; i < c->n; i++) x[i] += c->z[i];
  c->zeroguess = 0;
  return SUNLS_SUCCESS;
}

/* Column l of H: the earlier rotations applied, and a new one that zeroes its subdiagonal;
 * g rotated with it. Returns |g[l + 1]|, the residual norm. */
static double rotate(gmres *c, int l)
{
  double *h = c->H + (size_t)l * (size_t)(c->maxl + 1);
  for (int i = 0; i < l; i++) {
    const double a = h[i], b = h[i + 1];
    h[i] = c->cs[i] * a + c->sn[i] * b;
    h[i + 1] = -c->sn[i] * a + c->cs[i] * b;
  }
  const double a = h[l], b = h[l + 1];
  if (b == 0.0) {
    c->cs[l] = 1.0;
    c->sn[l] = 0.0;
  } else {
    const double r = hypot(a, b);
    c->cs[l] = a / r;
    c->sn[l] = b / r;
    h[l] = r;
  }
  h[l + 1] = 0.0;
  c->g[l + 1] = -c->sn[l] * c->g[l];
  c->g[l] = c->cs[l] * c->g[l];
  return fabs(c->g[l + 1]);
}

/* y from the triangular k x k system R y = g; 0, or -1 if R is singular. */
static int back_substitute(gmres *c, int k)
{
  const int ld = c->maxl + 1;
  for (int i = k - 1; i >= 0; i--) {
    double t = c->g[i];
    for (int j = i + 1; j < k; j++) t -= c->H[(size_t)j * (size_t)ld + (size_t)i] * c->y[j];
    const double rii = c->H[(size_t)i * (size_t)ld + (size_t)i];
    if (rii == 0.0) return -1;
    c->y[i] = t / rii;
  }
  return 0;
}

static int solve(SUNLinearSolver S, SUNMatrix A, N_Vector xv, N_Vector bv, double delta)
{
  (void)A;
  gmres *c = CONTENT(S);
  const int n = c->n, maxl = c->maxl, ld = maxl + 1;
  double *x = N_VGetArrayPointer(xv), **V = c->V;
  const double *b = N_VGetArrayPointer(bv);
  c->numiters = 0;
  /* V[0] = s2 (b - A x), its norm beta (V[0] normalised at the first iteration) */
  if (c->zeroguess) {
    memcpy(V[0], b, (size_t)n * sizeof *b);
  } else {
    if (rs_krylov_times(c->kry, x, V[0]) != RS_OK) return c->last_flag = SUNLS_ATIMES_FAIL_UNREC;
    for (int i = 0; i < n; i++) V[0][i] = b[i] - V[0][i];
  }
  double beta2 = 0.0;
  scale_and_dots(n, c->s2, V[0], V, 0, c->dots, &beta2);
  double beta = sqrt(beta2);
  const double beta0 = beta;
  c->resnorm = beta;
  if (beta <= delta) {
    if (c->zeroguess) memset(x, 0, (size_t)n * sizeof *x);
    return c->last_flag = SUNLS_SUCCESS;
  }
  if (!isfinite(beta)) return c->last_flag = SUNLS_CONV_FAIL;
  for (int restart = 0;; restart++) {
    for (int i = 0; i <= maxl; i++) c->g[i] = 0.0;
    c->g[0] = beta;
    c->raw[0] = beta;
    int k = 0;
    double rho = beta;
    for (int l = 0; l < maxl; l++) {
      /* V[l] normalised and z = V[l] / s1 in one pass; z <- P^-1 z; V[l+1] <- s2 A z */
      normalise_into(n, 1.0 / c->raw[l], V[l], c->s1, c->z);
      if (!V[l + 1] && !(V[l + 1] = malloc((size_t)n * sizeof **V)))
        return c->last_flag = SUNLS_MEM_FAIL;
      if (rs_krylov_psolve(c->kry, c->z) != RS_OK) return c->last_flag = SUNLS_PSOLVE_FAIL_REC;
      if (rs_krylov_times(c->kry, c->z, V[l + 1]) != RS_OK)
        return c->last_flag = SUNLS_ATIMES_FAIL_UNREC;
      /* classical Gram-Schmidt, a second pass where the first lost a factor FACTOR */
      double *h = c->H + (size_t)l * (size_t)ld, before2 = 0.0;
      scale_and_dots(n, c->s2, V[l + 1], V, l + 1, h, &before2);
      double after = sqrt(subtract(n, V[l + 1], V, l + 1, h));
      if (FACTOR * after < sqrt(before2)) {
        double again2 = 0.0;
        scale_and_dots(n, NULL, V[l + 1], V, l + 1, c->dots, &again2);
        after = sqrt(subtract(n, V[l + 1], V, l + 1, c->dots));
        for (int j = 0; j <= l; j++) h[j] += c->dots[j];
      }
      h[l + 1] = after;
      c->raw[l + 1] = after;
      c->numiters++;
      k = l + 1;
      rho = rotate(c, l);
      if (rho <= delta || !(after > 0.0)) break;
    }
    c->resnorm = rho;
    if (back_substitute(c, k) != 0) return c->last_flag = SUNLS_QRSOL_FAIL;
    const int converged = rho <= delta;
    if (converged || restart >= c->maxrs) {
      const int status = add_correction(c, x, k);
      if (status != SUNLS_SUCCESS) return c->last_flag = status;
      return c->last_flag = converged     ? SUNLS_SUCCESS
                            : rho < beta0 ? SUNLS_RES_REDUCED
                                          : SUNLS_CONV_FAIL;
    }
    /* Restart: x corrected; the new residual s2 (b - A x) = V_k+1 Q^T (0, .., g[k]) (V[k]
     * not normalised yet: its coefficient divided by its norm), into V[0]. */
    const int status = add_correction(c, x, k);
    if (status != SUNLS_SUCCESS) return c->last_flag = status;
    double *w = c->dots; /* k + 1 coefficients */
    for (int i = 0; i < k; i++) w[i] = 0.0;
    w[k] = c->g[k];
    for (int i = k - 1; i >= 0; i--) {
      const double a = w[i], bb = w[i + 1];
      w[i] = c->cs[i] * a - c->sn[i] * bb;
      w[i + 1] = c->sn[i] * a + c->cs[i] * bb;
    }
    w[k] /= c->raw[k];
    combine(n, V, k + 1, w, NULL, c->z);
    memcpy(V[0], c->z, (size_t)n * sizeof *c->z);
    beta = rho;
  }
}

static int numiters(SUNLinearSolver S) { return CONTENT(S)->numiters; }

static double resnorm(SUNLinearSolver S) { return CONTENT(S)->resnorm; }

static sunindextype lastflag(SUNLinearSolver S) { return CONTENT(S)->last_flag; }

static int space(SUNLinearSolver S, long *lrw, long *liw)
{
  const gmres *c = CONTENT(S);
  *lrw = (long)(c->maxl + 2) * c->n + (long)(c->maxl + 1) * (c->maxl + 6);
  *liw = 0;
  return SUNLS_SUCCESS;
}

static int gmres_free(SUNLinearSolver S)
{
  if (!S) return SUNLS_SUCCESS;
  gmres *c = CONTENT(S);
  if (c) {
    for (int j = 0; c->V && j <= c->maxl; j++) free(c->V[j]);
    free(c->V);
    free(c->z);
    free(c->H);
    free(c->raw);
    free(c->cs);
    free(c->sn);
    free(c->g);
    free(c->y);
    free(c->dots);
    free(c);
  }
  S->content = NULL;
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

SUNLinearSolver rs_gmres_create(rs_krylov *kry, N_Vector tmpl, int maxl, int max_restarts,
                                SUNContext ctx)
{
  if (maxl < 1 || maxl > 64) return NULL;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return NULL;
  S->ops->gettype = gettype;
  S->ops->getid = getid;
  S->ops->setatimes = setatimes;
  S->ops->setpreconditioner = setpreconditioner;
  S->ops->setscalingvectors = setscalingvectors;
  S->ops->setzeroguess = setzeroguess;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->numiters = numiters;
  S->ops->resnorm = resnorm;
  S->ops->lastflag = lastflag;
  S->ops->space = space;
  S->ops->free = gmres_free;
  gmres *c = calloc(1, sizeof *c);
  S->content = c;
  if (!c) {
    gmres_free(S);
    return NULL;
  }
  c->kry = kry;
  c->n = (int)N_VGetLength(tmpl);
  c->maxl = maxl;
  c->maxrs = max_restarts;
  const size_t nv = (size_t)c->n, m1 = (size_t)maxl + 1;
  c->V = calloc(m1, sizeof *c->V);
  c->z = malloc(nv * sizeof *c->z);
  c->H = calloc(m1 * (size_t)maxl, sizeof *c->H);
  c->raw = calloc(m1, sizeof *c->raw);
  c->cs = calloc(m1, sizeof *c->cs);
  c->sn = calloc(m1, sizeof *c->sn);
  c->g = calloc(m1, sizeof *c->g);
  c->y = calloc(m1, sizeof *c->y);
  c->dots = calloc(m1, sizeof *c->dots);
  int ok = c->V && c->z && c->H && c->raw && c->cs && c->sn && c->g && c->y && c->dots;
  /* the first basis vector; the others when an iteration first reaches them (most solves
   * take a few of the maxl + 1, and memory in huge pages would count in full) */
  ok = ok && (c->V[0] = malloc(nv * sizeof **c->V)) != NULL;
  if (!ok) {
    gmres_free(S);
    return NULL;
  }
  return S;
}
