/* Elastic influence coefficients of the 2D (plane-strain) half-plane for
 * quasi-identical bodies, piecewise-constant tractions on equal cells (docs/model.md §2).
 *
 *   u_x(x) = 1/(pi G) Int [ 2(1-nu) ln(L/|x-s|) + 2 nu ] p_x(s) ds
 *   u_z(x) = 1/(pi G) Int   2(1-nu) ln(L/|x-s|)        p_n(s) ds
 *
 * The displacement at the centre of cell I due to unit traction on cell J depends
 * on k = I - J only (Toeplitz). Cell integrals in closed form with
 * Int ln|s| ds = s ln|s| - s. */
#ifndef ROLLSIM_ELASTIC_H
#define ROLLSIM_ELASTIC_H

#include "base/status.h"

#define RS_PI 3.14159265358979323846

typedef struct rs_elastic2d {
  int n;                      /* cells of the contact grid */
  double dx;                  /* cell width, mm */
  double *tang;               /* tangential coefficient for k = -n..n at tang[k + n], mm/(N/mm^2) */
  double *norm;               /* normal coefficient, same layout */
  struct rs_elastic_fft *fft; /* FFT plans and transformed kernels on large grids (NULL:
                                 direct sums); read-only after creation */
} rs_elastic2d;

/* Scratch of the FFT products (one per thread of evaluation): apply never writes
 * through a const rs_elastic2d. Empty (no allocation) for grids below the FFT size. */
typedef struct rs_elastic2d_work {
  double *in; /* [M] */
  void *out;  /* fftw_complex [M/2 + 1] */
} rs_elastic2d_work;
int rs_elastic2d_work_create(rs_elastic2d_work *w, const rs_elastic2d *el);
void rs_elastic2d_work_free(rs_elastic2d_work *w);

/* Grids from this many cells apply the influence coefficients by FFT convolution
 * (FFTW) instead of the direct O(n^2) sum (the crossover, bench/normal_timing.c). */
#define RS_ELASTIC_FFT_FROM 256

/* Coefficients for offsets -n..n (the offset n serves the padded point x_n, one
 * cell beyond the leading edge, docs/model.md §5). */
int rs_elastic2d_create(rs_elastic2d *el, int n, double dx, double shear_modulus,
                        double poisson_ratio, double reference_length, rs_msg *msg);
void rs_elastic2d_free(rs_elastic2d *el);

/* Coefficient for offset k = I - J, |k| <= n. */
static inline double rs_elastic2d_tang(const rs_elastic2d *el, int k)
{
  return el->tang[k + el->n];
}
static inline double rs_elastic2d_norm(const rs_elastic2d *el, int k)
{
  return el->norm[k + el->n];
}

/* u[I] = sum_J coef(I - J) p[J] for I = 0..nout-1 (nout <= n + 1), p of length n.
 * With coef_table el->tang or el->norm on a grid of RS_ELASTIC_FFT_FROM cells or
 * more, by FFT convolution in the buffers of w (the same sum up to roundoff). */
void rs_elastic2d_apply(const rs_elastic2d *el, rs_elastic2d_work *w, const double *coef_table,
                        const double *p, double *u, int nout);

#endif
