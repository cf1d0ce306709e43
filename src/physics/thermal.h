/* Surface temperature of the two bodies (docs/model.md §18): flash temperature from the
 * frictional and plastic heat of a converged contact solution, one-way coupled (the
 * temperature does not act back on the contact). Each body is a half-space moving through
 * the contact at the rolling velocity; along each material path the surface temperature is
 *   T = T_bulk + 1/(beta sqrt(pi)) int q(s)/sqrt(t - s) ds,   beta = sqrt(lambda rho c),
 * the 1D conduction into depth (conduction along the surface neglected: high Peclet number).
 * The kernel 1/sqrt(pi t) is a sum of exponentials, so the integral is carried by a few
 * modes per body marched cell by cell from the leading edge. Units: W, mm, s, K (degC). */
#ifndef ROLLSIM_THERMAL_H
#define ROLLSIM_THERMAL_H

#include "base/status.h"

/* The temperature: block of a case (docs/case-file.md). Index 0 is body 1 (the upper body,
 * the one p acts on), 1 body 2. */
typedef struct rs_thermal_params {
  int on;                       /* 0: no temperature (the block is absent) */
  double bulk[2];               /* degC */
  double conductivity[2];       /* lambda, W/(mm K) */
  double heat_capacity[2];      /* c, J/(kg K) */
  double density[2];            /* rho, kg/mm^3 */
  double plastic_heat_fraction; /* share of the plastic power turned into heat, [0, 1] */
  double kernel_tolerance;      /* relative error allowed in the kernel's step response */
} rs_thermal_params;

/* 1/sqrt(pi l) ~ sum_k weight_k exp(-rate_k l) + weight0 (a mode that does not decay) + a
 * local part, over the path length l (mm): the trapezoidal rule of
 *   1/sqrt(pi l) = (1/pi) int exp(u/2 - e^u l) du
 * on nodes u_k = ln rate_k spaced `step` apart, its two infinite tails summed in closed form
 * (the slow modes below the first node as one mode of rate 0, the fast ones above the last
 * as an instantaneous response). Built so that the step response
 *   S(l) = int_0^l 1/sqrt(pi s) ds = 2 sqrt(l/pi)
 * is met to a relative `error` <= the tolerance for l in [l_min, l_max]. */
typedef struct rs_thermal_kernel {
  int nmodes;
  double *weight; /* 1/sqrt(mm) [nmodes] */
  double *rate;   /* 1/mm [nmodes] */
  double weight0; /* 1/sqrt(mm): the mode of rate 0 */
  double local;   /* sqrt(mm): the instantaneous part of the step response */
  double step;    /* spacing of ln rate */
  double l_min, l_max;
  double error; /* max relative error of the step response over [l_min, l_max] */
} rs_thermal_kernel;

/* RS_ERR_INPUT for tol outside (0, 0.1] or a range not 0 < l_min < l_max. */
int rs_thermal_kernel_create(rs_thermal_kernel *k, double l_min, double l_max, double tol,
                             rs_msg *msg);
void rs_thermal_kernel_free(rs_thermal_kernel *k);
/* The kernel's step response at l >= 0 (mm^(1/2)); exact: 2 sqrt(l/pi). */
double rs_thermal_kernel_step(const rs_thermal_kernel *k, double l);

/* The march over a grid of nx x ny cells of length dx along x (rows are material paths;
 * material enters at the high-x end, docs/model.md §1). */
typedef struct rs_thermal {
  rs_thermal_params par;
  double beta[2]; /* sqrt(lambda rho c), W s^(1/2)/(mm^2 K) */
  int nx, ny;
  double dx;   /* mm */
  double area; /* cell area, mm^2 (2D: dx, per mm of width) */
  rs_thermal_kernel ker;
  /* per mode: decay over half a cell and over a cell, and the integral of the decay over
   * them (mm) */
  double *decay_half, *decay_full, *gain_full;
  double self_half; /* the step response of half a cell, sqrt(mm) */
  double *theta;    /* scratch: the modes of both bodies [2 (nmodes + 1)] */
} rs_thermal;

/* Kernel fitted to the path lengths of the grid: half a cell to the whole path. */
int rs_thermal_create(rs_thermal *th, const rs_thermal_params *p, int nx, int ny, double dx,
                      double area, rs_msg *msg);
void rs_thermal_free(rs_thermal *th);

/* What the march reports: the hottest surface point and the heat flowing into each body. */
typedef struct rs_thermal_result {
  /* degC, the largest surface temperature in the contact (T1 = T2 there; outside it the
   * surfaces take their bulk temperatures ahead and relax towards them behind); NaN without
   * contact */
  double T_max;
  double heat_input[2]; /* W (2D: W per mm of width): sum of q_i dA */
} rs_thermal_result;

/* Surface temperatures at the cell centres for the heat flux density q (W/mm^2, per cell,
 * generated in the interface) at rolling velocity V > 0 (mm/s). In a cell of the contact
 * (contact[i] != 0) the two surfaces are in perfect thermal contact, T1 = T2, and
 * q1 + q2 = q: one 2x2 solve per cell. Outside the contact q1 = q2 = 0 and each surface
 * cools on its own. q1, q2 may be NULL. With V <= 0 (no material path) every output is NaN. */
void rs_thermal_march(rs_thermal *th, double V, const double *q, const signed char *contact,
                      double *T1, double *T2, double *q1, double *q2, rs_thermal_result *res);

#endif
