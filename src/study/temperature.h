/* The surface temperature of a run's records and of sweep points (docs/model.md §18): the heat
 * sources of a contact solution (physics/model.h) marched through physics/thermal.h. */
#ifndef ROLLSIM_STUDY_TEMPERATURE_H
#define ROLLSIM_STUDY_TEMPERATURE_H

#include <stdio.h>

#include "io/case.h"
#include "physics/model.h"
#include "physics/thermal.h"
#include "solve/steady.h"

typedef struct rs_temperature_run {
  int on; /* the case has a temperature: block */
  rs_thermal th;
  double *fric, *plast; /* power densities, N/(mm s) [n] */
  double *q;            /* heat flux density into both bodies, W/mm^2 [n] */
  double *T1, *T2;      /* surface temperatures, degC [n] */
  signed char *contact; /* p_n > 0 [n] */
  /* 1: a transient's modes are DAE state (docs/model.md §18, "Heat memory"), stored after
   * the model's neq unknowns of y; 0: each state's temperature is the steady march's */
  int modes;
  /* The couplings (docs/model.md §18): T_used, the temperature each cell's properties are read
   * at, the last iterate of the coupling [n] (NULL without a table); with mu(T)
   * (friction.temperature_table) the bound's factor mu_table(T)/mu_law(0) that the model reads
   * (rs_model.mu_factor) [n], with tau_c0(T) (plasticity.tau_c0_table) the yield limit's
   * factor tau_c0_table(T)/tau_c0 (rs_model.yield_factor) [n]; each NULL without its table. */
  double *T_used, *mu_factor, *yield_factor;
  const rs_history *mu_table, *tau_table;
  double mu_rest;         /* mu_law(0) */
  double tau_rest;        /* plasticity.tau_c0 */
  int coupling;           /* temperature.coupling: RS_COUPLING_NEWTON or RS_COUPLING_FIXED_POINT */
  long couplings;         /* coupled iterations (steady solves with the factors held), summed */
  long newton_steps;      /* Newton steps of the coupling, summed */
  long coupling_products; /* products with the coupling's Jacobian (GMRES), summed */
} rs_temperature_run;

/* Nothing to do (on = 0) when the case has no temperature: block. */
int rs_temperature_run_create(rs_temperature_run *t, const rs_case *c, const rs_model *m,
                              rs_msg *msg);
void rs_temperature_run_free(rs_temperature_run *t);
/* The temperatures of the state y from a work evaluated at (in, y) (rs_model_diagnostics):
 * fills T1, T2 and d's T_max and heat inputs; with modes from the modes of y, else from the
 * steady march of the sources. */
void rs_temperature_run_eval(rs_temperature_run *t, const rs_model *m, const rs_work *w,
                             const rs_inputs *in, const double *y, rs_diag *d);

/* With modes: the steady modes of the steady state y (rolling at in) into y after the
 * model's unknowns, their rates (0) into yp: the march of the steady sources (those of y' = 0;
 * the consistent rates of a steady state split the rates of cells at both bounds between slip
 * and flow otherwise, by a few 1e-4 of the power). rs_temperature_run_rates: the consistent
 * rates of the modes at (y, yp) into yp after the model's (the contact's rates consistent
 * already). Each evaluates the model into w. */
int rs_temperature_run_steady_modes(rs_temperature_run *t, const rs_model *m, rs_work *w,
                                    const rs_inputs *in, double *y, double *yp, rs_msg *msg);
int rs_temperature_run_rates(rs_temperature_run *t, const rs_model *m, rs_work *w,
                             const rs_inputs *in, const double *y, double *yp, rs_msg *msg);

/* With modes and a table: T_used and the factors from the temperatures of the modes in y (a
 * transient's start from rest or from a restart file: the coupling of transient.h), rolling at
 * in. Nothing to do otherwise. */
void rs_temperature_run_state_factors(rs_temperature_run *t, const rs_model *m, const rs_inputs *in,
                                      const double *y);

/* The case couples the contact to its temperature: friction.temperature_table or
 * plasticity.tau_c0_table. */
int rs_temperature_coupled(const rs_case *c);

/* The steady state coupled with mu(T) and tau_c0(T) (docs/model.md §18, "Couplings"): from the
 * last temperatures (the contact temperature of cold surfaces at the first call), the steady
 * solve with the factors of T_used warm-started from y, then the march of its sources, until the
 * largest change of the contact temperature is below RS_COUPLING_TOL of the rise; each update a
 * Newton step on G(T) = T - march(T) with the exact coupling Jacobian (t->coupling
 * RS_COUPLING_NEWTON), falling back to the Anderson-accelerated fixed point where its line search
 * fails, or that fixed point alone (RS_COUPLING_FIXED_POINT). Sets m->mu_factor and
 * m->yield_factor (those of its tables); adds its counts to stats. RS_ERR_SOLVER when it does not
 * converge in RS_COUPLING_MAX steady solves. Nothing to do without a table. */
#define RS_COUPLING_TOL 1e-9
#define RS_COUPLING_MAX 200
int rs_temperature_couple(rs_temperature_run *t, rs_model *m, rs_work *w, rs_steady *st, double *y,
                          rs_stats *stats, rs_msg *msg);

/* rollsim check: beta of each body, the kernel's modes and error, and the Peclet number
 * V a/(2 kappa) of each body at t = 0 (docs/model.md §18). Nothing without the block. */
int rs_temperature_print_derived(const rs_case *c, const rs_model *m, FILE *out, rs_msg *msg);

#endif
