/* The 3D elastic operator: coefficient tables and products by FFT convolution (docs/model.md §10).
 * The linear convolution u(I) = sum_J A(I - J) p(J) on the grid equals a circular one on the padded
 * grid mx x my (mx >= 2 nx, my >= 2 ny - 1): the kernel's offsets kx in [-(nx-1), nx] and ky in
 * [-(ny-1), ny-1] wrap to distinct indices, and p is zero beyond the grid. Kernels are transformed
 * once at creation (scaled by 1/(mx my), FFTW's transforms are unnormalised); the products use
 * FFTW's new-array execute functions on the caller's work buffers, so the plans are shared and
 * never written. */
#include "physics/elastic3d_internal.h"

#include "base/util.h"

#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct rs_elastic3d_fft {
  int mx, my, ncx;   /* padded grid; ncx = mx/2 + 1 complex columns */
  fftw_plan forward; /* r2c of my x mx (x fastest): the kernels */
  /* The products by rows and columns, pruned: p fills ny of the my rows and u is read from
   * ny rows, so the transforms along x run on those rows only (r2c / c2r of mx), the ones
   * along y (c2c of my, in place) on every column. */
  fftw_plan rows_fwd, cols_fwd, cols_bwd, rows_bwd;
  /* transformed kernels [my ncx]: real parts, and A_xy's imaginary parts where they are not
   * roundoff (NULL else; see rs_elastic3d_fft_create) */
  double *kxx, *kxy, *kyy, *kzz, *kxy_im;
};

int rs_elastic3d_fft_size(int m)
{
  for (int s = m > 1 ? m : 1;; s++) {
    int r = s;
    while (r % 2 == 0) r /= 2;
    while (r % 3 == 0) r /= 3;
    while (r % 5 == 0) r /= 5;
    if (r == 1) return s;
  }
}

/* The padded grid's column count my >= m: the transforms along y are complex ones of
 * length my over every column (c2c, strided), and FFTW's estimated plans for those are slow
 * for some 5-smooth lengths; a power of two up to 1.5 times longer is then faster (at 44 x 44
 * cells the product transforms take half the time with 128 columns instead of 90; beyond 1.5
 * times the length the power of two loses). The products are exact linear convolutions for any my
 * >= m (the padding's values are never read), so the choice changes only their roundoff. */
static int column_size(int m)
{
  const int smooth = rs_elastic3d_fft_size(m);
  int pow2 = 1;
  while (pow2 < m) pow2 *= 2;
  return 2 * pow2 <= 3 * smooth ? pow2 : smooth;
}

void rs_elastic3d_planner_thread_safe(void) { fftw_make_planner_thread_safe(); }

void rs_elastic3d_fft_free(struct rs_elastic3d_fft *f)
{
  if (!f) return;
  if (f->forward) fftw_destroy_plan(f->forward);
  fftw_plan plans[4] = {f->rows_fwd, f->cols_fwd, f->cols_bwd, f->rows_bwd};
  for (int k = 0; k < 4; k++)
    if (plans[k]) fftw_destroy_plan(plans[k]);
  fftw_free(f->kxx);
  fftw_free(f->kxy);
  fftw_free(f->kyy);
  fftw_free(f->kzz);
  fftw_free(f->kxy_im);
  free(f);
}

struct rs_elastic3d_fft *rs_elastic3d_fft_create(const rs_elastic3d *el)
{
  const int nx = el->nx, ny = el->ny;
  struct rs_elastic3d_fft *f = calloc(1, sizeof *f);
  if (!f) return NULL;
  f->mx = rs_elastic3d_fft_size(2 * nx);
  f->my = column_size(2 * ny - 1);
  f->ncx = f->mx / 2 + 1;
  const size_t nreal = (size_t)f->mx * (size_t)f->my, ncomplex = (size_t)f->my * (size_t)f->ncx;
  double *grid = fftw_alloc_real(nreal);
  fftw_complex *spec = fftw_alloc_complex(ncomplex);
  f->kxx = fftw_alloc_real(ncomplex);
  f->kxy = fftw_alloc_real(ncomplex);
  f->kyy = fftw_alloc_real(ncomplex);
  f->kzz = fftw_alloc_real(ncomplex);
  /* The offsets beyond the tables: the four coefficients of each |kx|, |ky| at once, by
   * one evaluation of the rectangle's integrals, which are even in kx and ky but for the
   * xy coefficient, odd in each (mirrored rectangles give mirrored values bit for bit:
   * rs_elastic3d_rect), so each distinct |kx|, |ky| is evaluated once. */
  const int hx = f->mx / 2 + 1, hy = f->my / 2 + 1;
  double(*outside)[4] = malloc((size_t)hx * (size_t)hy * sizeof *outside);
  int ok = grid && spec && f->kxx && f->kxy && f->kyy && f->kzz && outside;
  for (int ay = 0; ok && ay < hy; ay++)
    for (int ax = 0; ax < hx; ax++)
      if (ax > nx || ay > ny - 1)
        rs_elastic3d_rect(el->dx, el->dy, ax * el->dx, ay * el->dy, el->shear_modulus,
                          el->poisson_ratio, outside[(size_t)ay * (size_t)hx + (size_t)ax]);
  if (ok) {
    f->forward = fftw_plan_dft_r2c_2d(f->my, f->mx, grid, spec, FFTW_ESTIMATE);
    const int nrow = f->mx, ncol = f->my;
    f->rows_fwd = fftw_plan_many_dft_r2c(1, &nrow, ny, grid, NULL, 1, f->mx, spec, NULL, 1, f->ncx,
                                         FFTW_ESTIMATE);
    f->cols_fwd = fftw_plan_many_dft(1, &ncol, f->ncx, spec, NULL, f->ncx, 1, spec, NULL, f->ncx, 1,
                                     FFTW_FORWARD, FFTW_ESTIMATE);
    f->cols_bwd = fftw_plan_many_dft(1, &ncol, f->ncx, spec, NULL, f->ncx, 1, spec, NULL, f->ncx, 1,
                                     FFTW_BACKWARD, FFTW_ESTIMATE);
    f->rows_bwd = fftw_plan_many_dft_c2r(1, &nrow, ny, spec, NULL, 1, f->ncx, grid, NULL, 1, f->mx,
                                         FFTW_ESTIMATE);
    ok = f->forward && f->rows_fwd && f->cols_fwd && f->cols_bwd && f->rows_bwd;
  }
  for (int comp = 0; ok && comp < 4; comp++) {
    static const int ci[4] = {0, 0, 1, 2}, cj[4] = {0, 1, 1, 2};
    double *kernel = comp == 0 ? f->kxx : comp == 1 ? f->kxy : comp == 2 ? f->kyy : f->kzz;
    /* Index (qx, qy) holds the offset of minimal image kx in (-mx/2, mx/2], ky likewise.
     * The products read only the offsets of the tables, which are their own minimal
     * images (|kx| <= nx <= mx/2, |ky| <= ny-1 < my/2); the rest of the periodic grid is
     * never read by a product, and filling it with the kernel itself (not zeros) keeps
     * the circulant close to the half-space operator, positive definite for A_zz (see
     * rs_elastic3d_norm_lower_eigenvalue).
     * Every kernel is symmetric under (kx, ky) -> (-kx, -ky) (A_xx, A_yy, A_zz even in each,
     * A_xy odd in each), so its transform is real, and the products take two real
     * multiplications per frequency instead of a complex one. On a grid of even length the
     * Nyquist offset mx/2 (my/2) is its own mirror, where the odd A_xy must be 0 for the
     * symmetry: it is set so where no product reads it (my/2 > ny - 1 always; mx/2 > nx
     * unless mx = 2 nx, where the offset nx is read and A_xy keeps its imaginary parts). */
    for (int qy = 0; qy < f->my; qy++)
      for (int qx = 0; qx < f->mx; qx++) {
        const int kx = 2 * qx <= f->mx ? qx : qx - f->mx, ky = 2 * qy <= f->my ? qy : qy - f->my;
        const int ax = kx < 0 ? -kx : kx, ay = ky < 0 ? -ky : ky;
        const double sign = comp == 1 && (kx < 0) != (ky < 0) ? -1.0 : 1.0;
        const int nyquist = 2 * ax == f->mx || 2 * ay == f->my, table = ax <= nx && ay <= ny - 1;
        grid[(size_t)qy * (size_t)f->mx + (size_t)qx] =
            table                  ? rs_elastic3d_coef(el, ci[comp], cj[comp], kx, ky)
            : comp == 1 && nyquist ? 0.0
                                   : sign * outside[(size_t)ay * (size_t)hx + (size_t)ax][comp];
      }
    fftw_execute_dft_r2c(f->forward, grid, spec);
    double re = 0.0, im = 0.0;
    for (size_t q = 0; q < ncomplex; q++) {
      kernel[q] = creal(spec[q]) / (double)nreal;
      re = fmax(re, fabs(creal(spec[q])));
      im = fmax(im, fabs(cimag(spec[q])));
    }
    if (im > 1e-12 * re) { /* A_xy read at the Nyquist offset (above) */
      ok = comp == 1 && (f->kxy_im = fftw_alloc_real(ncomplex)) != NULL;
      for (size_t q = 0; ok && q < ncomplex; q++) f->kxy_im[q] = cimag(spec[q]) / (double)nreal;
    }
  }
  fftw_free(grid);
  fftw_free(spec);
  free(outside);
  if (!ok) {
    rs_elastic3d_fft_free(f);
    return NULL;
  }
  return f;
}

int rs_elastic3d_create(rs_elastic3d *el, int nx, int ny, double dx, double dy,
                        double shear_modulus, double poisson_ratio, rs_msg *msg)
{
  el->xx = el->xy = el->yy = el->zz = NULL;
  el->fft = NULL;
  if (nx < 1 || ny < 1 || nx > 16384 || ny > 16384)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "3D elastic grid: %d x %d cells (each side needs 1 to 16384 cells)", nx, ny);
  if (!(dx > 0.0) || !(dy > 0.0) || !isfinite(dx) || !isfinite(dy))
    return rs_msg_set(msg, RS_ERR_INPUT, "3D elastic grid: cell size %g x %g mm (must be > 0)", dx,
                      dy);
  if (!(shear_modulus > 0.0) || !isfinite(shear_modulus))
    return rs_msg_set(msg, RS_ERR_INPUT, "shear modulus %g N/mm^2 (must be > 0)", shear_modulus);
  if (!(poisson_ratio > -1.0 && poisson_ratio <= 0.5))
    return rs_msg_set(msg, RS_ERR_INPUT, "Poisson ratio %g (must be in (-1, 0.5])", poisson_ratio);
  el->nx = nx;
  el->ny = ny;
  el->dx = dx;
  el->dy = dy;
  el->shear_modulus = shear_modulus;
  el->poisson_ratio = poisson_ratio;
  const size_t count = (size_t)(nx + 1) * (size_t)ny;
  el->xx = malloc(count * sizeof *el->xx);
  el->xy = malloc(count * sizeof *el->xy);
  el->yy = malloc(count * sizeof *el->yy);
  el->zz = malloc(count * sizeof *el->zz);
  if (!el->xx || !el->xy || !el->yy || !el->zz) {
    rs_elastic3d_free(el);
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "out of memory for the 3D influence coefficients "
                      "(%d x %d cells)",
                      nx, ny);
  }
  for (int ky = 0; ky < ny; ky++)
    for (int kx = 0; kx <= nx; kx++) {
      double c[4];
      rs_elastic3d_rect(dx, dy, kx * dx, ky * dy, shear_modulus, poisson_ratio, c);
      const size_t at = (size_t)ky * (size_t)(nx + 1) + (size_t)kx;
      el->xx[at] = c[0];
      el->xy[at] = c[1];
      el->yy[at] = c[2];
      el->zz[at] = c[3];
    }
  if (!(el->fft = rs_elastic3d_fft_create(el))) {
    rs_elastic3d_free(el);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not set up the 3D FFT products (%d x %d cells)",
                      nx, ny);
  }
  return RS_OK;
}

void rs_elastic3d_free(rs_elastic3d *el)
{
  free(el->xx);
  free(el->xy);
  free(el->yy);
  free(el->zz);
  rs_elastic3d_fft_free(el->fft);
  el->xx = el->xy = el->yy = el->zz = NULL;
  el->fft = NULL;
}

int rs_elastic3d_work_create(rs_elastic3d_work *work, const rs_elastic3d *el, rs_msg *msg)
{
  const struct rs_elastic3d_fft *f = el->fft;
  work->mx = f->mx;
  work->my = f->my;
  work->threads = 1;
  work->grid = fftw_alloc_real((size_t)f->mx * (size_t)f->my);
  work->grid2 = fftw_alloc_real((size_t)f->mx * (size_t)f->my);
  work->spectrum[0] = fftw_alloc_complex((size_t)f->my * (size_t)f->ncx);
  work->spectrum[1] = fftw_alloc_complex((size_t)f->my * (size_t)f->ncx);
  if (!work->grid || !work->grid2 || !work->spectrum[0] || !work->spectrum[1]) {
    rs_elastic3d_work_free(work);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the 3D FFT work (%d x %d)", f->mx,
                      f->my);
  }
  return RS_OK;
}

void rs_elastic3d_work_free(rs_elastic3d_work *work)
{
  fftw_free(work->grid);
  fftw_free(work->grid2);
  fftw_free(work->spectrum[0]);
  fftw_free(work->spectrum[1]);
  work->grid = work->grid2 = NULL;
  work->spectrum[0] = work->spectrum[1] = NULL;
}

/* p (nx x ny, row length nx) into the first ny rows of the work grid (zero beyond nx),
 * then the forward transform: rows, the spectrum's other rows zero, columns. */
static void transform_in(const struct rs_elastic3d_fft *f, const rs_elastic3d *el, double *grid,
                         const double *p, fftw_complex *spec)
{
  for (int iy = 0; iy < el->ny; iy++) {
    double *row = grid + (size_t)iy * (size_t)f->mx;
    memcpy(row, p + (size_t)iy * (size_t)el->nx, (size_t)el->nx * sizeof *p);
    memset(row + el->nx, 0, (size_t)(f->mx - el->nx) * sizeof *row);
  }
  fftw_execute_dft_r2c(f->rows_fwd, grid, spec);
  memset(spec + (size_t)el->ny * (size_t)f->ncx, 0,
         (size_t)(f->my - el->ny) * (size_t)f->ncx * sizeof *spec);
  fftw_execute_dft(f->cols_fwd, spec, spec);
}

/* Backward transform (destroys spec): columns, then the first ny rows; their first nxout
 * columns into u. */
static void transform_out(const struct rs_elastic3d_fft *f, const rs_elastic3d *el, double *grid,
                          fftw_complex *spec, double *u, int nxout)
{
  fftw_execute_dft(f->cols_bwd, spec, spec);
  fftw_execute_dft_c2r(f->rows_bwd, spec, grid);
  for (int iy = 0; iy < el->ny; iy++)
    memcpy(u + (size_t)iy * (size_t)nxout, grid + (size_t)iy * (size_t)f->mx,
           (size_t)nxout * sizeof *u);
}

void rs_elastic3d_apply_tang(const rs_elastic3d *el, rs_elastic3d_work *work, const double *px,
                             const double *py, double *ux, double *uy, int nxout)
{
  const struct rs_elastic3d_fft *f = el->fft;
  fftw_complex *sx = work->spectrum[0], *sy = work->spectrum[1];
  const size_t ncomplex = (size_t)f->my * (size_t)f->ncx;
  /* The two components' transforms side by side when work->threads asks for two
   * (solver.threads; FFTW's new-array execute functions may run one plan in two threads at
   * once); each thread computes what one thread would, so the results do not depend on it. */
#pragma omp parallel num_threads(rs_threads(work->threads))
  {
#pragma omp sections
    {
#pragma omp section
      transform_in(f, el, work->grid, px, sx);
#pragma omp section
      transform_in(f, el, work->grid2, py, sy);
    }
    /* (u_x, u_y)^ = [A_xx A_xy; A_xy A_yy]^ (p_x, p_y)^ per frequency: real kernels times
     * the spectra's real and imaginary parts */
    if (!f->kxy_im) {
#pragma omp for schedule(static)
      for (size_t q = 0; q < ncomplex; q++) {
        const double ar = creal(sx[q]), ai = cimag(sx[q]), br = creal(sy[q]), bi = cimag(sy[q]);
        const double xx = f->kxx[q], xy = f->kxy[q], yy = f->kyy[q];
        sx[q] = (xx * ar + xy * br) + I * (xx * ai + xy * bi);
        sy[q] = (xy * ar + yy * br) + I * (xy * ai + yy * bi);
      }
    } else { /* A_xy complex: (x + iy)(u + iv) = (xu - yv) + i(xv + yu) for its terms */
#pragma omp for schedule(static)
      for (size_t q = 0; q < ncomplex; q++) {
        const double ar = creal(sx[q]), ai = cimag(sx[q]), br = creal(sy[q]), bi = cimag(sy[q]);
        const double xx = f->kxx[q], xy = f->kxy[q], xyi = f->kxy_im[q], yy = f->kyy[q];
        sx[q] = (xx * ar + (xy * br - xyi * bi)) + I * (xx * ai + (xy * bi + xyi * br));
        sy[q] = ((xy * ar - xyi * ai) + yy * br) + I * ((xy * ai + xyi * ar) + yy * bi);
      }
    }
#pragma omp sections
    {
#pragma omp section
      transform_out(f, el, work->grid, sx, ux, nxout);
#pragma omp section
      transform_out(f, el, work->grid2, sy, uy, nxout);
    }
  }
}

void rs_elastic3d_apply_norm(const rs_elastic3d *el, rs_elastic3d_work *work, const double *pn,
                             double *uz, int nxout)
{
  const struct rs_elastic3d_fft *f = el->fft;
  fftw_complex *s = work->spectrum[0];
  transform_in(f, el, work->grid, pn, s);
  const size_t ncomplex = (size_t)f->my * (size_t)f->ncx;
  for (size_t q = 0; q < ncomplex; q++)
    s[q] = f->kzz[q] * creal(s[q]) + I * (f->kzz[q] * cimag(s[q]));
  transform_out(f, el, work->grid, s, uz, nxout);
}

double rs_elastic3d_norm_lower_eigenvalue(const rs_elastic3d *el)
{
  /* The transform (real: the kernel is symmetric) gives the circulant's eigenvalues; the
   * half-spectrum of a real kernel holds all of them. */
  const struct rs_elastic3d_fft *f = el->fft;
  const size_t ncomplex = (size_t)f->my * (size_t)f->ncx;
  double low = INFINITY;
  for (size_t q = 0; q < ncomplex; q++) low = fmin(low, f->kzz[q]);
  return low * (double)f->mx * (double)f->my;
}
