/* Transient integration of the rolling-contact DAE (docs/model.md §6): IDA (variable-order
 * BDF) whose nonlinear systems are solved by KINSOL through a custom
 * SUNNonlinearSolver, with the generalized Jacobian in a SUNSparseMatrix (CSR) factored
 * by KLU, or with its sparse rows eliminated and the Schur complement of the dense
 * traction rows factored by LAPACK (see rs_linear). Also the solver statistics and the
 * choice of linear algebra shared with the steady solver (solve/steady.h). */
#ifndef ROLLSIM_TRANSIENT_H
#define ROLLSIM_TRANSIENT_H

#include <signal.h>
#include <sundials/sundials_context.h>

#include "physics/model.h"
#include "physics/thermal.h"
#include "base/status.h"

/* One SUNDIALS context per run: the driver creates it and every solver of the run
 * (steady, coarse grids, pseudo-transient, transient) uses it. A solver created with
 * ctx = NULL makes a context of its own (for a single solve, e.g. in a test). */

typedef struct rs_stats {
  long steps;          /* IDA steps (transient) */
  long nonlin_iters;   /* Newton iterations (KINSOL, summed) */
  long nonlin_fails;   /* nonlinear solves that failed (IDA then cuts the step) */
  long err_test_fails; /* IDA error-test failures */
  long res_evals;      /* residual evaluations */
  long jac_evals;      /* Jacobian evaluations = KLU factorizations */
  long klu_analyses;   /* KLU symbolic analyses (the sparsity pattern changed) */
  long lin_solves;     /* linear solves (direct) or Krylov iterations (steady solver) */
  long
      factorizations; /* of the iteration matrix (transient; a matrix equal to the last keeps it) */
  long refused;       /* steady solutions refused by rs_model_check_steady (then recomputed
                         by rolling the material, or the solve failed) */
  long couplings;     /* steady solves of mu(T), tau_c0(T) coupled states (docs/model.md §18) */
  long coupling_newton;   /* their Newton steps */
  long coupling_products; /* and the products with their Jacobian (GMRES iterations; in a
                             transient those of the exact coupling, rs_transient_coupling) */
} rs_stats;

/* Linear algebra of the steady Newton iteration (all give the same solution to the
 * Newton tolerance): KLU on the whole sparse Jacobian; DENSE, the sparse rows
 * eliminated and the Schur complement on the dense traction rows factored by LAPACK;
 * KRYLOV, GMRES with FFT elastic products and a KLU-factored near-field
 * preconditioner; AUTO picks KRYLOV for elastic models from 300 cells, DENSE
 * otherwise (KLU when the model has unknowns beyond the per-cell ones). */
typedef enum { RS_LINEAR_AUTO = 0, RS_LINEAR_KLU, RS_LINEAR_DENSE, RS_LINEAR_KRYLOV } rs_linear;

/* Transient integration. */
typedef struct rs_transient rs_transient;
typedef struct rs_transient_opts {
  double rtol;                      /* relative tolerance */
  double atol;                      /* absolute tolerance of tractions, N/mm^2 */
  int max_order;                    /* BDF order limit, 1..5 */
  long max_steps;                   /* per call of rs_transient_advance */
  int max_newton;                   /* Newton iterations per step (KINSOL), default 10 */
  double t_stop;                    /* IDA never steps beyond this time (INFINITY: no limit) */
  volatile sig_atomic_t *interrupt; /* set asynchronously: stop at once (may be NULL) */
  double max_step;                  /* s, 0: no limit */
  /* Called after every accepted time step with the solution there (may be NULL);
   * a status other than RS_OK stops the integration with that status. */
  int (*step_hook)(void *ctx, double t, const double *y, const double *yp);
  void *hook_ctx;
  /* Linear algebra of the Newton iterations: KLU, or the dense Schur complement for
   * AUTO (0), DENSE and KRYLOV alike (Newton-Krylov with the near-field preconditioner
   * was about 10 times slower than DENSE on the 400-cell start-up: with c_j > 0 the
   * elastic rows carry the slowly decaying A(i-j) itself); KLU whenever the model has
   * unknowns beyond the 3 n per-cell ones. */
  rs_linear linear;
  /* NULL, or inputs held at these values whatever the time (the steady solver's
   * pseudo-transient: the material rolls at the inputs of one time). */
  const rs_inputs *frozen;
  /* NULL, or the surface temperature carried as DAE state (docs/model.md §18, "Heat
   * memory"): y and y' then hold rs_thermal_nstate(thermal) mode values after the model's
   * neq unknowns (rs_transient_neq). Without coupling the contact rows do not depend on them:
   * each step's contact system is solved as without them, then the modes' rows exactly
   * (rs_thermal_dae_solve). Used from one solver at a time. */
  rs_thermal *thermal;
  /* With thermal: NULL, or the contact coupled to its temperature (docs/model.md §18,
   * "Couplings"): each step's contact and modes solved together (rs_transient_coupling). */
  const struct rs_transient_coupling *coupling;
} rs_transient_opts;

/* mu(T) and tau_c0(T) in a transient (docs/model.md §18, "Couplings"): the factors the model
 * reads (rs_model.mu_factor, rs_model.yield_factor, each NULL without its table) are
 * table(T)/rest at each cell's temperature T read from the modes (rs_thermal_state_temperature),
 * so that the contact rows depend on the DAE state, not on the heat of the point itself (that
 * would be a friction law falling with the slip velocity: ill-posed without memory). Each
 * step's system, contact and modes, is solved by one of:
 * - exact (fixed_point = 0): the modes eliminated, the step's rows solved exactly for them
 *   (rs_thermal_dae_solve, affine in the heat) at every evaluation of the contact rows, so that
 *   these read the factors of the modes the point would leave after the step; Newton on the
 *   contact unknowns. On the direct path (2D), once an iteration of a step's solve contracts
 *   poorly, its step has the coupling's Jacobian J_ctheta dtheta/dy (the Schur complement's
 *   term) added to the contact's, applied matrix-free with the held factorisation as
 *   preconditioner (nls_kinsol.h); otherwise, and on the Krylov path (3D), the step is the
 *   contact's own (the term's products cost more time than the iterations they save where the
 *   coupling is weak, bench/RESULTS.md issue 43);
 * - alternation (fixed_point = 1): the factors of the predicted modes, the contact rows solved
 *   with them held, the modes' rows exactly at that point, the factors of the new modes, until
 *   a pass changes no contact row beyond the contact's Newton test (block Gauss-Seidel on
 *   (contact | modes) within the step).
 * Both solve the same equations, to the contact's Newton test. */
typedef struct rs_transient_coupling {
  const rs_history *mu_table, *tau_table; /* NULL: no such table */
  double mu_rest, tau_rest;               /* mu_law(0) and plasticity.tau_c0 */
  double *mu_factor, *yield_factor;       /* [n], those the model points at */
  double *T_used;                         /* [n]: the temperatures of the factors */
  int fixed_point;                        /* 1: the alternation (temperature.coupling) */
} rs_transient_coupling;

/* Unknowns of the integrated system: the model's neq, plus the temperature modes. */
int rs_transient_neq(const rs_model *m, const rs_thermal *thermal);

/* solver.rtol: auto (docs/model.md §9, "Tolerances"): the relative tolerance that keeps the
 * time integration's error below the grid's own discretisation error: 0.06 dx/a (dx the
 * cell length along x, a the Hertz semi-axis or half-width along x), at most 3e-3 (the
 * 44 x 44 grid over 1.1 a each way) and at least 1e-6; 1e-6 in 2D with friction memory. */
double rs_transient_auto_rtol(const rs_model *m);

/* y0, yp0: a consistent initial state (see rs_model_consistent_rates). */
int rs_transient_create(rs_transient **tr, const rs_model *m, SUNContext ctx, double t0,
                        const double *y0, const double *yp0, const rs_transient_opts *opts,
                        rs_msg *msg);
/* Integrate to tout; y, yp receive the (interpolated) solution at tout. */
int rs_transient_advance(rs_transient *tr, double tout, double *y, double *yp, rs_msg *msg);
/* Restart at time t from a consistent state (after a breakpoint of an input
 * history: IDA never integrates across a kink or jump); new stop time t_stop.
 * Step statistics keep accumulating. */
int rs_transient_restart(rs_transient *tr, double t, const double *y, const double *yp,
                         double t_stop, rs_msg *msg);
void rs_transient_get_stats(const rs_transient *tr, rs_stats *stats);
void rs_transient_free(rs_transient *tr);

#endif
