/* netCDF output (interfaces.md "Output file"): CF-1.10, dimension time (unlimited)
 * and x, one record per output time, synced to disk after every record so that the
 * file stays readable with every record written so far if the process dies.
 * The output module knows nothing of the solver: it writes what it is given. */
#ifndef ROLLSIM_OUTPUT_H
#define ROLLSIM_OUTPUT_H

#include <stddef.h>
#include "rollsim/status.h"

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
} rs_output_rig;

typedef struct rs_output_spec {
  const char *path;         /* file to create (overwritten if it exists) */
  const char *title;        /* global attribute title */
  const char *case_text;    /* global attribute case: the full YAML as run */
  const char *history;      /* global attribute history: e.g. the command line and date */
  int dimension;            /* 2: force units N/mm; 3: N */
  size_t nx;                /* number of cells */
  const double *x;          /* cell centres, mm [nx] */
  unsigned fields;          /* RS_FIELD_* mask (rollsim/case.h): which (time, x) fields to write */
  const rs_output_rig *rig; /* twin-disc summaries, or NULL */
} rs_output_spec;

/* One record. Scalars per model.md §7; field arrays have nx entries (NULL allowed
 * for fields not in the mask). */
typedef struct rs_record {
  double time;     /* s */
  double Fx, Fn;   /* N/mm (2D) */
  double creepage; /* 1 */
  double velocity; /* mm/s */
  int n_exterior, n_adhesion, n_slip, n_plastic;
  double frictional_power;                           /* N mm/s per mm */
  double plastic_power;                              /* N mm/s per mm */
  double elastic_energy;                             /* N mm per mm */
  const double *px, *pn, *slip, *upl, *ustar, *tauc; /* [nx] */
  const signed char *regime;                         /* [nx]: 0 E, 1 H, 2 S, 3 P */
} rs_record;

/* Create the file, define everything, write x, set status = "running".
 * Returns RS_ERR_OUTPUT with a message naming the path on failure. */
int rs_output_create(rs_output **out, const rs_output_spec *spec, rs_msg *msg);
/* Append one record and sync it to disk. */
int rs_output_write(rs_output *out, const rs_record *rec, rs_msg *msg);
/* Twin-disc: mean traction coefficient F_x/F_n and mean slip over the averaging window
 * of protocol step i, or over revolution i; synced. */
int rs_output_put_step(rs_output *out, size_t i, double traction_coefficient, double slip,
                       rs_msg *msg);
int rs_output_put_revolution(rs_output *out, size_t i, double traction_coefficient, double slip,
                             rs_msg *msg);
/* Number of records written so far. */
size_t rs_output_records(const rs_output *out);
/* The status attribute is stored NUL-padded to this fixed length (longer texts are
 * truncated to RS_OUTPUT_STATUS_LEN - 1 characters), so that rewriting it never changes
 * the size of the file header: a kill during the rewrite cannot tear the header. */
#define RS_OUTPUT_STATUS_LEN 256

/* Set the status attribute ("running", "complete", "failed: <why>", "interrupted") and sync. */
int rs_output_set_status(rs_output *out, const char *status, rs_msg *msg);
/* Close the file (status is left as it is) and free. NULL is allowed. */
int rs_output_close(rs_output *out, rs_msg *msg);

/* ---- Sweep files: one dimension per swept key, scalar results over them ---- */
typedef struct rs_sweep_output rs_sweep_output;

typedef struct rs_sweep_output_spec {
  const char *path, *title, *case_text, *history;
  int dimension; /* units of forces: 2 -> N/mm, 3 -> N */
  int naxes;
  const char *const *keys;     /* dotted case keys [naxes]; variable names get '_' for '.' */
  const int *sizes;            /* [naxes] */
  const double *const *values; /* coordinate values [naxes][sizes[a]] */
} rs_sweep_output_spec;

/* The scalar results of one sweep point (NaN where the point failed). */
typedef struct rs_sweep_point {
  double Fx, Fn, creepage, velocity;
  int n_exterior, n_adhesion, n_slip, n_plastic;
  double frictional_power, plastic_power, elastic_energy;
  int converged;
} rs_sweep_point;

int rs_sweep_output_create(rs_sweep_output **out, const rs_sweep_output_spec *spec, rs_msg *msg);
/* Write the point at flat index (row-major over the axes, last fastest) and sync. */
int rs_sweep_output_write(rs_sweep_output *out, size_t index, const rs_sweep_point *pt,
                          rs_msg *msg);
int rs_sweep_output_close(rs_sweep_output *out, const char *status, rs_msg *msg);
#endif
