/* Private: a SUNNonlinearSolver (rootfinding type) for IDA that solves each BDF
 * step's system F(t, ypred + ycor, yppred + cj ycor) = 0 with the generalized Jacobian
 * (docs/model.md §6, §9), so the contact regimes are re-resolved in every step. Direct
 * linear algebra (ls, linsys.h: KLU on the whole matrix, or the Schur-complement solver
 * of linsys_reduced.h): modified Newton that keeps a factorisation across iterations and
 * steps while no cell changes regime and c_j stays within a factor 4, and sets up a fresh
 * one otherwise. Newton-Krylov (kry): KINSOL's exact Newton,
 * its linear solves as precise as the Newton test needs. */
#ifndef ROLLSIM_NLS_KINSOL_H
#define ROLLSIM_NLS_KINSOL_H

#include <sundials/sundials_nonlinearsolver.h>

#include "solve/linsys.h"
#include "solve/linsys_krylov.h"

/* What the solver needs from the integrator it serves: where the DAE residual reads
 * the current cj (it sets the scaling r), and the model's inputs at a time (held ones
 * when the integrator freezes them). */
typedef struct rs_nls_host {
  double *cj_slot;
  const rs_inputs *(*inputs_at)(void *ctx, double t);
  void *ctx;
  /* NULL, or the integrator's system extends the model's neq unknowns by a tail whose rows
   * the contact rows do not depend on (the temperature modes, transient.h): the contact
   * system is then solved on the first neq entries as without the tail, and tail() solves the
   * tail's rows at the converged point, its correction into ycor[neq...] (ypred, yppred the
   * predictors, full length; the last residual evaluation was at the converged point).
   * RS_OK or a failure. */
  int (*tail)(void *ctx, double cj, const double *ypred, const double *yppred, double *ycor);
  int neq_full; /* with tail: the length of the integrator's vectors */
  /* with tail: set to 0 while the contact system is solved (the integrator's residual may then
   * leave the tail's rows out: nothing reads them), to 1 otherwise */
  int *tail_rows;
  /* with tail: the contact's Newton test takes IDA's weights times this (the integrator scales
   * them to keep the tail from diluting its error norm) */
  double weight_scale;
  /* with tail: NULL, or the contact rows depend on the tail through data the host holds (the
   * temperature's factors, transient.h): after each tail solve couple() updates that data from
   * the step's point (ypred + ycor, full length) and sets *change to the largest change it
   * makes to a contact row, scaled by the contact's weights wc; while that is above the contact's
   * Newton test the contact rows are solved again from the current correction, then the tail. */
  int (*couple)(void *ctx, const double *ypred, const double *ycor, const double *wc,
                double *change);
  /* with tail and couple NULL: NULL, or the contact rows depend on the tail, eliminated exactly
   * by the host at each of their evaluations (the exact coupling, transient.h):
   * couple_begin(ctx, cj, ypred, yppred) before a step's contact solve (IDA's predictors, full
   * length) and with ypred NULL after it; couple_jv(ctx, v, Cv) the coupling's part of the
   * contact Jacobian (the Schur complement's J_ct J_tt^-1 J_tc, here its sign already such that
   * the Jacobian is J_cc + C) added to Cv, at the point of the last evaluation. On the direct
   * path, from the first iteration of a solve that contracts poorly on, the Newton step solves
   * (P + C) d = -F with P the held factorisation (the Neumann series' first two terms or GMRES
   * on I + P^-1 C, nls_kinsol.c); before that, with couple_jv NULL and on the Krylov path the
   * step leaves C out (Newton on the exact residual with the contact's own Jacobian). */
  int (*couple_begin)(void *ctx, double cj, const double *ypred, const double *yppred);
  int (*couple_jv)(void *ctx, const double *v, double *Cv);
} rs_nls_host;

/* The linear algebra: ls (direct: KLU or the Schur complement), or Newton-Krylov with
 * kry's near-field preconditioner and exact products in the SPGMR solver gmres (kry
 * non-NULL; ls then unused), GMRES reducing the residual to about the Newton test, by a
 * factor forcing at least. max_iters: Newton iterations per step before the step is
 * declared failed. tmpl: a vector of the model's neq unknowns. */
SUNNonlinearSolver rs_nls_kinsol_create(const rs_model *m, rs_work *w, rs_linsys *ls,
                                        rs_krylov *kry, SUNLinearSolver gmres, double forcing,
                                        rs_nls_host host, int max_iters, N_Vector tmpl,
                                        SUNContext ctx);

#endif
