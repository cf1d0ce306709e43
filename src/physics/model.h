/* The rolling-contact model with local plasticity (docs/model.md §4-5), semi-discretised in
 * space: the DAE F(t, y, y') = 0 on the contact grid (physics/grid.h) with the unknowns
 * of physics/layout.h (traction, plastic displacement, accumulated plastic deformation
 * per cell; with a prescribed tangential force the creepage as an extra unknown with
 * the equation sum p dA = F_x(t), docs/model.md §6). Per cell the contact law
 * (physics/contact_law.h) gives the residual rows and their local generalized Jacobian;
 * this module supplies the kinematics (v_s, Du_pl/Dt, Dustar/Dt through the elastic
 * operator and the upwind material derivative) and chains the two: residual, Jacobian
 * (whole or near field), exact J v products and the row structure the solvers need.
 * Pure physics: plain arrays and values, no SUNDIALS, no case files. */
#ifndef ROLLSIM_MODEL_H
#define ROLLSIM_MODEL_H

#include <stdint.h>

#include "physics/contact_law.h"
#include "physics/elastic_op.h"
#include "physics/grid.h"
#include "physics/history.h"
#include "physics/layout.h"
#include "base/status.h"

/* Regime of a cell (paper eqs. 7-10); the values are the netCDF flag values. */
typedef enum { RS_EXTERIOR = 0, RS_ADHESION = 1, RS_SLIP = 2, RS_PLASTIC = 3 } rs_regime;

/* Pressure the tangential problem sees: the discrete normal solution or Hertz's. */
typedef enum { RS_NORMAL_DISCRETE = 0, RS_NORMAL_HERTZ = 1 } rs_normal_solution;

/* Choice of the semismooth scaling r (docs/model.md §4, §9): r = 1/(c_j*C_self + V*C_shift/dx)
 * with C_shift the steady self-compliance difference (A(0)-A(dx)) or the self-compliance A(0). */
typedef enum { RS_SCALING_AUTO = 0, RS_SCALING_DIFFERENCE = 1, RS_SCALING_SELF = 2 } rs_scaling;

/* Model parameters: plain values (the driver builds them from a case). The histories
 * are copied by rs_model_create. */
typedef struct rs_model_params {
  int dimension;           /* 2: line contact (per mm of width); 3: elliptic point contact */
  int cells, cells_y;      /* along x; along y (3D) */
  int grid_from_range;     /* 1: x_range (and y_range) given; 0: +-extent Hertz semi-axes */
  double x_range[2];       /* mm, outer edges of the potential contact area */
  double y_range[2];       /* mm (3D) */
  double extent, extent_y; /* half-lengths in Hertz semi-axes a, b at the largest load */
  double radius;           /* combined radius, mm: gap x^2/(2R) (3D: Rx) */
  double radius_y;         /* 3D: Ry, gap x^2/(2Rx) + y^2/(2Ry) */
  /* 3D: the undeformed gap (mm) at a cell centre (x, y) (mm) from the caller, for a contact
   * that is not Hertzian (wheel-rail profiles); radius and radius_y then only give the
   * Hertz scales (a, b, p0) the solvers' weights use, so they should be the surfaces'
   * curvature radii at the gap's minimum. gap_ctx must outlive the model. NULL: the
   * quadratic gap above. */
  double (*gap_at)(const void *gap_ctx, double x, double y);
  const void *gap_ctx;
  /* 3D with gap_at and a constant load: the normal solution on this grid (cells row by row
   * along x) and its approach, when the caller has solved it already (the wheel-rail patches);
   * copied at creation, not solved again (a regridded model solves its own). NULL: solved. */
  const double *normal_pressure;
  double normal_approach;
  rs_normal_solution normal_solution;
  double reference_length; /* mm, L of the 2D kernel */
  double shear_modulus, poisson_ratio;
  double layer_thickness, layer_shear_modulus; /* third-body layer: h3 (0: none), G3 */
  rs_friction friction;
  rs_plasticity plasticity;
  rs_history load;             /* normal load, N/mm (3D: N) */
  rs_history velocity;         /* V, mm/s */
  rs_history creepage;         /* xi (not used with force control) */
  rs_history lateral_creepage; /* eta (3D; not used with force control) */
  rs_history spin;             /* phi, 1/mm (3D) */
  rs_history shift_velocity;   /* rigid shift rate along x, mm/s */
  int force_control;           /* 1: the creepages are unknown, the forces prescribed */
  rs_history force;            /* F_x, N/mm (3D: N) */
  rs_history force_y;          /* F_y, N (3D) */
  double end_time;             /* s: the grid is sized on the largest load up to it */
  rs_scaling scaling;
  int threads;       /* for the 3D work a solve splits in two (rs_threads); 0 or 1: one */
  double time_scale; /* s: sets r when there is neither rolling nor a time step */
} rs_model_params;

typedef struct rs_model {
  rs_model_params par; /* owns copies of the histories */
  rs_grid grid;
  rs_layout lay;
  rs_elastic_op el;
  double layer_flex;  /* h3/G3, mm/(N/mm^2), added to the self term only */
  double normal_load; /* the largest load of the run (it sizes the grid) */
  int load_varies;    /* the load is a history: p_n(t) from rs_model_normal_at */
  double hertz_a, hertz_p0;
  double hertz_b;         /* 3D: the semi-axis across the rolling direction (2D: 0) */
  double contact_measure; /* 2a (2D) or pi a b (3D): the scale of the force rows */
  double approach;        /* delta of the normal solution at t = 0, mm */
  double *gap;            /* undeformed gap at the cell centres [n] */
  double *pn;             /* pressure at t = 0 [n] */
  double *bound;          /* traction bound g = mu p_n at t = 0 [n] */
  /* State of the material entering at the leading edge: fresh (0), or the twin-disc
   * memory when set (physics/rig.h; owned by the caller, updated between time steps). */
  const struct rs_rig_memory *memory;
  /* Per-cell factor on the friction bound (docs/model.md §18, mu(T)): g = f_I mu(...) p_n;
   * NULL: none (factor 1). Owned by the caller, read at every evaluation. */
  const double *mu_factor;
  /* Per-cell factor on the yield limit (docs/model.md §18, tau_c0(T)): cell I yields at
   * max(f_I tau_c_min, f_I tau_c0 + k_tau u*), the floor keeping its ratio to tau_c0; NULL:
   * none (factor 1). Owned by the caller, read at every evaluation
   * (rs_model_cell_plasticity). */
  const double *yield_factor;
} rs_model;

/* Grid, elastic operator and the normal solution from plain parameters. */
int rs_model_create(rs_model *m, const rs_model_params *par, rs_msg *msg);
void rs_model_free(rs_model *m);

/* The same model on a grid of `cells` cells over the same extent (coarse-grid solves
 * that start Newton on the fine grid, docs/model.md §13). Free with rs_model_free. */
int rs_model_regrid(const rs_model *m, int cells, rs_model *out, rs_msg *msg);

/* The time-dependent inputs at one time: every history of the model is evaluated here
 * and nowhere else. A frozen copy (rates zero, the inflow looked up at its own t) holds
 * the inputs of one time for the steady solver's pseudo-transient. */
typedef struct rs_inputs {
  double t;                /* s: their time (the inflow state is looked up there) */
  double velocity;         /* V, mm/s */
  double creepage;         /* xi (prescribed; with force control the unknown is used) */
  double lateral_creepage; /* eta (3D; idem) */
  double spin;             /* phi, 1/mm (3D) */
  double shift_velocity;   /* mm/s */
  double load;             /* normal load */
  double force, force_y;   /* prescribed F_x, F_y (force control) */
  double load_rate, force_rate, force_y_rate; /* d/dt of load and forces */
  int linear; /* 1: the linear part only: no rigid slip, no inflow (J v) */
  int newton; /* 1: an evaluation of steady Newton's (its weights, rs_model_evaluate) */
} rs_inputs;
void rs_model_inputs_at(const rs_model *m, double t, rs_inputs *in);
/* Inputs held at their values: rates zero. */
void rs_inputs_freeze(rs_inputs *in);

/* Compressed sparse row matrix (the generalized Jacobian). Indices are int64 to match
 * SUNDIALS' sunindextype. */
typedef struct rs_csr {
  int64_t nrows, cap_rows, cap; /* rows assembled, rows of the matrix, entries capacity */
  int64_t *rowptr;              /* [nrows + 1] */
  int64_t *col;                 /* [cap] */
  double *val;                  /* [cap] */
} rs_csr;

/* Work arrays for residual/Jacobian evaluation (one per solver: every evaluation writes
 * here, never into the model). */
typedef struct rs_work {
  rs_elastic_work ew;
  double *uel;           /* tangential elastic displacement, padded grid [ncomp (nx+1) ny] */
  double *ueldot;        /* its time derivative on the grid [ncomp n] */
  double *vslip;         /* slip velocity v_s [ncomp n] */
  double *dupl;          /* Du_pl/Dt [ncomp n] */
  double *dustar;        /* Dustar/Dt [n] */
  double *dmu;           /* Dmu/Dt with friction memory [n] (else NULL) */
  unsigned char *branch; /* RS_BRANCH_* flags per cell [n] */
  rs_law_out *law;       /* per cell: rows and local Jacobian of the last evaluation [n] */
  /* Row structure of the last Jacobian (rs_model_jacobian), per row k < neq: dense[k] = 1
   * if the row couples to every traction through the elastic operator (it involves v_s:
   * traction rows, and with friction memory the memory rows in the contact); pivot[k] =
   * the unknown a direct solver eliminates on a dense row (the traction, or the plastic
   * displacement when the cell's yield rows fix the traction; mu for a memory row). */
  unsigned char *dense;
  int *pivot;
  /* The local Jacobians' present entries, cell by cell (cell i: jv_start[i] to
   * jv_start[i + 1]), each its local row times 16 plus its variable, and its value: the J v
   * products read these instead of every entry of law[i].jac [n + 1, n rows vars]; allocated
   * by the first linearisation (NULL in a work that only evaluates). */
  int *jv_start;
  unsigned char *jv_idx;
  double *jv_val;
  double r;                   /* scaling of the last evaluation */
  double r_yield;             /* and of its yield projections (3D) */
  const double *pn, *bound;   /* pressure and traction bound at the time of the last evaluation */
  double *pn_buf, *bound_buf; /* their storage when the load varies [n] */
  double load_cached;         /* load of pn_buf (NAN: none) */
  double *inflow;             /* state entering at the leading edge, per row: u_pl (ncomp), u* */
  rs_msg msg;                 /* why the last evaluation failed */
  /* NULL, or called by every evaluation into this work after the kinematics and before the
   * local laws (the factors of mu(T), tau_c0(T) set from the heat of the point itself, the
   * transient's exact coupling, docs/model.md §18 "Couplings"); a status other than RS_OK
   * fails the evaluation. Set by the work's owner; rs_work_create leaves it NULL. */
  int (*before_laws)(void *ctx, const struct rs_work *w, const rs_inputs *in, const double *y);
  void *before_laws_ctx;
} rs_work;

int rs_work_create(rs_work *w, const rs_model *m);
/* A work for the kinematics only (rs_model_kinematics_scaled, the vectors of J v): no
 * local laws (law, dense, pivot stay NULL), about 770 bytes a cell less. */
int rs_work_create_kinematics(rs_work *w, const rs_model *m);
void rs_work_free(rs_work *w);

/* Pressure and traction bound for the inputs into w->pn, w->bound: the model's arrays at
 * a constant load; with a normal-load history the normal solution for in->load, cached. */
int rs_model_normal_at(const rs_model *m, rs_work *w, const rs_inputs *in, rs_msg *msg);

/* Creepage at (inputs, y): the prescribed one, or the unknown with force control; the
 * lateral creepage (3D) alike. */
double rs_model_creepage(const rs_model *m, const rs_inputs *in, const double *y);
double rs_model_lateral_creepage(const rs_model *m, const rs_inputs *in, const double *y);

/* The semismooth scaling r (traction per slip velocity), docs/model.md §4:
 * r = 1 / (cj * C_self + V * C_shift / dx). */
double rs_model_scaling(const rs_model *m, const rs_inputs *in, double cj);

/* Residual F(t, y, yp) (traction units, every row) with r from cj, into F (may be NULL:
 * only the kinematics, branches and local laws in w). On failure w->msg says why. */
int rs_model_residual(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, double *F);

/* The generalized Jacobian dF/dy + cj dF/dy' at (y, yp), assembled row by row into J
 * (CSR, sorted columns; J->rowptr/col/val of capacity rs_model_jac_capacity). band = 0:
 * every entry, structurally zero ones left out (the pattern follows the branches);
 * band > 0: the near field, tractions of cells at most `band` cells away in x and at
 * most band_y cells away in y (band_y = 0: the cell's own line along x), on a pattern
 * that does not depend on the branches (every traction row holds its near field and its
 * own plastic-displacement columns, zeros included; in 3D every other row too holds the
 * cell's traction, plastic displacements, u* and mu at the cell and upstream), for a
 * preconditioner whose symbolic analysis is done once. Also fills w->law, w->dense and w->pivot. */
int rs_model_jacobian(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                      const double *yp, double cj, int band, int band_y, rs_csr *J);
int64_t rs_model_jac_capacity(const rs_model *m, int band, int band_y);
/* The residual's rows of cell I (its p, u_pl, u* and, with memory, mu rows: their indices in
 * row, their values in R, each of at most RS_LAW_NROW) with its law evaluated afresh on the
 * kinematics of w (a residual evaluated at y) and the model's factors as they are now: a
 * caller varying mu_factor[I] or yield_factor[I] gets the rows' dependence on them
 * (docs/model.md §18, "Couplings"). Returns the number of rows. */
int rs_model_cell_rows(const rs_model *m, const rs_work *w, const double *y, int I, int *row,
                       double *R);
/* rs_model_jacobian in two parts: the local laws with their Jacobians at (y, yp) into w
 * (w->law, w->branch, w->dense, w->pivot: what rs_model_jv needs), and the assembly of J
 * from them (in and cj as given to rs_model_linearise). */
int rs_model_linearise(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                       const double *yp, double cj);
/* rs_model_linearise that also gives the residual at (y, yp) in F (as rs_model_residual): a
 * Newton iteration's residual at a trial point and, if the point is accepted, the
 * linearisation there in one evaluation. */
int rs_model_linearise_residual(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                                const double *yp, double cj, double *F);
int rs_model_jacobian_assemble(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                               int band, int band_y, rs_csr *J);

/* The 3D near field's couplings between neighbouring lines along x, for a line
 * Gauss-Seidel preconditioner: the entries that a near field with band_y = 1 adds to the
 * one with band_y = 0 (rows of the cells of line iy, the tractions of lines iy - 1 and
 * iy + 1 within `band` cells in x), applied as r <- r - J_y x to the rows of the cells of
 * lines iy0 <= iy < iy1 whose parity is `parity`; x is read on the lines of the other
 * parity only. w holds the linearisation (rs_model_linearise). */
enum { RS_YLINK_MAX_BAND = 8 };
void rs_model_near_ylink(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                         int band, int parity, int iy0, int iy1, const double *x, double *r);
/* The same in two steps: the couplings' coefficients of a linearisation gathered once
 * (rs_model_near_ylink_prepare: the kernel's entries at iy +- 1 and each cell's local
 * Jacobian entries, in a table that the first call allocates; RS_OK or RS_ERR_INTERNAL),
 * then applied as often as needed (rs_model_near_ylink_apply: the same sums in the same
 * order as rs_model_near_ylink, bit for bit). Up to RS_YLINK_SLOTS calls of apply may run
 * at once on one table, each with its own slot (its scratch rows). */
enum { RS_YLINK_SLOTS = 2 };
typedef struct rs_ylink {
  int band, nrow, ncell, nx, on;
  double st[2][2][2][2 * RS_YLINK_MAX_BAND + 1]; /* [c][b][side][band + offset] */
  double *coef;                                  /* [cell][row][c], 0 where not present */
  unsigned char *rows; /* [cell]: bit k when row k has a coupling; 0: none (or exterior) */
  double *pad;         /* per slot: four rows of nx + 2 band + 4, zero beyond the lines */
} rs_ylink;
int rs_model_near_ylink_prepare(const rs_model *m, const rs_work *w, const rs_inputs *in, double cj,
                                int band, rs_ylink *t);
void rs_model_near_ylink_apply(const rs_model *m, const rs_ylink *t, int slot, int parity, int iy0,
                               int iy1, const double *x, double *r);
void rs_ylink_free(rs_ylink *t);
/* rs_model_jacobian_assemble for the rows of the cells of the lines iy with lines[iy] set,
 * into J as it was assembled last with the same band, band_y and pattern (no extras):
 * those rows rewritten in place, the others kept. RS_ERR_SOLVER if a row's length is not
 * what it was (J is then to be assembled whole). */
int rs_model_jacobian_assemble_lines(const rs_model *m, const rs_work *w, const rs_inputs *in,
                                     double cj, int band, int band_y, const unsigned char *lines,
                                     rs_csr *J);

/* Jv = (dF/dy + cj dF/dy') v, exactly (up to roundoff), at the point of the last
 * rs_model_jacobian or rs_model_linearise on w; wlin is scratch for the kinematics of v (a second
 * work). */
int rs_model_jv(const rs_model *m, const rs_work *w, rs_work *wlin, const rs_inputs *in, double cj,
                const double *v, double *Jv);

/* Consistent rates at a state y (docs/model.md §9 "consistent start"): solves the adhesion
 * rows for p', exterior p' = 0, at the bound p' = g'; upl' and ustar' from their
 * transport equations. With force control the adhesion rows are bordered by
 * sum p' dA = F'(t), which also gives the creepage: its unknown in y is set. */
int rs_model_consistent_rates(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                              double *yp, rs_msg *msg);

/* The state at rest into y [neq]: no traction, fresh material (u_pl = u* = 0; with
 * friction memory mu = mu_law(0)), extras 0. */
void rs_model_rest_state(const rs_model *m, double *y);

/* The steady state of full sliding into y [neq] (3D plastic models with Coulomb friction, no
 * memory, no force control): each material path from the leading edge with the elastic slip
 * neglected against the rigid slip, |p| = min(g, tau_c) against the rigid slip's direction,
 * u* and u_pl grown by the rigid slip while a cell yields (docs/model.md §13). RS_OK, or
 * RS_ERR_SOLVER (y untouched) where it does not apply: another model, or a rigid slip below
 * SLIDE_FACTOR times the largest bound over G somewhere in the contact. */
int rs_model_sliding_state(const rs_model *m, rs_work *w, const rs_inputs *in, double *y);

/* Make the tractions of y admissible (after a jump of an input history): p = 0 outside
 * the contact, |p| <= g inside (a cell whose bound dropped keeps its direction). */
int rs_model_project_state(const rs_model *m, rs_work *w, const rs_inputs *in, double *y,
                           rs_msg *msg);

/* Interpolate a state of model `from` to the grid of model `to` (linear in x between
 * cell centres, constant beyond the outer centres), then made admissible. */
int rs_model_interpolate_state(const rs_model *from, const double *y_from, const rs_model *to,
                               rs_work *w_to, const rs_inputs *in, double *y_to, rs_msg *msg);

/* Quantities of docs/model.md §7 at (y, yp). Arrays of one value per cell, any may be NULL. */
typedef struct rs_diag {
  double Fx, Fn, creepage, velocity;
  double Fy, Mz, lateral_creepage, spin; /* 3D (0 in 2D) */
  int count[4];                          /* by rs_regime */
  double frictional_power, plastic_power, elastic_energy, rigid_slip_power;
  double hertz_a, hertz_b; /* 3D: Hertz semi-axes (mm) at the inputs' load (0 in 2D) */
  /* Surface temperature (docs/model.md §18), filled by the driver when a case asks for it (0
   * otherwise): the largest in the contact, degC, and the heat into each body, W (2D: W/mm). */
  double T_max, heat_input_1, heat_input_2;
  /* Discretisation error estimates of Fx, Fy, Mz (magnitudes), set by the driver
   * (study/errest.h) and only when error_state is not RS_ERROR_NONE (zero here). */
  double Fx_error, Fy_error, Mz_error;
  /* Fx, Fy, Mz extrapolated to zero cell size from the same three grids, where the estimate
   * is reliable (NaN elsewhere and without an estimate; docs/model.md §19). */
  double Fx_extrapolated, Fy_extrapolated, Mz_extrapolated;
  int error_state;
} rs_diag;
/* error_state: no estimate; the observed order in the asymptotic band; the fallback. */
enum { RS_ERROR_NONE = 0, RS_ERROR_RELIABLE = 1, RS_ERROR_UNRELIABLE = 2 };

/* slip: ncomp blocks of one value per cell (relative slip v_s/V, or v_s when V = 0). */
int rs_model_diagnostics(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                         const double *yp, rs_diag *d, double *slip, double *tauc,
                         signed char *regime);
/* The same from a work evaluated at (in, y, yp) with c_j = 0 already (rs_model_residual or
 * rs_model_linearise_residual): no evaluation of its own. */
void rs_model_diagnostics_of(const rs_model *m, const rs_work *w, const rs_inputs *in,
                             const double *y, rs_diag *d, double *slip, double *tauc,
                             signed char *regime);

/* Per cell the frictional power density -p . v_s and the plastic one p . Du_pl/Dt
 * (N/(mm s), i.e. mW/mm^2) from a work evaluated at (in, y) as for rs_model_diagnostics_of:
 * their sums times the cell area are its frictional_power and plastic_power. */
void rs_model_power_densities(const rs_model *m, const rs_work *w, const double *y,
                              double *frictional, double *plastic);
/* Their change in the direction v of the unknowns with rates vp = cj v (both are bilinear in
 * the tractions and the rates: d(-p . v_s) = -(v_p . v_s + p . dv_s), the plastic one alike),
 * at the point y of w (evaluated there); wlin is scratch for the kinematics of v (as
 * rs_model_jv). */
void rs_model_power_jv(const rs_model *m, const rs_work *w, rs_work *wlin, const rs_inputs *in,
                       double cj, const double *y, const double *v, const double *vp,
                       double *dfrictional, double *dplastic);

/* Checks a steady state y (y' = 0): the paper's contact conditions cell by cell (eqs.
 * 7-10: |p| <= min(g, tau_c); slip only at the bound and opposite to p; plastic flow
 * only at the yield limit and parallel to p; Dustar/Dt = |Du_pl/Dt|; nothing outside
 * the contact) and the transient residual there (the DAE residual with the scaling of a
 * time step, not the steady one), each to RS_STEADY_CHECK_TOL times the largest traction
 * bound (rates in traction units through r). RS_OK, or RS_ERR_SOLVER with the first
 * failed condition, cell and values in msg. */
#define RS_STEADY_CHECK_TOL 1e-6
int rs_model_check_steady(const rs_model *m, rs_work *w, const rs_inputs *in, const double *y,
                          rs_msg *msg);
/* The same with ws a work evaluated at the steady state already (in, y, y' = 0, c_j = 0),
 * or NULL; w is evaluated for the rest. */
int rs_model_check_steady_with(const rs_model *m, const rs_work *ws, rs_work *w,
                               const rs_inputs *in, const double *y, rs_msg *msg);

/* Next kink or jump of an input history after t (INFINITY if none). */
double rs_model_next_breakpoint(const rs_model *m, double t);

/* The plasticity of cell I: the model's, or with a yield factor its copy in buf with tau_c0
 * and tau_c_min scaled by the cell's factor. */
static inline const rs_plasticity *rs_model_cell_plasticity(const rs_model *m, int I,
                                                            rs_plasticity *buf)
{
  if (!m->yield_factor) return &m->par.plasticity;
  *buf = m->par.plasticity;
  buf->tau_c0 *= m->yield_factor[I];
  buf->tau_c_min *= m->yield_factor[I];
  return buf;
}

/* Yield limit of cell I with accumulated plastic deformation ustar. */
static inline double rs_model_yield_limit(const rs_model *m, int I, double ustar)
{
  rs_plasticity buf;
  return rs_yield_limit(rs_model_cell_plasticity(m, I, &buf), ustar);
}

#endif
