/* The generalized Jacobian of the model (physics/model.h): each row is the contact law's
 * local row (physics/contact_law.h) chained with the derivatives of the local variables:
 *   p_c(I)         -> 1 on p_c(I)
 *   v_s,c(I)       -> cj A_cb(I-J) - a (A_cb(up-J) - A_cb(I-J)) on p_b(J) (+ the layer
 *                     (cj + a) c3 on p_c(I), -a c3 on p_c(up)), cj + a on u_pl,c(I),
 *                     -a on u_pl,c(up), V on the creepage (force control)
 *   Du_pl,c/Dt(I)  -> cj + a on u_pl,c(I), -a on u_pl,c(up)
 *   Dustar/Dt(I)   -> cj + a on u*(I), -a on u*(up)
 *   u*(I)          -> 1 on u*(I)
 *   Dmu/Dt(I)      -> cj + a on mu(I), -a on mu(up)            (friction memory)
 *   mu(I)          -> 1 on mu(I)
 * with a = V/dx and up the upstream neighbour (docs/model.md §5). The same chain gives exact
 * J v products: the local rows applied to the kinematics of v. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "physics/model_internal.h"

/* Append an entry to the current row of a CSR matrix. */
static void csr_put(rs_csr *J, int64_t col, double val)
{
  const int64_t k = J->rowptr[J->nrows + 1]++; /* rowptr[nrows + 1]: end of the open row */
  J->col[k] = col;
  J->val[k] = val;
}

static void csr_next_row(rs_csr *J)
{
  J->nrows++;
  if (J->nrows < J->cap_rows) J->rowptr[J->nrows + 1] = J->rowptr[J->nrows];
}

int64_t rs_model_jac_capacity(const rs_model *m, int band, int band_y)
{
  const rs_layout *L = &m->lay;
  const int64_t n = L->n, nc = L->ncomp;
  int64_t near = nc * n;
  if (band > 0) {
    const int64_t bx = 2 * (int64_t)band + 1 < m->grid.nx ? 2 * (int64_t)band + 1 : m->grid.nx;
    const int64_t by = 2 * (int64_t)band_y + 1 < m->grid.ny ? 2 * (int64_t)band_y + 1 : m->grid.ny;
    near = nc * bx * by;
  }
  /* traction rows: near field, own plastic displacements, extras; plasticity rows: at
   * most the traction, u* and two plastic displacements; u* rows: four entries; force
   * rows: every traction and the extras */
  int64_t cap = nc * n * (near + 2 * nc + L->nextra) + nc * n * (2 + 2 * nc) + n * (2 * nc + 2) +
                L->nextra * (nc * n + L->nextra);
  /* 3D near field: every row on the fixed pattern of put_row (up to the traction, both
   * plastic displacements, u* and mu at the cell and upstream, the extras) */
  if (band > 0 && m->el.dim == 3) cap += L->ncell * n * (3 * nc + 4 + L->nextra);
  /* friction memory: mu(I) in each traction row; memory rows as traction rows plus mu(I),
   * mu(up) */
  if (L->memory) cap += nc * n + n * (near + 2 * nc + L->nextra + 2);
  return cap;
}

/* The sparse columns of a local row (everything but the tractions), in column order:
 * u_pl,c(I), u_pl,c(up) per component, u*(I), u*(up), the extras. */
typedef struct sparse_cols {
  double upl[RS_MAX_COMP][2], us[2], mu[2], extra[RS_MAX_COMP];
  unsigned char has_upl[RS_MAX_COMP][2], has_us[2], has_mu[2], has_extra[RS_MAX_COMP];
} sparse_cols;

static void add(double *v, unsigned char *has, double x)
{
  *v = *has ? *v + x : x;
  *has = 1;
}

/* r dv_s,c/dp_b at the offset (kx, ky) from the cell, without the layer: the kinematics'
 * cj A_cb(kx, ky) - a (A_cb(kx + 1, ky) - A_cb(kx, ky)), a = V/dx (docs/model.md §5). */
static double kin_coef(const rs_model *m, int c, int b, int kx, int ky, double cj, double a)
{
  const double A0 = rs_elastic_op_coef(&m->el, c, b, kx, ky);
  return cj * A0 - a * (rs_elastic_op_coef(&m->el, c, b, kx + 1, ky) - A0);
}

/* The 3D near field along x (band_y = 0, two components) as a table of kin_coef(c, b, kx, 0)
 * (+ the layer on the cell and its upstream neighbour), t[2 c + b][band + kx]: the same sums
 * as the loop of put_traction_columns, once per assembly instead of once per row. */
typedef struct line_table {
  int on;
  double t[4][2 * RS_YLINK_MAX_BAND + 1];
} line_table;

static void line_table_make(const rs_model *m, double cj, double a, int band, int band_y,
                            line_table *tab)
{
  tab->on =
      m->el.dim == 3 && m->lay.ncomp == 2 && band > 0 && band_y == 0 && band <= RS_YLINK_MAX_BAND;
  if (!tab->on) return;
  const double c3 = m->layer_flex;
  for (int c = 0; c < 2; c++)
    for (int b = 0; b < 2; b++)
      for (int kx = -band; kx <= band; kx++) {
        double d = kin_coef(m, c, b, kx, 0, cj, a);
        if (b == c && kx == 0) d += (cj + a) * c3;
        if (b == c && kx == -1) d -= a * c3; /* the upstream neighbour I + 1 */
        tab->t[2 * c + b][band + kx] = d;
      }
}

/* Traction row of cell I, local row lr: its entries in the columns of the tractions. */
static void put_traction_columns(const rs_model *m, const rs_law_out *o, int lr, int I, double cj,
                                 double a, int band, int band_y, int keep_own,
                                 const line_table *tab, rs_csr *J)
{
  const rs_layout *L = &m->lay;
  const int nc = L->ncomp, nx = m->grid.nx;
  int any_vs = 0;
  for (int c = 0; c < nc; c++) any_vs |= o->present[lr][rs_law_var_vs(nc, c)];
  const int ix = I % nx, iy = I / nx, up = rs_grid_upstream(&m->grid, I);
  const double c3 = m->layer_flex;
  for (int b = 0; b < nc; b++) {
    const int has_p = o->present[lr][rs_law_var_p(b)];
    const double cp = has_p ? o->jac[lr][rs_law_var_p(b)] : 0.0;
    if (!any_vs && band == 0) { /* sparse: the traction of the cell itself */
      if (has_p || keep_own) csr_put(J, rs_at_p(L, b, I), has_p ? cp : 0.0);
      continue;
    }
    const int jx0 = band > 0 && ix > band ? ix - band : 0;
    const int jx1 = band > 0 && ix + band < nx ? ix + band + 1 : nx;
    const int jy0 = band > 0 && iy > band_y ? iy - band_y : 0;
    const int jy1 = band > 0 && iy + band_y < m->grid.ny ? iy + band_y + 1 : m->grid.ny;
    if (nc == 1 && m->el.dim == 2) { /* the line kernel: the hot loop of 2D assemblies */
      const double *restrict coef = m->el.line.tang + m->el.line.n; /* coef[k] = A(k) */
      const int64_t k0 = J->rowptr[J->nrows + 1];
      int64_t *restrict col = J->col + k0 - jx0;
      double *restrict val = J->val + k0 - jx0;
      if (any_vs) {
        const double cvs = o->jac[lr][rs_law_var_vs(1, 0)];
        for (int j = jx0; j < jx1; j++) {
          col[j] = j;
          val[j] = cvs * (cj * coef[ix - j] - a * (coef[ix + 1 - j] - coef[ix - j]));
        }
        /* the layer on the diagonal and at the upstream neighbour, as the same sums */
        double d = cj * coef[0] - a * (coef[1] - coef[0]) + (cj + a) * c3;
        if (ix >= jx0 && ix < jx1) val[ix] = cvs * d;
        if (up >= jx0 && up < jx1) {
          d = cj * coef[ix - up] - a * (coef[ix + 1 - up] - coef[ix - up]);
          val[up] = cvs * (d - a * c3);
        }
      } else {
        for (int j = jx0; j < jx1; j++) {
          col[j] = j;
          val[j] = 0.0;
        }
      }
      if (has_p && ix >= jx0 && ix < jx1) val[ix] += cp;
      J->rowptr[J->nrows + 1] = k0 + (jx1 - jx0);
      continue;
    }
    if (tab->on && band > 0) { /* 3D along x: the table */
      const int v0 = rs_law_var_vs(2, 0), v1 = rs_law_var_vs(2, 1);
      const double j0 = o->present[lr][v0] ? o->jac[lr][v0] : 0.0;
      const double j1 = o->present[lr][v1] ? o->jac[lr][v1] : 0.0;
      const int p0 = o->present[lr][v0], p1 = o->present[lr][v1];
      const double *t0 = tab->t[b] + band + ix, *t1 = tab->t[2 + b] + band + ix;
      const int64_t k0 = J->rowptr[J->nrows + 1], c0 = rs_at_p(L, b, iy * nx);
      for (int jx = jx0; jx < jx1; jx++) {
        double v = 0.0; /* the sum of the loop below, term for term */
        if (p0) v += j0 * t0[-jx];
        if (p1) v += j1 * t1[-jx];
        if (has_p && jx == ix) v += cp;
        J->col[k0 + jx - jx0] = c0 + jx;
        J->val[k0 + jx - jx0] = v;
      }
      J->rowptr[J->nrows + 1] = k0 + (jx1 - jx0);
      continue;
    }
    for (int jy = jy0; jy < jy1; jy++)
      for (int jx = jx0; jx < jx1; jx++) {
        const int Jc = jy * nx + jx, kx = ix - jx, ky = iy - jy;
        double v = 0.0;
        for (int c = 0; c < nc && any_vs; c++) {
          if (!o->present[lr][rs_law_var_vs(nc, c)]) continue;
          /* r dv_s/dp_j = r [cj A(i-j) - a (A(i+1-j) - A(i-j))] (+ layer on the diagonal) */
          double d = kin_coef(m, c, b, kx, ky, cj, a);
          if (b == c && Jc == I) d += (cj + a) * c3;
          if (b == c && Jc == up) d -= a * c3;
          v += o->jac[lr][rs_law_var_vs(nc, c)] * d;
        }
        if (has_p && Jc == I) v += cp;
        csr_put(J, rs_at_p(L, b, Jc), v);
      }
  }
}

/* 3D near field (band > 0, the preconditioner): a yielding cell's flow block in its yield
 * rows, -(tau_c/|z|) r_yield (I - z z^T/|z|^2) (the disk projection's derivative), is
 * singular along the flow; there the rows pivot on u* instead of u_pl, and KLU's
 * refactorisation, which keeps the pivot order of the last factorisation, met zero or tiny
 * pivots whenever cells began or stopped yielding. NEAR_YIELD_SHIFT times the block's trace
 * on its diagonal keeps every pivot order valid. The exact Jacobian (band 0) and 2D are
 * untouched. 1e-2 leaves GMRES's iterations as they were and avoids almost every full
 * factorisation; a smaller shift does not, a larger one costs GMRES iterations. */
#define NEAR_YIELD_SHIFT 1e-2

/* One residual row of cell I (local row lr), all columns, sorted. */
static void put_row(const rs_model *m, const rs_law_out *o, int lr, int I, const rs_inputs *in,
                    double cj, int band, int band_y, int traction_row, const line_table *tab,
                    rs_csr *J)
{
  const rs_layout *L = &m->lay;
  const int nc = L->ncomp;
  const double a = in->velocity / m->grid.dx, V = in->velocity;
  /* Near field: a traction row keeps its own plastic displacements (and the extras),
   * zeros included, so that the pattern does not depend on the branches. In 3D every row
   * keeps a pattern that does not depend on the branches (the cell's traction, plastic
   * displacements, u* and mu, at the cell and upstream), so that KLU analyses once instead
   * of at most set-ups. */
  /* In 3D steady assemblies (cj = 0) a traction or memory row of a cell outside the
   * contact keeps its own entries only (the traction's 1, the memory's mu): the contact
   * does not change with the branches, and the cell then stays out of the near field's
   * line blocks. The transient keeps the full pattern: its factorisation serves many
   * steps, and with the shorter rows (the same matrix, another block triangular form in
   * KLU) its Newton iterations rose by an eighth. */
  const int out3 =
      traction_row && band > 0 && m->el.dim == 3 && cj == 0.0 && (o->branch & RS_BRANCH_EXTERIOR);
  const int fixed = traction_row && band > 0 && !out3, fixed3 = band > 0 && m->el.dim == 3 && !out3;
  put_traction_columns(m, o, lr, I, cj, a, traction_row && !out3 ? band : 0, band_y, fixed3, tab,
                       J);
  sparse_cols s;
  memset(&s, 0, sizeof s);
  for (int c = 0; c < nc; c++) {
    const int vs = rs_law_var_vs(nc, c), fl = rs_law_var_flow(nc, c);
    if (o->present[lr][vs]) {
      add(&s.upl[c][0], &s.has_upl[c][0], o->jac[lr][vs] * (cj + a));
      add(&s.upl[c][1], &s.has_upl[c][1], o->jac[lr][vs] * -a);
      if (c < L->nextra) add(&s.extra[c], &s.has_extra[c], o->jac[lr][vs] * V);
    }
    if (o->present[lr][fl]) {
      add(&s.upl[c][0], &s.has_upl[c][0], o->jac[lr][fl] * (cj + a));
      add(&s.upl[c][1], &s.has_upl[c][1], o->jac[lr][fl] * -a);
    }
  }
  if (band > 0 && m->el.dim == 3 && !traction_row && (o->branch & RS_BRANCH_YIELD))
    for (int r = 0; r < nc; r++) {
      if (lr != rs_law_row_pl(nc, r)) continue;
      double trace = 0.0; /* of the yield rows' flow block: -(tau_c/|z|) r_yield */
      for (int c = 0; c < nc; c++)
        if (o->present[rs_law_row_pl(nc, c)][rs_law_var_flow(nc, c)])
          trace += o->jac[rs_law_row_pl(nc, c)][rs_law_var_flow(nc, c)];
      add(&s.upl[r][0], &s.has_upl[r][0], NEAR_YIELD_SHIFT * trace * (cj + a));
    }
  const int dus = rs_law_var_dustar(nc), us = rs_law_var_ustar(nc);
  if (o->present[lr][dus]) {
    add(&s.us[0], &s.has_us[0], o->jac[lr][dus] * (cj + a));
    add(&s.us[1], &s.has_us[1], o->jac[lr][dus] * -a);
  }
  if (o->present[lr][us]) add(&s.us[0], &s.has_us[0], o->jac[lr][us]);
  if (L->memory) {
    const int mu = rs_law_var_mu(nc), dmu = rs_law_var_dmu(nc);
    if (o->present[lr][dmu]) {
      add(&s.mu[0], &s.has_mu[0], o->jac[lr][dmu] * (cj + a));
      add(&s.mu[1], &s.has_mu[1], o->jac[lr][dmu] * -a);
    }
    if (o->present[lr][mu]) add(&s.mu[0], &s.has_mu[0], o->jac[lr][mu]);
  }
  const int up = rs_grid_upstream(&m->grid, I), keep = fixed || fixed3;
  for (int c = 0; c < nc; c++) {
    if (s.has_upl[c][0] || keep) csr_put(J, rs_at_upl(L, c, I), s.upl[c][0]);
    if (up >= 0 && (s.has_upl[c][1] || keep)) csr_put(J, rs_at_upl(L, c, up), s.upl[c][1]);
  }
  if (s.has_us[0] || fixed3) csr_put(J, rs_at_ustar(L, I), s.us[0]);
  if (up >= 0 && (s.has_us[1] || fixed3)) csr_put(J, rs_at_ustar(L, up), s.us[1]);
  /* near field with memory: a traction row keeps mu(I) (present at the bound only) */
  if (s.has_mu[0] || (keep && L->memory)) csr_put(J, rs_at_mu(L, I), s.mu[0]);
  if (up >= 0 && (s.has_mu[1] || (fixed3 && L->memory))) csr_put(J, rs_at_mu(L, up), s.mu[1]);
  for (int k = 0; k < L->nextra; k++)
    if (s.has_extra[k] || keep) csr_put(J, rs_at_extra(L, k), s.extra[k]);
  csr_next_row(J);
}

int rs_model_linearise(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                       const double *yp, double cj)
{
  return rs_model_linearise_residual(m, w, in, y, yp, cj, NULL);
}

int rs_model_linearise_residual(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                                const double *yp, double cj, double *F)
{
  return rs_model_evaluate(m, w, in, y, yp, cj, F, 1);
}

int rs_model_jacobian_assemble(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                               int band, int band_y, rs_csr *J)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  /* Rows in the order of the unknowns (physics/layout.h). */
  J->nrows = 0;
  J->cap_rows = L->neq;
  J->rowptr[0] = J->rowptr[1] = 0;
  line_table tab;
  line_table_make(m, cj, in->velocity / m->grid.dx, band, band_y, &tab);
  for (int c = 0; c < nc; c++)
    for (int i = 0; i < n; i++)
      put_row(m, &w->law[i], rs_law_row_f(c), i, in, cj, band, band_y, 1, &tab, J);
  for (int c = 0; c < nc; c++)
    for (int i = 0; i < n; i++)
      put_row(m, &w->law[i], rs_law_row_pl(nc, c), i, in, cj, band, band_y, 0, &tab, J);
  for (int i = 0; i < n; i++)
    put_row(m, &w->law[i], rs_law_row_star(nc), i, in, cj, band, band_y, 0, &tab, J);
  /* Memory rows: in the near field like traction rows (a pattern fixed by the contact) */
  for (int i = 0; i < n && L->memory; i++)
    put_row(m, &w->law[i], rs_law_row_mu(nc), i, in, cj, band, band_y, 1, &tab, J);
  /* Force rows: (dA sum p_k - F_k)/(2a). */
  const double force_row = m->grid.area / m->contact_measure;
  for (int k = 0; k < L->nextra; k++) {
    for (int j = 0; j < n; j++) csr_put(J, rs_at_p(L, k, j), force_row);
    csr_put(J, rs_at_extra(L, k), 0.0); /* structural: the pattern of the bordered system */
    csr_next_row(J);
  }
  return RS_OK;
}

/* The length of one scratch row of rs_model_near_ylink_apply: the line, band zeros each
 * side, and room for the last vector of four cells. */
static int ylink_pad_len(int nx, int band) { return nx + 2 * band + 4; }

int rs_model_near_ylink_prepare(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                                int band, rs_ylink *t)
{
  const rs_layout *L = &m->lay;
  const int nc = L->ncomp, n = L->n, nb = 2 * band + 1;
  const double a = in->velocity / m->grid.dx;
  t->on = nc == 2 && band <= RS_YLINK_MAX_BAND;
  if (!t->on) return RS_OK;
  if (!t->coef || t->ncell != n || t->nx != m->grid.nx || t->band != band) {
    rs_ylink_free(t);
    const size_t len = (size_t)ylink_pad_len(m->grid.nx, band);
    t->coef = malloc((size_t)n * 6 * sizeof *t->coef);
    t->rows = malloc((size_t)n);
    t->pad = calloc(RS_YLINK_SLOTS * 4 * len, sizeof *t->pad);
    t->ncell = n;
    t->nx = m->grid.nx;
    t->band = band;
    if (!t->coef || !t->rows || !t->pad) {
      rs_ylink_free(t);
      return RS_ERR_INTERNAL;
    }
    t->on = 1;
  }
  t->nrow = L->memory ? 3 : 2;
  /* kin_coef at ky = +-1, as put_traction_columns; no layer term there (the layer acts on
   * the cell and its upstream neighbour only) */
  for (int c = 0; c < 2; c++)
    for (int b = 0; b < 2; b++)
      for (int s = 0; s < 2; s++)
        for (int q = 0; q < nb; q++)
          t->st[c][b][s][q] = kin_coef(m, c, b, q - band, s == 0 ? 1 : -1, cj, a);
  for (int I = 0; I < n; I++) {
    const rs_law_out *o = &w->law[I];
    double *cf = t->coef + (size_t)I * 6;
    unsigned char rows = 0;
    /* rows as put_row: a steady assembly keeps the exterior's own entries only */
    const int skip = cj == 0.0 && (o->branch & RS_BRANCH_EXTERIOR);
    for (int k = 0; k < t->nrow; k++) {
      const int lr = k < 2 ? rs_law_row_f(k) : rs_law_row_mu(nc);
      for (int c = 0; c < 2; c++) {
        const int on = !skip && o->present[lr][rs_law_var_vs(nc, c)];
        cf[2 * k + c] = on ? o->jac[lr][rs_law_var_vs(nc, c)] : 0.0;
        if (on) rows |= (unsigned char)(1u << (2 * k + c));
      }
    }
    t->rows[I] = rows;
  }
  return RS_OK;
}

/* r of cell I's rows less its couplings' coefficients times the sums. */
static inline void ylink_cell_apply(const rs_model *m, const rs_ylink *t, int I, double sum0,
                                    double sum1, double *r)
{
  const unsigned rows = t->rows[I];
  if (!rows) return;
  const double *cf = t->coef + (size_t)I * 6, sum[2] = {sum0, sum1};
  for (int k = 0; k < t->nrow; k++) {
    double v = 0.0;
    for (int c = 0; c < 2; c++)
      if (rows & (1u << (2 * k + c))) v += cf[2 * k + c] * sum[c];
    r[k < 2 ? rs_at_p(&m->lay, k, I) : rs_at_mu(&m->lay, I)] -= v;
  }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RS_YLINK_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RS_YLINK_CLONES
#endif

/* Four partial results side by side; loads from any double's address. */
typedef double ylink_v4 __attribute__((vector_size(4 * sizeof(double)), aligned(sizeof(double))));

RS_YLINK_CLONES void rs_model_near_ylink_apply(const rs_model *m, const rs_ylink *t, int slot,
                                               int parity, int iy0, int iy1, const double *x,
                                               double *r)
{
  if (!t->on) return;
  const rs_layout *L = &m->lay;
  const int nx = m->grid.nx, ny = m->grid.ny, band = t->band, len = ylink_pad_len(nx, band);
  /* The neighbouring lines' tractions with zeros beyond the line's ends (the slot's rows,
   * zero from their allocation but where a line is copied): four cells at once, their sums
   * in the lanes of two vectors, each lane's terms in the order of one cell alone (s, b, jx
   * ascending; a term beyond the ends adds a zero product to a sum that is never -0, which
   * leaves it as it is), so bit for bit the same sums. One cell at a time, the chains of
   * additions of each cell's two sums bound this product. */
  double *pad = t->pad + (size_t)slot * 4 * (size_t)len;
  for (int iy = iy0 + ((iy0 & 1) != parity); iy < iy1; iy += 2) {
    int have[2];
    for (int s = 0; s < 2; s++) {
      const int jy = s == 0 ? iy - 1 : iy + 1;
      have[s] = jy >= 0 && jy < ny;
      for (int b = 0; b < 2 && have[s]; b++)
        memcpy(pad + (size_t)(2 * s + b) * (size_t)len + band, x + rs_at_p(L, b, jy * nx),
               (size_t)nx * sizeof *x);
    }
    for (int ix = 0; ix < nx; ix += 4) {
      ylink_v4 s0 = {0.0, 0.0, 0.0, 0.0}, s1 = s0;
      for (int s = 0; s < 2; s++) {
        if (!have[s]) continue;
        for (int b = 0; b < 2; b++) {
          const double *xb = pad + (size_t)(2 * s + b) * (size_t)len + band + ix;
          for (int d = -band; d <= band; d++) { /* jx = ix + d, ascending */
            ylink_v4 xv;
            memcpy(&xv, xb + d, sizeof xv);
            s0 += t->st[0][b][s][band - d] * xv;
            s1 += t->st[1][b][s][band - d] * xv;
          }
        }
      }
      for (int l = 0; l < 4 && ix + l < nx; l++)
        ylink_cell_apply(m, t, iy * nx + ix + l, s0[l], s1[l], r);
    }
  }
}

void rs_ylink_free(rs_ylink *t)
{
  free(t->coef);
  free(t->rows);
  free(t->pad);
  t->coef = NULL;
  t->rows = NULL;
  t->pad = NULL;
  t->ncell = t->nx = t->band = 0;
  t->on = 0;
}

void rs_model_near_ylink(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                         int band, int parity, int iy0, int iy1, const double *x, double *r)
{
  rs_ylink t = {0};
  if (rs_model_near_ylink_prepare(m, w, in, cj, band, &t) == RS_OK)
    rs_model_near_ylink_apply(m, &t, 0, parity, iy0, iy1, x, r);
  rs_ylink_free(&t);
}

/* put_row for row r of a matrix assembled before with the same pattern: the row rewritten
 * in place, the other rows' bounds kept; 0 if its length is not the row's there. */
static int put_row_at(const rs_model *m, const rs_law_out *o, int lr, int I, const rs_inputs *in,
                      double cj, int band, int band_y, int traction_row, const line_table *tab,
                      int64_t r, rs_csr *J)
{
  const int64_t end = J->rowptr[r + 1], next = r + 1 < J->cap_rows ? J->rowptr[r + 2] : 0;
  J->nrows = r;
  J->rowptr[r + 1] = J->rowptr[r];
  put_row(m, o, lr, I, in, cj, band, band_y, traction_row, tab, J);
  const int same = J->rowptr[r + 1] == end;
  J->rowptr[r + 1] = end;
  if (r + 1 < J->cap_rows) J->rowptr[r + 2] = next;
  return same;
}

int rs_model_jacobian_assemble_lines(const rs_model *m, const rs_work *w, const rs_inputs *in,
                                     double cj, int band, int band_y, const unsigned char *lines,
                                     rs_csr *J)
{
  const rs_layout *L = &m->lay;
  const int nc = L->ncomp, nx = m->grid.nx, ny = m->grid.ny;
  if (L->nextra != 0 || J->nrows != L->neq) return RS_ERR_SOLVER;
  line_table tab;
  line_table_make(m, cj, in->velocity / m->grid.dx, band, band_y, &tab);
  int same = 1;
  for (int iy = 0; iy < ny && same; iy++) {
    if (!lines[iy]) continue;
    for (int I = iy * nx; I < (iy + 1) * nx && same; I++) {
      const rs_law_out *o = &w->law[I];
      for (int c = 0; c < nc; c++) {
        same &= put_row_at(m, o, rs_law_row_f(c), I, in, cj, band, band_y, 1, &tab,
                           rs_at_p(L, c, I), J);
        same &= put_row_at(m, o, rs_law_row_pl(nc, c), I, in, cj, band, band_y, 0, &tab,
                           rs_at_upl(L, c, I), J);
      }
      same &= put_row_at(m, o, rs_law_row_star(nc), I, in, cj, band, band_y, 0, &tab,
                         rs_at_ustar(L, I), J);
      if (L->memory)
        same &= put_row_at(m, o, rs_law_row_mu(nc), I, in, cj, band, band_y, 1, &tab,
                           rs_at_mu(L, I), J);
    }
  }
  J->nrows = L->neq;
  return same ? RS_OK : RS_ERR_SOLVER;
}

int rs_model_jacobian(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, int band, int band_y, rs_csr *J)
{
  const int status = rs_model_linearise(m, w, in, y, yp, cj);
  return status != RS_OK ? status : rs_model_jacobian_assemble(m, w, in, cj, band, band_y, J);
}

int rs_model_jv(const rs_model *m, const rs_work *w, rs_work *wlin, const rs_inputs *in, double cj,
                const double *v, double *Jv)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nc = L->ncomp;
  /* Kinematics of v: the linear part (no rigid slip, no inflow), with v' = cj v. */
  rs_inputs lin = *in;
  lin.linear = 1;
  for (int k = 0; k < L->neq; k++) Jv[k] = cj * v[k]; /* Jv holds v' until the rows are set */
  rs_model_kinematics_scaled(m, wlin, &lin, v, Jv, cj);
  for (int i = 0; i < n; i++) {
    double d[RS_LAW_NVAR];
    for (int c = 0; c < nc; c++) {
      d[rs_law_var_p(c)] = v[rs_at_p(L, c, i)];
      d[rs_law_var_vs(nc, c)] = wlin->vslip[c * n + i];
      d[rs_law_var_flow(nc, c)] = wlin->dupl[c * n + i];
    }
    d[rs_law_var_dustar(nc)] = wlin->dustar[i];
    d[rs_law_var_ustar(nc)] = v[rs_at_ustar(L, i)];
    const int mem = L->memory;
    if (mem) {
      d[rs_law_var_mu(nc)] = v[rs_at_mu(L, i)];
      d[rs_law_var_dmu(nc)] = wlin->dmu[i];
    }
    double sum[RS_LAW_NROW] = {0.0};
    for (int e = w->jv_start[i]; e < w->jv_start[i + 1]; e++)
      sum[w->jv_idx[e] >> 4] += w->jv_val[e] * d[w->jv_idx[e] & 15];
    for (int c = 0; c < nc; c++) {
      Jv[rs_at_p(L, c, i)] = sum[c];
      Jv[rs_at_upl(L, c, i)] = sum[nc + c];
    }
    Jv[rs_at_ustar(L, i)] = sum[2 * nc];
    if (mem) Jv[rs_at_mu(L, i)] = sum[2 * nc + 1];
  }
  const double force_row = m->grid.area / m->contact_measure;
  for (int k = 0; k < L->nextra; k++) {
    double sum = 0.0;
    for (int j = 0; j < n; j++) sum += v[rs_at_p(L, k, j)];
    Jv[rs_at_extra(L, k)] = force_row * sum;
  }
  return RS_OK;
}
