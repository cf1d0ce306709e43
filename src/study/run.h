/* Running a case end to end: model, initial state, steady or transient solve,
 * netCDF records during the run, status attribute, summary numbers. */
#ifndef ROLLSIM_RUN_H
#define ROLLSIM_RUN_H

#include <signal.h>
#include <stddef.h>
#include "io/case.h"
#include "physics/model.h"
#include "solve/steady.h"
#include "base/status.h"

/* The quantities of every record of a run, in order (rs_run_opts.records); free d and t. */
typedef struct rs_record_diags {
  rs_diag *d;
  double *t; /* the records' times, s */
  size_t n, cap;
} rs_record_diags;

/* The (x) fields of one record, n cells each, in caller-owned arrays. */
typedef struct rs_fields {
  int n;
  double *px, *pn, *slip, *upl, *ustar, *tauc;
  signed char *regime;
  double *mu; /* mu(|v_s|) per cell, NaN outside the contact (velocity-dependent laws) */
} rs_fields;

typedef struct rs_run_opts {
  const char *output_path; /* overrides case output.file when non-NULL */
  const char *history;     /* netCDF history attribute (command line and date) */
  int progress;            /* draw a progress bar on stderr */
  int no_output;           /* compute only (sweep points): no netCDF file */
  /* Transient mode: continue from the last record (state and time) of this earlier
   * output file (io/restart.h) instead of rest or steady rolling; the run then
   * covers [t_last, end_time] on the same output grid k*output_interval. Steady mode:
   * the stored state is Newton's start (the result is checked like every steady one). */
  const char *restart_path;
  /* With restart_path (transient): continue in that file instead of a new one (its
   * records are kept, new ones appended, history gains a line, status is updated). */
  int append;
  /* When set (and final_fields->n is the case's number of cells): receives the fields
   * of the last record (sweep points store them). */
  rs_fields *final_fields;
  /* Warn on stderr when the first steps of a transient run project a long run
   * (study/warnings.h; off for sweep points). */
  int cost_warning;
  /* Set asynchronously (signal handler) to stop at the next output record. */
  volatile sig_atomic_t *interrupt_flag;
  /* When set: every record's quantities appended (the error estimate's companion runs). */
  rs_record_diags *records;
  /* The model's parameters instead of the case's (a wheel-rail patch, study/wheel_rail.h; the
   * case still gives the mode, times, tolerances, outputs and temperature). NULL: the case's. */
  const rs_model_params *params;
  const char *patch; /* with params: the file's wheel_rail_patch attribute */
} rs_run_opts;

typedef struct rs_run_result {
  rs_diag final; /* quantities at the last record */
  double mu;
  double time; /* simulated time of the last record, s */
  rs_stats stats;
  double wall_seconds;
  size_t records;
  char file[1024];
  /* Twin-disc runs: per protocol step, mean traction coefficient and slip over its
   * averaging window (NaN if not reached); revolutions completed. Freed by
   * rs_run_result_free. */
  size_t rig_nsteps;
  double *rig_step_mu, *rig_step_slip;
  size_t rig_nrev;    /* revolutions of the protocol */
  double *rig_rev_mu; /* per revolution: mean traction coefficient (NaN if not reached) */
  double rig_revolutions;
  /* temperature.disc_mass: each disc's bulk temperature after the last completed revolution
   * (degC; the case's bulk temperatures otherwise) */
  double rig_bulk[2];
  double dx;           /* cell size, mm */
  double rolled;       /* transient: distance rolled from the start to the last record, mm */
  double rtol;         /* transient: the relative tolerance run (solver.rtol, auto resolved) */
  char backup[1040];   /* an older file at the output path kept under this name, or "" */
  size_t file_records; /* records in the output file (more than records with append) */
  /* Steady runs: the grid solved ([nx, ny], ny 1 in 2D), whether grid.accuracy chose it,
   * why there is no error estimate ("" when there is one, or none was asked for) and the
   * wall time of the estimate's companion solves. */
  int cells[2];
  int grid_chosen, accuracy_met;
  char error_note[256];
  double error_seconds;
} rs_run_result;

void rs_run_result_free(rs_run_result *res);

/* Returns RS_OK, RS_ERR_SOLVER (status "failed: ..."), RS_ERR_INTERRUPTED,
 * RS_ERR_OUTPUT or RS_ERR_INTERNAL; msg says what happened. Records written
 * before a failure are kept. RS_ERR_INPUT for an invalid restart (file
 * missing or unreadable, a state field missing, another grid, nothing left to run):
 * then no file is written. */
int rs_run(const rs_case *c, const rs_run_opts *o, rs_run_result *res, rs_msg *msg);

/* The model's plain parameters from a case (shallow: the histories are the case's;
 * rs_model_create copies them), and the model itself. */
void rs_model_params_from_case(const rs_case *c, rs_model_params *p);
int rs_model_from_case(rs_model *m, const rs_case *c, rs_msg *msg);

/* Print derived parameters of a case (Hertz a, p0, grid, scaling, ...) for `check`. */
int rs_run_print_derived(const rs_case *c, FILE *out, rs_msg *msg);

#endif
