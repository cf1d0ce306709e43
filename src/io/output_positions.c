/* The file of a sweep on profiles (io/output.h, docs/file-format.md "Wheel-rail sweep files"):
 * dimensions `position` and `patch`, one variable per column, written whole to PATH.part and
 * renamed over PATH, so PATH never holds a half-written file. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output.h"
#include "io/output_internal.h"

static int define_column(int ncid, const rs_positions_column *col, const int *dims, int *id)
{
  int err = nc_def_var(ncid, col->name, NC_DOUBLE, col->per_patch ? 2 : 1, dims, id);
  const double fill = NAN;
  if (!err) err = nc_put_att_double(ncid, *id, "_FillValue", NC_DOUBLE, 1, &fill);
  if (!err && col->units) err = rs_output_put_text(ncid, *id, "units", col->units);
  if (!err) err = rs_output_put_text(ncid, *id, "long_name", col->long_name);
  return err;
}

int rs_positions_output_write(const rs_positions_output *o, char *backup, size_t backup_len,
                              rs_msg *msg)
{
  int status = rs_output_make_parent_dirs(o->path, msg);
  if (status != RS_OK) return status;
  const size_t plen = strlen(o->path) + 6, npatch = o->npatch > 0 ? (size_t)o->npatch : 1;
  char *part = malloc(plen);
  int *ids = calloc((size_t)o->ncols + 1, sizeof *ids);
  double *buf = malloc(o->npos * npatch * sizeof *buf + 8);
  if (!part || !ids || !buf) {
    free(part);
    free(ids);
    free(buf);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  snprintf(part, plen, "%s.part", o->path);
  int ncid = -1, dims[2];
  int err = nc_create(part, NC_CLOBBER | NC_64BIT_OFFSET, &ncid);
  if (!err) err = nc_def_dim(ncid, o->dim ? o->dim : "position", o->npos, &dims[0]);
  if (!err) err = nc_def_dim(ncid, "patch", npatch, &dims[1]);
  for (int k = 0; !err && k < o->ncols; k++) err = define_column(ncid, &o->cols[k], dims, &ids[k]);
  char source[64];
  snprintf(source, sizeof source, "rollsim %s", RS_VERSION);
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "Conventions", "CF-1.10");
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "title", o->title ? o->title : "");
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "source", source);
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "history", o->history ? o->history : "");
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "case", o->case_text ? o->case_text : "");
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "status", o->status);
  if (!err) err = rs_output_put_text(ncid, NC_GLOBAL, "frames", o->frames ? o->frames : "");
  if (!err) err = nc_enddef(ncid);
  for (int k = 0; !err && k < o->ncols; k++) {
    const rs_positions_column *col = &o->cols[k];
    if (!col->per_patch) {
      err = nc_put_var_double(ncid, ids[k], col->data);
      continue;
    }
    for (size_t i = 0; i < o->npos; i++)
      for (size_t j = 0; j < npatch; j++) buf[i * npatch + j] = col->data[i * o->stride + j];
    err = nc_put_var_double(ncid, ids[k], buf);
  }
  if (ncid >= 0) {
    const int cerr = nc_close(ncid);
    if (!err) err = cerr;
  }
  status = rs_output_commit_part(err, part, o->path, 1, backup, backup_len,
                                 "writing the sweep file", msg);
  free(part);
  free(ids);
  free(buf);
  return status;
}
