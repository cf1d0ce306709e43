/* Sweeps (docs/case-file.md, docs/file-format.md): the case's `sweep:` block maps dotted
 * case keys to value lists (or {linspace: [from, to, n]}); `rollsim sweep` runs every
 * combination and writes one netCDF file with one dimension per swept key.
 * Steady sweeps continue from the previous point along the last key (creep-force
 * curves: continuation in creepage). */
#ifndef ROLLSIM_SWEEP_H
#define ROLLSIM_SWEEP_H

#include <stddef.h>
#include "io/case.h"
#include "io/case_sweep.h"
#include "study/run.h"
#include "base/status.h"

/* Point results (the scalars of the sweep file). */
typedef struct rs_sweep_result {
  size_t points_done, points_failed;
  double wall_seconds;
  long newton_iters;
  long lin_solves;   /* steady points: linear solves (direct) or Krylov iterations */
  long jac_evals;    /* steady points: Jacobian evaluations */
  long refused;      /* steady solutions refused by the physical check (rs_model_check_steady) */
  long refined;      /* continuation steps halved where the regimes jumped or Newton failed */
  long midpoints;    /* approximate intermediate points before steps with many regime changes */
  long lines_in_two; /* lines solved in two parts at once (solver.threads: 2) */
  /* mu(T), tau_c0(T): steady solves, Newton steps, products with the coupling's Jacobian */
  long couplings, coupling_newton, coupling_products;
  /* --resume: the points of the lines complete in the file (counted in points_done and
   * points_failed, not computed again) */
  size_t points_kept;
  char file[1024];
  char backup[1040]; /* an older file at the output path kept under this name, or "" */
  /* Steady sweeps with the error estimate: points computed with one, those of them whether
   * reliable, and the largest estimated error of F_x/F_n (0 when none) */
  int error_estimate;
  size_t points_estimated, points_reliable;
  double max_mu_error;
} rs_sweep_result;

/* Run every point of the loaded case c (rs_case_load, its sweep read by rs_sweep_load);
 * write o->output_path (case output.file when NULL). With output.fields the file holds
 * every point's profiles too, when all points share c's grid (else a warning on stderr
 * and scalars only). Returns RS_OK, RS_ERR_SOLVER when some points failed (their results
 * are NaN), RS_ERR_INTERRUPTED, RS_ERR_OUTPUT or RS_ERR_INPUT. */
int rs_sweep_run(const rs_sweep *s, const rs_case *c, const rs_run_opts *o, rs_sweep_result *res,
                 rs_msg *msg);

#endif
