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
  /* twin-disc rig (docs/model.md §18, "Twin-disc rig"): the surface's convective loss to the
   * disc's bulk temperature between contacts, W/(mm^2 K) (0: none), and each disc's mass for
   * its lumped bulk temperature, kg (0: that bulk temperature held) */
  double convection;
  double disc_mass[2];
  /* not a case key: the longest path length the kernel must cover, mm (0: the grid's length;
   * a rig's run: the distance rolled over the run) */
  double path_max;
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
  double *inv_gain; /* 1/gain_full, then 1/dx for the mode of rate 0 (1/mm) [nmodes + 1] */
  double self_half; /* the step response of half a cell, sqrt(mm) */
  double *theta;    /* scratch: the modes of both bodies [2 (nmodes + 1)] */
  /* Twin-disc rig (rs_thermal_rig_attach; all NULL otherwise: material enters at its bulk
   * temperature): the modes leaving the trailing cells recorded in `memory` (per body, mode
   * and row: [(b (nmodes + 1) + k) ny + iy]), re-entering after each disc's delay through the
   * transfer matrix of its free path, transfer[b][j][k] (row j: the entering mode j). */
  const struct rs_rig_memory *memory;
  double *transfer; /* [2][nmodes + 1][nmodes + 1] */
  double *inflow;   /* the modes entering the leading cells, laid out as in memory */
  double *exit_buf; /* scratch [2 (nmodes + 1) ny] */
} rs_thermal;

/* Kernel fitted to the path lengths of the grid: half a cell to the whole path. */
int rs_thermal_create(rs_thermal *th, const rs_thermal_params *p, int nx, int ny, double dx,
                      double area, rs_msg *msg);
void rs_thermal_free(rs_thermal *th);

/* A twin-disc rig's heat memory (docs/model.md §18, "Twin-disc rig"): the modes leaving the
 * grid (recorded by the caller in mem, width 2 (nmodes + 1) ny, delays those of the discs)
 * re-enter at the leading edge after the free path path[b] (mm) of disc b, each decayed over
 * it by e^(-rate_k path) (pure conduction into the depth), or with par.convection > 0 marched
 * over the path under the surface loss h (T - T_bulk) at rolling velocity V > 0. */
struct rs_rig_memory;
int rs_thermal_rig_attach(rs_thermal *th, const struct rs_rig_memory *mem, const double path[2],
                          double V, rs_msg *msg);
/* The modes entering at time t (s) into th->inflow (nothing without a rig). */
void rs_thermal_inflow_at(rs_thermal *th, double t);
/* The mean over the rows of each body's surface temperature entering the contact (degC), from
 * th->inflow as set by rs_thermal_inflow_at, at rolling velocity V > 0. */
void rs_thermal_inlet_temperature(const rs_thermal *th, double V, double T[2]);

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

/* The modes as state of the transient DAE (docs/model.md §18, "Heat memory"): per body b,
 * mode k (the nmodes decaying ones, then the mode of rate 0) and cell I the mode leaving the
 * cell at its downstream edge, stored by blocks, cells inside a block:
 *   state[(b (nmodes + 1) + k) n + I],   rs_thermal_nstate values.
 * Each obeys theta' = c_k (theta_out - theta), c_k = V rate_k/(1 - e^(-rate_k dx)) (V/dx for
 * the mode of rate 0), theta_out the exact step of the march from the modes of the upstream
 * cell (0 at the leading edge: material enters at its bulk temperature) under the cell's
 * share q_b of the heat, the partition T1 = T2 solved in closed form per cell: the first-order
 * upwind material derivative, exponentially fitted so that its steady state is the march.
 * With V <= 0 the modes are frozen (theta' = 0). */
static inline int rs_thermal_nstate(const rs_thermal *th)
{
  return 2 * (th->ker.nmodes + 1) * th->nx * th->ny;
}
/* The march that also stores its modes in state (the DAE's steady state). */
void rs_thermal_march_state(rs_thermal *th, double V, const double *q, const signed char *contact,
                            double *T1, double *T2, double *q1, double *q2, rs_thermal_result *res,
                            double *state);
/* The temperatures, shares and result of the DAE state `state` under the sources q: each
 * cell as in the march, with the modes entering it taken from the state upstream. */
void rs_thermal_state_eval(rs_thermal *th, double V, const double *q, const signed char *contact,
                           const double *state, double *T1, double *T2, double *q1, double *q2,
                           rs_thermal_result *res);
/* The DAE's rows F = theta' - f(theta) at (state, rate) [rs_thermal_nstate]. */
void rs_thermal_dae_residual(rs_thermal *th, double V, const double *q, const signed char *contact,
                             const double *state, const double *rate, double *F);
/* theta' = f(theta): the consistent rates of a state. */
void rs_thermal_dae_rates(rs_thermal *th, double V, const double *q, const signed char *contact,
                          const double *state, double *rate);
/* A BDF step's rows solved exactly: the correction cor with state = pred + cor and
 * theta' = ratepred + cj cor zeroing the rows, one pass from the leading edge (each cell's
 * rows are linear in its own modes given those upstream). */
void rs_thermal_dae_solve(rs_thermal *th, double V, const double *q, const signed char *contact,
                          double cj, const double *pred, const double *ratepred, double *state,
                          double *cor);

/* Body 1's surface temperature at each cell centre read from the DAE state alone (degC, T [n]):
 * the modes entering the cell decayed over half a cell, plus the cell's own flux q_1 taken from
 * its modes of rate 0 (leaving minus entering, over dx) through the half-cell step response. At
 * a steady state (the march) that is the march's T1; in a transient it follows the heat through
 * the modes' relaxation, not instantaneously (docs/model.md §18, "Couplings"). V > 0. */
void rs_thermal_state_temperature(rs_thermal *th, double V, const double *state, double *T);

/* The heat sources of a contact evaluation (w evaluated at y: rs_model_residual or the
 * diagnostics): the power densities fric, plast (N/(mm s)) of rs_model_power_densities,
 * q = 1e-3 (fric + beta_pl plast) W/mm^2 and contact = p_n > 0, per cell. */
struct rs_model;
struct rs_work;
void rs_thermal_sources(const rs_thermal *th, const struct rs_model *m, const struct rs_work *w,
                        const double *y, double *fric, double *plast, double *q,
                        signed char *contact);

#endif
