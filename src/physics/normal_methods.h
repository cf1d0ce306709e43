/* Internal to the normal-problem module (docs/model.md §3):
 *   normal.c     Hertz formulas, the start estimate, the dense active-set method and
 *                the choice between the methods (rs_normal2d_solve_with)
 *   normal2d_cg.c  the constrained conjugate-gradient method (normal_cg.c, any dimension)
 *                  on the line kernel with FFT products */
#ifndef ROLLSIM_NORMAL_METHODS_H
#define ROLLSIM_NORMAL_METHODS_H

#include <math.h>

#include "physics/normal.h"

/* The start of both methods: the Hertz contact estimated from the influence
 * coefficients themselves (their far field A(k) ~ -K dx ln|k dx| + const gives the
 * compliance K): for a parabolic gap h = x^2/2R the Hertz half-width is
 * a = sqrt(2 q R K), i.e. the contact is where h < q K, with the pressure shape
 * sqrt(1 - h/(q K)). Returns q K, the gap at the estimated contact edge (INFINITY
 * when it cannot be estimated: tiny grid, load <= 0). */
static inline double rs_normal2d_start_gap(const rs_elastic2d *el, double load)
{
  /* K = 2(1-nu)/(pi G) read off the far field of the coefficients
   * (A(k) ~ -K dx ln|k dx| + const). */
  const int n = el->n;
  if (n < 8 || !(load > 0.0)) return INFINITY;
  const double K =
      (rs_elastic2d_norm(el, n / 4) - rs_elastic2d_norm(el, n / 2)) / (el->dx * log(2.0));
  return K > 0.0 ? load * K : INFINITY;
}

/* The two methods behind rs_normal2d_solve_with (same arguments and outputs). */
int rs_normal2d_solve_direct(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h,
                             double load, double *pn, double *delta, int *iterations, rs_msg *msg);
int rs_normal2d_solve_cg(const rs_elastic2d *el, rs_elastic2d_work *w, const double *h, double load,
                         double *pn, double *delta, int *iterations, rs_msg *msg);

#endif
