/* The fields of one record kept for sweep files, and which profiles a sweep stores
 * (sweep_fields.c). */
#ifndef ROLLSIM_STUDY_SWEEP_FIELDS_H
#define ROLLSIM_STUDY_SWEEP_FIELDS_H

#include <stddef.h>

#include "io/case.h"
#include "io/case_sweep.h"
#include "study/run.h"

int rs_fields_alloc(rs_fields *f, int n);
void rs_fields_free(rs_fields *f);
void rs_fields_copy(rs_fields *f, int n, const double *y, const double *pn, const double *slip,
                    const double *tauc, const signed char *regime, const double *mu);
/* The profile fields a sweep of case c stores: output.fields, tau_c only with plasticity,
 * mu with a velocity-dependent friction law; none in 3D (a 3D sweep file holds the forces
 * and counts; a warning says so on stderr when `warn` and fields were asked for). */
unsigned rs_sweep_profile_fields(const rs_case *c, int warn);

/* Whether every point of the sweep has the grid of the loaded case c (*common; the
 * profiles then share one x axis): the model of c and of each swept value (the other keys
 * at c's values) are compared; a rolling input under a constant normal load leaves the grid
 * as it is and is not built. Common: x (malloc'ed) and n hold the grid; else why says which
 * key changes it. Returns a status (case or model errors). */
int rs_sweep_common_grid(const rs_sweep *s, const rs_case *c, int *common, double **x, int *n,
                         char *why, size_t why_len, rs_msg *msg);

#endif
