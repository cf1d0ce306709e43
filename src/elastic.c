/* 2D plane-strain influence coefficients, piecewise-constant tractions (model.md §2;
 * Johnson 1985, ch. 2; Kalker 1990, ch. 1). */
#include "rollsim/elastic.h"

#include <math.h>
#include <stdlib.h>

/* Primitive of ln|s|: s ln|s| - s, with the limit 0 at s = 0. */
static double ln_primitive(double s)
{
  return s == 0.0 ? 0.0 : s * log(fabs(s)) - s;
}

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
  return RS_OK;
}

void rs_elastic2d_free(rs_elastic2d *el)
{
  free(el->tang);
  free(el->norm);
  el->tang = el->norm = NULL;
}

void rs_elastic2d_apply(const rs_elastic2d *el, const double *coef_table, const double *p,
                        double *u, int nout)
{
  const int n = el->n;
  int nonzero = 0;
  for (int j = 0; j < n && !nonzero; j++) nonzero = p[j] != 0.0;
  if (!nonzero) { /* e.g. the rates in steady rolling */
    for (int i = 0; i < nout; i++) u[i] = 0.0;
    return;
  }
  for (int i = 0; i < nout; i++) {
    const double *row = coef_table + i + n; /* row[-j] = coef(i - j) */
    double sum = 0.0;
    for (int j = 0; j < n; j++) sum += row[-j] * p[j];
    u[i] = sum;
  }
}
