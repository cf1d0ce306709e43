/* Newton-Krylov products and near-field preconditioner (see linsys_krylov.h). */
#include "solve/linsys_krylov.h"

#include <stdlib.h>
#include <string.h>

int rs_krylov_create(rs_krylov *k, const rs_model *m, int band) {
  memset(k, 0, sizeof *k);
  if (m->neq != 3 * m->n) return RS_ERR_INTERNAL; /* the 3 n per-cell unknowns only */
  k->m = m;
  k->lin = *m;
  k->band = band;
  k->dense = calloc((size_t)m->n, 1);
  k->vp = calloc((size_t)m->neq, sizeof *k->vp);
  k->rp = malloc(((size_t)m->neq + 1) * sizeof *k->rp);
  k->cap = (int64_t)m->neq * 4 + (int64_t)m->n * (2 * band + 3);
  k->ci = malloc((size_t)k->cap * sizeof *k->ci);
  k->vx = malloc((size_t)k->cap * sizeof *k->vx);
  k->rp_old = calloc((size_t)m->neq + 1, sizeof *k->rp_old);
  k->ci_old = malloc((size_t)k->cap * sizeof *k->ci_old);
  if (!k->dense || !k->vp || !k->rp || !k->ci || !k->vx || !k->rp_old || !k->ci_old ||
      rs_work_create(&k->wlin, m->n) != RS_OK || !klu_l_defaults(&k->common)) {
    rs_krylov_free(k);
    return RS_ERR_INTERNAL;
  }
  /* No row scaling: the rows are scaled already (r gives the traction rows a unit
   * diagonal), and KLU's scaling was 5 % of the elastic creep curve at 850 cells. */
  k->common.scale = 0;
  return RS_OK;
}

void rs_krylov_free(rs_krylov *k) {
  if (k->num) klu_l_free_numeric(&k->num, &k->common);
  if (k->sym) klu_l_free_symbolic(&k->sym, &k->common);
  rs_work_free(&k->wlin);
  free(k->dense);
  free(k->vp);
  free(k->rp);
  free(k->ci);
  free(k->vx);
  free(k->rp_old);
  free(k->ci_old);
  memset(k, 0, sizeof *k);
}

int rs_krylov_setup(rs_krylov *k, const rs_csr *full, double t, double cj) {
  const rs_model *m = k->m;
  const int n = m->n, neq = m->neq, w = k->band;
  k->t = t;
  k->cj = cj;
  k->r = rs_model_scaling(m, t, cj);
  /* The linear part of v_s at time t: inputs frozen, rigid slip and inflow removed. */
  k->lin.velocity =
      (rs_history){.kind = RS_HISTORY_CONSTANT, .value = rs_history_eval(&m->velocity, t)};
  k->lin.creepage = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 0.0};
  k->lin.shift = (rs_history){.kind = RS_HISTORY_CONSTANT, .value = 0.0};
  k->lin.memory = NULL; /* fresh inflow: no twin-disc memory in the linear part */
  k->setups++;

  /* The near-field matrix: the assembled one (full->band = k->band) on a pattern that
   * does not depend on the contact regimes, so that the symbolic analysis (AMD, BTF)
   * is done once: every traction row holds its band and its upl columns (a row at a
   * bound has explicit zeros there); the other rows are copied. */
  if (full->band != w) return RS_ERR_INTERNAL;
  int64_t nnz = 0;
  k->rp[0] = 0;
  for (int i = 0; i < neq; i++) {
    const int64_t b = full->rowptr[i], e = full->rowptr[i + 1];
    if (i < n) {
      k->dense[i] = (unsigned char)(e - b > 1);
      const int j0 = i > w ? i - w : 0, j1 = i + w < n ? i + w + 1 : n;
      const int64_t band_len = j1 - j0, len = band_len + (i + 1 < n ? 2 : 1);
      if (nnz + len > k->cap) return RS_ERR_INTERNAL;
      for (int64_t q = 0; q < len; q++) k->vx[nnz + q] = 0.0;
      for (int j = j0; j < j1; j++) k->ci[nnz + j - j0] = j;
      k->ci[nnz + band_len] = n + i;
      if (i + 1 < n) k->ci[nnz + band_len + 1] = n + i + 1;
      for (int64_t q = b; q < e; q++) {
        const int64_t c = full->col[q];
        int64_t at = -1;
        if (c >= j0 && c < j1) at = c - j0;
        else if (c == n + i) at = band_len;
        else if (c == n + i + 1 && i + 1 < n) at = band_len + 1;
        if (at < 0) return RS_ERR_INTERNAL; /* not a near-field matrix */
        k->vx[nnz + at] = full->val[q];
      }
      nnz += len;
    } else {
      if (nnz + (e - b) > k->cap) return RS_ERR_INTERNAL;
      for (int64_t q = b; q < e; q++, nnz++) {
        k->ci[nnz] = full->col[q];
        k->vx[nnz] = full->val[q];
      }
    }
    k->rp[i + 1] = nnz;
  }
  const int same = k->sym && nnz == k->nnz_old &&
                   !memcmp(k->rp, k->rp_old, ((size_t)neq + 1) * sizeof *k->rp) &&
                   !memcmp(k->ci, k->ci_old, (size_t)nnz * sizeof *k->ci);
  if (!same) {
    if (k->num) klu_l_free_numeric(&k->num, &k->common);
    if (k->sym) klu_l_free_symbolic(&k->sym, &k->common);
    memcpy(k->rp_old, k->rp, ((size_t)neq + 1) * sizeof *k->rp);
    memcpy(k->ci_old, k->ci, (size_t)nnz * sizeof *k->ci);
    k->nnz_old = nnz;
    k->sym = klu_l_analyze(neq, k->rp, k->ci, &k->common);
    k->analyses++;
    if (!k->sym) return RS_ERR_SOLVER;
  }
  /* Same pattern: refactor with the pivot order of the last factorisation; a new
   * factorisation (partial pivoting) if that meets a zero pivot or a pivot so small
   * (diagonal of U, relative) that the preconditioner would be poor. Rows change
   * between band rows and unit rows with the contact regimes, so the old order is
   * not always good. */
  if (same && k->num && klu_l_refactor(k->rp, k->ci, k->vx, k->sym, k->num, &k->common) &&
      k->common.status == KLU_OK && klu_l_rcond(k->sym, k->num, &k->common) &&
      k->common.rcond > 1e-8)
    return RS_OK;
  if (k->num) klu_l_free_numeric(&k->num, &k->common);
  k->num = klu_l_factor(k->rp, k->ci, k->vx, k->sym, &k->common);
  if (!k->num || k->common.status != KLU_OK) return RS_ERR_SOLVER;
  return RS_OK;
}

int rs_krylov_times(rs_krylov *k, const rs_csr *full, const double *v, double *Jv) {
  const rs_model *m = k->m;
  const int n = m->n, neq = m->neq;
  for (int i = 0; i < neq; i++)
    k->vp[i] = k->cj * v[i];
  int status = rs_model_eval(&k->lin, &k->wlin, k->t, v, k->vp, k->cj, NULL, NULL);
  if (status != RS_OK) return status;
  for (int i = 0; i < neq; i++) {
    if (i < n && k->dense[i]) {
      Jv[i] = k->r * k->wlin.vslip[i];
    } else {
      double sum = 0.0;
      for (int64_t q = full->rowptr[i]; q < full->rowptr[i + 1]; q++)
        sum += full->val[q] * v[full->col[q]];
      Jv[i] = sum;
    }
  }
  k->products++;
  return RS_OK;
}

int rs_krylov_psolve(rs_krylov *k, double *v) {
  if (!k->num) return RS_ERR_SOLVER;
  /* KLU holds the transpose (CSR read as CSC): tsolve applies the inverse of P. */
  return klu_l_tsolve(k->sym, k->num, k->m->neq, 1, v, &k->common) ? RS_OK : RS_ERR_SOLVER;
}
