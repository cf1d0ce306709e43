/* netCDF output (docs/file-format.md "Run files"): CF-1.10, dimension time (unlimited)
 * and x, one record per output time, synced to disk after every record so that the
 * file stays readable with every record written so far if the process dies.
 * The output module knows nothing of the solver: it writes what it is given. */
#ifndef ROLLSIM_OUTPUT_H
#define ROLLSIM_OUTPUT_H

#include <stddef.h>
#include "base/status.h"

typedef struct rs_output rs_output;

/* Twin-disc summaries (fixed dimensions protocol_step and revolution): the protocol is
 * written at creation, the traction coefficients as each step or revolution completes
 * (NaN until then). */
typedef struct rs_output_rig {
  size_t nsteps, nrevolutions;
  const double *slip_start, *slip_end; /* [nsteps], rig slip (V1 - V2)/V */
  const double *time_start, *time_end; /* [nsteps], s */
  const double *window_start;          /* [nsteps], s: start of the averaging window */
  double revolution_time;              /* s */
  double recovery;
  /* a temperature: block: the per-revolution temperatures (revolution_T_max, ...), and with
   * bulk also the discs' bulk temperatures (temperature.disc_mass) */
  int temperature, bulk;
} rs_output_rig;

typedef struct rs_output_spec {
  const char *path;      /* file to create (overwritten if it exists) */
  const char *title;     /* global attribute title */
  const char *case_text; /* global attribute case: the full YAML as run */
  const char *history;   /* global attribute history: e.g. the command line and date */
  const char *patch;     /* global attribute wheel_rail_patch: which patch of a run on
                          * profiles the file holds (NULL: none) */
  int dimension;         /* 2: force units N/mm; 3: N, fields over (time, y, x) */
  size_t nx;             /* number of cells (3D: along x) */
  const double *x;       /* cell centres, mm [nx] */
  size_t ny;             /* 3D: cells along y (2D: 0 or 1, no y dimension) */
  const double *y;       /* 3D: cell centres along y, mm [ny] */
  unsigned fields;       /* RS_FIELD_* mask (io/case.h): which (time, x) fields to write */
  /* The fields output.fields asked for (0: all of `fields`). Fields written beyond them
   * (the state a restart needs) carry a `comment` saying so; the global attribute
   * output_fields lists the requested ones. */
  unsigned requested_fields;
  const rs_output_rig *rig; /* twin-disc summaries, or NULL */
  /* 3D: the Hertz semi-axes (mm) at the load hertz_load (N, the run's largest), written as
   * the global attributes hertz_a, hertz_b, hertz_load (0: none written). */
  double hertz_a, hertz_b, hertz_load;
  /* Transient runs: IDA's relative tolerance as run (solver.rtol, `auto` resolved), written
   * as the global attribute solver_rtol (0: none written). */
  double rtol;
  /* Steady runs: the error estimate's variables (error_reliable, Fx_error,
   * traction_coefficient_error; 3D Fy_error, Mz_error) per record, and the global attribute
   * grid_cells_used (the grid grid.accuracy chose: [nx] or [nx, ny]) when grid_chosen. */
  int error_estimate;
  int grid_chosen;
  /* Transient runs with a temperature: block: the surface temperature's modes per cell
   * (2 (K + 1), physics/thermal.h), written as temperature_modes over (time,
   * temperature_mode, [y,] x) for --restart (0: none). */
  int temperature_modes;
} rs_output_spec;

/* One record. Scalars per docs/model.md §7; field arrays have n = nx (3D: nx ny, y slowest)
 * entries (NULL allowed for fields not in the mask). In 3D px, slip and upl hold both
 * components, the x one in the first n entries and the y one in the next n; they are
 * written as px/py, slip_x/slip_y and upl_x/upl_y. */
typedef struct rs_record {
  double time;                   /* s */
  double Fx, Fn;                 /* N/mm (2D), N (3D) */
  double creepage;               /* 1 */
  double Fy, Mz;                 /* 3D: N, N mm (not written in 2D) */
  double lateral_creepage, spin; /* 3D: 1, 1/mm */
  double velocity;               /* mm/s */
  int n_exterior, n_adhesion, n_slip, n_plastic;
  double frictional_power;                           /* N mm/s per mm */
  double plastic_power;                              /* N mm/s per mm */
  double elastic_energy;                             /* N mm per mm */
  const double *px, *pn, *slip, *upl, *ustar, *tauc; /* [nx] */
  const signed char *regime;                         /* [nx]: 0 E, 1 H, 2 S, 3 P */
  const double *mu; /* [nx]: mu(|v_s|) in the contact, NaN outside (not Coulomb) */
  /* RS_FIELD_TEMPERATURE: surface temperatures of body 1 and 2 (degC) [nx], the largest
   * (degC) and the heat into each body (W; 2D: W/mm) */
  const double *T1, *T2;
  double T_max, heat_input_1, heat_input_2;
  /* Error estimates (files with error_estimate): magnitudes, NaN where none was made;
   * error_reliable 1 (observed order in the band), 0 (fallback) or -1 (no estimate); the
   * forces extrapolated to zero cell size where error_reliable is 1 (NaN elsewhere). */
  double Fx_error, Fy_error, Mz_error;
  double Fx_extrapolated, Fy_extrapolated, Mz_extrapolated;
  int error_reliable;
  /* files with temperature_modes: the modes, mode slowest, then y, then x */
  const double *temperature_modes;
} rs_record;

/* Create the file, define everything, write x, set status = "running". The file is
 * built as PATH.part and renamed to PATH once its header is complete; an existing file
 * PATH is kept as PATH~ at that moment (rs_output_backup names it).
 * Returns RS_ERR_OUTPUT with a message naming the path on failure. */
int rs_output_create(rs_output **out, const rs_output_spec *spec, rs_msg *msg);
/* Where rs_output_create kept an older file of the same name (PATH~), or NULL. */
const char *rs_output_backup(const rs_output *out);

/* Continue an existing time-history file (rollsim run --restart OLD.nc --append):
 * open it for writing, check that it is a rollsim time-history file on the grid x[nx]
 * (3D: and y[ny], ny > 1; 2D: ny = 1, y unused) holding every field of `fields` (it may hold more:
 * those are written too), append `history_line` to its history attribute (one line per command that
 * wrote to the file) and set status "running". Records then go after the last one
 * (rs_output_write). RS_ERR_INPUT for a file of another layout (message names the file and what
 * differs), RS_ERR_OUTPUT for I/O errors. */
int rs_output_open_append(rs_output **out, const char *path, size_t nx, const double *x, size_t ny,
                          const double *y, unsigned fields, const char *history_line, rs_msg *msg);
/* Append one record and sync it to disk. */
int rs_output_write(rs_output *out, const rs_record *rec, rs_msg *msg);
/* Twin-disc: mean traction coefficient F_x/F_n and mean slip over the averaging window
 * of protocol step i, or over revolution i; synced. */
int rs_output_put_step(rs_output *out, size_t i, double traction_coefficient, double slip,
                       rs_msg *msg);
int rs_output_put_revolution(rs_output *out, size_t i, double traction_coefficient, double slip,
                             rs_msg *msg);
/* Revolution i: the energy dissipated over it (N mm/mm in 2D, N mm in 3D) and the u* of
 * the surface leaving the contact, its mean over the revolution and its largest value (mm). */
int rs_output_put_revolution_energy(rs_output *out, size_t i, double energy, double ustar_mean,
                                    double ustar_max, rs_msg *msg);
/* Revolution i with temperature: v = the largest contact temperature (degC), the mean inlet
 * temperature of disc 1 and 2 (degC), the heat input into disc 1 and 2 over the revolution
 * (J/mm in 2D, J in 3D), the bulk temperatures of disc 1 and 2 at its end (degC; written only
 * with the bulk variables). */
int rs_output_put_revolution_temperature(rs_output *out, size_t i, const double v[7], rs_msg *msg);
/* Number of records written so far. */
size_t rs_output_records(const rs_output *out);
/* The status attribute is stored NUL-padded to this fixed length (longer texts are
 * truncated to RS_OUTPUT_STATUS_LEN - 1 characters), so that rewriting it never changes
 * the size of the file header: a kill during the rewrite cannot tear the header. */
#define RS_OUTPUT_STATUS_LEN 256
/* The sweep file's writer attribute ("HOST PID"), fixed length like the status. */
#define RS_SWEEP_WRITER_LEN  160

/* Set the status attribute ("running", "complete", "failed: <why>", "interrupted") and sync. */
int rs_output_set_status(rs_output *out, const char *status, rs_msg *msg);
/* Close the file (status is left as it is) and free. NULL is allowed. */
int rs_output_close(rs_output *out, rs_msg *msg);
/* Close a file whose writes failed (a full disk, a file-size limit) and free: the records
 * before the failure stay, and the status attribute is rewritten in place through a fresh
 * handle, since the failed handle's own sync keeps retrying the failed write. */
int rs_output_abandon(rs_output *out, const char *status, rs_msg *msg);

/* ---- Sweep files: one dimension per swept key, scalar results over them ---- */
typedef struct rs_sweep_output rs_sweep_output;

typedef struct rs_sweep_output_spec {
  const char *path, *title, *case_text, *history;
  int dimension; /* units of forces: 2 -> N/mm, 3 -> N */
  int naxes;
  const char *const *keys;     /* dotted case keys [naxes]; variable names get '_' for '.';
                                  units from the key table (rs_case_key_units) */
  const int *sizes;            /* [naxes] */
  const double *const *values; /* coordinate values [naxes][sizes[a]] */
  /* Profiles per point (output.fields): RS_FIELD_* mask, 0 for none; then every field
   * is a variable over (swept keys..., x) with the coordinate x[nx] (mm). */
  unsigned fields;
  size_t nx;
  const double *x;
  /* Distributed sweeps (0 for a serial sweep: neither is in the file): ranks > 0 adds the
   * per-point variable `rank` (which process computed it) and the global attribute
   * `ranks`; parts > 0 the global attributes `part` and `parts` (rollsim sweep --part). */
  int ranks;
  int part, parts;
  /* 1: the per-point scalars T_max, heat_input_1, heat_input_2 (a temperature: block) */
  int temperature;
  /* Steady sweeps with the error estimate: the per-point variables error_reliable, Fx_error,
   * traction_coefficient_error (3D: Fy_error, Mz_error). */
  int error_estimate;
} rs_sweep_output_spec;

/* The results of one sweep point (NaN, counts -1, where the point failed). Field
 * arrays have nx entries; NULL writes NaN (regime -1) for that point. */
typedef struct rs_sweep_point {
  double Fx, Fn, creepage, velocity;
  double Fy, Mz, lateral_creepage, spin; /* 3D only (not written in 2D) */
  double hertz_a, hertz_b;               /* 3D only: Hertz semi-axes at the point's load, mm */
  int n_exterior, n_adhesion, n_slip, n_plastic;
  double frictional_power, plastic_power, elastic_energy;
  int converged;
  const double *px, *pn, *slip, *upl, *ustar, *tauc;
  const signed char *regime;
  int rank;         /* the process that computed it (files with ranks > 0) */
  const double *mu; /* mu(|v_s|) (velocity-dependent friction) */
  double T_max, heat_input_1, heat_input_2; /* files with temperature: degC, W (2D: W/mm) */
  /* error estimates (magnitudes, NaN: none) and error_reliable (1, 0, -1: no estimate); the
   * forces extrapolated to zero cell size (NaN unless error_reliable is 1) */
  double Fx_error, Fy_error, Mz_error;
  double Fx_extrapolated, Fy_extrapolated, Mz_extrapolated;
  int error_reliable;
} rs_sweep_point;

/* Create the sweep file (an existing file of that name is kept as PATH~, see
 * rs_sweep_output_backup). Counts are NC_INT without a _FillValue (valid_min 0: -1 marks
 * a failed point, netCDF's default fill one not computed), so that readers keep them as
 * integers; doubles have _FillValue NaN. */
int rs_sweep_output_create(rs_sweep_output **out, const rs_sweep_output_spec *spec, rs_msg *msg);
const char *rs_sweep_output_backup(const rs_sweep_output *out);
/* Reopen the file spec->path of an interrupted sweep to write its missing points
 * (rollsim sweep --resume). The file must be a sweep file of spec's layout (the same swept
 * keys and values, fields and x, part and parts) and the same `case` text (the case as
 * run, after --set); else RS_ERR_INPUT saying why, with the file untouched (also for a
 * truncated or unreadable file). converged[npoints] gets the file's `converged`
 * (NC_FILL_INT where no point was written), *kept the points written. The history gets
 * spec->history as a new line (with the points kept), the status "running". */
int rs_sweep_output_resume(rs_sweep_output **out, const rs_sweep_output_spec *spec, int *converged,
                           size_t *kept, rs_msg *msg);
/* Give the point at flat index (row-major over the axes, last fastest). Points are written
 * (and synced) in batches: when one arrives RS_SWEEP_FLUSH_SECONDS or more after the last
 * write, when the batch's memory is full, and at close. A killed process leaves a readable
 * file holding every point but those given less than RS_SWEEP_FLUSH_SECONDS after the last
 * write (io/output_sweep.c). */
#define RS_SWEEP_FLUSH_SECONDS 0.5
int rs_sweep_output_write(rs_sweep_output *out, size_t index, const rs_sweep_point *pt,
                          rs_msg *msg);
/* Write the points not yet written, set the status attribute and close. */
int rs_sweep_output_close(rs_sweep_output *out, const char *status, rs_msg *msg);

/* The file of a sweep on profiles (docs/file-format.md "Wheel-rail sweep files"): dimensions
 * position and patch, one double variable per column (NaN where a position has no such patch
 * or its point failed), written whole to PATH.part and renamed over PATH (an older file kept
 * as PATH~, its name in backup, else ""). */
typedef struct rs_positions_column {
  const char *name, *units, *long_name;
  int per_patch; /* 1: over (position, patch), data [npos][stride]; 0: [npos] */
  const double *data;
} rs_positions_column;

typedef struct rs_positions_output {
  const char *path, *title, *history, *case_text;
  const char *status; /* "complete", "interrupted" or "failed: ..." */
  const char *frames; /* global attribute: the frames the forces are given in */
  const char *dim;    /* the first dimension's name: NULL "position", or "time" */
  size_t npos;
  int npatch, stride; /* patches written (at least 1), patches stored per position */
  int ncols;
  const rs_positions_column *cols;
} rs_positions_output;
int rs_positions_output_write(const rs_positions_output *o, char *backup, size_t backup_len,
                              rs_msg *msg);
#endif
