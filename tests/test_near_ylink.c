/* The 3D preconditioner's line Gauss-Seidel (solve/linsys_krylov.h) against an independent
 * path, on a plastic 3D ellipse (30 x 30 cells, partial slip and yield, so that the near
 * field is split in two halves with two threads), steady (c_j = 0) and with a transient c_j:
 *
 * 1. rs_model_near_ylink (the couplings between neighbouring lines, from a table of kernel
 *    differences) against the entries that the general assembly adds when the near field
 *    spans one line more each way (rs_model_jacobian_assemble with band_y = 1 minus the
 *    same with band_y = 0), applied to a random vector: the same products summed in another
 *    order, so they agree to roundoff (1e-13 of the sum of the terms' magnitudes).
 * 2. P^-1 r of a set-up is the solution of the block lower-triangular system
 *    (J_0 + Y) x = r, where J_0 is the assembled near field along x and Y holds the
 *    couplings of the odd lines' rows to the even lines' tractions (band_y = 1 entries):
 *    the residual of x in that system is the LU solve's rounding: the solves read the
 *    factors in single precision (unit roundoff u = 6e-8), and a line's backward error is
 *    at most about n u, n = 150 unknowns per line (30 cells, 5 unknowns each): 9e-6 of
 *    |J| |x|; while J_0 x - r alone is not (checked, so that the first test of 2. can
 *    fail), with one thread and two.
 * 3. rs_model_jacobian_assemble_lines at a second state into the matrix of the first: the
 *    rows of the chosen lines equal the whole assembly's at the second state, bit for bit,
 *    and the other rows the first state's (the two states differ in those rows, checked). */
#include <stdlib.h>
#include <string.h>

#include "base/util.h"
#include "solve/linsys_krylov.h"
#include "test_krylov_support.h"

static double norm_max(const double *a, int n)
{
  double d = 0.0;
  for (int i = 0; i < n; i++) d = fmax(d, fabs(a[i]));
  return d;
}

static int line_of(const rs_model *m, int64_t g) { return (int)((g % m->lay.n) / m->grid.nx); }

static int csr_alloc(rs_csr *J, const rs_model *m, int band, int band_y)
{
  const int64_t cap = rs_model_jac_capacity(m, band, band_y);
  J->rowptr = malloc(((size_t)m->lay.neq + 1) * sizeof *J->rowptr);
  J->col = malloc((size_t)cap * sizeof *J->col);
  J->val = malloc((size_t)cap * sizeof *J->val);
  J->cap = cap;
  return J->rowptr && J->col && J->val ? RS_OK : RS_ERR_INTERNAL;
}

static void csr_free(rs_csr *J)
{
  free(J->rowptr);
  free(J->col);
  free(J->val);
}

/* out = r - Y x on the rows of odd lines (Y: the entries of J1 in columns of other lines),
 * r elsewhere; mag: the sum of |terms| per row */
static void reference(const rs_model *m, const rs_csr *J1, const double *r, const double *x,
                      double *out, double *mag)
{
  for (int64_t i = 0; i < m->lay.neq; i++) {
    out[i] = r[i];
    mag[i] = fabs(r[i]);
    const int li = line_of(m, i);
    if (!(li & 1)) continue;
    for (int64_t e = J1->rowptr[i]; e < J1->rowptr[i + 1]; e++)
      if (line_of(m, J1->col[e]) != li) {
        out[i] -= J1->val[e] * x[J1->col[e]];
        mag[i] += fabs(J1->val[e] * x[J1->col[e]]);
      }
  }
}

int main(void)
{
  rs_model m;
  double *y = NULL;
  if (ts_plastic_ellipse_state(30, &m, &y)) return 1;
  const int neq = m.lay.neq;
  double *buf = calloc(6 * (size_t)neq, sizeof *buf); /* y', x, r and three results */
  if (!buf) return 1;
  double *yp = buf, *x = buf + neq, *r = buf + 2 * neq, *a = buf + 3 * neq, *b = buf + 4 * neq;
  double *mag = buf + 5 * (size_t)neq;
  rs_work w;
  rs_work_create(&w, &m);
  rs_csr J0, J1;
  TS_CHECK(csr_alloc(&J0, &m, RS_KRYLOV_BAND_3D, 0) == RS_OK &&
               csr_alloc(&J1, &m, RS_KRYLOV_BAND_3D, 1) == RS_OK,
           "out of memory");
  unsigned long seed = 2026;
  const rs_inputs in = ts_inputs(&m, 0.0);
  for (int pass = 0; pass < 2; pass++) {
    const char *tag = NULL;
    const double cj = ts_krylov_pass(&m, pass, y, yp, &seed, &tag);
    for (int i = 0; i < neq; i++) {
      x[i] = ts_random(&seed);
      r[i] = ts_random(&seed);
    }
    /* 1. the couplings */
    TS_CHECK(rs_model_linearise(&m, &w, &in, y, yp, cj) == RS_OK, "%s: linearisation", tag);
    rs_model_jacobian_assemble(&m, &w, &in, cj, RS_KRYLOV_BAND_3D, 1, &J1);
    reference(&m, &J1, r, x, a, mag);
    memcpy(b, r, (size_t)neq * sizeof *b);
    rs_model_near_ylink(&m, &w, &in, cj, RS_KRYLOV_BAND_3D, 1, 0, m.grid.ny, x, b);
    double err = 0.0, coupled = 0.0;
    for (int i = 0; i < neq; i++) {
      err = fmax(err, fabs(a[i] - b[i]) / (mag[i] > 0.0 ? mag[i] : 1.0));
      coupled = fmax(coupled, fabs(b[i] - r[i]));
    }
    printf("%s: couplings max |Y x| %.3e, relative difference from the assembly %.3e\n", tag,
           coupled, err);
    TS_CHECK(coupled > 1e-3 * norm_max(r, neq), "%s: no coupling between lines", tag);
    TS_CHECK(err <= 1e-13, "%s: couplings differ from the assembly by %.3e", tag, err);
    /* rows of even lines are untouched, and x is read on even lines only */
    double untouched = 0.0;
    for (int i = 0; i < neq; i++)
      if (!(line_of(&m, i) & 1)) untouched = fmax(untouched, fabs(b[i] - r[i]));
    memcpy(a, r, (size_t)neq * sizeof *a);
    for (int i = 0; i < neq; i++)
      if (line_of(&m, i) & 1) x[i] += 1.0;
    rs_model_near_ylink(&m, &w, &in, cj, RS_KRYLOV_BAND_3D, 1, 0, m.grid.ny, x, a);
    double moved = 0.0;
    for (int i = 0; i < neq; i++) moved = fmax(moved, fabs(a[i] - b[i]));
    TS_CHECK(untouched == 0.0 && moved == 0.0,
             "%s: even rows changed by %.3e, odd lines' x moved the result by %.3e", tag, untouched,
             moved);
    /* 2. the preconditioner */
    for (int threads = 1; threads <= 2; threads++) {
      m.par.threads = threads;
      rs_krylov k;
      TS_CHECK(rs_krylov_create(&k, &m, RS_KRYLOV_BAND_3D, RS_KRYLOV_BAND_3D_Y) == RS_OK, "krylov");
      TS_CHECK(rs_krylov_setup(&k, &in, y, yp, cj) == RS_OK, "%s: set-up", tag);
      printf("%s, %d thread(s): %d parts, line Gauss-Seidel %s\n", tag, threads, k.nparts,
             k.ylink ? "on" : "off");
      TS_CHECK(k.ylink && k.nparts == m.grid.ny && k.nsplit == rs_threads(threads), "%s: parts %d",
               tag, k.nparts);
      memcpy(x, r, (size_t)neq * sizeof *x);
      TS_CHECK(rs_krylov_psolve(&k, x) == RS_OK, "%s: psolve", tag);
      /* (J_0 + Y) x - r, J_0 as factored (k.near), Y from J1 */
      double res = 0.0, res0 = 0.0, scale = 0.0;
      const rs_csr *N = &k.near;
      for (int64_t i = 0; i < neq; i++) {
        double s0 = -r[i], sa = 0.0;
        for (int64_t e = N->rowptr[i]; e < N->rowptr[i + 1]; e++) {
          s0 += N->val[e] * x[N->col[e]];
          sa += fabs(N->val[e] * x[N->col[e]]);
        }
        double s1 = s0;
        if (line_of(&m, i) & 1)
          for (int64_t e = J1.rowptr[i]; e < J1.rowptr[i + 1]; e++)
            if (line_of(&m, J1.col[e]) != line_of(&m, i)) {
              s1 += J1.val[e] * x[J1.col[e]];
              sa += fabs(J1.val[e] * x[J1.col[e]]);
            }
        res = fmax(res, fabs(s1));
        res0 = fmax(res0, fabs(s0));
        scale = fmax(scale, sa);
      }
      printf("%s, %d thread(s): |(J_0 + Y) x - r| %.3e, |J_0 x - r| %.3e, |J| |x| %.3e\n", tag,
             threads, res, res0, scale);
      TS_CHECK(res <= 9e-6 * scale, "%s: the line Gauss-Seidel solve's residual %.3e", tag, res);
      TS_CHECK(res0 > 1e-4 * scale, "%s: the couplings did not enter the solve", tag);
      rs_krylov_free(&k);
    }
  }
  /* 3. the lines' assembly: J0 at y, the lines iy = 3 mod 4 then at y2 */
  {
    const rs_inputs in0 = ts_inputs(&m, 0.0);
    double *y2 = malloc((size_t)neq * sizeof *y2), *yp0 = calloc((size_t)neq, sizeof *yp0);
    unsigned char *lines = calloc((size_t)m.grid.ny, 1);
    rs_csr J2;
    TS_CHECK(y2 && yp0 && lines && csr_alloc(&J2, &m, RS_KRYLOV_BAND_3D, 0) == RS_OK, "memory");
    for (int i = 0; i < neq; i++) y2[i] = y[i] * (1.0 + 0.01 * ts_random(&seed));
    for (int iy = 3; iy < m.grid.ny; iy += 4) lines[iy] = 1;
    rs_model_linearise(&m, &w, &in0, y, yp0, 0.0);
    rs_model_jacobian_assemble(&m, &w, &in0, 0.0, RS_KRYLOV_BAND_3D, 0, &J0);
    rs_model_linearise(&m, &w, &in0, y2, yp0, 0.0);
    rs_model_jacobian_assemble(&m, &w, &in0, 0.0, RS_KRYLOV_BAND_3D, 0, &J2);
    const int st3 =
        rs_model_jacobian_assemble_lines(&m, &w, &in0, 0.0, RS_KRYLOV_BAND_3D, 0, lines, &J0);
    TS_CHECK(st3 == RS_OK, "lines' assembly refused the pattern");
    long wrong = 0, moved = 0, kept = 0;
    for (int64_t i = 0; i < neq; i++) {
      const int mine = lines[line_of(&m, i)];
      wrong += J0.rowptr[i + 1] != J2.rowptr[i + 1];
      for (int64_t e = J2.rowptr[i]; e < J2.rowptr[i + 1] && J0.rowptr[i + 1] == J2.rowptr[i + 1];
           e++) {
        if (mine) wrong += J0.col[e] != J2.col[e] || J0.val[e] != J2.val[e];
        if (!mine) kept += J0.val[e] != J2.val[e]; /* the first state's, not the second's */
      }
    }
    rs_model_linearise(&m, &w, &in0, y, yp0, 0.0);
    rs_model_jacobian_assemble(&m, &w, &in0, 0.0, RS_KRYLOV_BAND_3D, 0, &J1);
    for (int64_t i = 0; i < neq; i++)
      for (int64_t e = J1.rowptr[i]; e < J1.rowptr[i + 1] && !lines[line_of(&m, i)]; e++)
        wrong += J1.val[e] != J0.val[e];
    for (int64_t i = 0; i < neq; i++)
      for (int64_t e = J1.rowptr[i]; e < J1.rowptr[i + 1] && lines[line_of(&m, i)]; e++)
        moved += J1.val[e] != J0.val[e];
    printf("lines' assembly: %ld entries wrong; %ld entries of the chosen lines moved, %ld of "
           "the others differ from the second state's\n",
           wrong, moved, kept);
    TS_CHECK(wrong == 0, "lines' assembly: %ld entries differ", wrong);
    TS_CHECK(moved > 0 && kept > 0, "lines' assembly: the two states do not differ");
    csr_free(&J2);
    free(y2);
    free(yp0);
    free(lines);
  }
  csr_free(&J0);
  csr_free(&J1);
  rs_work_free(&w);
  rs_model_free(&m);
  free(y);
  free(buf);
  printf("%s\n", ts_failures ? "FAILED" : "passed");
  return ts_failures ? 1 : 0;
}
