/* One cycle of GMRES for small matrix-free systems given as plain arrays (the temperature
 * couplings' Newton steps; solve/gmres.h is KINSOL's, on an rs_krylov): modified Gram-Schmidt,
 * Givens rotations, the basis in the caller's storage. */
#ifndef ROLLSIM_GMRES_CYCLE_H
#define ROLLSIM_GMRES_CYCLE_H

/* Most basis vectors of a cycle. */
#define RS_GMRES_CYCLE_MAX 30

/* out = A v; a nonzero return stops the cycle with that value. */
typedef int (*rs_gmres_op)(void *ctx, const double *v, double *out);

/* Up to mk (<= RS_GMRES_CYCLE_MAX) vectors of the Krylov space of A from V[0..n), the initial
 * residual r0 normalised (beta = |r0|_2), until the residual's estimate is at most tol; V holds
 * (mk + 1) n values. Then x[j] += (V y)[j] / div[j] (div NULL: 1), y minimising
 * |beta e1 - H y|. *res gets the residual's estimate, *used the vectors used. Returns 0 or
 * op's nonzero value (x then unchanged). */
int rs_gmres_cycle(int n, int mk, rs_gmres_op op, void *ctx, double *V, double beta, double tol,
                   const double *div, double *x, double *res, int *used);

#endif
