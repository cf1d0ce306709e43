/* 2D plane-strain influence coefficients, piecewise-constant tractions (docs/model.md §2;
 * Johnson 1985, ch. 2; Kalker 1990, ch. 1). */
#include "physics/elastic2d.h"

#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Linear convolution as a circular one of length M >= 2n: the kernel at offsets
 * -(n-1)..n wraps to distinct indices mod M. */
struct rs_elastic_fft {
  int M;
  double *in;                  /* [M]: plan-time buffer (the products use a work's) */
  fftw_complex *out;           /* [M/2 + 1] */
  fftw_complex *ktang, *knorm; /* transformed kernels, scaled by 1/M [M/2 + 1] */
  fftw_plan fwd, bwd;
};

static void fft_free(struct rs_elastic_fft *f)
{
  if (!f) return;
  if (f->fwd) fftw_destroy_plan(f->fwd);
  if (f->bwd) fftw_destroy_plan(f->bwd);
  fftw_free(f->in);
  fftw_free(f->out);
  fftw_free(f->ktang);
  fftw_free(f->knorm);
  free(f);
}

/* Smallest 2^a 3^b 5^c >= m (FFTW's fast sizes). */
static int fft_size(int m)
{
  for (int s = m;; s++) {
    int r = s;
    while (r % 2 == 0) r /= 2;
    while (r % 3 == 0) r /= 3;
    while (r % 5 == 0) r /= 5;
    if (r == 1) return s;
  }
}

static struct rs_elastic_fft *fft_create(const rs_elastic2d *el)
{
  const int n = el->n;
  struct rs_elastic_fft *f = calloc(1, sizeof *f);
  if (!f) return NULL;
  f->M = fft_size(2 * n + 2);
  const int M = f->M, nc = M / 2 + 1;
  f->in = fftw_alloc_real((size_t)M);
  f->out = fftw_alloc_complex((size_t)nc);
  f->ktang = fftw_alloc_complex((size_t)nc);
  f->knorm = fftw_alloc_complex((size_t)nc);
  if (!f->in || !f->out || !f->ktang || !f->knorm) goto fail;
  f->fwd = fftw_plan_dft_r2c_1d(M, f->in, f->out, FFTW_ESTIMATE);
  f->bwd = fftw_plan_dft_c2r_1d(M, f->out, f->in, FFTW_ESTIMATE);
  if (!f->fwd || !f->bwd) goto fail;
  for (int which = 0; which < 2; which++) {
    const double *coef = which ? el->norm : el->tang;
    fftw_complex *k = which ? f->knorm : f->ktang;
    memset(f->in, 0, (size_t)M * sizeof *f->in);
    for (int d = -(n - 1); d <= n; d++) f->in[(d + M) % M] = coef[d + n];
    fftw_execute(f->fwd);
    for (int q = 0; q < nc; q++) k[q] = f->out[q] / M;
  }
  return f;
fail:
  fft_free(f);
  return NULL;
}

/* Primitive of ln|s|: s ln|s| - s, with the limit 0 at s = 0. */
static double ln_primitive(double s) { return s == 0.0 ? 0.0 : s * log(fabs(s)) - s; }

int rs_elastic2d_create(rs_elastic2d *el, int n, double dx, double shear_modulus,
                        double poisson_ratio, double reference_length, rs_msg *msg)
{
  el->n = n;
  el->dx = dx;
  el->tang = malloc((size_t)(2 * n + 1) * sizeof *el->tang);
  el->norm = malloc((size_t)(2 * n + 1) * sizeof *el->norm);
  if (!el->tang || !el->norm) {
    rs_elastic2d_free(el);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for %d influence coefficients", n);
  }
  const double nu = poisson_ratio, c = 1.0 / (RS_PI * shear_modulus);
  const double h = 0.5 * dx;
  for (int k = -n; k <= n; k++) {
    const double s = k * dx;
    /* Int over the source cell of ln|x_I - xi| d xi = F(s + h) - F(s - h). */
    const double int_ln = ln_primitive(s + h) - ln_primitive(s - h);
    const double int_ln_l = dx * log(reference_length) - int_ln; /* Int ln(L/|.|) */
    el->norm[k + n] = c * 2.0 * (1.0 - nu) * int_ln_l;
    el->tang[k + n] = c * (2.0 * (1.0 - nu) * int_ln_l + 2.0 * nu * dx);
  }
  el->fft = NULL;
  if (n >= RS_ELASTIC_FFT_FROM && !(el->fft = fft_create(el))) {
    rs_elastic2d_free(el);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "could not set up the FFT products (%d cells)", n);
  }
  return RS_OK;
}

void rs_elastic2d_free(rs_elastic2d *el)
{
  free(el->tang);
  free(el->norm);
  fft_free(el->fft);
  el->tang = el->norm = NULL;
  el->fft = NULL;
}

int rs_elastic2d_work_create(rs_elastic2d_work *w, const rs_elastic2d *el)
{
  memset(w, 0, sizeof *w);
  if (!el->fft) return RS_OK;
  const int M = el->fft->M;
  w->in = fftw_alloc_real((size_t)M);
  w->out = fftw_alloc_complex((size_t)(M / 2 + 1));
  if (!w->in || !w->out) {
    rs_elastic2d_work_free(w);
    return RS_ERR_INTERNAL;
  }
  return RS_OK;
}

void rs_elastic2d_work_free(rs_elastic2d_work *w)
{
  fftw_free(w->in);
  fftw_free(w->out);
  memset(w, 0, sizeof *w);
}

void rs_elastic2d_apply(const rs_elastic2d *el, rs_elastic2d_work *w, const double *coef_table,
                        const double *p, double *u, int nout)
{
  const int n = el->n;
  int nonzero = 0;
  for (int j = 0; j < n && !nonzero; j++) nonzero = p[j] != 0.0;
  if (!nonzero) { /* e.g. the rates in steady rolling */
    for (int i = 0; i < nout; i++) u[i] = 0.0;
    return;
  }
  const struct rs_elastic_fft *f = el->fft;
  if (f && w->in && (coef_table == el->tang || coef_table == el->norm)) {
    const fftw_complex *k = coef_table == el->tang ? f->ktang : f->knorm;
    fftw_complex *out = w->out;
    memcpy(w->in, p, (size_t)n * sizeof *p);
    memset(w->in + n, 0, (size_t)(f->M - n) * sizeof *w->in);
    fftw_execute_dft_r2c(f->fwd, w->in, out);
    for (int q = 0; q < f->M / 2 + 1; q++) out[q] *= k[q];
    fftw_execute_dft_c2r(f->bwd, out, w->in);
    memcpy(u, w->in, (size_t)nout * sizeof *u);
    return;
  }
  for (int i = 0; i < nout; i++) {
    const double *row = coef_table + i + n; /* row[-j] = coef(i - j) */
    double s[4] = {0.0, 0.0, 0.0, 0.0};     /* independent partial sums: no add latency chain */
    int j = 0;
    for (; j + 4 <= n; j += 4)
      for (int k = 0; k < 4; k++) s[k] += row[-(j + k)] * p[j + k];
    for (; j < n; j++) s[0] += row[-j] * p[j];
    u[i] = (s[0] + s[1]) + (s[2] + s[3]);
  }
}
