/* Gauss-Legendre rules for the tests' reference integrals (Golub & Welsch 1969: the
 * nodes are the eigenvalues of the symmetric tridiagonal Jacobi matrix of the Legendre
 * recurrence, the weights 2 v_0^2 from the normalised eigenvectors; LAPACK dstev). */
#ifndef ROLLSIM_TEST_QUADRATURE_H
#define ROLLSIM_TEST_QUADRATURE_H

#include <math.h>
#include <stdlib.h>

extern void dstev_(const char *jobz, const int *n, double *d, double *e, double *z, const int *ldz,
                   double *work, int *info);

/* n-point rule on [-1, 1] into node[n], weight[n]; returns 0 on success. */
static inline int tq_gauss_legendre(int n, double *node, double *weight)
{
  double *off = malloc((size_t)n * sizeof *off);
  double *vec = malloc((size_t)n * (size_t)n * sizeof *vec);
  double *work = malloc((size_t)(2 * n) * sizeof *work);
  int info = -1;
  if (off && vec && work) {
    for (int k = 0; k < n; k++) {
      node[k] = 0.0;
      off[k] = (k + 1) / sqrt(4.0 * (k + 1) * (k + 1) - 1.0); /* beta_k = k/sqrt(4k^2-1) */
    }
    dstev_("V", &n, node, off, vec, &n, work, &info);
    for (int k = 0; k < n && info == 0; k++)
      weight[k] = 2.0 * vec[(size_t)k * n] * vec[(size_t)k * n];
  }
  free(off);
  free(vec);
  free(work);
  return info;
}

#endif
