/* netCDF output (io/output.h, docs/file-format.md "Run files").
 *
 * Crash safety: the file must stay readable, holding every record written so far, if the
 * process is killed (SIGKILL) at any moment. Nothing here can make a kill wait, so the file
 * is laid out and written in an order where every prefix of the write() calls leaves a
 * valid file:
 *
 *  - Format: classic 64-bit offset (CDF-2), not netCDF-4/HDF5. A classic file is a header
 *    plus flat arrays; readers take the record count from one 4-byte field (numrecs, at
 *    offset 4), which a single write() either changes or not. HDF5 updates B-trees and its
 *    superblock in several places and a kill between them can leave the file unreadable.
 *  - Creation: the file is built under PATH.part (header and x written and synced) and
 *    renamed to PATH, so PATH never names a file without a complete header.
 *  - Records: netCDF's posix I/O layer (without NC_SHARE) keeps one buffer of at most two
 *    blocks; numrecs is only written by nc_sync, which pages out the buffered record data
 *    before it reads the header block to update numrecs, then writes that block. The record
 *    section is aligned to two blocks (r_align below), so record data never shares a
 *    buffer (hence a write()) with numrecs: the data of record n reach the file before
 *    numrecs becomes n+1. A kill in between leaves numrecs = n and the half-written record
 *    beyond what readers see. (Checked with strace and by tests/check_output_crash.py.)
 *  - Header rewrites (status attribute): the status text has a fixed, NUL-padded length
 *    (RS_OUTPUT_STATUS_LEN), so the rewrite is done in data mode and the header keeps its
 *    size and layout; only the status bytes change and a torn write can at worst mix old
 *    and new status text. Extra header space is reserved anyway (nc__enddef h_minfree) so
 *    that a future attribute change never needs to move the data.
 *  - The last record variable is always a double (the scalars follow the fields), so a file
 *    with n complete records is as long as its header says (no trailing padding missing).
 *
 * nc_sync does not fsync: the data are in the kernel's page cache, which survives a killed
 * process (not a power failure). */
#define _POSIX_C_SOURCE 200809L

#include "io/output.h"
#include "io/output_internal.h"

#include <errno.h>
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "io/case.h"

#ifndef RS_VERSION
#define RS_VERSION "unknown"
#endif

/* Free header space reserved beyond the case text (nc__enddef h_minfree). */
#define RS_HEADER_RESERVE ((size_t)4096)

/* (time, x) fields: the table of docs/file-format.md (types in io/output_internal.h). */
const rs_field_var rs_field_vars[RS_N_FIELDS] = {
    {RS_FIELD_PX, "px", "N/mm2", "tangential traction on body 1", offsetof(rs_record, px)},
    {RS_FIELD_PN, "pn", "N/mm2", "normal pressure", offsetof(rs_record, pn)},
    {RS_FIELD_SLIP, "slip", "1", "relative slip v_s/V (slip velocity in mm/s when V = 0)",
     offsetof(rs_record, slip)},
    {RS_FIELD_UPL, "upl", "mm", "plastic displacement", offsetof(rs_record, upl)},
    {RS_FIELD_USTAR, "ustar", "mm", "accumulated plastic deformation", offsetof(rs_record, ustar)},
    {RS_FIELD_TAUC, "tauc", "N/mm2", "current yield limit", offsetof(rs_record, tauc)},
    {RS_FIELD_REGIME, "regime", "1", "contact regime of the cell", 0},
    {RS_FIELD_MU, "mu", "1",
     "coefficient of friction of the cell: mu(|v_s|) (NaN outside the contact), or with "
     "friction memory the memory state (carried outside the contact too)",
     offsetof(rs_record, mu)},
};

/* Scalars per output time (docs/model.md §7). Units depend on the dimension: per unit width
 * in 2D. traction_coefficient is computed here (Fx/Fn). */
const rs_scalar_var rs_scalar_vars[RS_N_SCALARS] = {
    {"Fx", NC_DOUBLE, offsetof(rs_record, Fx), "N/mm", "N", "total tangential force on body 1"},
    {"Fn", NC_DOUBLE, offsetof(rs_record, Fn), "N/mm", "N", "total normal force on body 1"},
    {"traction_coefficient", NC_DOUBLE, 0, "1", "1", "traction coefficient Fx/Fn"},
    {"creepage", NC_DOUBLE, offsetof(rs_record, creepage), "1", "1", "creepage"},
    {"velocity", NC_DOUBLE, offsetof(rs_record, velocity), "mm/s", "mm/s", "rolling velocity"},
    {"n_exterior", NC_INT, offsetof(rs_record, n_exterior), "1", "1",
     "number of cells outside the contact area"},
    {"n_adhesion", NC_INT, offsetof(rs_record, n_adhesion), "1", "1",
     "number of cells in adhesion"},
    {"n_slip", NC_INT, offsetof(rs_record, n_slip), "1", "1", "number of cells in slip"},
    {"n_plastic", NC_INT, offsetof(rs_record, n_plastic), "1", "1",
     "number of cells in plastic flow"},
    {"frictional_power", NC_DOUBLE, offsetof(rs_record, frictional_power), "N mm/s/mm", "N mm/s",
     "frictional power dissipated by slip"},
    {"plastic_power", NC_DOUBLE, offsetof(rs_record, plastic_power), "N mm/s/mm", "N mm/s",
     "plastic power dissipated"},
    {"elastic_energy", NC_DOUBLE, offsetof(rs_record, elastic_energy), "N mm/mm", "N mm",
     "elastic energy"},
};

/* 3D only: the lateral force, the spin moment and the two further creepages. */
const rs_scalar_var rs_scalar_vars_3d[RS_N_SCALARS_3D] = {
    {"Fy", NC_DOUBLE, offsetof(rs_record, Fy), "N", "N", "total lateral force on body 1"},
    {"Mz", NC_DOUBLE, offsetof(rs_record, Mz), "N mm", "N mm",
     "spin moment on body 1 about the contact centre"},
    {"lateral_creepage", NC_DOUBLE, offsetof(rs_record, lateral_creepage), "1", "1",
     "lateral creepage"},
    {"spin", NC_DOUBLE, offsetof(rs_record, spin), "1/mm", "1/mm", "spin creepage"},
};

/* RS_FIELD_TEMPERATURE (docs/model.md §18): two fields, then three scalars. */
const rs_scalar_var rs_temperature_vars[RS_N_TEMPERATURE_VARS] = {
    {"T1", NC_DOUBLE, offsetof(rs_record, T1), "degC", "degC", "surface temperature of body 1"},
    {"T2", NC_DOUBLE, offsetof(rs_record, T2), "degC", "degC", "surface temperature of body 2"},
    {"T_max", NC_DOUBLE, offsetof(rs_record, T_max), "degC", "degC",
     "largest surface temperature in the contact"},
    {"heat_input_1", NC_DOUBLE, offsetof(rs_record, heat_input_1), "W/mm", "W",
     "heat flowing into body 1 through its surface"},
    {"heat_input_2", NC_DOUBLE, offsetof(rs_record, heat_input_2), "W/mm", "W",
     "heat flowing into body 2 through its surface"},
};

const char *rs_field_name(int f, int three_d, int comp)
{
  static const char *const names3d[RS_N_FIELDS][2] = {
      {"px", "py"},    {"pn", NULL},   {"slip_x", "slip_y"}, {"upl_x", "upl_y"},
      {"ustar", NULL}, {"tauc", NULL}, {"regime", NULL},     {"mu", NULL}};
  if (f < 0 || f >= RS_N_FIELDS || comp < 0 || comp > 1) return NULL;
  if (!three_d) return comp == 0 ? rs_field_vars[f].name : NULL;
  return names3d[f][comp];
}

/* A double variable over one dimension with units, long_name and a NaN fill value. */
static int def_rig_var(int ncid, const char *name, int dim, const char *units,
                       const char *long_name, int *id)
{
  const double fill = NAN;
  int err;
  if ((err = nc_def_var(ncid, name, NC_DOUBLE, 1, &dim, id)) ||
      (err = rs_output_put_text(ncid, *id, "units", units)) ||
      (err = rs_output_put_text(ncid, *id, "long_name", long_name)) ||
      (err = nc_put_att_double(ncid, *id, "_FillValue", NC_DOUBLE, 1, &fill)))
    return err;
  return NC_NOERR;
}

const char *const rs_error_var_names[RS_N_ERROR_VARS] = {
    "error_reliable", "Fx_error",        "traction_coefficient_error",        "Fy_error",
    "Mz_error",       "Fx_extrapolated", "traction_coefficient_extrapolated", "Fy_extrapolated",
    "Mz_extrapolated"};

int rs_output_define_error_vars(int ncid, int ndims, const int *dims, int three_d,
                                int ids[RS_N_ERROR_VARS])
{
  static const char *const long_names[RS_N_ERROR_VARS] = {
      "1: the error estimate's observed order lies in the asymptotic band; 0: it does not (the "
      "conservative fallback); -1: no estimate",
      "estimated discretisation error of Fx (magnitude)",
      "estimated discretisation error of Fx/Fn (magnitude)",
      "estimated discretisation error of Fy (magnitude)",
      "estimated discretisation error of Mz (magnitude)",
      "Fx extrapolated to zero cell size (where error_reliable is 1)",
      "Fx/Fn extrapolated to zero cell size (where error_reliable is 1)",
      "Fy extrapolated to zero cell size (where error_reliable is 1)",
      "Mz extrapolated to zero cell size (where error_reliable is 1)"};
  const char *force = three_d ? "N" : "N/mm";
  const char *units[RS_N_ERROR_VARS] = {"1", force, "1", "N", "N mm", force, "1", "N", "N mm"};
  const double fill = NAN;
  int err = 0;
  for (int k = 0; k < RS_N_ERROR_VARS && !err; k++) {
    ids[k] = -1;
    if ((k == 3 || k == 4 || k == 7 || k == 8) && !three_d) continue;
    err = nc_def_var(ncid, rs_error_var_names[k], k ? NC_DOUBLE : NC_INT, ndims, dims, &ids[k]);
    if (!err) err = rs_output_put_text(ncid, ids[k], "units", units[k]);
    if (!err) err = rs_output_put_text(ncid, ids[k], "long_name", long_names[k]);
    if (!err && k) err = nc_put_att_double(ncid, ids[k], "_FillValue", NC_DOUBLE, 1, &fill);
    if (!err && !k)
      err = nc_put_att_int(ncid, ids[k], "valid_range", NC_INT, 2, (const int[]){-1, 1});
  }
  return err;
}

/* The error estimate's record variables (docs/file-format.md): the flag first, so that the
 * last record variable stays a double. */
static int define_errors(rs_output *out, int time_dim, int three_d)
{
  const int err = rs_output_define_error_vars(out->ncid, 1, &time_dim, three_d, out->error_id);
  out->has_errors = !err;
  return err;
}

/* Twin-disc summary variables (defined when spec->rig is given). */
static int define_rig(rs_output *out, const rs_output_rig *rig)
{
  const int ncid = out->ncid;
  int err, sdim, rdim;
  if ((err = nc_def_dim(ncid, "protocol_step", rig->nsteps, &sdim)) ||
      (err = nc_def_dim(ncid, "revolution", rig->nrevolutions, &rdim)))
    return err;
  struct {
    const char *name;
    int dim;
    const char *units, *long_name;
    int *id;
  } vars[] = {
      {"step_slip_start", sdim, "1", "rig slip (V1 - V2)/V at the start of the protocol step",
       &out->rig_meta_id[0]},
      {"step_slip_end", sdim, "1", "rig slip (V1 - V2)/V at the end of the protocol step",
       &out->rig_meta_id[1]},
      {"step_time_start", sdim, "s", "start of the protocol step", &out->rig_meta_id[2]},
      {"step_time_end", sdim, "s", "end of the protocol step", &out->rig_meta_id[3]},
      {"step_window_start", sdim, "s",
       "start of the window (ending with the step) over which step values are averaged",
       &out->rig_meta_id[4]},
      {"revolution_time_end", rdim, "s", "end of the revolution of disc 1", &out->rig_meta_id[5]},
      {"step_traction_coefficient", sdim, "1",
       "mean F_x/F_n over the averaging window of the protocol step", &out->step_mu_id},
      {"step_slip", sdim, "1", "mean rig slip over the averaging window of the protocol step",
       &out->step_slip_id},
      {"revolution_traction_coefficient", rdim, "1", "mean F_x/F_n over the revolution",
       &out->rev_mu_id},
      {"revolution_slip", rdim, "1", "mean rig slip over the revolution", &out->rev_slip_id},
      {"revolution_dissipated_energy", rdim, out->three_d ? "N mm" : "N mm/mm",
       "energy dissipated in the contact over the revolution: the time integral of "
       "frictional_power + plastic_power",
       &out->rev_energy_id},
      {"revolution_ustar_exit_mean", rdim, "mm",
       "accumulated plastic deformation u* of the surface leaving the contact (the trailing "
       "cells), mean over the revolution (and across y in 3D)",
       &out->rev_ustar_id},
      {"revolution_ustar_exit_max", rdim, "mm",
       "largest u* of the surface leaving the contact over the revolution", &out->rev_ustar_max_id},
  };
  for (size_t i = 0; i < sizeof vars / sizeof *vars; i++)
    if ((err = def_rig_var(ncid, vars[i].name, vars[i].dim, vars[i].units, vars[i].long_name,
                           vars[i].id)))
      return err;
  /* with a temperature: block (docs/model.md §18, "Twin-disc rig") */
  const char *en = out->three_d ? "J" : "J/mm";
  const struct {
    const char *name, *units, *long_name;
  } tvars[7] = {
      {"revolution_T_max", "degC",
       "largest surface temperature in the contact over the revolution (at the accepted steps)"},
      {"revolution_inlet_temperature_1", "degC",
       "surface temperature of disc 1 entering the contact, mean over the revolution"},
      {"revolution_inlet_temperature_2", "degC",
       "surface temperature of disc 2 entering the contact, mean over the revolution"},
      {"revolution_heat_input_1", en, "heat flowing into disc 1 over the revolution"},
      {"revolution_heat_input_2", en, "heat flowing into disc 2 over the revolution"},
      {"revolution_bulk_temperature_1", "degC",
       "bulk temperature of disc 1 at the end of the revolution (temperature.disc_mass)"},
      {"revolution_bulk_temperature_2", "degC",
       "bulk temperature of disc 2 at the end of the revolution (temperature.disc_mass)"}};
  for (int k = 0; k < 7; k++) {
    out->rev_temp_id[k] = -1;
    if (!rig->temperature || (k >= 5 && !rig->bulk)) continue;
    if ((err = def_rig_var(ncid, tvars[k].name, rdim, tvars[k].units, tvars[k].long_name,
                           &out->rev_temp_id[k])))
      return err;
  }
  if ((err = nc_put_att_double(ncid, NC_GLOBAL, "twin_disc_revolution_time", NC_DOUBLE, 1,
                               &rig->revolution_time)) ||
      (err =
           nc_put_att_double(ncid, NC_GLOBAL, "twin_disc_recovery", NC_DOUBLE, 1, &rig->recovery)))
    return err;
  out->has_rig = 1;
  return NC_NOERR;
}

/* After enddef: the protocol, the revolution ends, NaN in the results. */
static int write_rig_meta(rs_output *out, const rs_output_rig *rig)
{
  const int ncid = out->ncid;
  const double *meta[5] = {rig->slip_start, rig->slip_end, rig->time_start, rig->time_end,
                           rig->window_start};
  int err;
  for (int k = 0; k < 5; k++)
    if ((err = nc_put_var_double(ncid, out->rig_meta_id[k], meta[k]))) return err;
  const double t_end = rig->nsteps ? rig->time_end[rig->nsteps - 1] : 0.0;
  const size_t nmax = rig->nsteps > rig->nrevolutions ? rig->nsteps : rig->nrevolutions;
  double *buf = malloc((nmax ? nmax : 1) * sizeof *buf);
  if (!buf) return NC_ENOMEM;
  for (size_t i = 0; i < rig->nrevolutions; i++)
    buf[i] = fmin((double)(i + 1) * rig->revolution_time, t_end);
  err = nc_put_var_double(ncid, out->rig_meta_id[5], buf);
  for (size_t i = 0; i < nmax; i++) buf[i] = NAN;
  const int ids[7] = {out->step_mu_id,    out->step_slip_id, out->rev_mu_id,       out->rev_slip_id,
                      out->rev_energy_id, out->rev_ustar_id, out->rev_ustar_max_id};
  for (int k = 0; k < 7 && !err; k++) err = nc_put_var_double(ncid, ids[k], buf);
  for (int k = 0; k < 7 && !err; k++)
    if (out->rev_temp_id[k] >= 0) err = nc_put_var_double(ncid, out->rev_temp_id[k], buf);
  free(buf);
  return err;
}

static int put_pair(rs_output *out, int id_a, int id_b, size_t i, double a, double b, rs_msg *msg)
{
  if (!out->has_rig)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "output file %s: no twin-disc variables", out->path);
  int err;
  if ((err = nc_put_var1_double(out->ncid, id_a, &i, &a)) ||
      (err = nc_put_var1_double(out->ncid, id_b, &i, &b)) || (err = nc_sync(out->ncid)))
    return rs_output_nc_failure(msg, out->path, "writing a twin-disc summary", err);
  return RS_OK;
}

int rs_output_put_step(rs_output *out, size_t i, double traction_coefficient, double slip,
                       rs_msg *msg)
{
  return put_pair(out, out->step_mu_id, out->step_slip_id, i, traction_coefficient, slip, msg);
}

int rs_output_put_revolution(rs_output *out, size_t i, double traction_coefficient, double slip,
                             rs_msg *msg)
{
  return put_pair(out, out->rev_mu_id, out->rev_slip_id, i, traction_coefficient, slip, msg);
}

int rs_output_put_revolution_energy(rs_output *out, size_t i, double energy, double ustar_mean,
                                    double ustar_max, rs_msg *msg)
{
  int status = put_pair(out, out->rev_energy_id, out->rev_ustar_id, i, energy, ustar_mean, msg);
  int err;
  if (status == RS_OK &&
      ((err = nc_put_var1_double(out->ncid, out->rev_ustar_max_id, &i, &ustar_max)) ||
       (err = nc_sync(out->ncid))))
    status = rs_output_nc_failure(msg, out->path, "writing a twin-disc summary", err);
  return status;
}

int rs_output_put_revolution_temperature(rs_output *out, size_t i, const double v[7], rs_msg *msg)
{
  if (!out->has_rig)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "output file %s: no twin-disc variables", out->path);
  int err = NC_NOERR;
  for (int k = 0; k < 7 && !err; k++)
    if (out->rev_temp_id[k] >= 0)
      err = nc_put_var1_double(out->ncid, out->rev_temp_id[k], &i, &v[k]);
  if (err || (err = nc_sync(out->ncid)))
    return rs_output_nc_failure(msg, out->path, "writing a twin-disc summary", err);
  return RS_OK;
}

int rs_output_nc_failure(rs_msg *msg, const char *path, const char *what, int err)
{
  return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: %s: %s", path, what, nc_strerror(err));
}

int rs_output_put_text(int ncid, int varid, const char *name, const char *text)
{
  return nc_put_att_text(ncid, varid, name, strlen(text), text);
}

/* The status attribute text, NUL-padded to its fixed length. */
void rs_output_status_text(char buf[RS_OUTPUT_STATUS_LEN], const char *status)
{
  memset(buf, 0, RS_OUTPUT_STATUS_LEN);
  if (status) {
    size_t n = strlen(status);
    memcpy(buf, status, n < RS_OUTPUT_STATUS_LEN - 1 ? n : RS_OUTPUT_STATUS_LEN - 1);
  }
}

int rs_output_keep_old(const char *path, char *backup, size_t len, rs_msg *msg)
{
  backup[0] = '\0';
  struct stat st;
  if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return RS_OK;
  if ((size_t)snprintf(backup, len, "%s~", path) >= len) {
    backup[0] = '\0';
    return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: name too long", path);
  }
  if (rename(path, backup) != 0) {
    const int e = errno;
    backup[0] = '\0';
    return rs_msg_set(msg, RS_ERR_OUTPUT,
                      "output file %s: cannot keep the existing file as %s~: %s", path, path,
                      strerror(e));
  }
  return RS_OK;
}

int rs_output_commit_part(int nc_err, const char *part, const char *path, int keep_old,
                          char *backup, size_t len, const char *what, rs_msg *msg)
{
  int status = RS_OK;
  if (nc_err) {
    status = rs_output_nc_failure(msg, path, what, nc_err);
    remove(part);
  } else if (keep_old && (status = rs_output_keep_old(path, backup, len, msg)) != RS_OK) {
    remove(part);
  } else if (rename(part, path) != 0) {
    status = rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: cannot rename %s to it", path, part);
    remove(part);
  }
  return status;
}

char *rs_output_get_text(int ncid, int varid, const char *name)
{
  size_t len = 0;
  nc_type type;
  if (nc_inq_att(ncid, varid, name, &type, &len) != NC_NOERR || type != NC_CHAR) len = 0;
  char *text = calloc(len + 1, 1);
  if (text && len && nc_get_att_text(ncid, varid, name, text) != NC_NOERR) text[0] = '\0';
  return text;
}

int rs_output_same_case(int ncid, const char *case_text)
{
  char *text = rs_output_get_text(ncid, NC_GLOBAL, "case");
  const int same = text && !strcmp(text, case_text ? case_text : "");
  free(text);
  return same;
}

const char *rs_output_backup(const rs_output *out)
{
  return out && out->backup[0] ? out->backup : NULL;
}

/* mkdir -p for the directory part of path (results/<case>.nc by default). */
int rs_output_make_parent_dirs(const char *path, rs_msg *msg)
{
  char *dir = strdup(path);
  if (!dir) return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: out of memory", path);
  int status = RS_OK;
  char *slash = strrchr(dir, '/');
  if (slash && slash != dir) {
    *slash = '\0';
    for (char *p = dir + 1;; p++) {
      if (*p != '/' && *p != '\0') continue;
      char saved = *p;
      *p = '\0';
      if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        status = rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: cannot create directory %s: %s",
                            path, dir, strerror(errno));
        break;
      }
      *p = saved;
      if (saved == '\0') break;
    }
  }
  free(dir);
  return status;
}

/* Dimensions, variables and attributes (define mode). Returns a netCDF error code and
 * the name of what failed in *what. */
static int define_file(rs_output *out, const rs_output_spec *spec, const char **what)
{
  const int ncid = out->ncid;
  const int three_d = spec->dimension == 3;
  int err, time_dim, x_dim;

  *what = "defining global attributes";
  if ((err = rs_output_put_text(ncid, NC_GLOBAL, "Conventions", "CF-1.10")) ||
      (err = rs_output_put_text(ncid, NC_GLOBAL, "title", spec->title ? spec->title : "")) ||
      (err = rs_output_put_text(ncid, NC_GLOBAL, "source", "rollsim " RS_VERSION)) ||
      (err = rs_output_put_text(ncid, NC_GLOBAL, "history", spec->history ? spec->history : "")) ||
      (err = rs_output_put_text(ncid, NC_GLOBAL, "case", spec->case_text ? spec->case_text : "")))
    return err;
  if (spec->patch && (err = rs_output_put_text(ncid, NC_GLOBAL, "wheel_rail_patch", spec->patch)))
    return err;
  char status[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(status, "running");
  if ((err = nc_put_att_text(ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, status))) return err;

  *what = "defining dimensions";
  int y_dim = -1;
  if ((err = nc_def_dim(ncid, "time", NC_UNLIMITED, &time_dim)) ||
      (three_d && (err = nc_def_dim(ncid, "y", spec->ny, &y_dim))) ||
      (err = nc_def_dim(ncid, "x", spec->nx, &x_dim)))
    return err;
  if (three_d) {
    const int dim = 3;
    if ((err = nc_put_att_int(ncid, NC_GLOBAL, "dimension", NC_INT, 1, &dim))) return err;
  }
  if (three_d && spec->hertz_a > 0.0 &&
      ((err = nc_put_att_double(ncid, NC_GLOBAL, "hertz_a", NC_DOUBLE, 1, &spec->hertz_a)) ||
       (err = nc_put_att_double(ncid, NC_GLOBAL, "hertz_b", NC_DOUBLE, 1, &spec->hertz_b)) ||
       (err = nc_put_att_double(ncid, NC_GLOBAL, "hertz_load", NC_DOUBLE, 1, &spec->hertz_load))))
    return err;

  if (spec->rtol > 0.0 &&
      (err = nc_put_att_double(ncid, NC_GLOBAL, "solver_rtol", NC_DOUBLE, 1, &spec->rtol)))
    return err;

  *what = "defining coordinate variables";
  if ((err = nc_def_var(ncid, "time", NC_DOUBLE, 1, &time_dim, &out->time_id)) ||
      (err = rs_output_put_text(ncid, out->time_id, "units", "s")) ||
      (err = rs_output_put_text(ncid, out->time_id, "long_name", "time since start")) ||
      (err = rs_output_put_text(ncid, out->time_id, "standard_name", "time")) ||
      (err = rs_output_put_text(ncid, out->time_id, "axis", "T")))
    return err;
  if ((err = nc_def_var(ncid, "x", NC_DOUBLE, 1, &x_dim, &out->x_id)) ||
      (err = rs_output_put_text(ncid, out->x_id, "units", "mm")) ||
      (err = rs_output_put_text(ncid, out->x_id, "long_name", "cell centre, rolling direction")) ||
      (err = rs_output_put_text(ncid, out->x_id, "axis", "X")))
    return err;
  out->y_id = -1;
  if (three_d &&
      ((err = nc_def_var(ncid, "y", NC_DOUBLE, 1, &y_dim, &out->y_id)) ||
       (err = rs_output_put_text(ncid, out->y_id, "units", "mm")) ||
       (err = rs_output_put_text(ncid, out->y_id, "long_name", "cell centre, lateral direction")) ||
       (err = rs_output_put_text(ncid, out->y_id, "axis", "Y"))))
    return err;

  if (spec->rig) {
    *what = "defining the twin-disc summaries";
    if ((err = define_rig(out, spec->rig))) return err;
  }

  /* Fields first, scalars last: the last record variable is a double (see top). */
  *what = "defining field variables";
  const int field_dims[3] = {time_dim, three_d ? y_dim : x_dim, x_dim};
  const int ndims = three_d ? 3 : 2;
  for (int f = 0; f < RS_N_FIELDS; f++) {
    const rs_field_var *fv = &rs_field_vars[f];
    out->field_id[f] = out->field_id2[f] = -1;
    if (!(spec->fields & fv->bit)) continue;
    const nc_type type = f == RS_REGIME_FIELD ? NC_BYTE : NC_DOUBLE;
    int id;
    for (int comp = 0; comp < 2; comp++) {
      const char *name = rs_field_name(f, three_d, comp);
      if (!name) break;
      char long_name[128];
      snprintf(long_name, sizeof long_name, "%s%s", fv->long_name,
               !three_d || !rs_field_is_vector(f) ? ""
               : comp                             ? ", y component"
                                                  : ", x component");
      if ((err = nc_def_var(ncid, name, type, ndims, field_dims, &id)) ||
          (err = rs_output_put_text(ncid, id, "units", fv->units)) ||
          (err = rs_output_put_text(ncid, id, "long_name", long_name)))
        return err;
      if (comp == 1) out->field_id2[f] = id;
    }
    if (three_d && rs_field_is_vector(f)) {
      if ((err = nc_inq_varid(ncid, rs_field_name(f, 1, 0), &id))) return err;
    }
    if (f == RS_REGIME_FIELD) {
      static const signed char flag_values[4] = {0, 1, 2, 3};
      if ((err = nc_put_att_schar(ncid, id, "flag_values", NC_BYTE, 4, flag_values)) ||
          (err = rs_output_put_text(ncid, id, "flag_meanings", "exterior adhesion slip plastic")))
        return err;
    }
    const unsigned asked = spec->requested_fields ? spec->requested_fields : spec->fields;
    if (!(asked & fv->bit) &&
        ((err = rs_output_put_text(ncid, id, "comment",
                                   "not in output.fields: stored for rollsim run --restart")) ||
         (out->field_id2[f] >= 0 &&
          (err = rs_output_put_text(ncid, out->field_id2[f], "comment",
                                    "not in output.fields: stored for rollsim run --restart")))))
      return err;
    out->field_id[f] = id;
  }
  {
    const unsigned asked = spec->requested_fields ? spec->requested_fields : spec->fields;
    char names[192] = "";
    for (int f = 0; f < RS_N_FIELDS; f++)
      if (asked & spec->fields & rs_field_vars[f].bit)
        for (int comp = 0; comp < 2 && rs_field_name(f, three_d, comp); comp++)
          strcat(strcat(names, *names ? " " : ""), rs_field_name(f, three_d, comp));
    if ((err = rs_output_put_text(ncid, NC_GLOBAL, "output_fields", names))) return err;
  }

  *what = "defining scalar variables";
  for (int s = 0; s < RS_N_SCALARS; s++) {
    const rs_scalar_var *sv = &rs_scalar_vars[s];
    int id;
    if ((err = nc_def_var(ncid, sv->name, sv->type, 1, &time_dim, &id)) ||
        (err = rs_output_put_text(ncid, id, "units", three_d ? sv->units_3d : sv->units_2d)) ||
        (err = rs_output_put_text(ncid, id, "long_name", sv->long_name)))
      return err;
    out->scalar_id[s] = id;
  }
  for (int s = 0; s < RS_N_SCALARS_3D; s++) {
    const rs_scalar_var *sv = &rs_scalar_vars_3d[s];
    out->scalar3_id[s] = -1;
    if (!three_d) continue;
    if ((err = nc_def_var(ncid, sv->name, sv->type, 1, &time_dim, &out->scalar3_id[s])) ||
        (err = rs_output_put_text(ncid, out->scalar3_id[s], "units", sv->units_3d)) ||
        (err = rs_output_put_text(ncid, out->scalar3_id[s], "long_name", sv->long_name)))
      return err;
  }

  *what = "defining the temperature variables";
  for (int v = 0; v < RS_N_TEMPERATURE_VARS; v++) {
    const rs_scalar_var *tv = &rs_temperature_vars[v];
    out->temp_id[v] = -1;
    if (!(spec->fields & RS_FIELD_TEMPERATURE)) continue;
    const int field = v < RS_N_TEMPERATURE_FIELDS;
    if ((err = nc_def_var(ncid, tv->name, NC_DOUBLE, field ? ndims : 1,
                          field ? field_dims : &time_dim, &out->temp_id[v])) ||
        (err = rs_output_put_text(ncid, out->temp_id[v], "units",
                                  three_d ? tv->units_3d : tv->units_2d)) ||
        (err = rs_output_put_text(ncid, out->temp_id[v], "long_name", tv->long_name)))
      return err;
  }
  if (spec->error_estimate) {
    *what = "defining the error estimate's variables";
    if ((err = define_errors(out, time_dim, three_d))) return err;
  }
  if (spec->grid_chosen) {
    const int cells[2] = {(int)spec->nx, (int)spec->ny};
    if ((err = nc_put_att_int(ncid, NC_GLOBAL, "grid_cells_used", NC_INT, three_d ? 2 : 1, cells)))
      return err;
  }

  out->modes_id = -1;
  if (spec->temperature_modes > 0) {
    *what = "defining the temperature modes";
    int mode_dim;
    const int dims[4] = {time_dim, 0, three_d ? y_dim : x_dim, x_dim};
    if ((err = nc_def_dim(ncid, "temperature_mode", (size_t)spec->temperature_modes, &mode_dim)))
      return err;
    const int mdims[4] = {dims[0], mode_dim, dims[2], dims[3]};
    if ((err = nc_def_var(ncid, "temperature_modes", NC_DOUBLE, three_d ? 4 : 3, mdims,
                          &out->modes_id)) ||
        (err = rs_output_put_text(ncid, out->modes_id, "units", "W/mm")) ||
        (err = rs_output_put_text(ncid, out->modes_id, "long_name",
                                  "surface temperature modes of body 1, then body 2 (the "
                                  "transient's heat memory, read by --restart)")))
      return err;
    out->nmodes = (size_t)spec->temperature_modes;
  }

  /* Record data are written in full every time: no fill pass needed. */
  int old_fill;
  *what = "setting the fill mode";
  return nc_set_fill(ncid, NC_NOFILL, &old_fill);
}

int rs_output_create(rs_output **outp, const rs_output_spec *spec, rs_msg *msg)
{
  *outp = NULL;
  if (!spec || !spec->path || !*spec->path)
    return rs_msg_set(msg, RS_ERR_OUTPUT, "output file: no path given");
  if (spec->nx == 0 || !spec->x || (spec->dimension != 2 && spec->dimension != 3) ||
      (spec->dimension == 3 && (spec->ny == 0 || !spec->y)))
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "output file %s: invalid grid (nx = %zu, ny = %zu, dimension = %d)",
                      spec->path, spec->nx, spec->ny, spec->dimension);
  /* The file is built under PATH.part and renamed over PATH: never over a device, pipe or
   * directory (as root, `-o /dev/null` would otherwise replace /dev/null). */
  struct stat st;
  if (stat(spec->path, &st) == 0 && !S_ISREG(st.st_mode))
    return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: exists and is not a regular file (%s)",
                      spec->path, S_ISDIR(st.st_mode) ? "a directory" : "a device, pipe or socket");

  rs_output *out = calloc(1, sizeof *out);
  const size_t path_len = strlen(spec->path);
  char *part = malloc(path_len + sizeof ".part");
  if (!out || !part || !(out->path = strdup(spec->path))) {
    free(part);
    if (out) free(out->path);
    free(out);
    return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: out of memory", spec->path);
  }
  memcpy(part, spec->path, path_len);
  memcpy(part + path_len, ".part", sizeof ".part");
  out->nx = spec->nx;
  out->three_d = spec->dimension == 3;
  out->ny = out->three_d ? spec->ny : 1;
  out->fields = spec->fields;

  int status = rs_output_make_parent_dirs(spec->path, msg);
  if (status != RS_OK) {
    free(part);
    free(out->path);
    free(out);
    return status;
  }

  size_t block = RS_IO_BLOCK;
  int err = nc__create(part, NC_CLOBBER | NC_64BIT_OFFSET, 0, &block, &out->ncid);
  if (err != NC_NOERR) {
    status = rs_output_nc_failure(msg, spec->path, "cannot create", err);
    free(part);
    free(out->path);
    free(out);
    return status;
  }
  if (block == 0) block = RS_IO_BLOCK;

  const char *what = "";
  err = define_file(out, spec, &what);
  if (err == NC_NOERR) {
    /* Records start on a multiple of two I/O blocks, beyond the buffer holding numrecs. */
    const size_t h_minfree = RS_HEADER_RESERVE + (spec->case_text ? strlen(spec->case_text) : 0);
    what = "writing the header";
    err = nc__enddef(out->ncid, h_minfree, 4, 0, 2 * block);
  }
  if (err == NC_NOERR) {
    what = "writing x";
    err = nc_put_var_double(out->ncid, out->x_id, spec->x);
  }
  if (err == NC_NOERR && out->three_d) {
    what = "writing y";
    err = nc_put_var_double(out->ncid, out->y_id, spec->y);
  }
  if (err == NC_NOERR && spec->rig) {
    what = "writing the twin-disc protocol";
    err = write_rig_meta(out, spec->rig);
  }
  if (err == NC_NOERR) {
    what = "syncing";
    err = nc_sync(out->ncid);
  }
  if (err != NC_NOERR) {
    status = rs_output_nc_failure(msg, spec->path, what, err);
  } else if ((status = rs_output_keep_old(spec->path, out->backup, sizeof out->backup, msg)) !=
             RS_OK) {
    /* the message says why; the old file is where it was */
  } else if (rename(part, spec->path) != 0) {
    status = rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: cannot rename %s to it: %s",
                        spec->path, part, strerror(errno));
  }
  if (status != RS_OK) {
    (void)nc_close(out->ncid); /* already failing: the first error is the one reported */
    (void)remove(part);
    free(part);
    free(out->path);
    free(out);
    return status;
  }
  free(part);
  *outp = out;
  return RS_OK;
}

/* The array of field f in rec (NULL when the caller has none). */
static const void *field_data(const rs_record *rec, int f)
{
  if (f == RS_REGIME_FIELD) return rec->regime;
  return *(const double *const *)((const char *)rec + rs_field_vars[f].member);
}

int rs_output_write(rs_output *out, const rs_record *rec, rs_msg *msg)
{
  const int ncid = out->ncid;
  const size_t start[3] = {out->records, 0, 0};
  const size_t count[3] = {1, out->three_d ? out->ny : out->nx, out->nx};
  const size_t n = out->nx * out->ny;
  int err;

  /* Refuse before writing anything: a put at index n already makes n+1 the record count
   * netCDF will write on the next sync or close. */
  for (int f = 0; f < RS_N_FIELDS; f++)
    if (out->field_id[f] >= 0 && !field_data(rec, f))
      return rs_msg_set(msg, RS_ERR_INTERNAL, "output file %s: record %zu has no data for field %s",
                        out->path, out->records, rs_field_vars[f].name);
  if (out->temp_id[0] >= 0 && (!rec->T1 || !rec->T2))
    return rs_msg_set(msg, RS_ERR_INTERNAL,
                      "output file %s: record %zu has no surface temperatures", out->path,
                      out->records);

  if (out->modes_id >= 0 && !rec->temperature_modes)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "output file %s: record %zu has no temperature modes",
                      out->path, out->records);

  if ((err = nc_put_var1_double(ncid, out->time_id, start, &rec->time))) goto fail;

  for (int f = 0; f < RS_N_FIELDS; f++) {
    if (out->field_id[f] < 0) continue;
    const void *data = field_data(rec, f);
    err = f == RS_REGIME_FIELD ? nc_put_vara_schar(ncid, out->field_id[f], start, count, data)
                               : nc_put_vara_double(ncid, out->field_id[f], start, count, data);
    if (err) goto fail;
    if (out->field_id2[f] >= 0 &&
        (err = nc_put_vara_double(ncid, out->field_id2[f], start, count, (const double *)data + n)))
      goto fail;
  }

  for (int s = 0; s < RS_N_SCALARS; s++) {
    const rs_scalar_var *sv = &rs_scalar_vars[s];
    const char *member = (const char *)rec + sv->member;
    if (s == RS_TRACTION_SCALAR) {
      const double mu = rec->Fn != 0.0 ? rec->Fx / rec->Fn : 0.0; /* NaN-free */
      err = nc_put_var1_double(ncid, out->scalar_id[s], start, &mu);
    } else if (sv->type == NC_INT) {
      err = nc_put_var1_int(ncid, out->scalar_id[s], start, (const int *)member);
    } else {
      err = nc_put_var1_double(ncid, out->scalar_id[s], start, (const double *)member);
    }
    if (err) goto fail;
  }

  for (int s = 0; s < RS_N_SCALARS_3D; s++)
    if (out->scalar3_id[s] >= 0 &&
        (err =
             nc_put_var1_double(ncid, out->scalar3_id[s], start,
                                (const double *)((const char *)rec + rs_scalar_vars_3d[s].member))))
      goto fail;

  for (int v = 0; v < RS_N_TEMPERATURE_VARS; v++) {
    if (out->temp_id[v] < 0) continue;
    const char *member = (const char *)rec + rs_temperature_vars[v].member;
    err = v < RS_N_TEMPERATURE_FIELDS
              ? nc_put_vara_double(ncid, out->temp_id[v], start, count,
                                   *(const double *const *)member)
              : nc_put_var1_double(ncid, out->temp_id[v], start, (const double *)member);
    if (err) goto fail;
  }
  if (out->has_errors) {
    const double fn = rec->Fn != 0.0 ? fabs(rec->Fn) : NAN;
    const double v[RS_N_ERROR_VARS] = {0.0,
                                       rec->Fx_error,
                                       rec->Fx_error / fn,
                                       rec->Fy_error,
                                       rec->Mz_error,
                                       rec->Fx_extrapolated,
                                       rec->Fn != 0.0 ? rec->Fx_extrapolated / rec->Fn : NAN,
                                       rec->Fy_extrapolated,
                                       rec->Mz_extrapolated};
    if ((err = nc_put_var1_int(ncid, out->error_id[0], start, &rec->error_reliable))) goto fail;
    for (int k = 1; k < RS_N_ERROR_VARS; k++)
      if (out->error_id[k] >= 0 && (err = nc_put_var1_double(ncid, out->error_id[k], start, &v[k])))
        goto fail;
  }

  if (out->modes_id >= 0) {
    const size_t mstart[4] = {out->records, 0, 0, 0};
    const size_t mcount[4] = {1, out->nmodes, out->three_d ? out->ny : out->nx, out->nx};
    if ((err = nc_put_vara_double(ncid, out->modes_id, mstart, mcount, rec->temperature_modes)))
      goto fail;
  }

  /* Data first, then numrecs: one nc_sync does both, in that order (see top). */
  if ((err = nc_sync(ncid))) goto fail;
  out->records++;
  return RS_OK;

fail:
  /* An I/O error (e.g. disk full) part-way: the record may be incomplete on disk. */
  return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: writing record %zu (t = %g s): %s",
                    out->path, out->records, rec->time, nc_strerror(err));
}

size_t rs_output_records(const rs_output *out) { return out ? out->records : 0; }

int rs_output_set_status(rs_output *out, const char *status, rs_msg *msg)
{
  char text[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(text, status);
  /* Same size as before: allowed in data mode, and the header keeps its layout. */
  int err = nc_put_att_text(out->ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, text);
  if (err) return rs_output_nc_failure(msg, out->path, "setting the status attribute", err);
  if ((err = nc_sync(out->ncid)))
    return rs_output_nc_failure(msg, out->path, "syncing the status attribute", err);
  return RS_OK;
}

int rs_output_abandon(rs_output *out, const char *status, rs_msg *msg)
{
  if (!out) return RS_OK;
  (void)nc_close(out->ncid); /* fails again on the pending write; the handle is freed anyway */
  char text[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(text, status);
  int ncid, err = nc_open(out->path, NC_WRITE, &ncid);
  if (!err) {
    err = nc_put_att_text(ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, text);
    const int err2 = nc_close(ncid);
    if (!err) err = err2;
  }
  const int rc =
      err ? rs_output_nc_failure(msg, out->path, "setting the status attribute", err) : RS_OK;
  free(out->path);
  free(out);
  return rc;
}

int rs_output_close(rs_output *out, rs_msg *msg)
{
  if (!out) return RS_OK;
  int status = RS_OK;
  int err = nc_close(out->ncid);
  if (err) status = rs_output_nc_failure(msg, out->path, "closing", err);
  free(out->path);
  free(out);
  return status;
}
