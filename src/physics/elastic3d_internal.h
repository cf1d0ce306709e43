/* Internal to the 3D elastic module (physics/elastic3d.h):
 *   elastic3d.c      closed-form rectangle coefficients and direct sums
 *   elastic3d_fft.c  the operator: coefficient tables, FFT plans and transformed kernels,
 *                    work, products */
#ifndef ROLLSIM_ELASTIC3D_INTERNAL_H
#define ROLLSIM_ELASTIC3D_INTERNAL_H

#include "physics/elastic3d.h"

/* Plans and transformed kernels for the products on the padded mx x my grid. */
struct rs_elastic3d_fft;

/* Set up el->fft from the coefficient tables (NULL on failure: out of memory). */
struct rs_elastic3d_fft *rs_elastic3d_fft_create(const rs_elastic3d *el);
void rs_elastic3d_fft_free(struct rs_elastic3d_fft *fft);

/* Smallest 2^a 3^b 5^c >= m (FFTW's fast sizes). */
int rs_elastic3d_fft_size(int m);

#endif
