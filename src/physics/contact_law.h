/* The contact law of one cell (docs/model.md §4, paper eqs. 7-10): the semismooth residual
 * of friction, plasticity and hardening and its local generalized Jacobian, from the
 * cell's local quantities. The model (physics/model.h) computes the local quantities
 * from the unknowns (kinematics) and chains the local Jacobian with their derivatives;
 * the same law serves the residual, the Jacobian, J v products, consistent rates,
 * state projection and diagnostics.
 *
 *   R_f  = p - proj_{|.| <= g}(p - r v_s)            friction (g = mu p_n)
 *   R_pl = p - proj_{|.| <= tau_c}(p + r Du_pl/Dt)   plasticity
 *   R_*  = r (Dustar/Dt - |Du_pl/Dt|)                   hardening
 * outside the contact (p_n = 0): R_f = p, R_pl = r Du_pl/Dt, R_* as above.
 * proj is the projection on the interval [-b, b] (2D, one component: a 1 x 1
 * generalized-Jacobian block) or the disk of radius b (3D: 2 x 2 blocks). */
#ifndef ROLLSIM_CONTACT_LAW_H
#define ROLLSIM_CONTACT_LAW_H

#include "physics/friction.h"

/* Local plasticity: yield limit tau_c = max(tau_c_min, tau_c0 + k_tau u*). */
typedef struct rs_plasticity {
  int on;        /* 0: elastic (tau_c infinite) */
  double tau_c0; /* N/mm^2 */
  double k_tau;  /* N/mm^3 */
  double tau_c_min;
} rs_plasticity;

/* The yield limit sees u* >= 0 only: u* never decreases along the material path and
 * enters at >= 0, so a solution has u* >= 0 everywhere, but a Newton iterate can have
 * u* < 0 (the linearised |Du_pl/Dt| with the wrong sign). Without the clamp such an
 * iterate lowers tau_c towards the floor, every slipping cell then "yields", and the
 * active set jumps wildly (Newton then fails to converge on plastic Carter cases). */
double rs_yield_limit(const rs_plasticity *pl, double ustar);
/* d tau_c / d u*: k_tau above the floor and for u* >= 0, 0 otherwise. */
double rs_yield_slope(const rs_plasticity *pl, double ustar);

/* Active branch of each semismooth equation of a cell (bit flags). */
enum { RS_BRANCH_EXTERIOR = 1, RS_BRANCH_SLIP = 2, RS_BRANCH_YIELD = 4 };

/* Most components per cell (3D). */
#define RS_MAX_COMP 2
/* Local variables of a cell, in this order: p (ncomp), v_s (ncomp), Du_pl/Dt (ncomp),
 * Dustar/Dt, u*, and with friction memory mu, Dmu/Dt. Local rows: R_f (ncomp), R_pl
 * (ncomp), R_*, and with friction memory R_mu. */
#define RS_LAW_NVAR (3 * RS_MAX_COMP + 4)
#define RS_LAW_NROW (2 * RS_MAX_COMP + 2)
static inline int rs_law_var_p(int c) { return c; }
static inline int rs_law_var_vs(int ncomp, int c) { return ncomp + c; }
static inline int rs_law_var_flow(int ncomp, int c) { return 2 * ncomp + c; }
static inline int rs_law_var_dustar(int ncomp) { return 3 * ncomp; }
static inline int rs_law_var_ustar(int ncomp) { return 3 * ncomp + 1; }
static inline int rs_law_row_f(int c) { return c; }
static inline int rs_law_row_pl(int ncomp, int c) { return ncomp + c; }
static inline int rs_law_row_star(int ncomp) { return 2 * ncomp; }
static inline int rs_law_var_mu(int ncomp) { return 3 * ncomp + 2; }
static inline int rs_law_var_dmu(int ncomp) { return 3 * ncomp + 3; }
static inline int rs_law_row_mu(int ncomp) { return 2 * ncomp + 1; }

/* A cell's local quantities. */
typedef struct rs_law_in {
  int ncomp;
  int in_contact;           /* p_n > 0 */
  double p[RS_MAX_COMP];    /* traction, N/mm^2 */
  double vs[RS_MAX_COMP];   /* slip velocity v_s, mm/s */
  double flow[RS_MAX_COMP]; /* Du_pl/Dt, mm/s */
  double dustar;            /* Dustar/Dt, mm/s */
  double ustar;             /* mm */
  double g;                 /* traction bound mu p_n (Coulomb, or at rest) */
  double r;                 /* semismooth scaling, traction per slip velocity */
  double r_yield; /* 3D: the yield projection's parameter (0: r; model.c sets 0.2 r in steady) */
  /* Velocity-dependent friction (NULL or Coulomb: g above is the bound). Otherwise the
   * bound is g = mu(eta) p_n with eta the slip speed along the bound's direction
   * (eta = -s.v_s, s the sign of p - r v_s, in 3D its unit direction): |v_s| at a
   * solution, but smooth where slip starts (with |v_s| Newton cycles between the branches
   * there). */
  const rs_friction *friction;
  double pn; /* pressure, N/mm^2 */
  /* Friction memory (friction has memory; 1 or 2 components): the state mu of the cell and
   * its material rate. The bound is then g = mu p_n (in->g is ignored) and the row
   *   R_mu = r (d_c Dmu/Dt + max(|v_s|, s0) (mu - mu_law(eta)))   in the contact,
   *   R_mu = r d_c Dmu/Dt                                         outside,
   * with eta the slip speed along the bound's direction as above. */
  int memory;
  double mu, dmu; /* -, 1/s */
} rs_law_in;

/* The residual rows of a cell, their active branches, and the local generalized
 * Jacobian: jac[row][var] with present[row][var] marking the structurally present
 * entries (explicit zeros included, e.g. the hardening term of a yield row on the
 * floor: the Jacobian's pattern depends on the branches only); entries not present are
 * not set (read jac only where present). */
typedef struct rs_law_out {
  double R[RS_LAW_NROW];
  unsigned char branch;
  double g; /* the traction bound the friction row used (mu(eta) p_n, or in->g) */
  /* the yield rows fix p without involving u* (yield without hardening): the traction
   * rows then determine the plastic flow (solvers eliminate on that unknown) */
  int pins_p;
  double jac[RS_LAW_NROW][RS_LAW_NVAR];
  unsigned char present[RS_LAW_NROW][RS_LAW_NVAR];
} rs_law_out;

/* Where a traction state lies (no rates known: consistent rates, projections): outside
 * the contact, inside the admissible set |p| < min(g, tau_c), at the friction bound
 * (g <= tau_c: slip follows g), or at the yield limit (tau_c < g: plastic flow), with a
 * relative margin of 1e-12. */
typedef enum { RS_STATE_OUTSIDE, RS_STATE_INSIDE, RS_STATE_AT_BOUND, RS_STATE_AT_YIELD } rs_state;
rs_state rs_contact_state(const rs_plasticity *pl, int in_contact, double p_norm, double g,
                          double ustar);

/* Evaluate the law of one cell; jac: also the local Jacobian (else only R, branch). */
void rs_contact_law(const rs_plasticity *pl, const rs_law_in *in, int jac, rs_law_out *out);

#endif
