/* Sweep files (docs/file-format.md): one dimension per swept key with a coordinate
 * variable holding its values (name: the dotted key with '_' for '.', attribute `key` =
 * the dotted key, `units` = the key's unit from the key table), the scalar results over
 * those dimensions and, with output.fields, the profiles of every point over (swept
 * keys..., x).
 *
 * Points are written in batches: the points given since the last write are kept in memory
 * and written, each run of consecutive points along the last axis as one hyperslab per
 * variable, then synced, when a point arrives RS_SWEEP_FLUSH_SECONDS or more after the last
 * write, when the batch is full, and at close (also after an interrupt or a failure). A
 * point costs a few system calls per batch instead of a read and a write of a file block
 * for every variable. A killed process (SIGKILL) leaves a readable file with every point
 * but those that arrived less than RS_SWEEP_FLUSH_SECONDS after the last write. As in
 * output.c, a sync is not an fsync: the page cache survives a killed process.
 *
 * Missing values: doubles carry _FillValue NaN (a failed point is NaN too). Integers
 * (cell counts, converged, regime) carry no _FillValue, which would make CF readers such
 * as xarray turn them into floats; instead valid_min (valid_range for flags) excludes the
 * markers: -1 for a failed point, netCDF's default fill for a point not computed. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "io/output_internal.h"
#include "io/case.h"
#include "io/output.h"

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
/* 3D only. */
static const sweep_var sweep_vars_3d[] = {
    {"Fy", "total lateral force on body 1", "F", SW_DOUBLE},
    {"Mz", "spin moment on body 1 about the contact centre", "E", SW_DOUBLE},
    {"lateral_creepage", "lateral creepage", "1", SW_DOUBLE},
    {"spin", "spin creepage", "1/mm", SW_DOUBLE},
    {"hertz_a", "Hertz semi-axis along x (rolling direction) at the point's load", "mm", SW_DOUBLE},
    {"hertz_b", "Hertz semi-axis along y at the point's load", "mm", SW_DOUBLE},
};
#define N_SWEEP_VARS_3D 6
/* With temperature (docs/model.md §18). */
static const sweep_var sweep_vars_t[] = {
    {"T_max", "largest surface temperature in the contact", "degC", SW_DOUBLE},
    {"heat_input_1", "heat flowing into body 1 through its surface", "W", SW_DOUBLE},
    {"heat_input_2", "heat flowing into body 2 through its surface", "W", SW_DOUBLE},
};
#define N_SWEEP_VARS_T 3
#define N_SWEEP_VARS   (sizeof sweep_vars / sizeof sweep_vars[0])
#define CONVERGED_VAR  (N_SWEEP_VARS - 1)

/* netCDF's I/O buffer: a batch goes to the file in writes of this size. */
#define SWEEP_IO_CHUNK    ((size_t)1 << 20)
/* Memory for the points of a batch (the fields' rows dominate). */
#define BATCH_BYTES       (8u << 20)
#define BATCH_MAX         4096
#define N_POINT_DOUBLES   (N_SWEEP_VARS + N_SWEEP_VARS_3D + N_SWEEP_VARS_T)
/* Free bytes left in a new file's header: a resume appends a line to `history`, which
 * then fits without netCDF moving every variable further into the file. */
#define SWEEP_HEADER_FREE 4096

/* The points given since the last write, in the order given. */
typedef struct batch {
  size_t cap, n;
  size_t *index;       /* [cap] flat index of each point */
  double *d;           /* [cap][N_POINT_DOUBLES] the scalars (counts in i) */
  int *i;              /* [cap][N_SWEEP_VARS] */
  int *rank;           /* [cap] */
  double *err;         /* [cap][RS_N_ERROR_VARS - 1] rs_error_var_names after error_reliable */
  int *reliable;       /* [cap] error_reliable */
  double *rows;        /* [RS_N_FIELDS][cap][nx] the stored fields' rows */
  signed char *regime; /* [cap][nx] */
  size_t *order;       /* [cap] the points by index (scratch of a write) */
  double *scratch;     /* [cap * max(nx, 1)] one variable of a run (scratch of a write) */
  double last_write;   /* s, monotonic clock */
} batch;

struct rs_sweep_output {
  int ncid, naxes;
  char *path;
  size_t sizes[NC_MAX_VAR_DIMS];
  int varid[N_SWEEP_VARS];
  int varid3[N_SWEEP_VARS_3D]; /* -1 in 2D */
  int varidt[N_SWEEP_VARS_T];  /* -1 without temperature */
  size_t nx;
  int field_id[RS_N_FIELDS];   /* -1: not stored */
  int rank_id;                 /* -1: not stored (serial sweeps) */
  int err_id[RS_N_ERROR_VARS]; /* rs_error_var_names */
  batch b;
  char backup[1040];
};

static double monotonic_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *unit_of(const sweep_var *v, int dimension)
{
  if (!strcmp(v->units, "F")) return dimension == 3 ? "N" : "N/mm";
  if (!strcmp(v->units, "P")) return dimension == 3 ? "N mm/s" : "N mm/s/mm";
  if (!strcmp(v->units, "E")) return dimension == 3 ? "N mm" : "N mm/mm";
  if (!strcmp(v->units, "W")) return dimension == 3 ? "W" : "W/mm";
  return v->units;
}

/* The coordinate variable of one swept key; a force given per width in 2D (N/mm) is a total
 * force (N) in 3D. */
static int define_axis(int ncid, const char *key, size_t size, int dimension, int *dim, int *coord)
{
  char name[NC_MAX_NAME + 1], long_name[NC_MAX_NAME + 64];
  snprintf(name, sizeof name, "%s", key);
  for (char *p = name; *p; p++)
    if (*p == '.') *p = '_';
  const char *units = rs_case_key_units(key), *note = rs_case_key_unit_note(key);
  if (units && dimension == 3 && !strcmp(units, "N/mm")) units = "N";
  snprintf(long_name, sizeof long_name, "%s%s%s%s", key, *note ? " (" : "", note, *note ? ")" : "");
  int err = nc_def_dim(ncid, name, size, dim);
  if (!err) err = nc_def_var(ncid, name, NC_DOUBLE, 1, dim, coord);
  if (!err) err = rs_output_put_text(ncid, *coord, "key", key);
  if (!err) err = rs_output_put_text(ncid, *coord, "long_name", long_name);
  if (!err) err = rs_output_put_text(ncid, *coord, "units", units ? units : "1");
  return err;
}

/* Profiles: dimension x with its coordinate, one variable per field over (axes..., x). */
static int define_fields(rs_sweep_output *o, const rs_sweep_output_spec *spec, const int *dims,
                         int *x_id)
{
  const int ncid = o->ncid;
  int fdims[NC_MAX_VAR_DIMS], x_dim;
  int err = nc_def_dim(ncid, "x", spec->nx, &x_dim);
  if (!err) err = nc_def_var(ncid, "x", NC_DOUBLE, 1, &x_dim, x_id);
  if (!err) err = rs_output_put_text(ncid, *x_id, "units", "mm");
  if (!err) err = rs_output_put_text(ncid, *x_id, "long_name", "cell centre, rolling direction");
  if (!err) err = rs_output_put_text(ncid, *x_id, "axis", "X");
  for (int a = 0; a < spec->naxes; a++) fdims[a] = dims[a];
  fdims[spec->naxes] = x_dim;
  for (int f = 0; f < RS_N_FIELDS && !err; f++) {
    const rs_field_var *fv = &rs_field_vars[f];
    if (!(spec->fields & fv->bit)) continue;
    const int regime = f == RS_REGIME_FIELD;
    int id;
    err = nc_def_var(ncid, fv->name, regime ? NC_BYTE : NC_DOUBLE, spec->naxes + 1, fdims, &id);
    if (!err) err = rs_output_put_text(ncid, id, "units", fv->units);
    if (!err) err = rs_output_put_text(ncid, id, "long_name", fv->long_name);
    if (!err && regime) {
      static const signed char flag_values[4] = {0, 1, 2, 3};
      err = nc_put_att_schar(ncid, id, "flag_values", NC_BYTE, 4, flag_values);
      if (!err)
        err = rs_output_put_text(ncid, id, "flag_meanings", "exterior adhesion slip plastic");
      if (!err)
        err = nc_put_att_schar(ncid, id, "valid_range", NC_BYTE, 2, (const signed char[]){0, 3});
    } else if (!err) {
      const double fill = NAN;
      err = nc_put_att_double(ncid, id, "_FillValue", NC_DOUBLE, 1, &fill);
    }
    o->field_id[f] = id;
  }
  return err;
}

/* The error estimate's per-point variables (docs/file-format.md). */
static int define_errors(rs_sweep_output *o, const rs_sweep_output_spec *spec, const int *dims)
{
  return rs_output_define_error_vars(o->ncid, spec->naxes, dims, spec->dimension == 3, o->err_id);
}

static void free_output(rs_sweep_output *o)
{
  free(o->path);
  free(o->b.index);
  free(o->b.d);
  free(o->b.i);
  free(o->b.rank);
  free(o->b.err);
  free(o->b.reliable);
  free(o->b.rows);
  free(o->b.regime);
  free(o->b.order);
  free(o->b.scratch);
  free(o);
}

/* The batch's memory: as many points as fit in BATCH_BYTES (at least one). */
static int batch_alloc(batch *b, size_t nx)
{
  const size_t per_point = (RS_N_FIELDS * sizeof(double) + 1) * nx + 256;
  size_t cap = BATCH_BYTES / per_point;
  cap = cap < 1 ? 1 : cap > BATCH_MAX ? BATCH_MAX : cap;
  const size_t row = nx > 0 ? nx : 1;
  b->cap = cap;
  b->index = malloc(cap * sizeof *b->index);
  b->d = malloc(cap * N_POINT_DOUBLES * sizeof *b->d);
  b->i = malloc(cap * N_SWEEP_VARS * sizeof *b->i);
  b->rank = malloc(cap * sizeof *b->rank);
  b->err = malloc(cap * (RS_N_ERROR_VARS - 1) * sizeof *b->err);
  b->reliable = malloc(cap * sizeof *b->reliable);
  b->rows = malloc(RS_N_FIELDS * cap * row * sizeof *b->rows);
  b->regime = malloc(cap * row);
  b->order = malloc(cap * sizeof *b->order);
  b->scratch = malloc(cap * (row > N_POINT_DOUBLES ? row : N_POINT_DOUBLES) * sizeof *b->scratch);
  b->last_write = monotonic_seconds();
  return b->index && b->d && b->i && b->rank && b->err && b->reliable && b->rows && b->regime &&
                 b->order && b->scratch
             ? RS_OK
             : RS_ERR_INTERNAL;
}

/* A writer for spec without its file: path, axes, fields none yet, an empty batch (NULL: out
 * of memory). */
static rs_sweep_output *output_new(const rs_sweep_output_spec *spec)
{
  rs_sweep_output *o = calloc(1, sizeof *o);
  if (!o || !(o->path = strdup(spec->path))) {
    free(o);
    return NULL;
  }
  o->naxes = spec->naxes;
  o->nx = spec->fields ? spec->nx : 0;
  for (int f = 0; f < RS_N_FIELDS; f++) o->field_id[f] = -1;
  for (int k = 0; k < RS_N_ERROR_VARS; k++) o->err_id[k] = -1;
  if (batch_alloc(&o->b, o->nx) != RS_OK) {
    free_output(o);
    return NULL;
  }
  return o;
}

/* The writer attribute: "HOST PID" of the process writing the file, NUL-padded to a fixed
 * length so that a resume rewrites it in place; rollsim status checks whether it still runs. */
static void writer_text(char buf[RS_SWEEP_WRITER_LEN])
{
  char host[RS_SWEEP_WRITER_LEN - 24];
  if (gethostname(host, sizeof host) != 0) snprintf(host, sizeof host, "unknown");
  host[sizeof host - 1] = '\0';
  memset(buf, 0, RS_SWEEP_WRITER_LEN);
  snprintf(buf, RS_SWEEP_WRITER_LEN, "%s %ld", host, (long)getpid());
}

int rs_sweep_output_create(rs_sweep_output **outp, const rs_sweep_output_spec *spec, rs_msg *msg)
{
  *outp = NULL;
  if (spec->naxes < 1 || spec->naxes + 1 > NC_MAX_VAR_DIMS)
    return rs_msg_set(msg, RS_ERR_INTERNAL, "sweep output: %d axes", spec->naxes);
  if (spec->fields && (spec->nx == 0 || !spec->x))
    return rs_msg_set(msg, RS_ERR_INTERNAL, "sweep output: fields without a grid");
  int status = rs_output_make_parent_dirs(spec->path, msg);
  if (status != RS_OK) return status;
  rs_sweep_output *o = output_new(spec);
  if (!o) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  /* The layout is written to PATH.part (netCDF fills every point: the file has its full size
   * from here on) and renamed over PATH, so a full disk leaves no file and the old one kept. */
  char part[sizeof o->backup];
  if ((size_t)snprintf(part, sizeof part, "%s.part", spec->path) >= sizeof part) {
    free_output(o);
    return rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: name too long", spec->path);
  }
  size_t chunk = SWEEP_IO_CHUNK;
  int err = nc__create(part, NC_CLOBBER | NC_64BIT_OFFSET, 0, &chunk, &o->ncid);
  if (err) {
    free_output(o);
    return rs_output_nc_failure(msg, spec->path, "cannot create", err);
  }
  int dims[NC_MAX_VAR_DIMS], coord[NC_MAX_VAR_DIMS], x_id = -1;
  for (int a = 0; a < spec->naxes && !err; a++) {
    o->sizes[a] = (size_t)spec->sizes[a];
    err = define_axis(o->ncid, spec->keys[a], o->sizes[a], spec->dimension, &dims[a], &coord[a]);
  }
  for (size_t v = 0; v < N_SWEEP_VARS && !err; v++) {
    const int is_int = sweep_vars[v].type == SW_INT;
    err = nc_def_var(o->ncid, sweep_vars[v].name, is_int ? NC_INT : NC_DOUBLE, spec->naxes, dims,
                     &o->varid[v]);
    if (!err) err = rs_output_put_text(o->ncid, o->varid[v], "long_name", sweep_vars[v].long_name);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varid[v], "units",
                               unit_of(&sweep_vars[v], spec->dimension));
    if (!err && is_int && v == CONVERGED_VAR)
      err = nc_put_att_int(o->ncid, o->varid[v], "valid_range", NC_INT, 2, (const int[]){0, 1});
    else if (!err && is_int)
      err = nc_put_att_int(o->ncid, o->varid[v], "valid_min", NC_INT, 1, (const int[]){0});
    else if (!err) {
      const double fill = NAN;
      err = nc_put_att_double(o->ncid, o->varid[v], "_FillValue", NC_DOUBLE, 1, &fill);
    }
  }
  for (int v = 0; v < N_SWEEP_VARS_3D; v++) {
    o->varid3[v] = -1;
    if (err || spec->dimension != 3) continue;
    const double fill = NAN;
    err = nc_def_var(o->ncid, sweep_vars_3d[v].name, NC_DOUBLE, spec->naxes, dims, &o->varid3[v]);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varid3[v], "long_name", sweep_vars_3d[v].long_name);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varid3[v], "units",
                               unit_of(&sweep_vars_3d[v], spec->dimension));
    if (!err) err = nc_put_att_double(o->ncid, o->varid3[v], "_FillValue", NC_DOUBLE, 1, &fill);
  }
  for (int v = 0; v < N_SWEEP_VARS_T; v++) {
    o->varidt[v] = -1;
    if (err || !spec->temperature) continue;
    const double fill = NAN;
    err = nc_def_var(o->ncid, sweep_vars_t[v].name, NC_DOUBLE, spec->naxes, dims, &o->varidt[v]);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varidt[v], "long_name", sweep_vars_t[v].long_name);
    if (!err)
      err = rs_output_put_text(o->ncid, o->varidt[v], "units",
                               unit_of(&sweep_vars_t[v], spec->dimension));
    if (!err) err = nc_put_att_double(o->ncid, o->varidt[v], "_FillValue", NC_DOUBLE, 1, &fill);
  }
  if (!err && o->nx) err = define_fields(o, spec, dims, &x_id);
  o->rank_id = -1;
  if (!err && spec->ranks > 0) {
    err = nc_def_var(o->ncid, "rank", NC_INT, spec->naxes, dims, &o->rank_id);
    if (!err)
      err = rs_output_put_text(o->ncid, o->rank_id, "long_name",
                               "MPI rank of the process that computed the point");
    if (!err) err = rs_output_put_text(o->ncid, o->rank_id, "units", "1");
    if (!err) err = nc_put_att_int(o->ncid, o->rank_id, "valid_min", NC_INT, 1, (const int[]){0});
    if (!err) err = nc_put_att_int(o->ncid, NC_GLOBAL, "ranks", NC_INT, 1, &spec->ranks);
  }
  if (!err && spec->error_estimate) err = define_errors(o, spec, dims);
  if (!err && spec->parts > 0) {
    err = nc_put_att_int(o->ncid, NC_GLOBAL, "part", NC_INT, 1, &spec->part);
    if (!err) err = nc_put_att_int(o->ncid, NC_GLOBAL, "parts", NC_INT, 1, &spec->parts);
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
  char writer[RS_SWEEP_WRITER_LEN];
  writer_text(writer);
  if (!err) err = nc_put_att_text(o->ncid, NC_GLOBAL, "writer", RS_SWEEP_WRITER_LEN, writer);
  /* room in the header for the history lines of resumes (rs_sweep_output_resume) */
  if (!err) err = nc__enddef(o->ncid, SWEEP_HEADER_FREE, 1, 0, 1);
  for (int a = 0; a < spec->naxes && !err; a++)
    err = nc_put_var_double(o->ncid, coord[a], spec->values[a]);
  if (!err && o->nx) err = nc_put_var_double(o->ncid, x_id, spec->x);
  if (!err) err = nc_sync(o->ncid);
  o->b.last_write = monotonic_seconds();
  if (err) {
    status = rs_output_nc_failure(msg, spec->path, "cannot write the sweep layout", err);
  } else if ((status = rs_output_keep_old(spec->path, o->backup, sizeof o->backup, msg)) == RS_OK &&
             rename(part, spec->path) != 0) {
    status = rs_msg_set(msg, RS_ERR_OUTPUT, "output file %s: cannot rename %s to it: %s",
                        spec->path, part, strerror(errno));
  }
  if (status != RS_OK) {
    (void)nc_close(o->ncid);
    (void)remove(part);
    free_output(o);
    return status;
  }
  *outp = o;
  return RS_OK;
}

/* Whether the coordinate variable of axis a (or x: key NULL) holds n values equal bit for
 * bit to values. */
static int same_coordinate(int ncid, const char *name, size_t n, const double *values)
{
  int id, dim;
  size_t len;
  if (nc_inq_varid(ncid, name, &id) || nc_inq_dimid(ncid, name, &dim) ||
      nc_inq_dimlen(ncid, dim, &len) || len != n)
    return 0;
  double *v = malloc(n * sizeof *v);
  int same = v && !nc_get_var_double(ncid, id, v) && !memcmp(v, values, n * sizeof *v);
  free(v);
  return same;
}

static int global_int(int ncid, const char *name)
{
  int v = 0;
  return nc_get_att_int(ncid, NC_GLOBAL, name, &v) ? 0 : v;
}

/* Why the file open in ncid cannot be resumed as spec's sweep ("" when it can), and its
 * `converged` (npoints values). */
static void resume_check(int ncid, const rs_sweep_output_spec *spec, int *converged, char *why,
                         size_t len)
{
  why[0] = '\0';
  int id, ndims, dims[NC_MAX_VAR_DIMS];
  if (nc_inq_varid(ncid, "converged", &id) || nc_inq_varid(ncid, "Fx", &ndims) ||
      nc_inq_varndims(ncid, id, &ndims) || ndims != spec->naxes ||
      nc_inq_vardimid(ncid, id, dims)) {
    snprintf(why, len, "not a sweep file of %d swept key%s", spec->naxes,
             spec->naxes == 1 ? "" : "s");
    return;
  }
  if (!rs_output_same_case(ncid, spec->case_text)) {
    snprintf(why, len, "%s", RS_OUTPUT_OTHER_CASE);
    return;
  }
  for (int a = 0; a < spec->naxes; a++) {
    char name[NC_MAX_NAME + 1];
    snprintf(name, sizeof name, "%s", spec->keys[a]);
    for (char *p = name; *p; p++)
      if (*p == '.') *p = '_';
    char dname[NC_MAX_NAME + 1];
    if (nc_inq_dimname(ncid, dims[a], dname) || strcmp(dname, name) ||
        !same_coordinate(ncid, name, (size_t)spec->sizes[a], spec->values[a])) {
      snprintf(why, len, "its swept key %d is not %s with the values of this sweep", a + 1,
               spec->keys[a]);
      return;
    }
  }
  const int part = global_int(ncid, "part"), parts = global_int(ncid, "parts");
  if (part != spec->part || parts != spec->parts) {
    if (parts > 0 && spec->parts > 0)
      snprintf(why, len, "the file is part %d/%d, not %d/%d", part, parts, spec->part, spec->parts);
    else if (parts > 0)
      snprintf(why, len, "the file is part %d/%d of the sweep (resume it with --part %d/%d)", part,
               parts, part, parts);
    else
      snprintf(why, len, "the file is the whole sweep, not part %d/%d", spec->part, spec->parts);
    return;
  }
  int fid;
  if ((nc_inq_varid(ncid, "Fy", &fid) == 0) != (spec->dimension == 3)) {
    snprintf(why, len, "the file is not of a %dD sweep", spec->dimension);
    return;
  }
  if ((nc_inq_varid(ncid, "T_max", &fid) == 0) != (spec->temperature != 0)) {
    snprintf(why, len, "the file %s temperatures, the case %s",
             spec->temperature ? "has no" : "has",
             spec->temperature ? "computes them" : "does not");
    return;
  }
  for (int f = 0; f < RS_N_FIELDS; f++) {
    const int want = spec->fields && (spec->fields & rs_field_vars[f].bit);
    if ((nc_inq_varid(ncid, rs_field_vars[f].name, &fid) == 0) != want ||
        (want && !same_coordinate(ncid, "x", spec->nx, spec->x))) {
      snprintf(why, len, "its profiles (output.fields, x) are not this sweep's");
      return;
    }
  }
  if (nc_get_var_int(ncid, id, converged)) snprintf(why, len, "cannot read its converged variable");
}

int rs_sweep_output_resume(rs_sweep_output **outp, const rs_sweep_output_spec *spec, int *converged,
                           size_t *kept, rs_msg *msg)
{
  *outp = NULL;
  *kept = 0;
  long long data_end = 0, file_size = 0;
  FILE *f = fopen(spec->path, "rb");
  if (!f)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: no such file (run the sweep without --resume)",
                      spec->path);
  fclose(f);
  if (rs_nc_classic_data_end(spec->path, &data_end, &file_size) != 0)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: not a readable sweep file (netCDF 64-bit offset)",
                      spec->path);
  if (file_size < data_end)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "%s: cannot resume: the file is truncated (%lld of %lld bytes)", spec->path,
                      file_size, data_end);
  int ncid;
  int err = nc_open(spec->path, NC_NOWRITE, &ncid);
  if (err)
    return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot resume: %s", spec->path, nc_strerror(err));
  char why[512];
  resume_check(ncid, spec, converged, why, sizeof why);
  nc_close(ncid);
  if (why[0]) return rs_msg_set(msg, RS_ERR_INPUT, "%s: cannot resume: %s", spec->path, why);
  size_t npoints = 1;
  for (int a = 0; a < spec->naxes; a++) npoints *= (size_t)spec->sizes[a];
  for (size_t k = 0; k < npoints; k++) *kept += converged[k] != NC_FILL_INT;

  rs_sweep_output *o = output_new(spec);
  if (!o) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  for (int a = 0; a < spec->naxes; a++) o->sizes[a] = (size_t)spec->sizes[a];
  size_t chunk = SWEEP_IO_CHUNK;
  err = nc__open(spec->path, NC_WRITE, &chunk, &o->ncid);
  for (size_t v = 0; v < N_SWEEP_VARS && !err; v++)
    err = nc_inq_varid(o->ncid, sweep_vars[v].name, &o->varid[v]);
  for (int v = 0; v < N_SWEEP_VARS_3D; v++)
    if (err || spec->dimension != 3 || nc_inq_varid(o->ncid, sweep_vars_3d[v].name, &o->varid3[v]))
      o->varid3[v] = -1;
  for (int v = 0; v < N_SWEEP_VARS_T; v++)
    if (err || !spec->temperature || nc_inq_varid(o->ncid, sweep_vars_t[v].name, &o->varidt[v]))
      o->varidt[v] = -1;
  for (int f = 0; f < RS_N_FIELDS && !err; f++)
    if (!o->nx || nc_inq_varid(o->ncid, rs_field_vars[f].name, &o->field_id[f]))
      o->field_id[f] = -1;
  /* a file of an MPI sweep keeps its rank variable (0 where a serial resume computed) */
  if (err || nc_inq_varid(o->ncid, "rank", &o->rank_id)) o->rank_id = -1;
  for (int k = 0; k < RS_N_ERROR_VARS; k++)
    if (err || !spec->error_estimate || nc_inq_varid(o->ncid, rs_error_var_names[k], &o->err_id[k]))
      o->err_id[k] = -1;
  char *old = err ? NULL : rs_output_get_text(o->ncid, NC_GLOBAL, "history");
  if (!err && !old) err = NC_ENOMEM;
  if (!err) {
    const size_t hl = strlen(old) + strlen(spec->history ? spec->history : "") + 160;
    char *history = malloc(hl);
    if (!history) err = NC_ENOMEM;
    if (!err) {
      char on[48] = "";
      if (spec->ranks > 1) snprintf(on, sizeof on, "; resumed on %d MPI ranks", spec->ranks);
      snprintf(history, hl, "%s%s%s (resumed: %zu of %zu points were there%s)", old,
               *old ? "\n" : "", spec->history ? spec->history : "", *kept, npoints, on);
      char status_buf[RS_OUTPUT_STATUS_LEN];
      rs_output_status_text(status_buf, "running");
      err = nc_redef(o->ncid);
      if (!err) err = rs_output_put_text(o->ncid, NC_GLOBAL, "history", history);
      if (!err)
        err = nc_put_att_text(o->ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, status_buf);
      char writer[RS_SWEEP_WRITER_LEN];
      writer_text(writer);
      if (!err) err = nc_put_att_text(o->ncid, NC_GLOBAL, "writer", RS_SWEEP_WRITER_LEN, writer);
      /* ranks: the most ranks any run of the file had (the rank variable's range) */
      int ranks = 0;
      if (!err && o->rank_id >= 0 && !nc_get_att_int(o->ncid, NC_GLOBAL, "ranks", &ranks) &&
          spec->ranks > ranks)
        err = nc_put_att_int(o->ncid, NC_GLOBAL, "ranks", NC_INT, 1, &spec->ranks);
      if (!err) err = nc__enddef(o->ncid, SWEEP_HEADER_FREE, 1, 0, 1);
      if (!err) err = nc_sync(o->ncid);
    }
    free(history);
  }
  free(old);
  if (err) {
    const int st = rs_output_nc_failure(msg, spec->path, "cannot reopen to resume", err);
    if (o->ncid) nc_close(o->ncid);
    free_output(o);
    return st;
  }
  o->b.last_write = monotonic_seconds();
  *outp = o;
  return RS_OK;
}

const char *rs_sweep_output_backup(const rs_sweep_output *o)
{
  return o && o->backup[0] ? o->backup : NULL;
}

/* Point k of the batch: the scalars, and the rows of the stored fields (NaN / -1 rows
 * where the point has none). */
static void batch_add(rs_sweep_output *o, size_t index, const rs_sweep_point *pt)
{
  batch *b = &o->b;
  const size_t k = b->n++, nx = o->nx;
  b->index[k] = index;
  const double ratio = pt->Fn != 0.0 ? pt->Fx / pt->Fn : NAN;
  const double dv[N_POINT_DOUBLES] = {pt->Fx,
                                      pt->Fn,
                                      ratio,
                                      pt->creepage,
                                      pt->velocity,
                                      0,
                                      0,
                                      0,
                                      0,
                                      pt->frictional_power,
                                      pt->plastic_power,
                                      pt->elastic_energy,
                                      0,
                                      pt->Fy,
                                      pt->Mz,
                                      pt->lateral_creepage,
                                      pt->spin,
                                      pt->hertz_a,
                                      pt->hertz_b,
                                      pt->T_max,
                                      pt->heat_input_1,
                                      pt->heat_input_2};
  const int iv[N_SWEEP_VARS] = {0,
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
  memcpy(b->d + k * N_POINT_DOUBLES, dv, sizeof dv);
  memcpy(b->i + k * N_SWEEP_VARS, iv, sizeof iv);
  b->rank[k] = pt->rank;
  const double ev[RS_N_ERROR_VARS - 1] = {
      pt->Fx_error,        pt->Fn != 0.0 ? pt->Fx_error / fabs(pt->Fn) : NAN,
      pt->Fy_error,        pt->Mz_error,
      pt->Fx_extrapolated, pt->Fn != 0.0 ? pt->Fx_extrapolated / pt->Fn : NAN,
      pt->Fy_extrapolated, pt->Mz_extrapolated};
  memcpy(b->err + k * (RS_N_ERROR_VARS - 1), ev, sizeof ev);
  b->reliable[k] = pt->error_reliable;
  /* in the order of rs_field_vars (the regime's slot unused) */
  const double *rows[RS_N_FIELDS] = {pt->px,    pt->pn,   pt->slip, pt->upl,
                                     pt->ustar, pt->tauc, NULL,     pt->mu};
  for (int f = 0; f < RS_N_FIELDS && nx; f++) {
    if (o->field_id[f] < 0) continue;
    if (f == RS_REGIME_FIELD) {
      if (pt->regime)
        memcpy(b->regime + k * nx, pt->regime, nx);
      else
        memset(b->regime + k * nx, -1, nx);
      continue;
    }
    double *dst = b->rows + ((size_t)f * b->cap + k) * nx;
    if (rows[f])
      memcpy(dst, rows[f], nx * sizeof *dst);
    else
      for (size_t i = 0; i < nx; i++) dst[i] = NAN;
  }
}

/* One variable over a run of len points (order[0..len)) at start: the scalars (field
 * -1: double d[v] or int i[v]; -2: rank) or a field's rows. */
static int put_run(rs_sweep_output *o, const size_t *order, size_t len, const size_t *start,
                   int varid, int field, int v, int is_int)
{
  batch *b = &o->b;
  size_t st[NC_MAX_VAR_DIMS], count[NC_MAX_VAR_DIMS];
  for (int a = 0; a < o->naxes; a++) {
    st[a] = start[a];
    count[a] = 1;
  }
  count[o->naxes - 1] = len;
  if (field >= 0) {
    st[o->naxes] = 0;
    count[o->naxes] = o->nx;
    if (field == RS_REGIME_FIELD) {
      signed char *out = (signed char *)b->scratch;
      for (size_t m = 0; m < len; m++) memcpy(out + m * o->nx, b->regime + order[m] * o->nx, o->nx);
      return nc_put_vara_schar(o->ncid, varid, st, count, out);
    }
    for (size_t m = 0; m < len; m++)
      memcpy(b->scratch + m * o->nx, b->rows + ((size_t)field * b->cap + order[m]) * o->nx,
             o->nx * sizeof *b->scratch);
    return nc_put_vara_double(o->ncid, varid, st, count, b->scratch);
  }
  if (is_int) {
    int *out = (int *)b->scratch;
    for (size_t m = 0; m < len; m++)
      out[m] = field == -2   ? b->rank[order[m]]
               : field == -3 ? b->reliable[order[m]]
                             : b->i[order[m] * N_SWEEP_VARS + (size_t)v];
    return nc_put_vara_int(o->ncid, varid, st, count, out);
  }
  for (size_t m = 0; m < len; m++)
    b->scratch[m] = field == -4 ? b->err[order[m] * (RS_N_ERROR_VARS - 1) + (size_t)v]
                                : b->d[order[m] * N_POINT_DOUBLES + (size_t)v];
  return nc_put_vara_double(o->ncid, varid, st, count, b->scratch);
}

/* Write the batch: its points by index (a point given twice: the later), each run of
 * consecutive indices along the last axis as one hyperslab per variable; then sync. */
static int batch_write(rs_sweep_output *o)
{
  batch *b = &o->b;
  int err = 0;
  for (size_t k = 0; k < b->n; k++) { /* insertion sort, stable (the batch is mostly in order) */
    size_t m = k;
    while (m > 0 && b->index[b->order[m - 1]] > b->index[k]) {
      b->order[m] = b->order[m - 1];
      m--;
    }
    b->order[m] = k;
  }
  const size_t nlast = o->sizes[o->naxes - 1];
  for (size_t r = 0; r < b->n && !err;) {
    const size_t first = b->index[b->order[r]];
    size_t len = 1;
    while (r + len < b->n && b->index[b->order[r + len]] == first + len &&
           (first + len) / nlast == first / nlast)
      len++;
    size_t start[NC_MAX_VAR_DIMS], rest = first;
    for (int a = o->naxes - 1; a >= 0; a--) {
      start[a] = rest % o->sizes[a];
      rest /= o->sizes[a];
    }
    const size_t *order = b->order + r;
    for (size_t v = 0; v < N_SWEEP_VARS && !err; v++)
      err = put_run(o, order, len, start, o->varid[v], -1, (int)v, sweep_vars[v].type == SW_INT);
    for (int v = 0; v < N_SWEEP_VARS_3D && !err; v++)
      if (o->varid3[v] >= 0)
        err = put_run(o, order, len, start, o->varid3[v], -1, (int)N_SWEEP_VARS + v, 0);
    for (int v = 0; v < N_SWEEP_VARS_T && !err; v++)
      if (o->varidt[v] >= 0)
        err = put_run(o, order, len, start, o->varidt[v], -1,
                      (int)N_SWEEP_VARS + N_SWEEP_VARS_3D + v, 0);
    for (int f = 0; f < RS_N_FIELDS && o->nx && !err; f++)
      if (o->field_id[f] >= 0) err = put_run(o, order, len, start, o->field_id[f], f, 0, 0);
    if (!err && o->rank_id >= 0) err = put_run(o, order, len, start, o->rank_id, -2, 0, 1);
    if (!err && o->err_id[0] >= 0) err = put_run(o, order, len, start, o->err_id[0], -3, 0, 1);
    for (int k = 1; k < RS_N_ERROR_VARS && !err; k++)
      if (o->err_id[k] >= 0) err = put_run(o, order, len, start, o->err_id[k], -4, k - 1, 0);
    r += len;
  }
  if (!err && b->n) err = nc_sync(o->ncid);
  b->n = 0;
  b->last_write = monotonic_seconds();
  return err;
}

int rs_sweep_output_write(rs_sweep_output *o, size_t index, const rs_sweep_point *pt, rs_msg *msg)
{
  batch_add(o, index, pt);
  int err = 0;
  if (o->b.n == o->b.cap || monotonic_seconds() - o->b.last_write >= RS_SWEEP_FLUSH_SECONDS)
    err = batch_write(o);
  return err ? rs_output_nc_failure(msg, o->path, "cannot write sweep points", err) : RS_OK;
}

int rs_sweep_output_close(rs_sweep_output *o, const char *status, rs_msg *msg)
{
  if (!o) return RS_OK;
  char buf[RS_OUTPUT_STATUS_LEN];
  rs_output_status_text(buf, status);
  int err = batch_write(o);
  if (!err) err = nc_put_att_text(o->ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, buf);
  int err2 = nc_close(o->ncid);
  int rc = RS_OK;
  if (err || err2) {
    rc = rs_output_nc_failure(msg, o->path, "cannot write the last points", err ? err : err2);
    /* A full disk: the batches written before stay, and the status says so, rewritten in
     * place through a fresh handle (the failed one keeps retrying its write). */
    if (!strncmp(status, "complete", 8) || !strncmp(status, "running", 7)) {
      char why[sizeof msg->text + 16];
      snprintf(why, sizeof why, "failed: %s", msg->text);
      rs_output_status_text(buf, why);
    }
    int ncid;
    if (!nc_open(o->path, NC_WRITE, &ncid)) {
      (void)nc_put_att_text(ncid, NC_GLOBAL, "status", RS_OUTPUT_STATUS_LEN, buf);
      (void)nc_close(ncid);
    }
  }
  free_output(o);
  return rc;
}
