/* 2D normal contact problem on the grid (model.md §3): find p_n >= 0 and the
 * approach delta with gap h - delta + A_zz p_n >= 0, complementarity, and
 * sum p_n dx = load. h(x) = x^2/(2R). Hertz line contact is the check:
 * a = sqrt(4 q R (1-nu)/(pi G)), p0 = 2q/(pi a). */
#ifndef ROLLSIM_NORMAL_H
#define ROLLSIM_NORMAL_H

#include "rollsim/elastic.h"
#include "rollsim/status.h"

/* Hertz half-width a (mm) and peak pressure p0 (N/mm^2) of a 2D line contact. */
void rs_hertz2d(double load, double radius, double shear_modulus, double poisson_ratio,
                double *a, double *p0);

/* Discrete solution by an active-set method with dense LU (LAPACK dgesv) on the
 * contact cells. x: cell centres [n]; pn: result [n]; delta: approach (may be NULL);
 * iterations: active-set iterations used (may be NULL). */
int rs_normal2d_solve(const rs_elastic2d *el, const double *x, double radius, double load,
                      double *pn, double *delta, int *iterations, rs_msg *msg);

/* Analytic Hertz pressure at the cell centres. */
void rs_normal2d_hertz(const double *x, int n, double a, double p0, double *pn);

#endif
