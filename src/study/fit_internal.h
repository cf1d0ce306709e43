/* Private to rollsim fit (study/fit*.c): evaluating the model on a data set, and the
 * finite-difference columns of the Jacobian (serial, or over MPI ranks). */
#ifndef ROLLSIM_FIT_INTERNAL_H
#define ROLLSIM_FIT_INTERNAL_H

#include <stddef.h>

#include "study/fit.h"
#include "physics/model.h"

/* The model evaluated on every data row at given parameter values. */
typedef struct rs_fit_eval {
  const rs_fit_spec *f;
  const rs_case *base;  /* the loaded case */
  rs_case_override *ov; /* [1 + nparams + ncols]: the parameters, the tolerance, then a
                         * line's other inputs */
  int rtol_key;         /* solver.rtol when a transient case leaves it auto, else -1 */
  int *param_key;       /* [nparams] key index of each parameter */
  int *input_key;       /* [ncols] key index of each input column (-1 for others) */
  int key_col;          /* the continued input column (steady fits) */
  size_t nlines;        /* continuation lines: rows [line_start[l], line_start[l + 1]) */
  size_t *line_start;
  double *xs;       /* [npoints] the continued input of each row */
  rs_diag *diag;    /* [npoints] */
  int *ok;          /* [npoints] */
  size_t line0;     /* first row of the line being solved */
  long evaluations; /* whole data sets evaluated */
} rs_fit_eval;

int rs_fit_eval_init(rs_fit_eval *e, const rs_fit_spec *f, const rs_case *base, rs_msg *msg);
void rs_fit_eval_free(rs_fit_eval *e);
/* sim[i]: the simulated output of data row i at parameters p. RS_ERR_SOLVER when a
 * point fails (the message names the parameter values). */
int rs_fit_eval_at(rs_fit_eval *e, const double *p, double *sim, rs_msg *msg);
/* Forward-difference step of a parameter at p (negative near the upper bound). */
double rs_fit_fd_step(const rs_fit_param *q, double p);

/* The Jacobian dr/dp by forward differences, column k = w (sim(p + h_k e_k) - sim0)/h_k,
 * column-major with leading dimension ld. Serial, or one column per MPI rank at a time
 * (the same numbers: each column is computed whole on one rank). */
typedef struct rs_fit_columns rs_fit_columns;
int rs_fit_columns_create(rs_fit_columns **c, const rs_fit_spec *f, int rank, int size,
                          rs_msg *msg);
void rs_fit_columns_free(rs_fit_columns *c);
int rs_fit_columns_eval(rs_fit_columns *c, rs_fit_eval *e, const double *p, const double *sim0,
                        const double *w, double *jac, int ld, rs_msg *msg);

/* MPI ranks > 0: compute the columns k = rank, rank + size, ... for every parameter vector
 * rank 0 sends, until it says stop. */
int rs_fit_columns_serve(rs_fit_columns *c, rs_fit_eval *e);

#endif
