/* Internal to the normal-problem module (model.md §3):
 *   normal.c     Hertz formulas, the start estimate, the dense active-set method and
 *                the choice between the methods (rs_normal2d_solve_with)
 *   normal_cg.c  the constrained conjugate-gradient method with FFT products */
#ifndef ROLLSIM_NORMAL_INTERNAL_H
#define ROLLSIM_NORMAL_INTERNAL_H

#include "rollsim/normal.h"

/* Half-width of the Hertz contact estimated from the influence coefficients
 * themselves (their far field A(k) ~ -K dx ln|k dx| + const gives the compliance K),
 * a = sqrt(2 q R K); INFINITY when it cannot be estimated (tiny grid, load <= 0). */
double rs_normal2d_start_width(const rs_elastic2d *el, double radius, double load);

/* The gap of the undeformed profiles at the cell centres x (the parabola x^2 / 2R of
 * the Hertz contact) into h[n]; returns max h. */
double rs_normal2d_profile(const double *x, int n, double radius, double *h);

/* The two methods behind rs_normal2d_solve_with (same arguments and outputs). */
int rs_normal2d_solve_direct(const rs_elastic2d *el, const double *x, double radius, double load,
                             double *pn, double *delta, int *iterations, rs_msg *msg);
int rs_normal2d_solve_cg(const rs_elastic2d *el, const double *x, double radius, double load,
                         double *pn, double *delta, int *iterations, rs_msg *msg);

#endif
