/* A rollsim case: every key of the case file (docs/case-file.md), resolved and
 * validated, with defaults filled in. Units: mm, N, s, N/mm^2 (docs/model.md §1). */
#ifndef ROLLSIM_CASE_H
#define ROLLSIM_CASE_H

#include <stdio.h>
#include "physics/history.h"
#include "physics/model.h"   /* rs_normal_solution, rs_scaling */
#include "physics/thermal.h" /* rs_thermal_params */
#include "base/status.h"

/* temperature.coupling (the order of its names in the case file) */
enum { RS_COUPLING_NEWTON = 0, RS_COUPLING_FIXED_POINT = 1 };

typedef enum { RS_MODE_TRANSIENT = 0, RS_MODE_STEADY = 1 } rs_mode;
typedef enum { RS_START_REST = 0, RS_START_STEADY = 1 } rs_initial_state;

/* Output fields (bit mask) */
enum {
  RS_FIELD_PX = 1 << 0,
  RS_FIELD_PN = 1 << 1,
  RS_FIELD_SLIP = 1 << 2,
  RS_FIELD_UPL = 1 << 3,
  RS_FIELD_USTAR = 1 << 4,
  RS_FIELD_TAUC = 1 << 5,
  RS_FIELD_REGIME = 1 << 6,
  /* mu(|v_s|) (with friction.temperature_table mu(|v_s|, T)) per cell: written whenever the
   * friction law is not Coulomb or the table is given (not a choice of output.fields) */
  RS_FIELD_MU = 1 << 7,
  /* the surface temperatures T1, T2 and the scalars T_max, heat_input_1, heat_input_2: written
   * whenever the case has a temperature: block (not a choice of output.fields) */
  RS_FIELD_TEMPERATURE = 1 << 8
};

/* One step of a twin-disc protocol: slip held (slip_start == slip_end) or ramped. */
typedef struct rs_rig_step {
  double slip_start, slip_end; /* rig slip s = (V1 - V2)/V = -creepage (s > 0: F_x > 0) */
  double revolutions;          /* of disc 1 */
} rs_rig_step;

/* twin_disc: block (docs/model.md §8). When present it sets contact.normal_load (F/width),
 * contact.radius, rolling.velocity, rolling.creepage and simulation.end_time. */
typedef struct rs_twin_disc {
  int on;
  double radius_1, radius_2;             /* mm */
  double crown_radius_1, crown_radius_2; /* mm, crowned discs (3D contact); 0: flat */
  double width;                          /* mm */
  double normal_force;                   /* N */
  double rpm;                            /* rolling speed as revolutions per minute of disc 1 */
  double rpm_1, rpm_2;                   /* alternative: the disc speeds (constant slip) */
  double revolutions;                    /* with rpm_1/rpm_2: length of the run */
  double recovery;                       /* fraction of u_pl, u* kept per revolution, [0, 1] */
  double average_window;                 /* trailing fraction of each step averaged, (0, 1] */
  size_t nsteps;
  rs_rig_step *steps;
  double revolution_time; /* s, 2 pi R1 / V (derived) */
} rs_twin_disc;

typedef struct rs_case {
  char *source_path; /* the case file as given on the command line */
  char *yaml_text;   /* the case as run (after --set), as YAML text */
  char *title;
  char *overrides; /* the --set assignments, "KEY=VALUE, KEY=VALUE" (NULL: none): the title
                      describes the file, these what was changed on the command line */

  /* contact: */
  int dimension;          /* 2: line contact; 3: elliptic point contact */
  rs_history normal_load; /* N/mm (2D) */
  double radius;          /* mm, combined radius (3D: Rx) */
  double radius_y;        /* mm, 3D: Ry (from contact.radius or contact.curvature) */
  rs_normal_solution normal_solution;
  double reference_length; /* mm, L of the 2D kernel */

  /* grid: */
  int cells;           /* along x */
  int cells_y;         /* 3D: along y */
  double extent;       /* half-length of the potential contact area, in Hertz a */
  double extent_y;     /* 3D: half-width, in Hertz b */
  int grid_from_range; /* 1: grid.x_range (3D: and y_range) given (instead of grid.extent) */
  int align_edges;     /* grid.align_edges (2D): extent set so that +-a fall on cell faces */
  double accuracy;     /* grid.accuracy: refine until the force error < accuracy mu F_n (0: off) */
  double y_range[2];   /* mm, 3D */
  double x_range[2];   /* mm, outer edges of the potential contact area */

  /* material: */
  double shear_modulus; /* G, N/mm^2 */
  double poisson_ratio; /* nu */

  /* friction: */
  double mu;            /* coulomb; with another law mu(0), the coefficient at rest */
  rs_friction friction; /* the law (kind from friction.law) and its parameters */
  /* friction.temperature_table: the coefficient at rest against the contact temperature,
   * piecewise linear (t: degC, strictly increasing; v: mu); n = 0: none (docs/model.md §18) */
  rs_history mu_table;

  /* layer: */
  double layer_thickness;     /* h3, mm */
  double layer_shear_modulus; /* G3, N/mm^2 */

  /* plasticity: */
  int has_plasticity; /* 0: the block is absent (purely elastic) */
  double tau_c0;      /* N/mm^2 */
  double k_tau;       /* N/mm^3 (k_rel converted: k_tau = G*k_rel/(1-k_rel)) */
  double tau_c_min;   /* N/mm^2, default 0.1*tau_c0 */
  /* plasticity.tau_c0_table: tau_c0 against the contact temperature, piecewise linear (t: degC,
   * strictly increasing; v: N/mm^2); n = 0: none (docs/model.md §18) */
  rs_history tau_c0_table;
  /* temperature.coupling: how steady states with either table are coupled to their
   * temperature (docs/model.md §18): RS_COUPLING_NEWTON (default) or RS_COUPLING_FIXED_POINT */
  int temperature_coupling;

  /* rolling: */
  rs_history velocity;           /* V, mm/s */
  rs_history creepage;           /* xi (unused when force_control) */
  rs_history lateral_creepage;   /* eta, 3D (unused when force_control) */
  rs_history spin;               /* phi, 1/mm, 3D */
  int force_control;             /* 1: rolling.tangential_force given, xi is an unknown */
  rs_history tangential_force;   /* F_x, N/mm (2D; N in 3D), when force_control */
  rs_history tangential_force_y; /* F_y, N (3D), when force_control */
  rs_history shift_velocity;     /* mm/s, rigid tangential shift rate (a history too) */

  /* simulation: */
  rs_mode mode;
  double end_time;        /* s (derived from rolled_distance when that was given) */
  double rolled_distance; /* mm, < 0 when not given */
  double output_interval; /* s */
  rs_initial_state initial_state;

  /* solver: */
  double rtol, atol; /* atol in N/mm^2 (tractions); rtol 0: auto (rs_transient_auto_rtol) */
  int max_order;
  int threads;        /* solver.threads: 1, or 2 for the 3D work a solve splits in two */
  rs_scaling scaling; /* solver.scaling: auto | difference | self */
  long max_steps;     /* solver.max_steps, default 1000000 */

  /* twin_disc: */
  rs_twin_disc rig;

  /* temperature: (on = 0 when the block is absent) */
  rs_thermal_params temperature;

  /* output: */
  char *output_file;
  unsigned fields;    /* RS_FIELD_* mask */
  int error_estimate; /* output.error_estimate: 1 (default) estimate steady results' errors */

  /* sweep: */
  int has_sweep; /* the case has a sweep: block (study/sweep.h) */

  /* profiles: (io/profile.h) */
  int has_profiles;               /* the case has a profiles: block */
  struct rs_wheel_rail *profiles; /* the profiles read (rs_case_load only; NULL in derived
                                     cases) */

  /* The case file as loaded (rs_case_load; owned, NULL in derived cases): what
   * rs_case_derive builds cases from, and where the sweep: and fit: blocks are read. */
  struct rs_case_source *source;
} rs_case;

/* Load and validate a case file. `sets` are the --set KEY=VALUE strings, applied
 * after parsing the file (a --set value is parsed as a YAML scalar/flow node).
 * On error returns RS_ERR_INPUT with msg like
 *   "cases/x.yaml:12: plasticity.k_tau: expected a number, got \"abc\""
 * and leaves *c freed/zeroed. */
int rs_case_load(rs_case *c, const char *path, const char *const *sets, int nsets, rs_msg *msg);
void rs_case_free(rs_case *c);

/* RS_ERR_INPUT with "CASE:LINE: profiles: ..." when the case has a profiles: block, which
 * `rollsim check`, `run` and `sweep` use (a fit on profiles is not built yet). */
int rs_case_refuse_profiles(const rs_case *c, rs_msg *msg);
/* The summary of the profiles for `rollsim check` (nothing without a profiles: block). */
void rs_case_print_profiles(const rs_case *c, FILE *out);

/* Index of a dotted key in the key table (docs/case-file.md), or -1; its name. */
int rs_case_key_index(const char *path);
const char *rs_case_key_name(int key);
/* 1 if a key takes a number: a number, whole-number or history key (a history given
 * as a number is constant). Sweeps and fits set only such keys. */
int rs_case_key_numeric(int key);

/* A typed override: a numeric key of the key table and its value. Sweep values, fit
 * parameters and fit inputs are applied to a loaded case as these, without reading or
 * parsing the case file again. */
typedef struct rs_case_override {
  int key; /* rs_case_key_index */
  double value;
} rs_case_override;

/* The case `base` (from rs_case_load) with the overrides applied in order, as if each were
 * one more --set KEY=VALUE after the command's: the same values, the same checks, and the
 * same messages ("--set KEY: ..."). The derived case has no yaml_text and no source (the
 * YAML as run is the base's); free it with rs_case_free. Safe to call from several threads
 * on one base. */
int rs_case_derive(const rs_case *base, const rs_case_override *ov, int nov, rs_case *c,
                   rs_msg *msg);

/* The rolling inputs along which a steady sweep continues from one point to the next (a
 * change of one of them leaves the rest of the model as it is). */
typedef enum rs_rolling_input {
  RS_ROLLING_NONE = 0,
  RS_ROLLING_CREEPAGE,
  RS_ROLLING_VELOCITY,
  RS_ROLLING_SHIFT_VELOCITY,
  RS_ROLLING_LATERAL_CREEPAGE,
  RS_ROLLING_SPIN
} rs_rolling_input;
/* The rolling input a key sets, or RS_ROLLING_NONE. */
rs_rolling_input rs_case_key_rolling(int key);

/* Print every resolved parameter, one "key: value  # unit" line each (for `rollsim check`).
 * Steady cases leave out the keys of the time axis (end time, rolled distance, output
 * interval, initial state), which do not apply to them. */
void rs_case_print(const rs_case *c, FILE *out);

/* Unit of a case key in UDUNITS-2 spelling for netCDF `units` attributes ("1" for
 * plain numbers, counts and multiples of the Hertz half-width); NULL for an unknown key.
 * rs_case_key_unit_note: what a "1" stands for when it is not a plain number
 * ("in Hertz half-widths a"), else "". */
const char *rs_case_key_units(const char *key);
const char *rs_case_key_unit_note(const char *key);

#endif
