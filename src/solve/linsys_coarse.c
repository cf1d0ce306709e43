/* Coarse-grid correction of the 3D near-field preconditioner (see linsys_coarse.h). */
#include "solve/linsys_coarse.h"

#include "base/util.h"
#include "physics/contact_law.h"

#include <stdlib.h>
#include <string.h>

void rs_coarse_free(rs_coarse *c)
{
  free(c->bx);
  free(c->by);
  free(c->block);
  free(c->s0);
  free(c->s1);
  free(c->a);
  free(c->ipiv);
  free(c->bm);
  free(c->am);
  free(c->x);
  memset(c, 0, sizeof *c);
}

/* The coefficient pairs (x, x), (x, y) = (y, x), (y, y). */
static const int pair_i[3] = {0, 0, 1}, pair_j[3] = {0, 1, 1};
static int pair_of(int c, int d) { return c + d; }

/* The elastic sums s0, s1 (linsys_coarse.h) in two separable stages: over the cells' y
 * offsets for each x offset, then over the x offsets. The layer's flexibility adds to the
 * self coefficients of xx and yy (as in the kinematics). */
static int tabulate(rs_coarse *c, const rs_model *m)
{
  const rs_elastic3d *el = &m->el.surf;
  const int nx = m->grid.nx, cx = c->cx, cy = c->cy, nb = c->nb, w = 2 * nx;
  const double c3 = m->layer_flex;
  double *t = malloc((size_t)3 * cy * cy * w * sizeof *t);
  if (!t) return RS_ERR_INTERNAL;
  for (int p = 0; p < 3; p++)
    for (int Iy = 0; Iy < cy; Iy++)
      for (int Jy = 0; Jy < cy; Jy++) {
        double *row = t + ((size_t)(p * cy + Iy) * cy + Jy) * w;
        for (int dx = -(nx - 1); dx <= nx; dx++) {
          double sum = 0.0;
          for (int iy = c->by[Iy]; iy < c->by[Iy + 1]; iy++)
            for (int ky = c->by[Jy]; ky < c->by[Jy + 1]; ky++) {
              sum += rs_elastic3d_coef(el, pair_i[p], pair_j[p], dx, iy - ky);
              if (dx == 0 && iy == ky && p != 1) sum += c3;
            }
          row[dx + nx - 1] = sum;
        }
      }
  for (int p = 0; p < 3; p++)
    for (int Iy = 0; Iy < cy; Iy++)
      for (int Jy = 0; Jy < cy; Jy++) {
        const double *row = t + ((size_t)(p * cy + Iy) * cy + Jy) * w + nx - 1;
        for (int Ix = 0; Ix < cx; Ix++)
          for (int Jx = 0; Jx < cx; Jx++) {
            double a0 = 0.0, a1 = 0.0;
            for (int ix = c->bx[Ix]; ix < c->bx[Ix + 1]; ix++)
              for (int kx = c->bx[Jx]; kx < c->bx[Jx + 1]; kx++) {
                a0 += row[ix - kx];
                a1 += row[ix + 1 - kx];
              }
            const size_t at = (size_t)p * nb * nb + (size_t)(Iy * cx + Ix) * nb + Jy * cx + Jx;
            c->s0[at] = a0;
            c->s1[at] = a1;
          }
      }
  free(t);
  return RS_OK;
}

int rs_coarse_create(rs_coarse *c, const rs_model *m, int size)
{
  memset(c, 0, sizeof *c);
  const int nx = m->grid.nx, ny = m->grid.ny;
  c->cx = (nx + size - 1) / size;
  c->cy = (ny + size - 1) / size;
  c->nb = c->cx * c->cy;
  const size_t nb = (size_t)c->nb, N = 2 * nb;
  c->bx = malloc(((size_t)c->cx + 1) * sizeof *c->bx);
  c->by = malloc(((size_t)c->cy + 1) * sizeof *c->by);
  c->block = malloc((size_t)nx * ny * sizeof *c->block);
  c->s0 = malloc(3 * nb * nb * sizeof *c->s0);
  c->s1 = malloc(3 * nb * nb * sizeof *c->s1);
  c->a = malloc(N * N * sizeof *c->a);
  c->ipiv = malloc(N * sizeof *c->ipiv);
  c->bm = malloc(4 * nb * sizeof *c->bm);
  c->am = malloc(4 * nb * sizeof *c->am);
  c->x = malloc(N * sizeof *c->x);
  if (!c->bx || !c->by || !c->block || !c->s0 || !c->s1 || !c->a || !c->ipiv || !c->bm || !c->am ||
      !c->x) {
    rs_coarse_free(c);
    return RS_ERR_INTERNAL;
  }
  for (int I = 0; I <= c->cx; I++) c->bx[I] = (int)((long)I * nx / c->cx);
  for (int I = 0; I <= c->cy; I++) c->by[I] = (int)((long)I * ny / c->cy);
  for (int Iy = 0; Iy < c->cy; Iy++)
    for (int iy = c->by[Iy]; iy < c->by[Iy + 1]; iy++)
      for (int Ix = 0; Ix < c->cx; Ix++)
        for (int ix = c->bx[Ix]; ix < c->bx[Ix + 1]; ix++) c->block[iy * nx + ix] = Iy * c->cx + Ix;
  if (tabulate(c, m) != RS_OK) {
    rs_coarse_free(c);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

int rs_coarse_setup(rs_coarse *c, const rs_model *m, const rs_work *w, const rs_inputs *in,
                    double cj)
{
  const int n = m->lay.n, nb = c->nb, N = 2 * nb;
  const double a = in->velocity / m->grid.dx;
  int *count = calloc((size_t)nb, sizeof *count);
  if (!count) return RS_ERR_INTERNAL;
  memset(c->bm, 0, 4 * (size_t)nb * sizeof *c->bm);
  memset(c->am, 0, 4 * (size_t)nb * sizeof *c->am);
  for (int i = 0; i < n; i++) {
    const int b = c->block[i];
    count[b]++;
    for (int e = w->jv_start[i]; e < w->jv_start[i + 1]; e++) {
      const int row = w->jv_idx[e] >> 4, var = w->jv_idx[e] & 15;
      if (row >= 2) continue;
      if (var == rs_law_var_p(0) || var == rs_law_var_p(1))
        c->am[4 * b + 2 * row + var - rs_law_var_p(0)] += w->jv_val[e];
      else if (var == rs_law_var_vs(2, 0) || var == rs_law_var_vs(2, 1))
        c->bm[4 * b + 2 * row + var - rs_law_var_vs(2, 0)] += w->jv_val[e];
    }
  }
  for (int b = 0; b < nb; b++)
    for (int k = 0; k < 4; k++) c->bm[4 * b + k] /= count[b] > 0 ? count[b] : 1;
  free(count);
  const size_t nn = (size_t)nb * nb;
  for (int d = 0; d < 2; d++)
    for (int J = 0; J < nb; J++) {
      double *col = c->a + (size_t)(d * nb + J) * N;
      for (int I = 0; I < nb; I++) {
        const size_t at = (size_t)I * nb + J;
        double g[2];
        for (int e = 0; e < 2; e++) {
          const size_t p = (size_t)pair_of(e, d) * nn + at;
          g[e] = (cj + a) * c->s0[p] - a * c->s1[p];
        }
        for (int r = 0; r < 2; r++)
          col[r * nb + I] = c->bm[4 * I + 2 * r] * g[0] + c->bm[4 * I + 2 * r + 1] * g[1] +
                            (I == J ? c->am[4 * I + 2 * r + d] : 0.0);
      }
    }
  int info = 0;
  dgetrf_(&N, &N, c->a, &N, c->ipiv, &info);
  c->ready = info == 0;
  return RS_OK;
}

void rs_coarse_apply(rs_coarse *c, const rs_model *m, const double *r, double *z)
{
  if (!c->ready) return;
  const rs_layout *L = &m->lay;
  const int n = L->n, nb = c->nb, N = 2 * nb, one = 1;
  memset(c->x, 0, (size_t)N * sizeof *c->x);
  for (int comp = 0; comp < 2; comp++)
    for (int i = 0; i < n; i++) c->x[comp * nb + c->block[i]] += r[rs_at_p(L, comp, i)];
  int info = 0;
  dgetrs_("N", &N, &one, c->a, &N, c->ipiv, c->x, &N, &info);
  if (info != 0) return;
  for (int comp = 0; comp < 2; comp++)
    for (int i = 0; i < n; i++) z[rs_at_p(L, comp, i)] += c->x[comp * nb + c->block[i]];
}

void rs_coarse_replace(rs_coarse *c, const rs_model *m, const double *r, double *z)
{
  if (!c->ready) return;
  const rs_layout *L = &m->lay;
  const int n = L->n, nb = c->nb, N = 2 * nb, one = 1;
  memset(c->x, 0, (size_t)N * sizeof *c->x);
  double *mean = calloc((size_t)N, sizeof *mean);
  int *count = calloc((size_t)nb, sizeof *count);
  for (int i = 0; i < n; i++) count[c->block[i]]++;
  for (int comp = 0; comp < 2; comp++)
    for (int i = 0; i < n; i++) {
      c->x[comp * nb + c->block[i]] += r[rs_at_p(L, comp, i)];
      mean[comp * nb + c->block[i]] += z[rs_at_p(L, comp, i)] / count[c->block[i]];
    }
  int info = 0;
  dgetrs_("N", &N, &one, c->a, &N, c->ipiv, c->x, &N, &info);
  for (int comp = 0; comp < 2; comp++)
    for (int i = 0; i < n; i++)
      z[rs_at_p(L, comp, i)] += c->x[comp * nb + c->block[i]] - mean[comp * nb + c->block[i]];
  free(mean);
  free(count);
}
