/* Continuing a time-history file in place (io/output.h, rs_output_open_append):
 * `rollsim run CASE --restart OLD.nc --append`. The file keeps its layout and every
 * record; new records go after the last one, written and synced as in output.c (record
 * data before numrecs), so the crash-safety argument there holds for the appended part.
 *
 * The history attribute grows by one line. That is the only header change that alters
 * the header's size: it is done in define mode with no extra free space requested, and
 * netCDF keeps the data where they are as long as the header still fits in front of them
 * (the header reserve of output.c leaves 4 kB for this). */
#define _POSIX_C_SOURCE 200809L

#include "io/output_internal.h"
#include "io/case.h" /* RS_FIELD_TEMPERATURE */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int layout_error(const char *path, rs_msg *msg, const char *what)
{
  return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: %s", path, what);
}

/* The variable `name` over exactly the dimensions dims[0..ndims), or -1. */
static int var_over(int ncid, const char *name, int ndims, const int *dims)
{
  int id, n, d[NC_MAX_VAR_DIMS];
  if (!name || nc_inq_varid(ncid, name, &id) || nc_inq_varndims(ncid, id, &n) || n != ndims ||
      nc_inq_vardimid(ncid, id, d))
    return -1;
  for (int i = 0; i < n; i++)
    if (d[i] != dims[i]) return -1;
  return id;
}

/* The grid coordinate `name` of the file (dimension and variable of that name) equals
 * the case's c[n], to 1e-12 of its largest value. */
static int check_coordinate(rs_output *out, const char *name, int dim, size_t n, const double *c,
                            int *var_id, rs_msg *msg)
{
  size_t len = 0;
  if (nc_inq_dimlen(out->ncid, dim, &len) || len != n)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "--append %s: its grid has %zu cells along %s, the case has %zu", out->path,
                      len, name, n);
  if ((*var_id = var_over(out->ncid, name, 1, &dim)) < 0)
    return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: no coordinate variable %s(%s)", out->path,
                      name, name);
  double *old = malloc(n * sizeof *old);
  if (!old) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  double cmax = 0.0;
  int same = nc_get_var_double(out->ncid, *var_id, old) == NC_NOERR;
  for (size_t i = 0; i < n; i++) cmax = fmax(cmax, fabs(c[i]));
  for (size_t i = 0; same && i < n; i++) same = fabs(old[i] - c[i]) <= 1e-12 * cmax;
  free(old);
  if (!same)
    return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: its grid %s differs from the case's",
                      out->path, name);
  return RS_OK;
}

static int check_layout(rs_output *out, size_t nx, const double *x, size_t ny, const double *y,
                        unsigned fields, rs_msg *msg)
{
  const int ncid = out->ncid;
  const char *path = out->path;
  const int three_d = ny > 1;
  int format = 0, time_dim, x_dim, y_dim = -1, unlimited = -1, id;
  size_t nrec;
  if (nc_inq_format(ncid, &format) || format != NC_FORMAT_64BIT_OFFSET ||
      nc_inq_dimid(ncid, "time", &time_dim) || nc_inq_dimid(ncid, "x", &x_dim) ||
      nc_inq_unlimdim(ncid, &unlimited) || unlimited != time_dim ||
      nc_inq_dimlen(ncid, time_dim, &nrec))
    return layout_error(path, msg,
                        "not a rollsim time-history file (netCDF 64-bit offset, "
                        "unlimited dimension time, dimension x)");
  const int file_3d = nc_inq_dimid(ncid, "y", &y_dim) == NC_NOERR;
  if (file_3d != three_d)
    return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: a %s file, but the case is %s", path,
                      file_3d ? "3D" : "2D", three_d ? "3D (contact.dimension: 3)" : "2D");
  if (nc_inq_varid(ncid, "step_traction_coefficient", &id) == NC_NOERR)
    return layout_error(path, msg,
                        "a twin_disc: run cannot be continued (the plastic state "
                        "around the discs is not stored in the output file)");
  if ((out->time_id = var_over(ncid, "time", 1, &time_dim)) < 0)
    return layout_error(path, msg, "no coordinate variable time(time)");
  int status = check_coordinate(out, "x", x_dim, nx, x, &out->x_id, msg);
  out->y_id = -1;
  if (status == RS_OK && three_d)
    status = check_coordinate(out, "y", y_dim, ny, y, &out->y_id, msg);
  if (status != RS_OK) return status;
  const int dims[3] = {time_dim, three_d ? y_dim : x_dim, x_dim};
  const int ndims = three_d ? 3 : 2;
  out->fields = 0;
  for (int f = 0; f < RS_N_FIELDS; f++) {
    out->field_id[f] = var_over(ncid, rs_field_name(f, three_d, 0), ndims, dims);
    const char *second = three_d && rs_field_is_vector(f) ? rs_field_name(f, 1, 1) : NULL;
    out->field_id2[f] = second ? var_over(ncid, second, ndims, dims) : -1;
    if (out->field_id[f] >= 0 && (!second || out->field_id2[f] >= 0))
      out->fields |= rs_field_vars[f].bit;
    else if (fields & rs_field_vars[f].bit)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--append %s: has no %s variable '%s'%s%s that the case's "
                        "output.fields asks for (continue into a new file: leave out --append)",
                        path, three_d ? "(time, y, x)" : "(time, x)", rs_field_name(f, three_d, 0),
                        second ? " and " : "", second ? second : "");
    else
      out->field_id[f] = out->field_id2[f] = -1;
  }
  for (int s = 0; s < RS_N_SCALARS; s++)
    if ((out->scalar_id[s] = var_over(ncid, rs_scalar_vars[s].name, 1, &time_dim)) < 0)
      return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: has no variable %s(time)", path,
                        rs_scalar_vars[s].name);
  for (int s = 0; three_d && s < RS_N_SCALARS_3D; s++)
    if ((out->scalar3_id[s] = var_over(ncid, rs_scalar_vars_3d[s].name, 1, &time_dim)) < 0)
      return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: has no variable %s(time)", path,
                        rs_scalar_vars_3d[s].name);
  /* the temperatures: in the file exactly when the case computes them (records without
   * them would leave their slots unwritten) */
  const int want_t = (fields & RS_FIELD_TEMPERATURE) != 0;
  for (int v = 0; v < RS_N_TEMPERATURE_VARS; v++) {
    const int field = v < RS_N_TEMPERATURE_FIELDS;
    out->temp_id[v] =
        var_over(ncid, rs_temperature_vars[v].name, field ? ndims : 1, field ? dims : &time_dim);
    if ((out->temp_id[v] >= 0) != want_t)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--append %s: %s variable %s, but the case has %s temperature: block "
                        "(continue into a new file: leave out --append)",
                        path, want_t ? "has no" : "has the", rs_temperature_vars[v].name,
                        want_t ? "a" : "no");
  }
  /* the temperature modes (a transient with a temperature: block): continued when present */
  int mode_dim;
  size_t nmodes = 0;
  out->modes_id = -1;
  if (want_t && nc_inq_dimid(ncid, "temperature_mode", &mode_dim) == NC_NOERR &&
      nc_inq_dimlen(ncid, mode_dim, &nmodes) == NC_NOERR) {
    const int mdims[4] = {time_dim, mode_dim, dims[1], dims[2]};
    out->modes_id = var_over(ncid, "temperature_modes", ndims + 1, mdims);
    out->nmodes = nmodes;
  }
  out->records = nrec;
  if (nrec == 0) return layout_error(path, msg, "holds no records");
  return RS_OK;
}

/* history += "\n" + line, status = "running"; the data stay where they are. */
static int update_header(rs_output *out, const char *history_line, rs_msg *msg)
{
  const int ncid = out->ncid;
  char *old = rs_output_get_text(ncid, NC_GLOBAL, "history");
  const size_t len = (old ? strlen(old) : 0) + strlen(history_line) + 2;
  char *history = malloc(len);
  if (!old || !history) {
    free(old);
    free(history);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  snprintf(history, len, "%s%s%s", old, *old ? "\n" : "", history_line);
  free(old);
  char status[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(status, "running");
  int err = nc_redef(ncid);
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "history", history);
  if (!err) err = nc_put_att_text(ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, status);
  /* No free space asked for and alignments every existing offset meets: netCDF then
   * moves nothing unless the header outgrew the space in front of the data. */
  const int end = nc__enddef(ncid, 0, 4, 0, 4);
  if (!err) err = end;
  free(history);
  int old_fill;
  if (!err) err = nc_set_fill(ncid, NC_NOFILL, &old_fill);
  if (!err) err = nc_sync(ncid);
  return err ? rs_output_nc_failure(msg, out->path, "updating history and status", err) : RS_OK;
}

int rs_output_open_append(rs_output **outp, const char *path, size_t nx, const double *x, size_t ny,
                          const double *y, unsigned fields, const char *history_line, rs_msg *msg)
{
  *outp = NULL;
  rs_output *out = calloc(1, sizeof *out);
  if (!out || !(out->path = strdup(path))) {
    free(out);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  out->nx = nx;
  out->ny = ny > 1 ? ny : 1;
  out->three_d = ny > 1;
  for (int f = 0; f < RS_N_FIELDS; f++) out->field_id2[f] = -1;
  for (int k = 0; k < RS_N_SCALARS_3D; k++) out->scalar3_id[k] = -1;
  for (int k = 0; k < RS_N_TEMPERATURE_VARS; k++) out->temp_id[k] = -1;
  out->modes_id = -1;
  size_t block = RS_IO_BLOCK;
  int err = nc__open(path, NC_WRITE, &block, &out->ncid);
  int status = err ? rs_msg_set(msg, RS_ERR_INPUT, "--append %s: cannot open for writing: %s", path,
                                nc_strerror(err))
                   : RS_OK;
  if (status == RS_OK) status = check_layout(out, nx, x, out->ny, y, fields, msg);
  if (status == RS_OK) status = update_header(out, history_line, msg);
  if (status != RS_OK) {
    if (!err) (void)nc_close(out->ncid);
    free(out->path);
    free(out);
    return status;
  }
  *outp = out;
  return RS_OK;
}
