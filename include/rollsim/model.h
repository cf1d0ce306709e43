/* The 2D rolling-contact model with local plasticity (model.md §4-5), semi-
 * discretised in space: the DAE F(t, y, y') = 0 with, per contact-grid cell I,
 *   y = [ p_0..p_{n-1} | upl_0..upl_{n-1} | ustar_0..ustar_{n-1} ( | xi ) ]
 * (tangential traction on body 1, plastic displacement difference, accumulated
 * plastic deformation; with a prescribed tangential force the creepage xi is the
 * last unknown, with the equation sum p dx = F_x(t) (model.md §6)). This module is pure physics: plain arrays, no SUNDIALS. */
#ifndef ROLLSIM_MODEL_H
#define ROLLSIM_MODEL_H

#include <stdint.h>
#include "rollsim/case.h"
#include "rollsim/elastic.h"
#include "rollsim/history.h"
#include "rollsim/status.h"

/* Regime of a cell (paper eqs. 7-10); the values are the netCDF flag values. */
typedef enum { RS_EXTERIOR = 0, RS_ADHESION = 1, RS_SLIP = 2, RS_PLASTIC = 3 } rs_regime;

/* Active branch of each semismooth equation of a cell (bit flags). */
enum { RS_BRANCH_EXTERIOR = 1, RS_BRANCH_SLIP = 2, RS_BRANCH_YIELD = 4 };

typedef struct rs_model {
  int n;                   /* contact-grid cells */
  int neq;                 /* 3 n, or 3 n + 1 with force control */
  int force_control;       /* 1: y[3n] = xi, row 3n: (sum p dx - F_x(t))/(2 a) */
  rs_history force;        /* F_x, N/mm */
  double dx;               /* mm */
  double *x;               /* cell centres, mm [n] */
  double hertz_a, hertz_p0;
  rs_elastic2d el;
  double layer_flex;       /* h3/G3, mm/(N/mm^2), added to the self term only */
  double normal_load;      /* N/mm: the largest load of the run (it sizes the grid) */
  double approach;         /* delta of the normal solution at t = 0, mm */
  double *pn;              /* pressure at t = 0 [n] */
  double *bound;           /* traction bound g = mu p_n at t = 0 [n] */
  double radius;           /* combined radius, mm */
  double shear_modulus, poisson_ratio;
  rs_normal_solution normal_solution;
  int load_varies;         /* 1: contact.normal_load is a history; p_n(t) from rs_model_normal_at */
  rs_history load;         /* N/mm */
  double mu;
  int has_plasticity;
  double tau_c0, k_tau, tau_c_min;
  double reference_length; /* mm, L of the 2D kernel */
  rs_history velocity, creepage;
  rs_history shift;        /* rigid shift velocity, mm/s (pure shift when V = 0) */
  rs_scaling scaling;
  double time_scale;       /* s: sets r when there is neither rolling nor a time step */
  /* State of the material entering at the leading edge: fresh (0), or the twin-disc
   * memory when set (rollsim/rig.h; owned by the caller, updated between time steps). */
  const struct rs_rig_memory *memory;
} rs_model;

/* Build grid, influence coefficients and the normal solution from a case. */
int rs_model_create(rs_model *m, const rs_case *c, rs_msg *msg);
void rs_model_free(rs_model *m);

/* The same model on a grid of n cells over the same extent (coarse-grid solves that
 * start Newton on the fine grid, model.md §9): new influence coefficients and normal
 * solution, the same inputs, material and memory. Free with rs_model_free. */
int rs_model_regrid(const rs_model *m, int n, rs_model *out, rs_msg *msg);


/* Compressed sparse row matrix (the generalized Jacobian). Indices are int64 to
 * match SUNDIALS' sunindextype. */
typedef struct rs_csr {
  int64_t nrows, cap_rows, cap; /* rows assembled, rows of the matrix, entries capacity */
  int64_t *rowptr; /* [nrows + 1] */
  int64_t *col;    /* [cap] */
  double *val;     /* [cap] */
  int64_t band;    /* 0: every entry; > 0: the dense traction rows of adhesion cells keep only
                      their traction columns j with |i - j| <= band (a near-field matrix) */
} rs_csr;

/* Work arrays for residual/Jacobian evaluation. */
typedef struct rs_work {
  double *uel;     /* elastic displacement difference on the padded grid [n + 1] */
  double *ueldot;  /* its time derivative [n] */
  double *vslip;   /* slip velocity v_s [n] */
  double *dupl;    /* Du_pl/Dt [n] */
  double *dustar;  /* Dustar/Dt [n] */
  unsigned char *branch; /* RS_BRANCH_* flags per cell [n] */
  const double *pn, *bound; /* pressure and traction bound at the time of the last evaluation */
  double *pn_buf, *bound_buf; /* their storage when the load varies [n] */
  double load_cached;      /* load of pn_buf (NAN: none) */
} rs_work;

int rs_work_create(rs_work *w, int n);
void rs_work_free(rs_work *w);

/* Pressure and traction bound at time t into w->pn, w->bound: the model's arrays at a
 * constant load; with a normal-load history the normal solution (discrete or Hertz, as
 * the case says) for the load at t, cached in w. Every evaluation below calls it. */
int rs_model_normal_at(const rs_model *m, rs_work *w, double t, rs_msg *msg);

/* Interpolate a state y_from of model from to the grid of model to (linear in x
 * between cell centres, constant beyond the outer centres; tractions then made
 * admissible at time t: zero outside the contact, |p| <= g). */
int rs_model_interpolate_state(const rs_model *from, const double *y_from, const rs_model *to,
                               rs_work *w_to, double t, double *y_to, rs_msg *msg);

/* Maximum number of Jacobian nonzeros (dense traction block plus bands). */
int64_t rs_model_jac_capacity(const rs_model *m);

/* The semismooth scaling r (traction per slip velocity), model.md §4:
 * r = 1 / (cj * C_self + V * C_shift / dx). */
double rs_model_scaling(const rs_model *m, double t, double cj);

/* Residual F(t, y, yp) (traction units, every row), with r from cj. F may be
 * NULL (only the work arrays are filled). If jac is non-NULL, the generalized
 * Jacobian dF/dy + cj dF/dyp is assembled in it (structurally zero entries are
 * left out; the pattern changes only when w->branch changes). */
int rs_model_eval(const rs_model *m, rs_work *w, double t, const double *y, const double *yp,
                  double cj, double *F, rs_csr *jac);

/* Consistent rates at a state y (model.md §9 "consistent start"): solves the
 * adhesion rows for p', exterior p' = 0, slip p' = g' (= 0 at constant load),
 * upl' and ustar' from their transport equations; plastic cells p' = 0. With force
 * control the adhesion rows are bordered by sum p' dx = F_x'(t), which also gives
 * the creepage: y[3n] is set. yp: output [neq]. */
int rs_model_consistent_rates(const rs_model *m, rs_work *w, double t, double *y, double *yp,
                              rs_msg *msg);

/* Creepage at (t, y): the history, or the unknown y[3n] with force control. */
double rs_model_creepage(const rs_model *m, double t, const double *y);

/* Make the tractions of y admissible at time t (after a jump of an input history):
 * p = 0 outside the contact, |p| <= g(t) = mu p_n(t) inside (a cell whose bound
 * dropped keeps its direction at the new bound). */
int rs_model_project_state(const rs_model *m, rs_work *w, double t, double *y, rs_msg *msg);

/* Quantities of model.md §7 at (t, y, yp). Arrays of length n, any may be NULL. */
typedef struct rs_diag {
  double Fx, Fn, creepage, velocity;
  int count[4]; /* by rs_regime */
  double frictional_power, plastic_power, elastic_energy, rigid_slip_power;
} rs_diag;

int rs_model_diagnostics(const rs_model *m, rs_work *w, double t, const double *y,
                         const double *yp, rs_diag *d, double *slip, double *tauc,
                         signed char *regime);

/* Next kink or jump of an input history after t (INFINITY if none). */
double rs_model_next_breakpoint(const rs_model *m, double t);

/* Yield limit of a cell with accumulated plastic deformation ustar. */
double rs_model_yield_limit(const rs_model *m, double ustar);

/* Checks a steady state y (y' = 0) at time t: the transient residual there (the DAE
 * residual with the scaling of a time step, not the steady one) and the paper's
 * contact conditions cell by cell (eqs. 7-10: |p| <= min(g, tau_c); slip only at the
 * bound and opposite to p; plastic flow only at the yield limit and parallel to p;
 * Dustar/Dt = |Du_pl/Dt|; nothing outside the contact), each to RS_STEADY_CHECK_TOL
 * times the largest traction bound (slip and flow rates in traction units through
 * r). RS_OK, or RS_ERR_SOLVER with the first failed condition, cell and values in msg. */
#define RS_STEADY_CHECK_TOL 1e-6
int rs_model_check_steady(const rs_model *m, rs_work *w, double t, const double *y, rs_msg *msg);

#endif
