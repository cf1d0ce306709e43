/* The coarse space of the 3D preconditioner (see linsys_coarse.h). */
#include "solve/linsys_coarse.h"

#include <stdlib.h>
#include <string.h>

#include "base/util.h"

/* The accumulation of E in 256-bit registers where the processor has them. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RS_COARSE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RS_COARSE_CLONES
#endif

void rs_coarse_free(rs_coarse *c)
{
  free(c->ta);
  free(c->td);
  free(c->tab);
  free(c->agg);
  free(c->keep);
  free(c->G);
  free(c->ipiv);
  free(c->e);
  memset(c, 0, sizeof *c);
}

/* The kinematic kernel's parts (docs/model.md §5; as the near field's rows,
 * model_jacobian.c): dv_s,c/dp_b at the offset (kx, ky) is cj KA - (V/dx) KD with
 *   KA = A_cb(kx, ky) + [c = b] h3/G3 at (0, 0),
 *   KD = A_cb(kx + 1, ky) - A_cb(kx, ky) - [c = b] h3/G3 at (0, 0) + [c = b] h3/G3 at (-1, 0)
 * (the layer on the cell and its upstream neighbour). */
static void kernel_parts(const rs_model *m, int c, int b, int kx, int ky, double *ka, double *kd)
{
  const double A0 = rs_elastic_op_coef(&m->el, c, b, kx, ky), c3 = c == b ? m->layer_flex : 0.0;
  *ka = A0 + (kx == 0 && ky == 0 ? c3 : 0.0);
  *kd = rs_elastic_op_coef(&m->el, c, b, kx + 1, ky) - A0 - (kx == 0 && ky == 0 ? c3 : 0.0) +
        (kx == -1 && ky == 0 ? c3 : 0.0);
}

/* The template tables: for the component pair cb = 2 c + b, the kernel summed over an
 * aggregate, T_cb(ox, oy) = sum over 0 <= jx, jy < s of K_cb(ox - jx, oy - jy), at the offset
 * (ox, oy) of a row cell from an aggregate's first cell. Stored so that a row cell reads the
 * aggregates of one row of them in sequence: the aggregates numbered from the high-x, high-y
 * corner, the offsets shifted to start at 0 (ox' = ox + ox0 + (ax - 1) s, likewise oy'), and
 * ox' = q s + rx split into its phase rx and quotient q: entry ((cb nyt + oy') s + rx) nq + q.
 * Offsets outside the kernel's range (no pair of cells has them) add nothing. */
static int make_tables(rs_coarse *c, const rs_model *m)
{
  const int nx = m->grid.nx, ny = m->grid.ny, sx = c->sx, sy = c->sy;
  const int oxmin = -c->ox0 - (c->ax - 1) * sx, oymin = -c->oy0 - (c->ay - 1) * sy;
  const int nox = c->nq * sx, nky = 2 * ny - 1;
  const size_t plane = (size_t)nox * (size_t)nky;
  double *sa = malloc(plane * sizeof *sa), *sd = malloc(plane * sizeof *sd);
  if (!sa || !sd) {
    free(sa);
    free(sd);
    return RS_ERR_INTERNAL;
  }
  for (int cb = 0; cb < 4; cb++) {
    const int cc = cb / 2, b = cb % 2;
    /* the sums along x, for every ky of the kernel's range */
    for (int k = 0; k < nky; k++) {
      const int ky = k - (ny - 1);
      for (int i = 0; i < nox; i++) {
        const int ox = oxmin + i;
        double a = 0.0, d = 0.0;
        for (int jx = 0; jx < sx; jx++) {
          const int kx = ox - jx;
          if (kx < -(nx - 1) || kx > nx - 1) continue;
          double ka, kd;
          kernel_parts(m, cc, b, kx, ky, &ka, &kd);
          a += ka;
          d += kd;
        }
        sa[(size_t)k * nox + i] = a;
        sd[(size_t)k * nox + i] = d;
      }
    }
    /* then along y, into the polyphase layout */
    for (int yy = 0; yy < c->nyt; yy++) {
      const int oy = oymin + yy;
      for (int i = 0; i < nox; i++) {
        double a = 0.0, d = 0.0;
        for (int jy = 0; jy < sy; jy++) {
          const int ky = oy - jy;
          if (ky < -(ny - 1) || ky > ny - 1) continue;
          a += sa[(size_t)(ky + ny - 1) * nox + i];
          d += sd[(size_t)(ky + ny - 1) * nox + i];
        }
        const size_t at = (((size_t)cb * c->nyt + yy) * sx + i % sx) * c->nq + i / sx;
        c->ta[at] = a;
        c->td[at] = d;
      }
    }
  }
  free(sa);
  free(sd);
  return RS_OK;
}

int rs_coarse_create(rs_coarse *c, const rs_model *m, int size, int size_y)
{
  memset(c, 0, sizeof *c);
  const int nx = m->grid.nx, ny = m->grid.ny, n = m->lay.n;
  c->sx = size;
  c->sy = size_y;
  if (size < 1 || size_y < 1) return RS_ERR_INTERNAL;
  c->ax = nx / size;
  c->ay = ny / size_y;
  if (c->ax < 1 || c->ay < 1) return RS_ERR_INTERNAL;
  c->nagg = c->ax * c->ay;
  c->ox0 = (nx - c->ax * size) / 2;
  c->oy0 = (ny - c->ay * size_y) / 2;
  c->nq = (nx - 1) / size + c->ax;
  c->nyt = ny + (c->ay - 1) * size_y;
  const size_t ntab = 4 * (size_t)c->nyt * (size_t)size * (size_t)c->nq;
  const size_t nf = 2 * (size_t)c->nagg;
  c->ta = malloc(ntab * sizeof *c->ta);
  c->td = malloc(ntab * sizeof *c->td);
  c->tab = malloc(ntab * sizeof *c->tab);
  c->agg = malloc((size_t)n * sizeof *c->agg);
  c->keep = malloc((size_t)c->nagg * sizeof *c->keep);
  c->G = malloc(nf * nf * sizeof *c->G);
  c->ipiv = malloc(nf * sizeof *c->ipiv);
  c->e = malloc(nf * sizeof *c->e);
  if (!c->ta || !c->td || !c->tab || !c->agg || !c->keep || !c->G || !c->ipiv || !c->e ||
      make_tables(c, m) != RS_OK) {
    rs_coarse_free(c);
    return RS_ERR_INTERNAL;
  }
  for (int I = 0; I < n; I++) {
    const int ix = I % nx - c->ox0, iy = I / nx - c->oy0;
    const int in = ix >= 0 && ix < c->ax * size && iy >= 0 && iy < c->ay * size_y;
    c->agg[I] = in ? (c->ay - 1 - iy / size_y) * c->ax + (c->ax - 1 - ix / size) : -1;
  }
  c->tab_cj = c->tab_a = -1.0; /* no table for any rate yet */
  return RS_OK;
}

RS_COARSE_CLONES int rs_coarse_setup(rs_coarse *c, const rs_model *m, const rs_work *w, double cj,
                                     double velocity)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nx = m->grid.nx, s = c->sx, sy = c->sy, nagg = c->nagg, nf = 2 * nagg;
  const double a = velocity / m->grid.dx;
  const size_t ntab = 4 * (size_t)c->nyt * (size_t)s * (size_t)c->nq;
  c->ready = 0;
  c->setups++;
  if (cj != c->tab_cj || a != c->tab_a) {
    for (size_t k = 0; k < ntab; k++) c->tab[k] = cj * c->ta[k] - a * c->td[k];
    c->tab_cj = cj;
    c->tab_a = a;
  }
  /* the aggregates with a cell in the contact */
  for (int g = 0; g < nagg; g++) c->keep[g] = -1;
  for (int I = 0; I < n; I++)
    if (c->agg[I] >= 0 && !(w->law[I].branch & RS_BRANCH_EXTERIOR)) c->keep[c->agg[I]] = 0;
  int nk = 0;
  for (int g = 0; g < nagg; g++)
    if (c->keep[g] == 0) c->keep[g] = nk++;
  c->nk = nk;
  c->nc = 2 * nk;
  if (nk == 0) return RS_OK;
  /* E (all aggregates) accumulated row cell by row cell: G[row nf + col] = E[row][col], row
   * c' nagg + (the cell's aggregate), col b nagg + (an aggregate) */
  for (int b = 0; b < 2; b++)
    for (int g = 0; g < nagg; g++)
      if (c->keep[g] >= 0) memset(c->G + ((size_t)b * nagg + g) * nf, 0, (size_t)nf * sizeof *c->G);
  const int vs0 = rs_law_var_vs(2, 0), vs1 = rs_law_var_vs(2, 1);
  for (int I = 0; I < n; I++) {
    const int beta = c->agg[I];
    if (beta < 0 || c->keep[beta] < 0) continue;
    const rs_law_out *o = &w->law[I];
    double d[2][2], dp[2][2];
    int any = 0;
    for (int r = 0; r < 2; r++) {
      const int row = rs_law_row_f(r);
      d[r][0] = o->present[row][vs0] ? o->jac[row][vs0] : 0.0;
      d[r][1] = o->present[row][vs1] ? o->jac[row][vs1] : 0.0;
      for (int b = 0; b < 2; b++)
        dp[r][b] = o->present[row][rs_law_var_p(b)] ? o->jac[row][rs_law_var_p(b)] : 0.0;
      any |= d[r][0] != 0.0 || d[r][1] != 0.0;
    }
    for (int r = 0; r < 2; r++)
      for (int b = 0; b < 2; b++)
        c->G[((size_t)r * nagg + beta) * nf + b * nagg + beta] += dp[r][b];
    if (!any) continue;
    const int ix = I % nx, iy = I / nx, rx = ix % s, qx = ix / s;
    for (int gy = 0; gy < c->ay; gy++) {
      const int oy = iy + gy * sy;
      const double *t[4];
      for (int cb = 0; cb < 4; cb++)
        t[cb] = c->tab + (((size_t)cb * c->nyt + oy) * s + rx) * c->nq + qx;
      for (int r = 0; r < 2; r++)
        for (int b = 0; b < 2; b++) {
          double *restrict g = c->G + ((size_t)r * nagg + beta) * nf + b * nagg + gy * c->ax;
          const double *restrict t0 = t[b], *restrict t1 = t[2 + b];
          const double d0 = d[r][0], d1 = d[r][1];
          const int ax = c->ax;
#pragma omp simd
          for (int gx = 0; gx < ax; gx++) g[gx] += d0 * t0[gx] + d1 * t1[gx];
        }
    }
  }
  /* the kept rows and columns, packed in place (kept indices never exceed their own):
   * E^T by columns for LAPACK */
  const int nc = c->nc;
  int *map = c->ipiv; /* scratch: full index -> kept index */
  for (int b = 0; b < 2; b++)
    for (int g = 0; g < nagg; g++) map[b * nagg + g] = c->keep[g] < 0 ? -1 : b * nk + c->keep[g];
  for (int row = 0; row < nf; row++) {
    if (map[row] < 0) continue;
    const double *src = c->G + (size_t)row * nf;
    double *dst = c->G + (size_t)map[row] * nc;
    for (int col = 0; col < nf; col++)
      if (map[col] >= 0) dst[map[col]] = src[col];
  }
  int info = 0;
  dgetrf_(&nc, &nc, c->G, &nc, c->ipiv, &info);
  c->ready = info == 0;
  return RS_OK;
}

void rs_coarse_solve(rs_coarse *c, const rs_model *m, const double *v, double *y)
{
  const rs_layout *L = &m->lay;
  const int n = L->n, nk = c->nk, nc = c->nc, one = 1;
  memset(c->e, 0, (size_t)nc * sizeof *c->e);
  for (int b = 0; b < 2; b++)
    for (int I = 0; I < n; I++) {
      const int g = c->agg[I];
      if (g >= 0 && c->keep[g] >= 0) c->e[b * nk + c->keep[g]] += v[rs_at_p(L, b, I)];
    }
  int info = 0;
  dgetrs_("T", &nc, &one, c->G, &nc, c->ipiv, c->e, &nc, &info);
  for (int b = 0; b < 2; b++)
    for (int I = 0; I < n; I++) {
      const int g = c->agg[I];
      y[rs_at_p(L, b, I)] = g >= 0 && c->keep[g] >= 0 ? c->e[b * nk + c->keep[g]] : 0.0;
    }
}
