/* Private: optimised kernels for SUNDIALS' serial N_Vector.
 *
 * Debian 12's SUNDIALS 6.4.1 (libsundials-nvecserial6) is compiled without
 * optimisation: N_VDotProd_Serial keeps its loop counter and its sum in stack memory
 * (one dependent load/add/store per element), several times slower than a plain -O2
 * loop, and the Newton-Krylov iterations spend much of their time in these kernels.
 *
 * rs_nvector_fast_ops replaces the operations of one serial vector that KINSOL,
 * IDA and SPGMR use in their inner loops by equivalent kernels compiled with this
 * project (BLAS level 1 where BLAS has the operation). Vectors cloned from it
 * (KINSOL's and IDA's work vectors, the Krylov basis) copy its operation table, so
 * it is enough to call it on the template vector before the solver is created.
 * The results equal the library's up to the order of floating-point summation. */
#ifndef ROLLSIM_NVECTOR_FAST_H
#define ROLLSIM_NVECTOR_FAST_H

#include <sundials/sundials_nvector.h>

/* RS_OK, or RS_ERR_INTERNAL if v is not a serial vector (left unchanged). */
int rs_nvector_fast_ops(N_Vector v);

#endif
