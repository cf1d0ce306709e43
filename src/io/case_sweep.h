/* The sweep: block of a case file (interfaces.md "Sweeps"): dotted case keys mapped to
 * value lists (or {linspace: [from, to, n]}), read and validated here; run by
 * rs_sweep_run (study/sweep.h). */
#ifndef ROLLSIM_CASE_SWEEP_H
#define ROLLSIM_CASE_SWEEP_H

#include <stddef.h>
#include "base/status.h"

typedef struct rs_sweep_axis {
  char *key;      /* dotted case key, e.g. "rolling.creepage" */
  int n;          /* number of values */
  double *values; /* [n] */
} rs_sweep_axis;

typedef struct rs_sweep {
  int naxes;
  rs_sweep_axis *axes; /* in file order; the last varies fastest */
  size_t npoints;      /* product of the axis lengths */
} rs_sweep;

/* Read the sweep block of a case file (after the --set assignments). Errors name
 * file:line and the key; every swept value is validated by loading the case with it. */
int rs_sweep_load(rs_sweep *s, const char *path, const char *const *sets, int nsets, rs_msg *msg);
void rs_sweep_free(rs_sweep *s);

#endif
