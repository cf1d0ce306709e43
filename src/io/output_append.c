/* Continuing a time-history file in place (rollsim/output.h, rs_output_open_append):
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
  if (nc_inq_varid(ncid, name, &id) || nc_inq_varndims(ncid, id, &n) || n != ndims ||
      nc_inq_vardimid(ncid, id, d))
    return -1;
  for (int i = 0; i < n; i++)
    if (d[i] != dims[i]) return -1;
  return id;
}

static int check_layout(rs_output *out, size_t nx, const double *x, unsigned fields, rs_msg *msg)
{
  const int ncid = out->ncid;
  const char *path = out->path;
  int format = 0, time_dim, x_dim, unlimited = -1, id;
  size_t len_x, nrec;
  if (nc_inq_format(ncid, &format) || format != NC_FORMAT_64BIT_OFFSET ||
      nc_inq_dimid(ncid, "time", &time_dim) || nc_inq_dimid(ncid, "x", &x_dim) ||
      nc_inq_unlimdim(ncid, &unlimited) || unlimited != time_dim ||
      nc_inq_dimlen(ncid, x_dim, &len_x) || nc_inq_dimlen(ncid, time_dim, &nrec))
    return layout_error(path, msg,
                        "not a rollsim time-history file (netCDF 64-bit offset, "
                        "unlimited dimension time, dimension x)");
  if (nc_inq_dimid(ncid, "y", &id) == NC_NOERR)
    return layout_error(path, msg,
                        "a 3D file cannot be continued in place yet (restart into a new file: "
                        "leave out --append)");
  if (nc_inq_varid(ncid, "step_traction_coefficient", &id) == NC_NOERR)
    return layout_error(path, msg,
                        "a twin_disc: run cannot be continued (the plastic state "
                        "around the discs is not stored in the output file)");
  if (len_x != nx)
    return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: its grid has %zu cells, the case has %zu",
                      path, len_x, nx);
  if ((out->time_id = var_over(ncid, "time", 1, &time_dim)) < 0 ||
      (out->x_id = var_over(ncid, "x", 1, &x_dim)) < 0)
    return layout_error(path, msg, "no coordinate variables time(time) and x(x)");
  double *xold = malloc(nx * sizeof *xold);
  if (!xold) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  double xmax = 0.0;
  int same = nc_get_var_double(ncid, out->x_id, xold) == NC_NOERR;
  for (size_t i = 0; i < nx; i++) xmax = fmax(xmax, fabs(x[i]));
  for (size_t i = 0; same && i < nx; i++) same = fabs(xold[i] - x[i]) <= 1e-12 * xmax;
  free(xold);
  if (!same) return layout_error(path, msg, "its grid x differs from the case's");
  const int dims2[2] = {time_dim, x_dim};
  out->fields = 0;
  for (int f = 0; f < RS_N_FIELDS; f++) {
    out->field_id[f] = var_over(ncid, rs_field_vars[f].name, 2, dims2);
    if (out->field_id[f] >= 0)
      out->fields |= rs_field_vars[f].bit;
    else if (fields & rs_field_vars[f].bit)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "--append %s: has no (time, x) variable '%s' that the case's "
                        "output.fields asks for (continue into a new file: leave out --append)",
                        path, rs_field_vars[f].name);
  }
  for (int s = 0; s < RS_N_SCALARS; s++)
    if ((out->scalar_id[s] = var_over(ncid, rs_scalar_vars[s].name, 1, &time_dim)) < 0)
      return rs_msg_set(msg, RS_ERR_INPUT, "--append %s: has no variable %s(time)", path,
                        rs_scalar_vars[s].name);
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

int rs_output_open_append(rs_output **outp, const char *path, size_t nx, const double *x,
                          unsigned fields, const char *history_line, rs_msg *msg)
{
  *outp = NULL;
  rs_output *out = calloc(1, sizeof *out);
  if (!out || !(out->path = strdup(path))) {
    free(out);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  out->nx = nx;
  out->ny = 1;
  for (int f = 0; f < RS_N_FIELDS; f++) out->field_id2[f] = -1;
  for (int k = 0; k < RS_N_SCALARS_3D; k++) out->scalar3_id[k] = -1;
  size_t block = RS_IO_BLOCK;
  int err = nc__open(path, NC_WRITE, &block, &out->ncid);
  int status = err ? rs_msg_set(msg, RS_ERR_INPUT, "--append %s: cannot open for writing: %s", path,
                                nc_strerror(err))
                   : RS_OK;
  if (status == RS_OK) status = check_layout(out, nx, x, fields, msg);
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
