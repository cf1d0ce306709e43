/* The surface temperature of a run's records and of sweep points (docs/model.md §18): the heat
 * sources of a contact solution (physics/model.h) marched through physics/thermal.h. */
#ifndef ROLLSIM_STUDY_TEMPERATURE_H
#define ROLLSIM_STUDY_TEMPERATURE_H

#include <stdio.h>

#include "io/case.h"
#include "physics/model.h"
#include "physics/thermal.h"

typedef struct rs_temperature_run {
  int on; /* the case has a temperature: block */
  rs_thermal th;
  double *fric, *plast; /* power densities, N/(mm s) [n] */
  double *q;            /* heat flux density into both bodies, W/mm^2 [n] */
  double *T1, *T2;      /* surface temperatures, degC [n] */
  signed char *contact; /* p_n > 0 [n] */
} rs_temperature_run;

/* Nothing to do (on = 0) when the case has no temperature: block. */
int rs_temperature_run_create(rs_temperature_run *t, const rs_case *c, const rs_model *m,
                              rs_msg *msg);
void rs_temperature_run_free(rs_temperature_run *t);
/* The temperatures of the state y from a work evaluated at (in, y) (rs_model_diagnostics):
 * fills T1, T2 and d's T_max and heat inputs. */
void rs_temperature_run_eval(rs_temperature_run *t, const rs_model *m, const rs_work *w,
                             const rs_inputs *in, const double *y, rs_diag *d);

/* rollsim check: beta of each body, the kernel's modes and error, and the Peclet number
 * V a/(2 kappa) of each body at t = 0 (docs/model.md §18). Nothing without the block. */
int rs_temperature_print_derived(const rs_case *c, const rs_model *m, FILE *out, rs_msg *msg);

#endif
