/* Schur-complement direct solver for the generalized Jacobian (see linsys_reduced.h). */
#include "solve/linsys_reduced.h"

#include <klu.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_matrix.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "base/util.h"

typedef struct red_content {
  int n, neq;
  const unsigned char *dense; /* [n]: row i is dense (from the model, per setup) */
  const int *pivot;           /* [n]: the unknown eliminated on dense row i */
  SUNLinearSolver fallback;
  SUNMatrix J;
  int use_fallback; /* the last setup fell back to the full KLU factorisation */
  long last_flag;
  rs_lsreduced_stats st;
  /* classification of the last setup */
  int h, nz, ncpl;
  int *drow, *dcol; /* [h]: dense row and its dense unknown */
  int *dpos, *zpos; /* [neq]: column -> dense index / Z index (-1 if not) */
  int *zcol, *srow; /* [neq]: Z index -> column, S index -> row */
  int *cpl;         /* [h]: dense indices whose column appears in sparse rows */
  /* J_SZ in CSR (KLU sees it as CSC of the transpose: klu_l_tsolve solves J_SZ x = b) */
  int64_t *sp, *si, *sp_old, *si_old;
  double *sx;
  int64_t scap, nnz_old;
  int nz_old;
  klu_l_common common;
  klu_l_symbolic *sym;
  klu_l_numeric *num;
  double *X; /* J_SZ^-1 J_SD, coupled columns only: row-major [nz][ncpl] */
  double *B; /* column-major [ncpl][nz] work for the multi-rhs solve */
  double *S; /* Schur complement, column-major h x h */
  int64_t xcap, bcap, Scap;
  int *cmap;          /* [n]: dense index -> coupled index */
  unsigned char *xnz; /* [neq]: row z of X has a nonzero */
  int *ipiv;
  double *t, *rd; /* [neq] */
  /* copy of the matrix of the last complete setup: an identical matrix (same active
   * set and coefficients, common at the last Newton iterations and between
   * neighbouring points of a creep curve) reuses the factorisations */
  int64_t *prev_rowptr, *prev_col, prev_cap;
  double *prev_val;
  int have_prev;
  /* the matrix of the last setup (its values are read again in solve) */
  const int64_t *rowptr, *col;
  const double *val;
} red_content;

#define RC(LS) ((red_content *)(LS)->content)

static SUNLinearSolver_Type red_gettype(SUNLinearSolver LS)
{
  (void)LS;
  return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID red_getid(SUNLinearSolver LS)
{
  (void)LS;
  return SUNLINEARSOLVER_CUSTOM;
}

static int red_initialize(SUNLinearSolver LS)
{
  RC(LS)->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

static sunindextype red_lastflag(SUNLinearSolver LS) { return (sunindextype)RC(LS)->last_flag; }

static int fallback_setup(SUNLinearSolver LS, SUNMatrix A)
{
  red_content *c = RC(LS);
  c->use_fallback = 1;
  c->st.fallbacks++;
  /* New symbolic analysis: the pattern may differ from the last KLU factorisation. */
  if (SUNLinSol_KLUReInit(c->fallback, A, SM_NNZ_S(A), SUNKLU_REINIT_PARTIAL) != 0) {
    c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
  const int flag = SUNLinSolSetup(c->fallback, A);
  c->last_flag = flag;
  return flag;
}

/* Grow a buffer to hold at least need elements. */
static int grow(void **p, int64_t *cap, int64_t need, size_t size)
{
  if (need <= *cap) return 0;
  void *q = realloc(*p, (size_t)need * size);
  if (!q) return -1;
  *p = q;
  *cap = need;
  return 0;
}

static int red_setup(SUNLinearSolver LS, SUNMatrix placeholder)
{
  (void)placeholder;
  red_content *c = RC(LS);
  SUNMatrix A = c->J;
  const int n = c->n, neq = c->neq;
  const int64_t *rowptr = SM_INDEXPTRS_S(A), *col = SM_INDEXVALS_S(A);
  const double *val = SM_DATA_S(A);
  c->rowptr = rowptr;
  c->col = col;
  c->val = val;
  c->use_fallback = 0;
  c->st.setups++;
  const int64_t nnz_all = rowptr[neq];
  if (c->have_prev && !memcmp(rowptr, c->prev_rowptr, ((size_t)neq + 1) * sizeof *rowptr) &&
      !memcmp(col, c->prev_col, (size_t)nnz_all * sizeof *col) &&
      !memcmp(val, c->prev_val, (size_t)nnz_all * sizeof *val)) {
    c->st.reuses++;
    c->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
  }
  c->have_prev = 0;

  /* Dense rows and their dense unknowns, as the model says (rs_work dense/pivot): the
   * traction p_i, or u_pl,i when the cell's yield row fixes p_i (yield without hardening)
   * and the traction row then determines the plastic flow; with hardening the yield row
   * ties p_i to u*_i and p_i stays the dense unknown (then only the two u_pl entries of a
   * dense row meet X, not every plastic p, which keeps the Schur update O(h n) instead of
   * O(h^3)). */
  int h = 0;
  for (int k = 0; k < neq; k++) c->dpos[k] = -1;
  for (int i = 0; i < n; i++) {
    if (!c->dense[i]) continue;
    c->drow[h] = i;
    c->dcol[h] = c->pivot[i];
    c->dpos[c->dcol[h]] = h;
    h++;
  }
  c->h = h;
  c->st.dense_rows_sum += h;
  int nz = 0;
  for (int k = 0; k < neq; k++) {
    c->zpos[k] = -1;
    if (c->dpos[k] < 0) {
      c->zpos[k] = nz;
      c->zcol[nz++] = k;
    }
  }
  c->nz = nz;

  /* J_SZ (rows not dense, columns not dense) and the coupled dense columns. */
  int s = 0;
  int64_t nnz = 0;
  for (int i = 0; i < n; i++) c->cpl[i] = 0; /* scratch marks, h <= n */
  c->sp[0] = 0;
  for (int r = 0; r < neq; r++) {
    if (r < n && c->dense[r]) continue;
    c->srow[s] = r;
    const int64_t need = nnz + (rowptr[r + 1] - rowptr[r]);
    if (need > c->scap) {
      int64_t cap_i = c->scap, cap_x = c->scap;
      if (grow((void **)&c->si, &cap_i, 2 * need, sizeof *c->si) ||
          grow((void **)&c->sx, &cap_x, 2 * need, sizeof *c->sx))
        return SUNLS_MEM_FAIL;
      c->scap = 2 * need;
    }
    for (int64_t k = rowptr[r]; k < rowptr[r + 1]; k++) {
      const int64_t j = col[k];
      if (c->zpos[j] >= 0) {
        c->si[nnz] = c->zpos[j];
        c->sx[nnz] = val[k];
        nnz++;
      } else {
        c->cpl[c->dpos[j]] = 1;
      }
    }
    c->sp[++s] = nnz;
  }
  if (s != nz) return fallback_setup(LS, A); /* cannot happen: one dense unknown per dense row */
  int ncpl = 0;
  for (int q = 0; q < h; q++)
    if (c->cpl[q]) c->cpl[ncpl++] = q; /* in place: ncpl <= q */
  c->ncpl = ncpl;

  /* KLU: symbolic analysis when the pattern of J_SZ changed, numeric factorisation always. */
  const int same = c->sym && nz == c->nz_old && nnz == c->nnz_old &&
                   !memcmp(c->sp, c->sp_old, (size_t)(nz + 1) * sizeof *c->sp) &&
                   !memcmp(c->si, c->si_old, (size_t)nnz * sizeof *c->si);
  if (!same) {
    if (c->num) klu_l_free_numeric(&c->num, &c->common);
    if (c->sym) klu_l_free_symbolic(&c->sym, &c->common);
    int64_t *spo = realloc(c->sp_old, (size_t)(nz + 1) * sizeof *spo);
    if (!spo) return SUNLS_MEM_FAIL;
    c->sp_old = spo;
    int64_t *sio = realloc(c->si_old, (size_t)(nnz > 0 ? nnz : 1) * sizeof *sio);
    if (!sio) return SUNLS_MEM_FAIL;
    c->si_old = sio;
    memcpy(c->sp_old, c->sp, (size_t)(nz + 1) * sizeof *c->sp);
    memcpy(c->si_old, c->si, (size_t)nnz * sizeof *c->si);
    c->nz_old = nz;
    c->nnz_old = nnz;
    c->sym = klu_l_analyze(nz, c->sp, c->si, &c->common);
    c->st.analyses++;
    if (!c->sym) return fallback_setup(LS, A);
  }
  if (c->num) klu_l_free_numeric(&c->num, &c->common);
  c->num = klu_l_factor(c->sp, c->si, c->sx, c->sym, &c->common);
  if (!c->num || c->common.status != KLU_OK) return fallback_setup(LS, A);

  /* X = J_SZ^-1 J_SD for the coupled dense columns. */
  if (ncpl > 0) {
    const int64_t need = (int64_t)ncpl * nz;
    if (grow((void **)&c->B, &c->bcap, need, sizeof *c->B)) return SUNLS_MEM_FAIL;
    if (grow((void **)&c->X, &c->xcap, need, sizeof *c->X)) return SUNLS_MEM_FAIL;
    memset(c->B, 0, (size_t)need * sizeof *c->B);
    for (int q = 0; q < ncpl; q++) c->cmap[c->cpl[q]] = q; /* dense index -> coupled index */
    for (int si = 0; si < nz; si++) {
      const int r = c->srow[si];
      for (int64_t k = rowptr[r]; k < rowptr[r + 1]; k++) {
        const int d = c->dpos[col[k]];
        if (d >= 0) c->B[(size_t)c->cmap[d] * nz + si] = val[k];
      }
    }
    if (!klu_l_tsolve(c->sym, c->num, nz, ncpl, c->B, &c->common)) return fallback_setup(LS, A);
    for (int z = 0; z < nz; z++) {
      int any = 0;
      for (int q = 0; q < ncpl; q++) {
        const double v = c->B[(size_t)q * nz + z];
        c->X[(size_t)z * ncpl + q] = v;
        any |= v != 0.0;
      }
      c->xnz[z] = (unsigned char)any;
    }
  }

  /* Schur complement S = J_DD - J_DZ X (column-major). */
  if (h > 0) {
    if (grow((void **)&c->S, &c->Scap, (int64_t)h * h, sizeof *c->S)) return SUNLS_MEM_FAIL;
    memset(c->S, 0, (size_t)h * (size_t)h * sizeof *c->S);
    double *acc = c->t; /* [ncpl] row of J_DZ X, contiguous */
    for (int r = 0; r < h; r++) {
      const int i = c->drow[r];
      for (int q = 0; q < ncpl; q++) acc[q] = 0.0;
      int hit = 0;
      for (int64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
        const int64_t j = col[k];
        const double v = val[k];
        if (c->dpos[j] >= 0) {
          c->S[(size_t)c->dpos[j] * h + r] += v;
        } else if (ncpl > 0 && v != 0.0 && c->xnz[c->zpos[j]]) { /* most rows of X are 0 */
          const double *x = c->X + (size_t)c->zpos[j] * ncpl;
          for (int q = 0; q < ncpl; q++) acc[q] += v * x[q];
          hit = 1;
        }
      }
      if (hit)
        for (int q = 0; q < ncpl; q++) c->S[(size_t)c->cpl[q] * h + r] -= acc[q];
    }
    int info = 0;
    dgetrf_(&h, &h, c->S, &h, c->ipiv, &info);
    if (info != 0) return fallback_setup(LS, A);
  }
  int64_t cap_c = c->prev_cap, cap_v = c->prev_cap;
  if (!grow((void **)&c->prev_col, &cap_c, nnz_all, sizeof *c->prev_col) &&
      !grow((void **)&c->prev_val, &cap_v, nnz_all, sizeof *c->prev_val)) {
    c->prev_cap = nnz_all > c->prev_cap ? nnz_all : c->prev_cap;
    memcpy(c->prev_rowptr, rowptr, ((size_t)neq + 1) * sizeof *rowptr);
    memcpy(c->prev_col, col, (size_t)nnz_all * sizeof *col);
    memcpy(c->prev_val, val, (size_t)nnz_all * sizeof *val);
    c->have_prev = 1;
  }
  c->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

static int red_solve(SUNLinearSolver LS, SUNMatrix placeholder, N_Vector x, N_Vector b,
                     sunrealtype tol)
{
  (void)placeholder;
  red_content *c = RC(LS);
  if (c->use_fallback) {
    const int flag = SUNLinSolSolve(c->fallback, c->J, x, b, tol);
    c->last_flag = flag;
    c->st.solves++;
    return flag;
  }
  const double *bv = N_VGetArrayPointer(b);
  double *xv = N_VGetArrayPointer(x);
  const int h = c->h, nz = c->nz, ncpl = c->ncpl;
  const int64_t *rowptr = c->rowptr, *col = c->col;
  const double *val = c->val;
  /* t = J_SZ^-1 b_S */
  for (int s = 0; s < nz; s++) c->t[s] = bv[c->srow[s]];
  if (nz > 0 && !klu_l_tsolve(c->sym, c->num, nz, 1, c->t, &c->common)) {
    c->last_flag = SUNLS_PACKAGE_FAIL_REC;
    return SUNLS_PACKAGE_FAIL_REC;
  }
  if (h > 0) {
    /* S x_D = b_D - J_DZ t */
    for (int r = 0; r < h; r++) {
      const int i = c->drow[r];
      double sum = bv[i];
      for (int64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
        const int z = c->zpos[col[k]];
        if (z >= 0) sum -= val[k] * c->t[z];
      }
      c->rd[r] = sum;
    }
    int one = 1, info = 0;
    dgetrs_("N", &h, &one, c->S, &h, c->ipiv, c->rd, &h, &info);
    if (info != 0) {
      c->last_flag = SUNLS_PACKAGE_FAIL_REC;
      return SUNLS_PACKAGE_FAIL_REC;
    }
    for (int r = 0; r < h; r++) xv[c->dcol[r]] = c->rd[r];
  }
  /* x_Z = t - X x_D */
  for (int z = 0; z < nz; z++) {
    double v = c->t[z];
    const double *xr = c->X + (size_t)z * ncpl;
    if (ncpl > 0 && c->xnz[z])
      for (int q = 0; q < ncpl; q++) v -= xr[q] * c->rd[c->cpl[q]];
    xv[c->zcol[z]] = v;
  }
  c->st.solves++;
  c->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

static int red_free(SUNLinearSolver LS)
{
  if (!LS) return SUNLS_SUCCESS;
  red_content *c = RC(LS);
  if (c) {
    if (c->num) klu_l_free_numeric(&c->num, &c->common);
    if (c->sym) klu_l_free_symbolic(&c->sym, &c->common);
    free(c->drow);
    free(c->dcol);
    free(c->dpos);
    free(c->zpos);
    free(c->zcol);
    free(c->srow);
    free(c->cpl);
    free(c->cmap);
    free(c->prev_rowptr);
    free(c->prev_col);
    free(c->prev_val);
    free(c->xnz);
    free(c->sp);
    free(c->si);
    free(c->sx);
    free(c->sp_old);
    free(c->si_old);
    free(c->X);
    free(c->B);
    free(c->S);
    free(c->ipiv);
    free(c->t);
    free(c->rd);
    free(c);
  }
  LS->content = NULL;
  SUNLinSolFreeEmpty(LS);
  return SUNLS_SUCCESS;
}

SUNLinearSolver rs_lsreduced_create(int n, int neq, const unsigned char *dense, const int *pivot,
                                    SUNMatrix J, SUNLinearSolver fallback, SUNContext ctx)
{
  SUNLinearSolver LS = SUNLinSolNewEmpty(ctx);
  if (!LS) return NULL;
  LS->ops->gettype = red_gettype;
  LS->ops->getid = red_getid;
  LS->ops->initialize = red_initialize;
  LS->ops->setup = red_setup;
  LS->ops->solve = red_solve;
  LS->ops->lastflag = red_lastflag;
  LS->ops->free = red_free;
  red_content *c = calloc(1, sizeof *c);
  LS->content = c;
  if (!c) goto fail;
  c->n = n;
  c->neq = neq;
  c->dense = dense;
  c->pivot = pivot;
  c->fallback = fallback;
  c->J = J;
  const size_t un = (size_t)n, ue = (size_t)neq;
  c->drow = malloc(un * sizeof *c->drow);
  c->dcol = malloc(un * sizeof *c->dcol);
  c->cpl = malloc(un * sizeof *c->cpl);
  c->dpos = malloc(ue * sizeof *c->dpos);
  c->zpos = malloc(ue * sizeof *c->zpos);
  c->zcol = malloc(ue * sizeof *c->zcol);
  c->srow = malloc(ue * sizeof *c->srow);
  c->sp = malloc((ue + 1) * sizeof *c->sp);
  c->scap = 8 * (int64_t)neq;
  c->si = malloc((size_t)c->scap * sizeof *c->si);
  c->sx = malloc((size_t)c->scap * sizeof *c->sx);
  c->cmap = malloc(un * sizeof *c->cmap);
  c->prev_rowptr = malloc((ue + 1) * sizeof *c->prev_rowptr);
  c->xnz = malloc(ue * sizeof *c->xnz);
  c->ipiv = malloc(un * sizeof *c->ipiv);
  c->t = malloc(ue * sizeof *c->t);
  c->rd = calloc(un, sizeof *c->rd);
  if (!c->drow || !c->dcol || !c->cpl || !c->dpos || !c->zpos || !c->zcol || !c->srow || !c->sp ||
      !c->si || !c->sx || !c->cmap || !c->prev_rowptr || !c->xnz || !c->ipiv || !c->t || !c->rd)
    goto fail;
  if (!klu_l_defaults(&c->common)) goto fail;
  return LS;
fail:
  red_free(LS);
  return NULL;
}

void rs_lsreduced_get_stats(SUNLinearSolver LS, rs_lsreduced_stats *st) { *st = RC(LS)->st; }
