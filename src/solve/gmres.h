/* Private: restarted GMRES for the 3D Newton-Krylov iterations (KINSOL's linear solver,
 * steady and transient), with the operator and preconditioner of an rs_krylov called
 * directly.
 *
 * It solves what SUNDIALS' SPGMR solves with right preconditioning: with the scaling
 * vectors s1, s2 KINSOL sets (both its fscale), the least-squares problem of
 * s2 A P^-1 s1^-1 in the Krylov space of s2 b, to ||s2 (b - A x)||_2 <= delta, restarted
 * up to max_restarts times, classical Gram-Schmidt with a second pass where the first lost
 * more than a factor 1000 of the norm. The vector work is fused: the scaling of A z with
 * the Gram-Schmidt dot products and the norm, the subtraction with the new norm, the
 * normalisation with the next preconditioner's input (z = v / s1, written where P^-1 then
 * works in place), the solution's combination with its unscaling; SPGMR makes a pass over
 * the vectors for each of these and copies the preconditioner's input once more (KINSOL's
 * psolve wrapper). The results equal SPGMR's up to roundoff (the sums' order differs). */
#ifndef ROLLSIM_GMRES_H
#define ROLLSIM_GMRES_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "solve/linsys_krylov.h"

/* A linear solver for KINSOL (KINSetLinearSolver with a NULL matrix; KINSetPreconditioner's
 * set-up is called by SUNLinSolSetup, its solve is not: rs_krylov_psolve and
 * rs_krylov_times of kry are). tmpl: a serial vector of the system's length. NULL when
 * out of memory. */
SUNLinearSolver rs_gmres_create(rs_krylov *kry, N_Vector tmpl, int maxl, int max_restarts,
                                SUNContext ctx);

#endif
