/* Private to the drivers: the twin-disc rig's bookkeeping during a transient run
 * (docs/model.md §8): the circumferential memory of the state leaving the contact, and the
 * time integrals of F_x/F_n and of the slip over each revolution and each protocol
 * step's averaging window (trapezoidal between accepted time steps), written to the
 * output as each completes; per revolution also the energy dissipated (frictional plus
 * plastic power integrated over it) and the u* of the surface leaving the contact (its
 * mean over the revolution and its largest value). */
#ifndef ROLLSIM_RIG_PROTOCOL_H
#define ROLLSIM_RIG_PROTOCOL_H

#include "io/output.h"
#include "physics/rig.h"
#include "study/run.h"
#include "study/temperature.h"

typedef struct rs_rig_run {
  const rs_case *c;
  const rs_model *m;
  rs_rig_memory mem;
  rs_output *out; /* NULL until the output file is open */
  rs_run_result *res;
  double *window_start, *slip_start, *slip_end, *time_start, *time_end; /* per step */
  double *exit_buf;       /* 3D: the exit state of every row (memory width values) */
  size_t nrev, rev, step; /* revolutions, current revolution, current step */
  double t_prev, mu_prev, slip_prev, power_prev, ustar_prev;
  double rev_mu, rev_slip, step_mu, step_slip; /* integrals so far */
  double rev_energy, rev_ustar, rev_ustar_max; /* of the current revolution so far */
  rs_work w;                                   /* the dissipated power's evaluation */
  /* With a temperature: block (rs_rig_run_heat; temp NULL otherwise): the surface modes
   * leaving the contact, carried around like the plastic state (docs/model.md §18), and per
   * revolution the largest contact temperature, the time integrals of each disc's inlet
   * temperature and heat input, and the discs' bulk temperatures (temperature.disc_mass). */
  rs_temperature_run *temp;
  rs_rig_memory heat;
  double *heat_buf;                            /* the modes leaving, [heat.width] */
  double rev_T_max, rev_inlet[2], rev_heat[2]; /* of the current revolution so far */
  double inlet_prev[2], heat_prev[2];
  int started;
  rs_msg msg;
} rs_rig_run;

/* The memory sized for the discs of c and the protocol's step times; the per-step
 * results in res (allocated here, freed by rs_run_result_free). */
int rs_rig_run_create(rs_rig_run *r, const rs_case *c, const rs_model *m, rs_run_result *res,
                      rs_msg *msg);
void rs_rig_run_free(rs_rig_run *r);
/* The rig's heat memory for the temperature modes of temp (a transient with a temperature:
 * block): attaches it to temp's thermal model. */
int rs_rig_run_heat(rs_rig_run *r, rs_temperature_run *temp, rs_msg *msg);
/* After every accepted time step (rs_transient_opts.step_hook): record the exit state,
 * integrate, write completed revolutions and steps. */
int rs_rig_run_step(void *rig, double t, const double *y, const double *yp);
/* The output file's description of the protocol (its arrays point into r). */
rs_output_rig rs_rig_run_output(const rs_rig_run *r);

#endif
