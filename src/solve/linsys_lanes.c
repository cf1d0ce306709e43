/* Lines of the 3D near field factored and solved side by side (see linsys_lanes.h). */
#include "solve/linsys_lanes.h"

#include <klu.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/status.h"

/* The vector operations in 256-bit registers where the processor has them (one function
 * of each kind, chosen when the program is loaded). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RS_LANES_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RS_LANES_CLONES
#endif

/* count vectors, zeroed, aligned to their size (calloc aligns to 16 bytes only). */
static rs_lane_vec *lane_alloc(int64_t count)
{
  const size_t bytes = (size_t)(count > 0 ? count : 1) * sizeof(rs_lane_vec);
  rs_lane_vec *v = aligned_alloc(sizeof(rs_lane_vec), bytes);
  if (v) memset(v, 0, bytes);
  return v;
}

static rs_lane_vecf *lane_alloc_f(int64_t count)
{
  const size_t bytes = (size_t)(count > 0 ? count : 1) * sizeof(rs_lane_vecf);
  rs_lane_vecf *v = aligned_alloc(sizeof(rs_lane_vecf), bytes);
  if (v) memset(v, 0, bytes);
  return v;
}

static int cmp_int(const void *a, const void *b)
{
  const int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

/* The union of the lines' patterns, as CSC (rows ascending in each column). */
static int union_pattern(rs_lanes *s, const rs_lane_line *lines)
{
  const int n = s->n;
  int *mark = malloc((size_t)n * sizeof *mark);
  int64_t cap = 0, nnz = 0, *urp = malloc(((size_t)n + 1) * sizeof *urp);
  int *ucol = NULL;
  int status = mark && urp ? RS_OK : RS_ERR_INTERNAL;
  for (int c = 0; status == RS_OK && c < n; c++) mark[c] = -1;
  if (status == RS_OK) urp[0] = 0;
  for (int r = 0; status == RS_OK && r < n; r++) {
    const int64_t start = nnz;
    for (int q = 0; q < s->nlines && status == RS_OK; q++)
      for (int64_t e = lines[q].rowptr[r]; e < lines[q].rowptr[r + 1]; e++) {
        const int c = (int)lines[q].col[e];
        if (mark[c] == r) continue;
        mark[c] = r;
        if (nnz == cap) {
          cap = cap ? 2 * cap : 16 * (int64_t)n;
          int *grown = realloc(ucol, (size_t)cap * sizeof *ucol);
          if (!grown) {
            status = RS_ERR_INTERNAL;
            break;
          }
          ucol = grown;
        }
        ucol[nnz++] = c;
      }
    if (status != RS_OK) break;
    qsort(ucol + start, (size_t)(nnz - start), sizeof *ucol, cmp_int);
    urp[r + 1] = nnz;
  }
  if (status == RS_OK) {
    s->ap = calloc((size_t)n + 2, sizeof *s->ap);
    s->ai = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof *s->ai);
    if (!s->ap || !s->ai) status = RS_ERR_INTERNAL;
  }
  if (status == RS_OK) { /* transpose: the rows of each column come out ascending */
    for (int64_t e = 0; e < nnz; e++) s->ap[ucol[e] + 2]++;
    for (int c = 0; c < n; c++) s->ap[c + 2] += s->ap[c + 1];
    for (int r = 0; r < n; r++)
      for (int64_t e = urp[r]; e < urp[r + 1]; e++) s->ai[s->ap[ucol[e] + 1]++] = r;
  }
  free(mark);
  free(urp);
  free(ucol);
  return status;
}

/* The CSC position of (r, c) in the common pattern (present by construction). */
static int position(const rs_lanes *s, int64_t r, int64_t c)
{
  int64_t lo = s->ap[c], hi = s->ap[c + 1] - 1;
  while (lo < hi) {
    const int64_t mid = (lo + hi) / 2;
    if (s->ai[mid] < r)
      lo = mid + 1;
    else
      hi = mid;
  }
  return (int)lo;
}

/* KLU's ordering and pivot order for the common pattern with line rep's values, and the
 * patterns of L and U without their diagonals (U's rows ascending in each column: a
 * left-looking refactorisation takes them in that order). */
static int pivot_order(rs_lanes *s, const double *rep_values, int rep)
{
  const int n = s->n;
  const int64_t nnz = s->ap[n];
  klu_l_common common;
  if (!klu_l_defaults(&common)) return RS_ERR_INTERNAL;
  common.scale = -1;
  common.btf = 0;
  double *ax = calloc((size_t)(nnz > 0 ? nnz : 1), sizeof *ax);
  if (!ax) return RS_ERR_INTERNAL;
  const int *map = s->amap[rep];
  for (int64_t e = 0; e < (int64_t)s->amap_len[rep]; e++) ax[map[e]] = rep_values[e];
  klu_l_symbolic *sym = klu_l_analyze(n, s->ap, s->ai, &common);
  klu_l_numeric *num = sym ? klu_l_factor(s->ap, s->ai, ax, sym, &common) : NULL;
  int status = num && common.status == KLU_OK ? RS_OK : RS_ERR_SOLVER;
  int64_t *ia = NULL;
  double *xa = NULL;
  if (status == RS_OK) {
    const int64_t lnz = num->lnz, unz = num->unz;
    ia = malloc((size_t)(2 * (n + 1) + lnz + unz + 2 * n + 2) * sizeof *ia);
    xa = malloc((size_t)(lnz + unz) * sizeof *xa);
    s->lp = malloc(((size_t)n + 1) * sizeof *s->lp);
    s->up = malloc(((size_t)n + 1) * sizeof *s->up);
    s->li = malloc((size_t)(lnz > 0 ? lnz : 1) * sizeof *s->li);
    s->ui = malloc((size_t)(unz > 0 ? unz : 1) * sizeof *s->ui);
    s->q = malloc((size_t)n * sizeof *s->q);
    s->pinv = malloc((size_t)n * sizeof *s->pinv);
    s->prow = malloc((size_t)n * sizeof *s->prow);
    if (!ia || !xa || !s->lp || !s->up || !s->li || !s->ui || !s->q || !s->pinv || !s->prow)
      status = RS_ERR_INTERNAL;
    int64_t *Lp = ia, *Up = Lp + n + 1, *Li = Up + n + 1, *Ui = Li + lnz, *P = Ui + unz, *Q = P + n;
    double *Lx = xa, *Ux = Lx + lnz;
    if (status == RS_OK && !klu_l_extract(num, sym, Lp, Li, Lx, Up, Ui, Ux, NULL, NULL, NULL, P, Q,
                                          NULL, NULL, &common))
      status = RS_ERR_SOLVER;
    int nl = 0, nu = 0;
    for (int k = 0; status == RS_OK && k < n; k++) {
      s->lp[k] = nl;
      for (int64_t e = Lp[k]; e < Lp[k + 1]; e++)
        if (Li[e] != k) s->li[nl++] = (int)Li[e];
      s->up[k] = nu;
      for (int64_t e = Up[k]; e < Up[k + 1]; e++)
        if (Ui[e] != k) s->ui[nu++] = (int)Ui[e];
      qsort(s->ui + s->up[k], (size_t)(nu - s->up[k]), sizeof *s->ui, cmp_int);
      s->q[k] = (int)Q[k];
      s->prow[k] = (int)P[k];
      s->pinv[P[k]] = k;
    }
    if (status == RS_OK) {
      s->lp[n] = nl;
      s->up[n] = nu;
    }
  }
  free(ia);
  free(xa);
  free(ax);
  if (num) klu_l_free_numeric(&num, &common);
  if (sym) klu_l_free_symbolic(&sym, &common);
  return status;
}

/* A triangle's pattern (cp, ci: by columns) by rows: rp, rc, and perm[e], the row-ordered
 * position of column-ordered entry e; each row's columns ascending, or descending. */
static int by_rows(int n, const int *cp, const int *ci, int ascending, int **rp, int **rc,
                   int **perm)
{
  const int nz = cp[n];
  *rp = calloc((size_t)n + 1, sizeof **rp);
  *rc = malloc((size_t)(nz > 0 ? nz : 1) * sizeof **rc);
  *perm = malloc((size_t)(nz > 0 ? nz : 1) * sizeof **perm);
  int *next = malloc(((size_t)n + 1) * sizeof *next);
  const int ok = *rp && *rc && *perm && next;
  if (ok) {
    for (int e = 0; e < nz; e++) (*rp)[ci[e] + 1]++;
    for (int r = 0; r < n; r++) (*rp)[r + 1] += (*rp)[r];
    for (int r = 0; r < n; r++) next[r] = (*rp)[r];
    for (int j = 0; j < n; j++) { /* columns in the row order wanted */
      const int k = ascending ? j : n - 1 - j;
      for (int e = cp[k]; e < cp[k + 1]; e++) {
        const int pos = next[ci[e]]++;
        (*rc)[pos] = k;
        (*perm)[e] = pos;
      }
    }
  }
  free(next);
  return ok ? RS_OK : RS_ERR_INTERNAL;
}

int rs_lanes_create(rs_lanes *s, int n, int nlines, const rs_lane_line *lines,
                    const double *const *values, int rep, const int *order, int norder,
                    const unsigned char *first_of_group)
{
  memset(s, 0, sizeof *s);
  s->n = n;
  s->nlines = nlines;
  int status = union_pattern(s, lines);
  if (status == RS_OK) {
    s->amap = calloc((size_t)nlines, sizeof *s->amap);
    s->amap_len = calloc((size_t)nlines, sizeof *s->amap_len);
    s->lines = malloc((size_t)nlines * sizeof *s->lines);
    if (!s->amap || !s->amap_len || !s->lines)
      status = RS_ERR_INTERNAL;
    else
      memcpy(s->lines, lines, (size_t)nlines * sizeof *lines);
  }
  for (int q = 0; status == RS_OK && q < nlines; q++) {
    const int64_t nz = lines[q].rowptr[n];
    s->amap_len[q] = nz;
    s->amap[q] = malloc((size_t)(nz > 0 ? nz : 1) * sizeof **s->amap);
    if (!s->amap[q]) {
      status = RS_ERR_INTERNAL;
      break;
    }
    for (int r = 0; r < n; r++)
      for (int64_t e = lines[q].rowptr[r]; e < lines[q].rowptr[r + 1]; e++)
        s->amap[q][e] = position(s, r, lines[q].col[e]);
  }
  if (status == RS_OK) status = pivot_order(s, values[rep], rep);
  if (status == RS_OK) status = by_rows(n, s->lp, s->li, 1, &s->lrp, &s->lrc, &s->lperm);
  if (status == RS_OK) status = by_rows(n, s->up, s->ui, 0, &s->urp, &s->urc, &s->uperm);
  /* the groups */
  if (status == RS_OK) {
    s->group = calloc((size_t)(norder > 0 ? norder : 1), sizeof *s->group);
    if (!s->group) status = RS_ERR_INTERNAL;
  }
  const int64_t nnz = status == RS_OK ? s->ap[n] : 0;
  for (int i = 0; status == RS_OK && i < norder; i++) {
    rs_lane_group *g = s->ngroups > 0 ? &s->group[s->ngroups - 1] : NULL;
    int lane = 0;
    if (g && !first_of_group[i])
      while (lane < RS_LANES && g->line[lane] >= 0) lane++;
    if (!g || first_of_group[i] || lane == RS_LANES) {
      g = &s->group[s->ngroups++];
      for (int l = 0; l < RS_LANES; l++) g->line[l] = -1;
      g->ax = lane_alloc(nnz);
      g->lx = lane_alloc(s->lp[n]);
      g->lr = lane_alloc_f(s->lp[n]);
      g->ux = lane_alloc_f(s->up[n]);
      g->ud = lane_alloc(n);
      g->w = lane_alloc(n);
      g->gin = malloc((size_t)n * RS_LANES * sizeof *g->gin);
      g->gout = malloc((size_t)n * RS_LANES * sizeof *g->gout);
      if (!g->ax || !g->lx || !g->lr || !g->ux || !g->ud || !g->w || !g->gin || !g->gout) {
        status = RS_ERR_INTERNAL;
        break;
      }
      lane = 0;
    }
    const int q = order[i];
    g->line[lane] = q;
    for (int k = 0; k < n; k++) {
      g->gin[k * RS_LANES + lane] = (int)lines[q].idx[s->prow[k]];
      g->gout[k * RS_LANES + lane] = (int)lines[q].idx[s->q[k]];
    }
  }
  for (int j = 0; status == RS_OK && j < s->ngroups; j++) { /* unused lanes read lane 0's */
    rs_lane_group *g = &s->group[j];
    for (int l = 1; l < RS_LANES; l++)
      if (g->line[l] < 0)
        for (int k = 0; k < n; k++) g->gin[k * RS_LANES + l] = g->gin[k * RS_LANES];
  }
  if (status != RS_OK) rs_lanes_free(s);
  return status;
}

void rs_lanes_free(rs_lanes *s)
{
  for (int j = 0; s->group && j < s->ngroups; j++) {
    rs_lane_group *g = &s->group[j];
    free(g->ax);
    free(g->lx);
    free(g->lr);
    free(g->ux);
    free(g->ud);
    free(g->w);
    free(g->gin);
    free(g->gout);
  }
  free(s->group);
  for (int q = 0; s->amap && q < s->nlines; q++) free(s->amap[q]);
  free(s->amap);
  free(s->amap_len);
  free(s->lines);
  free(s->ap);
  free(s->ai);
  free(s->q);
  free(s->pinv);
  free(s->prow);
  free(s->lp);
  free(s->li);
  free(s->up);
  free(s->ui);
  free(s->lrp);
  free(s->lrc);
  free(s->lperm);
  free(s->urp);
  free(s->urc);
  free(s->uperm);
  memset(s, 0, sizeof *s);
}

/* Group gi's lanes: the values of its refreshed lines scattered onto the common pattern,
 * read from the rows of the matrix they come from (gval, grp: no copy of each line's values
 * first). */
static void scatter_values(rs_lanes *s, rs_lane_group *g, const double *gval, const int64_t *grp,
                           const unsigned char *refresh)
{
  const int64_t nnz = s->ap[s->n];
  for (int l = 0; l < RS_LANES; l++) {
    const int q = g->line[l];
    if (q < 0 || !refresh[q]) continue;
    const int *map = s->amap[q];
    const int64_t *rp = s->lines[q].rowptr, *idx = s->lines[q].idx;
    for (int i = 0; i < s->n; i++) {
      const double *v = gval + grp[idx[i]] - rp[i];
      for (int64_t e = rp[i]; e < rp[i + 1]; e++) g->ax[map[e]][l] = v[e];
    }
  }
  /* unused lanes: lane 0's matrix (when it changed), never written back */
  for (int l = 1; l < RS_LANES && refresh[g->line[0]]; l++)
    if (g->line[l] < 0)
      for (int64_t e = 0; e < nnz; e++) g->ax[e][l] = g->ax[e][0];
}

/* Left-looking LU of m groups side by side on the fixed pattern (column k of P A Q): the
 * groups' updates are independent, so the processor overlaps them (one group's chain of
 * updates through its work column bound its refactorisation); each lane's operations are
 * those of a group alone. */
static inline __attribute__((always_inline)) void refactor_groups(rs_lanes *s, const int *gi, int m)
{
  const int n = s->n;
  rs_lane_vecf *lr[RS_LANES_BATCH], *ux[RS_LANES_BATCH];
  rs_lane_vec *W[RS_LANES_BATCH], *lx[RS_LANES_BATCH], *ud[RS_LANES_BATCH];
  const rs_lane_vec *ax[RS_LANES_BATCH];
  for (int j = 0; j < m; j++) {
    rs_lane_group *g = &s->group[gi[j]];
    W[j] = g->w;
    lx[j] = g->lx;
    lr[j] = g->lr;
    ux[j] = g->ux;
    ud[j] = g->ud;
    ax[j] = g->ax;
  }
  const int *lp = s->lp, *li = s->li, *up = s->up, *ui = s->ui;
  const int *lperm = s->lperm, *uperm = s->uperm;
  double umin[RS_LANES_BATCH][RS_LANES], umax[RS_LANES_BATCH][RS_LANES];
  for (int j = 0; j < m; j++)
    for (int l = 0; l < RS_LANES; l++) {
      umin[j][l] = INFINITY;
      umax[j][l] = 0.0;
    }
  const rs_lane_vec zero = {0.0};
  for (int k = 0; k < n; k++) {
    for (int e = up[k]; e < up[k + 1]; e++)
      for (int j = 0; j < m; j++) W[j][ui[e]] = zero;
    for (int j = 0; j < m; j++) W[j][k] = zero;
    for (int e = lp[k]; e < lp[k + 1]; e++)
      for (int j = 0; j < m; j++) W[j][li[e]] = zero;
    const int c = s->q[k];
    for (int64_t e = s->ap[c]; e < s->ap[c + 1]; e++) {
      const int r = s->pinv[s->ai[e]];
      for (int j = 0; j < m; j++) W[j][r] = ax[j][e];
    }
    for (int e = up[k]; e < up[k + 1]; e++) {
      const int r = ui[e], pos = uperm[e];
      rs_lane_vec ujk[RS_LANES_BATCH];
      for (int j = 0; j < m; j++) {
        ujk[j] = W[j][r];
        ux[j][pos] = __builtin_convertvector(ujk[j], rs_lane_vecf);
      }
      for (int f = lp[r]; f < lp[r + 1]; f++) {
        const int i = li[f];
        for (int j = 0; j < m; j++) W[j][i] -= lx[j][f] * ujk[j];
      }
    }
    for (int j = 0; j < m; j++) {
      const rs_lane_vec ukk = W[j][k], inv = 1.0 / ukk;
      ud[j][k] = inv;
      for (int e = lp[k]; e < lp[k + 1]; e++) {
        const rs_lane_vec lik = W[j][li[e]] * inv;
        lx[j][e] = lik;
        lr[j][lperm[e]] = __builtin_convertvector(lik, rs_lane_vecf);
      }
      for (int l = 0; l < RS_LANES; l++) {
        const double a = fabs(ukk[l]);
        umin[j][l] = a < umin[j][l] || a != a ? a : umin[j][l];
        umax[j][l] = a > umax[j][l] ? a : umax[j][l];
      }
    }
  }
  for (int j = 0; j < m; j++) {
    rs_lane_group *g = &s->group[gi[j]];
    for (int l = 0; l < RS_LANES; l++)
      g->ok[l] = g->line[l] >= 0 && umin[j][l] > 1e-8 * umax[j][l] && isfinite(umax[j][l]);
  }
}

RS_LANES_CLONES void rs_lanes_refactor(rs_lanes *s, const int *groups, int m, const double *gval,
                                       const int64_t *grp, const unsigned char *refresh)
{
  for (int j = 0; j < m; j++) scatter_values(s, &s->group[groups[j]], gval, grp, refresh);
  switch (m) { /* m a constant in each: the loops over the groups unrolled */
  case 4: refactor_groups(s, groups, 4); break;
  case 3: refactor_groups(s, groups, 3); break;
  case 2: refactor_groups(s, groups, 2); break;
  default: refactor_groups(s, groups, 1); break;
  }
}

/* The solves of m groups (m <= RS_LANES_BATCH) side by side. By rows: each unknown's updates
 * in the order a solve by columns makes them (the same results bit for bit), summed in a
 * register instead of read and written back to memory once per column; the groups' sums are
 * independent chains, which the processor overlaps (one group's chain of subtractions bound
 * its solve). The factors are read in single precision, the sums kept in double: on fine
 * grids the factors of all lines no longer fit the second-level cache and each solve streams
 * them (at 128 x 128 cells 32 groups of about 10,000 entries); half the bytes streamed
 * make the solves a sixth faster, and GMRES corrects the rounding (the same Newton and GMRES
 * counts). */
static inline __attribute__((always_inline)) void solve_groups(const rs_lanes *s, const int *gi,
                                                               int m, double *v)
{
  const int n = s->n;
  rs_lane_vec *X[RS_LANES_BATCH];
  const rs_lane_vecf *lr[RS_LANES_BATCH], *ux[RS_LANES_BATCH];
  const rs_lane_vec *ud[RS_LANES_BATCH];
  const int *lrp = s->lrp, *lrc = s->lrc, *urp = s->urp, *urc = s->urc;
  for (int j = 0; j < m; j++) {
    const rs_lane_group *g = &s->group[gi[j]];
    X[j] = g->w;
    lr[j] = g->lr;
    ux[j] = g->ux;
    ud[j] = g->ud;
    for (int k = 0; k < n; k++)
      for (int l = 0; l < RS_LANES; l++) X[j][k][l] = v[g->gin[k * RS_LANES + l]];
  }
  for (int k = 0; k < n; k++) { /* L: unit lower triangular */
    rs_lane_vec x[RS_LANES_BATCH];
    for (int j = 0; j < m; j++) x[j] = X[j][k];
    for (int e = lrp[k]; e < lrp[k + 1]; e++) {
      const int c = lrc[e];
      for (int j = 0; j < m; j++) x[j] -= __builtin_convertvector(lr[j][e], rs_lane_vec) * X[j][c];
    }
    for (int j = 0; j < m; j++) X[j][k] = x[j];
  }
  for (int k = n - 1; k >= 0; k--) { /* U */
    rs_lane_vec x[RS_LANES_BATCH];
    for (int j = 0; j < m; j++) x[j] = X[j][k];
    for (int e = urp[k]; e < urp[k + 1]; e++) {
      const int c = urc[e];
      for (int j = 0; j < m; j++) x[j] -= __builtin_convertvector(ux[j][e], rs_lane_vec) * X[j][c];
    }
    for (int j = 0; j < m; j++) X[j][k] = x[j] * ud[j][k];
  }
  for (int j = 0; j < m; j++) {
    const rs_lane_group *g = &s->group[gi[j]];
    for (int l = 0; l < RS_LANES; l++)
      if (g->ok[l])
        for (int k = 0; k < n; k++) v[g->gout[k * RS_LANES + l]] = X[j][k][l];
  }
}

RS_LANES_CLONES void rs_lanes_solve(const rs_lanes *s, const int *groups, int m, double *v)
{
  switch (m) { /* m a constant in each: the loops over the groups unrolled */
  case 4: solve_groups(s, groups, 4, v); break;
  case 3: solve_groups(s, groups, 3, v); break;
  case 2: solve_groups(s, groups, 2, v); break;
  default: solve_groups(s, groups, 1, v); break;
  }
}
