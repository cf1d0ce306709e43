/* rollsim fit: the bounded nonlinear least-squares problem of a case's fit: block
 * (io/fit_spec.h), solved with MINPACK's Levenberg-Marquardt (study/fit.c). */
#ifndef ROLLSIM_STUDY_FIT_H
#define ROLLSIM_STUDY_FIT_H

#include <signal.h>
#include <stddef.h>

#include "base/status.h"
#include "io/case.h"
#include "io/fit_spec.h"

typedef struct rs_fit_opts {
  const char *output_path; /* FIT.nc (default: the case's output.file) */
  const char *history;
  int progress;                          /* evaluation count and residual on stderr */
  volatile sig_atomic_t *interrupt_flag; /* Ctrl-C: stop, keep the best point */
  int mpi_rank, mpi_size; /* under MPI: the Jacobian's columns over the ranks (else 0, 1) */
  int resume; /* continue the fit in FIT.nc from its best point (rollsim fit --resume) */
} rs_fit_opts;

typedef struct rs_fit_result {
  int nparams;
  size_t npoints;
  double *fitted, *std_error; /* [nparams]; std_error and covariance NaN unless complete */
  double *covariance;         /* [nparams][nparams] */
  double *simulated;          /* [npoints] at the fitted values */
  double residual_norm;       /* |W (simulated - measured)| */
  long evaluations;           /* model evaluations (whole data sets), the resumed file's included */
  long evaluations_before;    /* --resume: those the file held (0 otherwise) */
  int resumed;                /* --resume: continued from the file's best point */
  int already_complete;       /* --resume of a complete file: nothing run, the file untouched */
  int minpack_info;           /* lmder's info */
  double wall_seconds;
  char stop_reason[256];
  char notes[2048]; /* bounds reached, no effect, correlated pairs ("" when none) */
  char file[1024];
  char backup[1040];
} rs_fit_result;

int rs_fit_run(const rs_fit_spec *f, const rs_case *c, const rs_fit_opts *o, rs_fit_result *res,
               rs_msg *msg);
void rs_fit_result_free(rs_fit_result *res);
/* MPI ranks > 0 of a fit: serve rank 0's Jacobian columns until it is done. */
int rs_fit_serve(const rs_fit_spec *f, const rs_case *c, const rs_fit_opts *o, rs_msg *msg);

#endif
