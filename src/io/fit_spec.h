/* The fit: block of a case (docs/case-file.md) and the fit file (docs/file-format.md): which
 * case keys to fit (start, bounds) and a CSV of measurements whose columns are inputs (swept
 * case keys, or a twin-disc protocol step) and one measured output. rs_fit_load reads and
 * checks it (io/fit_spec.c), rs_fit_output_write writes FIT.nc (io/output_fit.c); the fit
 * itself is study/fit.h. */
#ifndef ROLLSIM_IO_FIT_SPEC_H
#define ROLLSIM_IO_FIT_SPEC_H

#include <stddef.h>

#include "base/status.h"
#include "io/case.h"

typedef struct rs_fit_param {
  char *key;        /* dotted case key, e.g. "plasticity.tau_c0" */
  double start;     /* first guess */
  double lo, hi;    /* bounds, lo < hi, lo <= start <= hi */
  const char *unit; /* from the key table (static) */
} rs_fit_param;

/* What a data row is matched against. */
typedef enum {
  RS_FIT_STEADY = 0, /* steady points: the input columns are case keys (a sweep) */
  RS_FIT_RIG_STEP,   /* twin-disc protocol: the column `step` (1-based protocol step) */
  RS_FIT_RIG_SLIP,   /* twin-disc protocol: the column `twin_disc.slip` (a held step's slip) */
  RS_FIT_RIG_REV     /* twin-disc protocol: the column `revolution` (1-based, of disc 1) */
} rs_fit_kind;

/* Role of a CSV column. */
typedef enum { RS_FIT_COL_INPUT = 0, RS_FIT_COL_MEASURED, RS_FIT_COL_WEIGHT } rs_fit_role;

typedef struct rs_fit_spec {
  int nparams;
  rs_fit_param *params;
  char *data_path; /* the CSV as opened (relative to the case's directory) */
  char *measured;  /* output variable the measured column holds: traction_coefficient or Fx */
  char *weights;   /* column of per-point weights 1/sigma, or NULL */
  rs_fit_kind kind;
  int ncols;
  char **columns;               /* CSV header names [ncols] */
  char **input_keys;            /* [ncols]: dotted case key of an input column (NULL for others) */
  rs_fit_role *roles;           /* [ncols] */
  int measured_col, weight_col; /* weight_col -1: all weights 1 */
  size_t npoints;
  double *table; /* [npoints][ncols], rows in file order */
  int *row_line; /* [npoints] line of each row in the CSV file */
} rs_fit_spec;

/* Read and check the fit: block of a case (after --set) and its CSV. Errors name
 * case.yaml:line: fit.KEY or data.csv:line: column; nothing is run. */
int rs_fit_load(rs_fit_spec *f, const rs_case *c, rs_msg *msg);
void rs_fit_free(rs_fit_spec *f);

/* FIT.nc (io/output_fit.c): written whole to PATH.part and renamed over PATH (an older
 * file is kept as PATH~ the first time). */
typedef struct rs_fit_output {
  const char *path, *title, *case_text, *history, *status, *notes;
  const rs_fit_spec *spec;
  const double *start, *fitted, *std_error, *covariance, *simulated;
  double residual_norm;
  long evaluations;
  int keep_old;  /* rename an existing file to PATH~ first */
  int dimension; /* contact.dimension of the case: units of forces (N/mm in 2D, N in 3D) */
} rs_fit_output;
int rs_fit_output_write(const rs_fit_output *o, char *backup, size_t backup_len, rs_msg *msg);

/* What rollsim fit --resume continues from: an existing FIT.nc of the same fit. */
typedef struct rs_fit_previous {
  double *start, *fitted; /* [nparams] as stored (fitted: the best point so far) */
  double residual_norm;
  long evaluations;
  int complete; /* status "complete": nothing to resume */
  char *history;
} rs_fit_previous;
/* Read FIT.nc at path for a resume of the fit f of the case whose text is case_text. Refused
 * (RS_ERR_INPUT, "PATH: cannot resume: why"; the file only read) when it is missing,
 * truncated, not a fit file, or of another case text, other parameters or bounds, or other
 * data. */
int rs_fit_output_read_previous(const char *path, const rs_fit_spec *f, const char *case_text,
                                rs_fit_previous *prev, rs_msg *msg);
void rs_fit_previous_free(rs_fit_previous *prev);

#endif
