/* 2D normal contact problem on the grid (docs/model.md §3): find p_n >= 0 and the
 * approach delta with gap h - delta + A_zz p_n >= 0, complementarity, and
 * sum p_n dx = load, for the undeformed gap h at the cell centres (the model's is
 * x^2/(2R), rs_normal2d_profile). Hertz line contact is the check:
 * a = sqrt(4 q R (1-nu)/(pi G)), p0 = 2q/(pi a). */
#ifndef ROLLSIM_NORMAL_H
#define ROLLSIM_NORMAL_H

#include <math.h>

#include "physics/elastic2d.h"
#include "physics/elastic_op.h"
#include "base/status.h"

/* Hertz half-width a (mm) and peak pressure p0 (N/mm^2) of a 2D line contact. */
static inline void rs_hertz2d(double load, double radius, double shear_modulus,
                              double poisson_ratio, double *a, double *p0)
{
  *a = sqrt(4.0 * load * radius * (1.0 - poisson_ratio) / (RS_PI * shear_modulus));
  *p0 = 2.0 * load / (RS_PI * *a);
}

/* Methods for the discrete problem; both give the same solution (up to roundoff).
 * DIRECT: active-set method with dense LU (LAPACK dgesv) on the contact cells,
 *   O(m^3) per active-set iteration; iterations = active-set iterations.
 * CG: conjugate gradients on the contact cells with the load as a constraint and
 *   cells entering and leaving during the iteration (Polonsky & Keer 1999), products
 *   A p by rs_elastic2d_apply (FFT from RS_ELASTIC_FFT_FROM cells); iterations = CG
 *   iterations. Needs load > 0.
 * AUTO: CG from RS_NORMAL2D_CG_FROM cells (and load > 0), DIRECT below. */
typedef enum { RS_NORMAL2D_AUTO = 0, RS_NORMAL2D_DIRECT, RS_NORMAL2D_CG } rs_normal2d_method;

/* The crossover is where the products become FFT convolutions. Below it each CG
 * product is a direct O(n^2) sum and CG loses to one dense solve (it wins where the
 * active set takes two); from it CG wins by far (bench/normal_timing.c). */
#define RS_NORMAL2D_CG_FROM RS_ELASTIC_FFT_FROM

/* Discrete solution. h: undeformed gap at the cell centres [n] (mm); w: the FFT scratch
 * of el; pn: result [n]; delta: approach (may be NULL); iterations: iterations used (may
 * be NULL; see rs_normal2d_method). */
int rs_normal2d_solve_with(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h,
                           double load, rs_normal2d_method method, double *pn, double *delta,
                           int *iterations, rs_msg *msg);
/* rs_normal2d_solve_with(..., RS_NORMAL2D_AUTO, ...). */
int rs_normal2d_solve(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h, double load,
                      double *pn, double *delta, int *iterations, rs_msg *msg);

/* The gap of two parabolic profiles, x^2 / 2R, at the cell centres x into h[n]. */
void rs_normal2d_profile(const double *x, int n, double radius, double *h);

/* The normal problem on a grid for its elastic operator and the undeformed gap h at the
 * cell centres: p_n >= 0 and the approach delta with h - delta + A_zz p_n >= 0,
 * complementarity, sum p_n area = load (2D: rs_normal2d_solve). */
int rs_normal_solve(const rs_elastic_op *op, rs_elastic_work *w, const double *h, double load,
                    double *pn, double *delta, rs_msg *msg);

/* Analytic Hertz pressure at the cell centres. */
void rs_normal2d_hertz(const double *x, int n, double a, double p0, double *pn);

#endif
