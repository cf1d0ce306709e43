/* The lines of the 3D near field factored and solved side by side (solve/linsys_lanes.h),
 * on fifteen lines of 30 unknowns whose patterns differ (a band of half width 3, and in some
 * lines entries two bands farther out), so that the common pattern is larger than each
 * line's and one group of lanes is not full:
 *
 * 1. The solutions of the lines whose factors hold satisfy their own sparse systems: the
 *    residual |A x - b| at most 1.8e-6 of |A| |x| + |b| in every row, checked against the
 *    CSR matrices directly (an independent product). The lines are diagonally dominant and
 *    the LU is backward stable; the solves read the factors rounded to single precision
 *    (unit roundoff 6e-8), so the residual is that rounding's: at most n u = 30 x 6e-8
 *    per row.
 * 2. A line that needs other pivots than the common order (a pair of rows and columns
 *    coupled only to each other off the diagonal: a zero pivot) is reported (ok 0) and
 *    its entries of v are left as they were; the others still solve (1.).
 * 3. A refactorisation with one line's values changed (refresh of that line only) solves the
 *    new system of that line, and the other lines' solutions stay bit for bit.
 * 4. Groups solved side by side (two, three or four at once) give bit for bit the solutions
 *    of the groups solved one at a time (each line's operations are the same), and so do
 *    groups refactored side by side.
 * 5. The values read from the rows of a matrix in which each line's row is followed by
 *    entries of other lines (NaN here, which must not be read) give bit for bit the
 *    solutions of the matrix without them.
 * The lanes read the lines' values from the rows of the matrix they come from (row q N + i
 * holds line q's row i first): built by whole_matrix. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/status.h"
#include "solve/linsys_lanes.h"

enum { N = 30, LINES = 15, BAD = 5 };

static int failures;
static void check(int ok, const char *what)
{
  printf("%s: %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) failures++;
}

static double rnd(unsigned *s)
{
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffff) / 65536.0 - 0.5;
}

typedef struct line_mat {
  int64_t rowptr[N + 1], col[N * 12], idx[N];
  double val[N * 12];
} line_mat;

/* Line q: band |i - j| <= 3, and for odd q also |i - j| == 5; diagonally dominant, but for
 * q == BAD, whose rows and columns 10 and 11 hold only the block [0 9; 9 0] (stored zeros
 * elsewhere): a zero pivot in any order that does not swap them. */
static void make_line(line_mat *a, int q, unsigned *seed)
{
  int64_t nz = 0;
  a->rowptr[0] = 0;
  for (int i = 0; i < N; i++) {
    a->idx[i] = (int64_t)q * N + i;
    for (int j = i - 5; j <= i + 5; j++) {
      if (j < 0 || j >= N) continue;
      const int d = abs(i - j);
      if (d > 3 && !(d == 5 && (q & 1))) continue;
      double v = rnd(seed);
      if (d == 0) v = 8.0 + rnd(seed);
      if (q == BAD && (i == 10 || i == 11 || j == 10 || j == 11)) /* [0 9; 9 0] alone */
        v = (i == 10 && j == 11) || (i == 11 && j == 10) ? 9.0 : 0.0;
      a->col[nz] = j;
      a->val[nz++] = v;
    }
    a->rowptr[i + 1] = nz;
  }
}

/* max over rows of |A x - b| / (|A| |x| + |b|) */
static double residual(const line_mat *a, const double *x, const double *b)
{
  double worst = 0.0;
  for (int i = 0; i < N; i++) {
    double r = -b[i], mag = fabs(b[i]);
    for (int64_t e = a->rowptr[i]; e < a->rowptr[i + 1]; e++) {
      r += a->val[e] * x[a->col[e]];
      mag += fabs(a->val[e] * x[a->col[e]]);
    }
    worst = fmax(worst, fabs(r) / mag);
  }
  return worst;
}

/* The matrix of all lines: row q N + i is line q's row i, then pad NaNs. */
static double gval[LINES * N * 14];
static int64_t grp[LINES * N + 1];
static void whole_matrix(const line_mat *a, int pad)
{
  grp[0] = 0;
  for (int q = 0; q < LINES; q++)
    for (int i = 0; i < N; i++) {
      const int r = q * N + i;
      int64_t e = grp[r];
      for (int64_t k = a[q].rowptr[i]; k < a[q].rowptr[i + 1]; k++) gval[e++] = a[q].val[k];
      for (int k = 0; k < pad; k++) gval[e++] = NAN;
      grp[r + 1] = e;
    }
}

/* every group, batch groups at a time */
static void solve_batched(const rs_lanes *s, double *v, int batch)
{
  for (int g = 0; g < s->ngroups; g += batch) {
    int groups[RS_LANES_BATCH], m = 0;
    while (m < batch && g + m < s->ngroups) groups[m] = g + m, m++;
    rs_lanes_solve(s, groups, m, v);
  }
}

static void solve_all(const rs_lanes *s, double *v) { solve_batched(s, v, 1); }

int main(void)
{
  static line_mat a[LINES];
  unsigned seed = 12345u;
  rs_lane_line lines[LINES];
  const double *values[LINES];
  int order[LINES];
  unsigned char first[LINES] = {0}, refresh[LINES];
  for (int q = 0; q < LINES; q++) {
    make_line(&a[q], q, &seed);
    lines[q] = (rs_lane_line){a[q].rowptr, a[q].col, a[q].idx};
    values[q] = a[q].val;
    order[q] = q;
    refresh[q] = 1;
  }
  rs_lanes s;
  check(rs_lanes_create(&s, N, LINES, lines, values, 1, order, LINES, first) == RS_OK,
        "lanes created");
  check(s.ngroups == (LINES + RS_LANES - 1) / RS_LANES, "groups of RS_LANES lines");
  whole_matrix(a, 0);
  for (int g = 0; g < s.ngroups; g++) rs_lanes_refactor(&s, &g, 1, gval, grp, refresh);
  int ok_lines = 0, bad_ok = -1;
  for (int g = 0; g < s.ngroups; g++)
    for (int l = 0; l < RS_LANES; l++) {
      if (s.group[g].line[l] == BAD) bad_ok = s.group[g].ok[l];
      if (s.group[g].line[l] >= 0 && s.group[g].line[l] != BAD) ok_lines += s.group[g].ok[l];
    }
  check(ok_lines == LINES - 1, "the dominant lines' factors hold");
  check(bad_ok == 0, "the line with zero diagonal pivots is reported");

  double b[LINES * N], v[LINES * N], v1[LINES * N];
  for (int i = 0; i < LINES * N; i++) b[i] = rnd(&seed);
  memcpy(v, b, sizeof v);
  solve_all(&s, v);
  double worst = 0.0;
  for (int q = 0; q < LINES; q++)
    if (q != BAD) worst = fmax(worst, residual(&a[q], v + q * N, b + q * N));
  printf("  largest relative residual %.3g\n", worst);
  check(worst <= 1.8e-6, "solutions satisfy their lines' systems to the factors' rounding");
  check(!memcmp(v + BAD * N, b + BAD * N, N * sizeof *v), "the reported line's entries left");

  /* 3. line 2 changed, only it refreshed */
  for (int64_t e = 0; e < a[2].rowptr[N]; e++) a[2].val[e] *= 1.0 + 0.3 * rnd(&seed);
  for (int q = 0; q < LINES; q++) refresh[q] = q == 2;
  whole_matrix(a, 0);
  for (int g = 0; g < s.ngroups; g++) rs_lanes_refactor(&s, &g, 1, gval, grp, refresh);
  memcpy(v1, b, sizeof v1);
  solve_all(&s, v1);
  const double r2 = residual(&a[2], v1 + 2 * N, b + 2 * N);
  printf("  line 2 after its refactorisation: relative residual %.3g\n", r2);
  check(r2 <= 1.8e-6, "the refreshed line solves its new system");
  check(memcmp(v1 + 2 * N, v + 2 * N, N * sizeof *v) != 0, "and its solution moved");
  int same = 1;
  for (int q = 0; q < LINES; q++)
    if (q != 2) same &= !memcmp(v1 + q * N, v + q * N, N * sizeof *v);
  check(same, "the other lines' solutions bit for bit the same");

  /* 4. side by side */
  check(s.ngroups == 4, "four groups");
  for (int batch = 2; batch <= RS_LANES_BATCH; batch++) {
    double vb[LINES * N];
    memcpy(vb, b, sizeof vb);
    solve_batched(&s, vb, batch);
    char what[80];
    snprintf(what, sizeof what, "%d groups at once: bit for bit the solutions one at a time",
             batch);
    check(!memcmp(vb, v1, sizeof vb), what);
  }
  for (int q = 0; q < LINES; q++) refresh[q] = 1;
  int all[4] = {0, 1, 2, 3};
  rs_lanes_refactor(&s, all, 4, gval, grp, refresh);
  double vr[LINES * N];
  memcpy(vr, b, sizeof vr);
  solve_all(&s, vr);
  check(!memcmp(vr, v1, sizeof vr), "4 groups refactored at once: bit for bit the same solutions");

  /* 5. each row followed by two NaNs */
  whole_matrix(a, 2);
  rs_lanes_refactor(&s, all, 4, gval, grp, refresh);
  double vg[LINES * N];
  memcpy(vg, b, sizeof vg);
  solve_all(&s, vg);
  check(!memcmp(vg, v1, sizeof vg),
        "rows followed by other entries: bit for bit the solutions without them");
  rs_lanes_free(&s);
  return failures ? 1 : 0;
}
