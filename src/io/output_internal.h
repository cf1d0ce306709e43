/* Private to the netCDF writers: the time-history writer (output.c), appending to an
 * existing file (output_append.c) and the sweep writer (output_sweep.c). */
#ifndef ROLLSIM_OUTPUT_INTERNAL_H
#define ROLLSIM_OUTPUT_INTERNAL_H

#include <netcdf.h>
#include <stddef.h>

#include "io/output.h"

/* I/O block size passed to netCDF; its buffer holds at most two blocks (output.c). */
#define RS_IO_BLOCK ((size_t)4096)

/* (time, x) fields of docs/file-format.md, in RS_FIELD_* bit order; regime is NC_BYTE. */
typedef struct rs_field_var {
  unsigned bit; /* RS_FIELD_* */
  const char *name;
  const char *units;
  const char *long_name;
  size_t member; /* offsetof(rs_record, array), for the double fields */
} rs_field_var;
#define RS_N_FIELDS     8
#define RS_REGIME_FIELD 6
extern const rs_field_var rs_field_vars[RS_N_FIELDS];

/* Scalars per record (docs/model.md §7). */
typedef struct rs_scalar_var {
  const char *name;
  nc_type type;  /* NC_DOUBLE or NC_INT */
  size_t member; /* offsetof(rs_record, value); unused for traction_coefficient */
  const char *units_2d, *units_3d;
  const char *long_name;
} rs_scalar_var;
#define RS_N_SCALARS       12
#define RS_TRACTION_SCALAR 2
extern const rs_scalar_var rs_scalar_vars[RS_N_SCALARS];
/* Scalars written in 3D only (doubles). */
#define RS_N_SCALARS_3D 4
extern const rs_scalar_var rs_scalar_vars_3d[RS_N_SCALARS_3D];

/* RS_FIELD_TEMPERATURE: the fields T1, T2 over (time, [y,] x), then the scalars over time. */
#define RS_N_TEMPERATURE_VARS   5
#define RS_N_TEMPERATURE_FIELDS 2
extern const rs_scalar_var rs_temperature_vars[RS_N_TEMPERATURE_VARS];

/* The error estimate's variables: error_reliable, Fx_error, traction_coefficient_error,
 * Fy_error, Mz_error, then the extrapolated Fx, traction coefficient, Fy, Mz (Fy and Mz in 3D
 * only). */
#define RS_N_ERROR_VARS 9
extern const char *const rs_error_var_names[RS_N_ERROR_VARS];
/* Defines them over dims [ndims] (docs/file-format.md) with their units, long names and fill
 * values; ids gets their ids, -1 for those not made. A netCDF status. */
int rs_output_define_error_vars(int ncid, int ndims, const int *dims, int three_d,
                                int ids[RS_N_ERROR_VARS]);

/* Name of field f's variable: component comp (0, or 1 for the y component of the 3D
 * vector fields px, slip, upl); NULL when the field has no such component. */
const char *rs_field_name(int f, int three_d, int comp);
/* Whether field f is a vector field with a y component in 3D. */
static inline int rs_field_is_vector(int f) { return f == 0 || f == 2 || f == 3; }

struct rs_output {
  int ncid;
  char *path;    /* as given; error messages name it */
  size_t nx, ny; /* ny = 1 in 2D */
  int three_d;
  unsigned fields;
  size_t records; /* records in the file (written and synced) */
  int time_id, x_id, y_id;
  int field_id[RS_N_FIELDS];  /* -1 when not in the file */
  int field_id2[RS_N_FIELDS]; /* 3D: the y component of px, slip, upl; else -1 */
  int scalar_id[RS_N_SCALARS];
  int scalar3_id[RS_N_SCALARS_3D];
  int temp_id[RS_N_TEMPERATURE_VARS]; /* T1, T2, T_max, heat_input_1, heat_input_2; -1: none */
  int has_errors;                /* the error estimate's variables are in the file (steady runs) */
  int error_id[RS_N_ERROR_VARS]; /* rs_error_var_names */
  int modes_id;                  /* temperature_modes, -1: none */
  size_t nmodes;                 /* its temperature_mode dimension */
  int has_rig;
  int rig_meta_id[6];
  int step_mu_id, step_slip_id, rev_mu_id, rev_slip_id; /* twin-disc summaries */
  int rev_energy_id, rev_ustar_id, rev_ustar_max_id;    /* per revolution: wear inputs */
  int rev_temp_id[7]; /* per revolution: temperatures (rs_output_put_revolution_temperature) */
  char backup[1040];  /* where an older file of the same name was kept, or "" */
};

/* "output file PATH: WHAT: netCDF message", RS_ERR_OUTPUT. */
int rs_output_nc_failure(rs_msg *msg, const char *path, const char *what, int err);
/* Text attribute without the terminating NUL. */
int rs_output_put_text(int ncid, int varid, const char *name, const char *text);
/* The status attribute text, NUL-padded to its fixed length RS_OUTPUT_STATUS_LEN. */
void rs_output_status_text(char buf[RS_OUTPUT_STATUS_LEN], const char *status);
/* mkdir -p for the directory part of path. */
int rs_output_make_parent_dirs(const char *path, rs_msg *msg);
/* An existing regular file at path is renamed to path~ (replacing an older path~);
 * backup gets path~ then, else "". Nothing to do when path does not exist. */
int rs_output_keep_old(const char *path, char *backup, size_t len, rs_msg *msg);
/* A file written whole to PART moved over PATH: with nc_err (writing PART failed) the netCDF
 * failure ("output file PATH: WHAT: ..."); else the older PATH kept as PATH~ when keep_old
 * (rs_output_keep_old) and PART renamed to PATH. PART is removed on any failure. */
int rs_output_commit_part(int nc_err, const char *part, const char *path, int keep_old,
                          char *backup, size_t len, const char *what, rs_msg *msg);
/* Text of a global text attribute (malloc'ed, NUL-terminated; "" when absent), NULL
 * when out of memory. */
char *rs_output_get_text(int ncid, int varid, const char *name);
/* 1 when the file's `case` attribute equals case_text (the case as run, after --set): the
 * identity test of a file a run resumes; RS_OUTPUT_OTHER_CASE says why not. */
int rs_output_same_case(int ncid, const char *case_text);
#define RS_OUTPUT_OTHER_CASE                                                                       \
  "the file is of another case or other --set values (its `case` attribute differs from the "      \
  "case as run now)"
/* The end of a classic/64-bit-offset file's fixed-size data according to its header, and
 * the file's size: 0, or -1 when the file cannot be read or is not such a file
 * (io/nc_classic.c). A file shorter than its data is truncated (netCDF would read the
 * missing bytes as zeros). */
int rs_nc_classic_data_end(const char *path, long long *data_end, long long *file_size);

#endif
