/* The sweep: block of a case file (docs/case-file.md): dotted case keys mapped to value
 * lists (or {linspace: [from, to, n]}), read and validated here; run by rs_sweep_run
 * (study/sweep.h). */
#ifndef ROLLSIM_CASE_SWEEP_H
#define ROLLSIM_CASE_SWEEP_H

#include <stddef.h>
#include "base/status.h"
#include "io/case.h"

typedef struct rs_sweep_axis {
  char *key;      /* dotted case key, e.g. "rolling.creepage" */
  int key_index;  /* its index in the key table (rs_case_key_index) */
  int n;          /* number of values */
  double *values; /* [n] */
} rs_sweep_axis;

typedef struct rs_sweep {
  int naxes;
  rs_sweep_axis *axes; /* in file order; the last varies fastest */
  size_t npoints;      /* product of the axis lengths (positions: their common length) */
  /* 1: a sweep on profiles, a path of wheelset positions: keys of the profiles: block
   * (key_index -1), point k takes the k-th value of every axis */
  int positions;
} rs_sweep;

/* Read the sweep block of a loaded case (rs_case_load: after the --set assignments).
 * Errors name file:line and the key; every swept value is validated by deriving the case
 * with it (rs_case_derive), a position of a sweep on profiles by placing the wheelset there. */
int rs_sweep_load(rs_sweep *s, const rs_case *c, rs_msg *msg);
void rs_sweep_free(rs_sweep *s);

#endif
