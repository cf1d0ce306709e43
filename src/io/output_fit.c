/* FIT.nc (docs/file-format.md "Fit files"; io/fit_spec.h): dimension `parameter` with
 * parameter_name, start, fitted, standard_error, lower_bound, upper_bound and
 * covariance(parameter, parameter); dimension `point` with one variable per CSV column
 * (attribute `column` = its name in the CSV, `role` = input | measured | weight) plus
 * measured, simulated and weight; global attributes residual_norm, evaluations, status,
 * notes and the case text. The whole file is written to PATH.part and renamed over
 * PATH, so PATH always holds a complete file (the best point so far during a fit). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output_internal.h"
#include "io/case.h"
#include "io/fit_spec.h"

#define NAME_LEN 64

static int put_att_text(int ncid, int var, const char *name, const char *text)
{
  return nc_put_att_text(ncid, var, name, strlen(text ? text : ""), text ? text : "");
}

static int def_double(int ncid, const char *name, int ndims, const int *dims, const char *units,
                      const char *long_name, int *id)
{
  int err = nc_def_var(ncid, name, NC_DOUBLE, ndims, dims, id);
  const double fill = NAN;
  if (!err) err = nc_put_att_double(ncid, *id, "_FillValue", NC_DOUBLE, 1, &fill);
  if (!err && units) err = put_att_text(ncid, *id, "units", units);
  if (!err) err = put_att_text(ncid, *id, "long_name", long_name);
  return err;
}

/* netCDF variable name of a CSV column (dots become underscores). */
static void var_name(const char *column, char *out, size_t len)
{
  snprintf(out, len, "%s", column);
  for (char *p = out; *p; p++)
    if (*p == '.' || *p == ' ') *p = '_';
}

int rs_fit_output_write(const rs_fit_output *o, char *backup, size_t backup_len, rs_msg *msg)
{
  const rs_fit_spec *f = o->spec;
  const int n = f->nparams;
  const size_t m = f->npoints;
  int status = rs_output_make_parent_dirs(o->path, msg);
  if (status != RS_OK) return status;
  const size_t plen = strlen(o->path) + 6;
  char *part = malloc(plen);
  double *buf = malloc((m > (size_t)(n * n) ? m : (size_t)(n * n)) * sizeof *buf + 8);
  int *col_id = calloc((size_t)f->ncols, sizeof *col_id);
  if (!part || !buf || !col_id) {
    free(part);
    free(buf);
    free(col_id);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  snprintf(part, plen, "%s.part", o->path);
  int ncid = -1, err = nc_create(part, NC_CLOBBER | NC_64BIT_OFFSET, &ncid);
  int dpar, dpt, dlen, dims[2];
  int v_name, v_start, v_fit, v_se, v_lo, v_hi, v_cov, v_meas, v_sim, v_w;
  if (!err) err = nc_def_dim(ncid, "parameter", (size_t)n, &dpar);
  if (!err) err = nc_def_dim(ncid, "point", m, &dpt);
  if (!err) err = nc_def_dim(ncid, "name_strlen", NAME_LEN, &dlen);
  dims[0] = dpar;
  dims[1] = dlen;
  if (!err) err = nc_def_var(ncid, "parameter_name", NC_CHAR, 2, dims, &v_name);
  if (!err) err = put_att_text(ncid, v_name, "long_name", "dotted case key of the parameter");
  if (!err) err = def_double(ncid, "start", 1, &dpar, NULL, "first guess", &v_start);
  if (!err) err = def_double(ncid, "fitted", 1, &dpar, NULL, "fitted value", &v_fit);
  if (!err)
    err = def_double(ncid, "standard_error", 1, &dpar, NULL,
                     "standard error sqrt(covariance_kk), s^2 (J^T J)^-1 with s^2 = |r|^2/(m - n)",
                     &v_se);
  if (!err) err = def_double(ncid, "lower_bound", 1, &dpar, NULL, "lower bound", &v_lo);
  if (!err) err = def_double(ncid, "upper_bound", 1, &dpar, NULL, "upper bound", &v_hi);
  dims[0] = dims[1] = dpar;
  if (!err)
    err = def_double(ncid, "covariance", 2, dims, NULL, "covariance of the fitted parameters",
                     &v_cov);
  /* units of the parameters, in their order */
  char units[1024] = "";
  for (int k = 0; k < n; k++) {
    const size_t used = strlen(units);
    snprintf(units + used, sizeof units - used, "%s%s", k ? ", " : "",
             f->params[k].unit[0] ? f->params[k].unit : "1");
  }
  if (!err) err = put_att_text(ncid, v_fit, "parameter_units", units);
  for (int j = 0; !err && j < f->ncols; j++) {
    char name[NC_MAX_NAME];
    var_name(f->columns[j], name, sizeof name);
    char vname[NC_MAX_NAME + 8];
    snprintf(vname, sizeof vname, "%s%s", name,
             !strcmp(name, "measured") || !strcmp(name, "simulated") || !strcmp(name, "weight")
                 ? "_column"
                 : "");
    err = def_double(ncid, vname, 1, &dpt, NULL, "column of the measurements' CSV", &col_id[j]);
    if (!err) err = put_att_text(ncid, col_id[j], "column", f->columns[j]);
    if (!err)
      err = put_att_text(ncid, col_id[j], "role",
                         f->roles[j] == RS_FIT_COL_MEASURED ? "measured"
                         : f->roles[j] == RS_FIT_COL_WEIGHT ? "weight"
                                                            : "input");
    if (!err && f->input_keys && f->input_keys[j])
      err = put_att_text(ncid, col_id[j], "key", f->input_keys[j]);
    const char *key_units =
        f->input_keys && f->input_keys[j] ? rs_case_key_units(f->input_keys[j]) : NULL;
    if (!err && key_units)
      err = put_att_text(ncid, col_id[j], "units",
                         o->dimension == 3 && !strcmp(key_units, "N/mm") ? "N" : key_units);
  }
  /* the measured output: traction_coefficient (1) or Fx (a force, per width in 2D) */
  const char *measured_units = strcmp(f->measured, "Fx") ? "1" : o->dimension == 3 ? "N" : "N/mm";
  if (!err) err = def_double(ncid, "measured", 1, &dpt, measured_units, f->measured, &v_meas);
  if (!err) err = def_double(ncid, "simulated", 1, &dpt, measured_units, f->measured, &v_sim);
  if (!err) err = put_att_text(ncid, v_sim, "comment", "at the fitted parameters");
  if (!err) err = def_double(ncid, "weight", 1, &dpt, NULL, "weight (1/sigma, relative)", &v_w);
  char source[64];
  snprintf(source, sizeof source, "rollsim %s", RS_VERSION);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "Conventions", "CF-1.10");
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "title", o->title);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "source", source);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "history", o->history);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "case", o->case_text);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "status", o->status);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "notes", o->notes);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "data", f->data_path);
  if (!err) err = put_att_text(ncid, NC_GLOBAL, "measured", f->measured);
  if (!err)
    err = nc_put_att_double(ncid, NC_GLOBAL, "residual_norm", NC_DOUBLE, 1, &o->residual_norm);
  if (!err) {
    const int ev = o->evaluations > 2147483647L ? 2147483647 : (int)o->evaluations;
    err = nc_put_att_int(ncid, NC_GLOBAL, "evaluations", NC_INT, 1, &ev);
  }
  if (!err) err = nc_enddef(ncid);
  for (int k = 0; !err && k < n; k++) {
    char name[NAME_LEN] = {0};
    snprintf(name, sizeof name, "%s", f->params[k].key);
    const size_t start[2] = {(size_t)k, 0}, count[2] = {1, NAME_LEN};
    err = nc_put_vara_text(ncid, v_name, start, count, name);
  }
  if (!err) err = nc_put_var_double(ncid, v_start, o->start);
  if (!err) err = nc_put_var_double(ncid, v_fit, o->fitted);
  for (int k = 0; !err && k < n; k++) buf[k] = o->std_error ? o->std_error[k] : NAN;
  if (!err) err = nc_put_var_double(ncid, v_se, buf);
  for (int k = 0; !err && k < n; k++) buf[k] = f->params[k].lo;
  if (!err) err = nc_put_var_double(ncid, v_lo, buf);
  for (int k = 0; !err && k < n; k++) buf[k] = f->params[k].hi;
  if (!err) err = nc_put_var_double(ncid, v_hi, buf);
  for (int k = 0; !err && k < n * n; k++) buf[k] = o->covariance ? o->covariance[k] : NAN;
  if (!err) err = nc_put_var_double(ncid, v_cov, buf);
  for (int j = 0; !err && j <= f->ncols + 1; j++) {
    const int var = j < f->ncols ? col_id[j] : j == f->ncols ? v_meas : v_w;
    const int col = j < f->ncols ? j : j == f->ncols ? f->measured_col : f->weight_col;
    for (size_t i = 0; i < m; i++)
      buf[i] = col >= 0 ? f->table[i * (size_t)f->ncols + (size_t)col] : 1.0;
    err = nc_put_var_double(ncid, var, buf);
  }
  if (!err) err = nc_put_var_double(ncid, v_sim, o->simulated);
  if (ncid >= 0) {
    const int cerr = nc_close(ncid);
    if (!err) err = cerr;
  }
  status = rs_output_commit_part(err, part, o->path, o->keep_old, backup, backup_len,
                                 "writing the fit file", msg);
  free(part);
  free(buf);
  free(col_id);
  return status;
}

void rs_fit_previous_free(rs_fit_previous *prev)
{
  free(prev->start);
  free(prev->fitted);
  free(prev->history);
  memset(prev, 0, sizeof *prev);
}

/* Whether the variable `name` of the open file holds exactly the m values of column col of
 * the fit's table (1 for col -1: no weights). */
static int same_column(int ncid, const char *name, const rs_fit_spec *f, int col, double *buf)
{
  int id;
  if (nc_inq_varid(ncid, name, &id) || nc_get_var_double(ncid, id, buf)) return 0;
  for (size_t i = 0; i < f->npoints; i++) {
    const double want = col >= 0 ? f->table[i * (size_t)f->ncols + (size_t)col] : 1.0;
    if (memcmp(&buf[i], &want, sizeof want) && !(isnan(buf[i]) && isnan(want))) return 0;
  }
  return 1;
}

/* Why the open file cannot be resumed as the fit f of case_text ("" when it can); fills
 * prev from it. */
static void previous_check(int ncid, const rs_fit_spec *f, const char *case_text,
                           rs_fit_previous *prev, double *buf, char *why, size_t len)
{
  const int n = f->nparams;
  int v_name, v_start, v_fit, v_lo, v_hi, dpar, dpt;
  size_t np = 0, m = 0;
  if (nc_inq_varid(ncid, "parameter_name", &v_name) || nc_inq_varid(ncid, "start", &v_start) ||
      nc_inq_varid(ncid, "fitted", &v_fit) || nc_inq_varid(ncid, "lower_bound", &v_lo) ||
      nc_inq_varid(ncid, "upper_bound", &v_hi) || nc_inq_dimid(ncid, "parameter", &dpar) ||
      nc_inq_dimid(ncid, "point", &dpt) || nc_inq_dimlen(ncid, dpar, &np) ||
      nc_inq_dimlen(ncid, dpt, &m)) {
    snprintf(why, len, "not a fit file (no parameter_name, start, fitted and bounds)");
    return;
  }
  if (!rs_output_same_case(ncid, case_text)) {
    snprintf(why, len, "%s", RS_OUTPUT_OTHER_CASE);
    return;
  }
  if (np != (size_t)n) {
    snprintf(why, len, "the file fits %zu parameters, the case %d", np, n);
    return;
  }
  for (int k = 0; k < n; k++) {
    char name[NAME_LEN + 1] = {0};
    const size_t start[2] = {(size_t)k, 0}, count[2] = {1, NAME_LEN};
    double lo = NAN, hi = NAN;
    const size_t at = (size_t)k;
    if (nc_get_vara_text(ncid, v_name, start, count, name) ||
        nc_get_var1_double(ncid, v_lo, &at, &lo) || nc_get_var1_double(ncid, v_hi, &at, &hi) ||
        strcmp(name, f->params[k].key) || lo != f->params[k].lo || hi != f->params[k].hi) {
      snprintf(why, len, "its parameter %d is not %s with bounds [%g, %g]", k + 1, f->params[k].key,
               f->params[k].lo, f->params[k].hi);
      return;
    }
  }
  char *measured = rs_output_get_text(ncid, NC_GLOBAL, "measured");
  const int same_measured = measured && !strcmp(measured, f->measured);
  free(measured);
  int same_data = same_measured && m == f->npoints &&
                  same_column(ncid, "measured", f, f->measured_col, buf) &&
                  same_column(ncid, "weight", f, f->weight_col, buf);
  for (int j = 0; same_data && j < f->ncols; j++) {
    char name[NC_MAX_NAME], vname[NC_MAX_NAME + 8];
    var_name(f->columns[j], name, sizeof name);
    snprintf(vname, sizeof vname, "%s%s", name,
             !strcmp(name, "measured") || !strcmp(name, "simulated") || !strcmp(name, "weight")
                 ? "_column"
                 : "");
    same_data = same_column(ncid, vname, f, j, buf);
  }
  if (!same_data) {
    snprintf(why, len,
             "its data differ from %s (%zu points; the file holds %zu): the measurements "
             "changed since the fit began",
             f->data_path, f->npoints, m);
    return;
  }
  int ev = 0;
  if (nc_get_var_double(ncid, v_start, prev->start) ||
      nc_get_var_double(ncid, v_fit, prev->fitted) ||
      nc_get_att_double(ncid, NC_GLOBAL, "residual_norm", &prev->residual_norm) ||
      nc_get_att_int(ncid, NC_GLOBAL, "evaluations", &ev)) {
    snprintf(why, len, "cannot read its start, fitted, residual_norm and evaluations");
    return;
  }
  for (int k = 0; k < n; k++)
    if (!(prev->fitted[k] >= f->params[k].lo && prev->fitted[k] <= f->params[k].hi)) {
      snprintf(why, len, "its fitted %s = %g is not inside the bounds", f->params[k].key,
               prev->fitted[k]);
      return;
    }
  prev->evaluations = ev;
  char *status = rs_output_get_text(ncid, NC_GLOBAL, "status");
  prev->complete = status && !strcmp(status, "complete");
  free(status);
  prev->history = rs_output_get_text(ncid, NC_GLOBAL, "history");
  if (!prev->history) snprintf(why, len, "out of memory");
}

int rs_fit_output_read_previous(const char *path, const rs_fit_spec *f, const char *case_text,
                                rs_fit_previous *prev, rs_msg *msg)
{
  memset(prev, 0, sizeof *prev);
  long long data_end = 0, file_size = 0;
  FILE *fp = fopen(path, "rb");
  if (!fp)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: no such file (run the fit without --resume)", path);
  fclose(fp);
  if (rs_nc_classic_data_end(path, &data_end, &file_size) != 0)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: not a readable fit file (netCDF 64-bit offset)", path);
  if (file_size < data_end)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: the file is truncated (%lld of %lld bytes)", path,
                      file_size, data_end);
  const size_t m = f->npoints, n = (size_t)f->nparams;
  prev->start = calloc(n, sizeof *prev->start);
  prev->fitted = calloc(n, sizeof *prev->fitted);
  double *buf = calloc(m > 0 ? m : 1, sizeof *buf);
  if (!prev->start || !prev->fitted || !buf) {
    free(buf);
    rs_fit_previous_free(prev);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  int ncid;
  const int err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) {
    free(buf);
    rs_fit_previous_free(prev);
    return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot resume: %s", path, nc_strerror(err));
  }
  char why[512] = "";
  previous_check(ncid, f, case_text, prev, buf, why, sizeof why);
  nc_close(ncid);
  free(buf);
  if (!why[0]) return RS_OK;
  rs_fit_previous_free(prev);
  return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot resume: %s", path, why);
}
