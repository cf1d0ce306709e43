/* Sweep files (interfaces.md "Sweeps"): one dimension per swept key with a
 * coordinate variable holding its values (name: the dotted key with '_' for '.',
 * attribute `key` = the dotted key), and the scalar results over those
 * dimensions. Points are written as they are computed and synced, so an
 * interrupted sweep keeps what it had; points not computed read as the fill value,
 * points that failed as NaN with converged = 0. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output_internal.h"
#include "rollsim/output.h"

enum { SW_DOUBLE, SW_INT };
typedef struct sweep_var {
  const char *name, *long_name, *units; /* units: "F" = force units per dimension */
  int type;
} sweep_var;

static const sweep_var sweep_vars[] = {
    {"Fx", "total tangential force on body 1", "F", SW_DOUBLE},
    {"Fn", "total normal force", "F", SW_DOUBLE},
    {"traction_coefficient", "Fx/Fn", "1", SW_DOUBLE},
    {"creepage", "longitudinal creepage", "1", SW_DOUBLE},
    {"velocity", "rolling velocity", "mm/s", SW_DOUBLE},
    {"n_exterior", "cells in the exterior area", "1", SW_INT},
    {"n_adhesion", "cells in adhesion", "1", SW_INT},
    {"n_slip", "cells in slip", "1", SW_INT},
    {"n_plastic", "cells in plastic flow", "1", SW_INT},
    {"frictional_power", "frictional dissipation", "P", SW_DOUBLE},
    {"plastic_power", "plastic dissipation", "P", SW_DOUBLE},
    {"elastic_energy", "elastic energy", "E", SW_DOUBLE},
    {"converged", "1 if the point was solved, 0 if it failed", "1", SW_INT},
};
#define N_SWEEP_VARS (sizeof sweep_vars / sizeof sweep_vars[0])

struct rs_sweep_output {
  int ncid, naxes;
  char *path;
  size_t sizes[NC_MAX_VAR_DIMS];
  int varid[N_SWEEP_VARS];
};

static const char *unit_of(const sweep_var *v, int dimension)
{
  if (!strcmp(v->units, "F")) return dimension == 3 ? "N" : "N/mm";
  if (!strcmp(v->units, "P")) return dimension == 3 ? "N mm/s" : "N mm/s/mm";
  if (!strcmp(v->units, "E")) return dimension == 3 ? "N mm" : "N mm/mm";
  return v->units;
}

int rs_sweep_output_create(rs_sweep_output **outp, const rs_sweep_output_spec *spec, rs_msg *msg)
{
  *outp = NULL;
  if (spec->naxes < 1 || spec->naxes > NC_MAX_VAR_DIMS)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "sweep output: %d axes", spec->naxes);
  int status = rs_output_make_parent_dirs(spec->path, msg);
  if (status != RS_OK) return status;
  rs_sweep_output *o = calloc(1, sizeof *o);
  if (!o || !(o->path = strdup(spec->path))) {
    free(o);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  o->naxes = spec->naxes;
  int err = nc_create(spec->path, NC_CLOBBER | NC_64BIT_OFFSET, &o->ncid);
  if (err) {
    free(o->path);
    free(o);
    return rs_output_nc_failure(msg, spec->path, "cannot create", err);
  }
  int dims[NC_MAX_VAR_DIMS], coord[NC_MAX_VAR_DIMS];
  char name[NC_MAX_NAME + 1];
  for (int a = 0; a < spec->naxes && !err; a++) {
    snprintf(name, sizeof name, "%s", spec->keys[a]);
    for (char *p = name; *p; p++)
      if (*p == '.') *p = '_';
    o->sizes[a] = (size_t)spec->sizes[a];
    err = nc_def_dim(o->ncid, name, o->sizes[a], &dims[a]);
    if (!err) err = nc_def_var(o->ncid, name, NC_DOUBLE, 1, &dims[a], &coord[a]);
    if (!err) err = rs_output_put_text(o->ncid, coord[a], "key", spec->keys[a]);
    if (!err) err = rs_output_put_text(o->ncid, coord[a], "long_name", spec->keys[a]);
    if (!err) err = rs_output_put_text(o->ncid, coord[a], "units", "as in the case file");
  }
  for (size_t v = 0; v < N_SWEEP_VARS && !err; v++) {
    err = nc_def_var(o->ncid, sweep_vars[v].name, sweep_vars[v].type == SW_INT ? NC_INT : NC_DOUBLE,
                     spec->naxes, dims, &o->varid[v]);
    if (!err) err = rs_output_put_text(o->ncid, o->varid[v], "long_name", sweep_vars[v].long_name);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varid[v], "units",
                               unit_of(&sweep_vars[v], spec->dimension));
    if (!err && sweep_vars[v].type == SW_INT) {
      const int fill = -1;
      err = nc_put_att_int(o->ncid, o->varid[v], "_FillValue", NC_INT, 1, &fill);
    }
  }
  char status_buf[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(status_buf, "running");
  if (!err) err = rs_output_put_text(o->ncid, NC_GLOBAL, "Conventions", "CF-1.10");
  if (!err) err = rs_output_put_text(o->ncid, NC_GLOBAL, "title", spec->title ? spec->title : "");
  if (!err) err = rs_output_put_text(o->ncid, NC_GLOBAL, "source", "rollsim " RS_VERSION);
  if (!err)
    err = rs_output_put_text(o->ncid, NC_GLOBAL, "history", spec->history ? spec->history : "");
  if (!err)
    err = rs_output_put_text(o->ncid, NC_GLOBAL, "case", spec->case_text ? spec->case_text : "");
  if (!err) err = nc_put_att_text(o->ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, status_buf);
  if (!err) err = nc_enddef(o->ncid);
  for (int a = 0; a < spec->naxes && !err; a++)
    err = nc_put_var_double(o->ncid, coord[a], spec->values[a]);
  if (!err) err = nc_sync(o->ncid);
  if (err) {
    status = rs_output_nc_failure(msg, spec->path, "cannot write the sweep layout", err);
    nc_close(o->ncid);
    free(o->path);
    free(o);
    return status;
  }
  *outp = o;
  return RS_OK;
}

int rs_sweep_output_write(rs_sweep_output *o, size_t index, const rs_sweep_point *pt, rs_msg *msg)
{
  size_t start[NC_MAX_VAR_DIMS];
  for (int a = o->naxes - 1; a >= 0; a--) {
    start[a] = index % o->sizes[a];
    index /= o->sizes[a];
  }
  const double ratio = pt->Fn != 0.0 ? pt->Fx / pt->Fn : NAN;
  const double dv[] = {
      pt->Fx, pt->Fn, ratio, pt->creepage,         pt->velocity,      0,
      0,      0,      0,     pt->frictional_power, pt->plastic_power, pt->elastic_energy,
      0};
  const int iv[] = {0,
                    0,
                    0,
                    0,
                    0,
                    pt->n_exterior,
                    pt->n_adhesion,
                    pt->n_slip,
                    pt->n_plastic,
                    0,
                    0,
                    0,
                    pt->converged};
  int err = 0;
  for (size_t v = 0; v < N_SWEEP_VARS && !err; v++)
    err = sweep_vars[v].type == SW_INT ? nc_put_var1_int(o->ncid, o->varid[v], start, &iv[v])
                                       : nc_put_var1_double(o->ncid, o->varid[v], start, &dv[v]);
  if (!err) err = nc_sync(o->ncid);
  return err ? rs_output_nc_failure(msg, o->path, "cannot write a sweep point", err) : RS_OK;
}

int rs_sweep_output_close(rs_sweep_output *o, const char *status, rs_msg *msg)
{
  if (!o) return RS_OK;
  char buf[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(buf, status);
  int err = nc_put_att_text(o->ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, buf);
  int err2 = nc_close(o->ncid);
  int rc = RS_OK;
  if (err || err2) rc = rs_output_nc_failure(msg, o->path, "cannot finish", err ? err : err2);
  free(o->path);
  free(o);
  return rc;
}
