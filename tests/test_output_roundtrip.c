/* Output round trip: what rs_output writes is what the netCDF C API reads back —
 * every value of every record, the record count, units, flags and global attributes;
 * a field subset leaves the other field variables out; a 3D file has force units N;
 * an existing file is overwritten; missing parent directories are created.
 * Usage: test_output_roundtrip [DIR]  (default test_output_roundtrip.d) */
#define _POSIX_C_SOURCE 200809L

#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/case.h"
#include "io/output.h"
#include "test_support.h"

#ifndef RS_VERSION
#define RS_VERSION "unknown"
#endif

#define NX   7
#define NREC 3
#define ALL_FIELDS                                                                                 \
  (RS_FIELD_PX | RS_FIELD_PN | RS_FIELD_SLIP | RS_FIELD_UPL | RS_FIELD_USTAR | RS_FIELD_TAUC |     \
   RS_FIELD_REGIME)

/* A netCDF call on the reading side that must succeed. */
#define NC(call)                                                                                   \
  do {                                                                                             \
    int nc_err_ = (call);                                                                          \
    if (nc_err_ != NC_NOERR) {                                                                     \
      fprintf(stderr, "%s:%d: %s: %s\n", __FILE__, __LINE__, #call, nc_strerror(nc_err_));         \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

static const char *const case_yaml = "title: round trip\n"
                                     "contact:\n"
                                     "  normal_load: 178.9        # N/mm\n"
                                     "friction:\n"
                                     "  mu: 0.3\n";

/* Field f (0 px, 1 pn, 2 slip, 3 upl, 4 ustar, 5 tauc) of record rec at cell i. */
static double field_value(int f, int rec, int i) { return 10.0 * rec + i + 1000.0 * f; }
static signed char regime_value(int rec, int i) { return (signed char)((rec + i) % 4); }

typedef struct record_data {
  double fields[6][2 * NX]; /* 3D (ny = 1): the y components of px, slip, upl behind */
  signed char regime[NX];
  rs_record rec;
} record_data;

static void make_record(record_data *d, int rec, unsigned mask)
{
  for (int f = 0; f < 6; f++)
    for (int i = 0; i < 2 * NX; i++) d->fields[f][i] = field_value(f, rec, i);
  for (int i = 0; i < NX; i++) d->regime[i] = regime_value(rec, i);
  rs_record *r = &d->rec;
  memset(r, 0, sizeof *r);
  r->time = 0.5 * rec;
  r->Fx = 1.5 + rec;
  r->Fn = rec == 0 ? 0.0 : 100.0 + rec; /* record 0: Fn = 0 -> traction_coefficient 0 */
  r->creepage = -1e-3 * rec;
  r->velocity = 1000.0 + rec;
  r->n_exterior = rec;
  r->n_adhesion = 2 + rec;
  r->n_slip = 3;
  r->n_plastic = 4 + rec;
  r->frictional_power = 0.25 * rec;
  r->plastic_power = 0.125 * rec;
  r->elastic_energy = 0.0625 * rec;
  r->Fy = 7.5 + rec;
  r->Mz = -2.5 * rec;
  r->lateral_creepage = 2e-4;
  r->spin = 1e-5;
  r->px = mask & RS_FIELD_PX ? d->fields[0] : NULL;
  r->pn = mask & RS_FIELD_PN ? d->fields[1] : NULL;
  r->slip = mask & RS_FIELD_SLIP ? d->fields[2] : NULL;
  r->upl = mask & RS_FIELD_UPL ? d->fields[3] : NULL;
  r->ustar = mask & RS_FIELD_USTAR ? d->fields[4] : NULL;
  r->tauc = mask & RS_FIELD_TAUC ? d->fields[5] : NULL;
  r->regime = mask & RS_FIELD_REGIME ? d->regime : NULL;
}

static double cell_x(int i) { return -1.0 + 2.0 * (i + 0.5) / NX; }

/* Create PATH with the given fields and dimension, write nrec records, set status. */
static void write_file(const char *path, unsigned mask, int dimension, int nrec,
                       const char *final_status)
{
  double x[NX];
  const double y[1] = {0.0};
  for (int i = 0; i < NX; i++) x[i] = cell_x(i);
  rs_output_spec spec = {.path = path,
                         .ny = dimension == 3 ? 1 : 0,
                         .y = y,
                         .title = "output round trip",
                         .case_text = case_yaml,
                         .history = "test_output_roundtrip",
                         .dimension = dimension,
                         .nx = NX,
                         .x = x,
                         .fields = mask};
  rs_output *out = NULL;
  rs_msg msg = {{0}};
  int status = rs_output_create(&out, &spec, &msg);
  if (status != RS_OK) {
    fprintf(stderr, "rs_output_create(%s): %d: %s\n", path, status, msg.text);
    exit(1);
  }
  TS_CHECK(rs_output_records(out) == 0, "records after create");
  for (int rec = 0; rec < nrec; rec++) {
    record_data d;
    make_record(&d, rec, mask);
    status = rs_output_write(out, &d.rec, &msg);
    TS_CHECK(status == RS_OK, "write record %d: %s", rec, msg.text);
    TS_CHECK(rs_output_records(out) == (size_t)rec + 1, "records after write %d", rec);
    if (rec == 0) {
      status = rs_output_set_status(out, "failed: something long enough to differ", &msg);
      TS_CHECK(status == RS_OK, "set_status: %s", msg.text);
    }
  }
  status = rs_output_set_status(out, final_status, &msg);
  TS_CHECK(status == RS_OK, "set_status: %s", msg.text);
  status = rs_output_close(out, &msg);
  TS_CHECK(status == RS_OK, "close: %s", msg.text);
}

static void check_text_att(int ncid, int varid, const char *name, const char *expected)
{
  size_t len;
  nc_type type;
  int err = nc_inq_att(ncid, varid, name, &type, &len);
  TS_CHECK(err == NC_NOERR, "attribute %s (varid %d): %s", name, varid, nc_strerror(err));
  if (err != NC_NOERR) return;
  TS_CHECK(type == NC_CHAR, "attribute %s has type %d", name, (int)type);
  char *text = calloc(len + 1, 1);
  NC(nc_get_att_text(ncid, varid, name, text));
  /* text attributes may be NUL-padded (status): compare as C strings */
  TS_CHECK(strcmp(text, expected) == 0, "attribute %s = \"%s\", expected \"%s\"", name, text,
           expected);
  free(text);
}

static void check_var_text(int ncid, const char *var, const char *name, const char *expected)
{
  int varid;
  NC(nc_inq_varid(ncid, var, &varid));
  check_text_att(ncid, varid, name, expected);
}

static size_t dim_len(int ncid, const char *name)
{
  int dimid;
  size_t len;
  NC(nc_inq_dimid(ncid, name, &dimid));
  NC(nc_inq_dimlen(ncid, dimid, &len));
  return len;
}

static double get_scalar(int ncid, const char *name, int rec)
{
  int varid;
  double v;
  const size_t index[1] = {(size_t)rec};
  NC(nc_inq_varid(ncid, name, &varid));
  NC(nc_get_var1_double(ncid, varid, index, &v));
  return v;
}

static const char *const field_names[6] = {"px", "pn", "slip", "upl", "ustar", "tauc"};

static void check_full_file(const char *path)
{
  int ncid, varid;
  NC(nc_open(path, NC_NOWRITE, &ncid));

  int format;
  NC(nc_inq_format(ncid, &format));
  TS_CHECK(format == NC_FORMAT_64BIT_OFFSET, "format %d", format);

  int unlimdim, timedim;
  NC(nc_inq_unlimdim(ncid, &unlimdim));
  NC(nc_inq_dimid(ncid, "time", &timedim));
  TS_CHECK(unlimdim == timedim, "time is the unlimited dimension");
  TS_CHECK(dim_len(ncid, "time") == NREC, "records %zu", dim_len(ncid, "time"));
  TS_CHECK(dim_len(ncid, "x") == NX, "x length %zu", dim_len(ncid, "x"));

  /* global attributes */
  check_text_att(ncid, NC_GLOBAL, "Conventions", "CF-1.10");
  check_text_att(ncid, NC_GLOBAL, "title", "output round trip");
  check_text_att(ncid, NC_GLOBAL, "source", "rollsim " RS_VERSION);
  check_text_att(ncid, NC_GLOBAL, "history", "test_output_roundtrip");
  check_text_att(ncid, NC_GLOBAL, "case", case_yaml);
  check_text_att(ncid, NC_GLOBAL, "status", "complete");

  /* every variable has units and long_name */
  int nvars;
  NC(nc_inq_nvars(ncid, &nvars));
  TS_CHECK(nvars == 2 + 12 + 7, "nvars %d", nvars);
  for (int v = 0; v < nvars; v++) {
    char name[NC_MAX_NAME + 1];
    NC(nc_inq_varname(ncid, v, name));
    TS_CHECK(nc_inq_att(ncid, v, "units", NULL, NULL) == NC_NOERR, "%s has units", name);
    TS_CHECK(nc_inq_att(ncid, v, "long_name", NULL, NULL) == NC_NOERR, "%s has long_name", name);
  }

  /* coordinates */
  check_var_text(ncid, "time", "units", "s");
  check_var_text(ncid, "time", "standard_name", "time");
  check_var_text(ncid, "time", "axis", "T");
  check_var_text(ncid, "x", "units", "mm");
  check_var_text(ncid, "x", "axis", "X");
  double x[NX];
  NC(nc_inq_varid(ncid, "x", &varid));
  NC(nc_get_var_double(ncid, varid, x));
  for (int i = 0; i < NX; i++) TS_CHECK(x[i] == cell_x(i), "x[%d] = %g", i, x[i]);

  /* units of the scalars (2D) and fields */
  check_var_text(ncid, "Fx", "units", "N/mm");
  check_var_text(ncid, "Fn", "units", "N/mm");
  check_var_text(ncid, "traction_coefficient", "units", "1");
  check_var_text(ncid, "velocity", "units", "mm/s");
  check_var_text(ncid, "frictional_power", "units", "N mm/s/mm");
  check_var_text(ncid, "plastic_power", "units", "N mm/s/mm");
  check_var_text(ncid, "elastic_energy", "units", "N mm/mm");
  check_var_text(ncid, "px", "units", "N/mm2");
  check_var_text(ncid, "upl", "units", "mm");

  /* regime: NC_BYTE with CF flags */
  nc_type type;
  size_t len;
  NC(nc_inq_varid(ncid, "regime", &varid));
  NC(nc_inq_vartype(ncid, varid, &type));
  TS_CHECK(type == NC_BYTE, "regime type %d", (int)type);
  NC(nc_inq_att(ncid, varid, "flag_values", &type, &len));
  TS_CHECK(type == NC_BYTE && len == 4, "flag_values type %d len %zu", (int)type, len);
  signed char flags[4] = {-1, -1, -1, -1};
  NC(nc_get_att_schar(ncid, varid, "flag_values", flags));
  for (int k = 0; k < 4; k++) TS_CHECK(flags[k] == k, "flag_values[%d] = %d", k, flags[k]);
  check_text_att(ncid, varid, "flag_meanings", "exterior adhesion slip plastic");

  /* every value of every record */
  for (int rec = 0; rec < NREC; rec++) {
    record_data d;
    make_record(&d, rec, ALL_FIELDS);
    const rs_record *r = &d.rec;
    TS_CHECK(get_scalar(ncid, "time", rec) == r->time, "time[%d]", rec);
    TS_CHECK(get_scalar(ncid, "Fx", rec) == r->Fx, "Fx[%d]", rec);
    TS_CHECK(get_scalar(ncid, "Fn", rec) == r->Fn, "Fn[%d]", rec);
    const double mu = get_scalar(ncid, "traction_coefficient", rec);
    TS_CHECK(mu == (r->Fn != 0.0 ? r->Fx / r->Fn : 0.0), "traction_coefficient[%d] = %g", rec, mu);
    TS_CHECK(get_scalar(ncid, "creepage", rec) == r->creepage, "creepage[%d]", rec);
    TS_CHECK(get_scalar(ncid, "velocity", rec) == r->velocity, "velocity[%d]", rec);
    TS_CHECK(get_scalar(ncid, "n_exterior", rec) == r->n_exterior, "n_exterior[%d]", rec);
    TS_CHECK(get_scalar(ncid, "n_adhesion", rec) == r->n_adhesion, "n_adhesion[%d]", rec);
    TS_CHECK(get_scalar(ncid, "n_slip", rec) == r->n_slip, "n_slip[%d]", rec);
    TS_CHECK(get_scalar(ncid, "n_plastic", rec) == r->n_plastic, "n_plastic[%d]", rec);
    TS_CHECK(get_scalar(ncid, "frictional_power", rec) == r->frictional_power, "fp[%d]", rec);
    TS_CHECK(get_scalar(ncid, "plastic_power", rec) == r->plastic_power, "pp[%d]", rec);
    TS_CHECK(get_scalar(ncid, "elastic_energy", rec) == r->elastic_energy, "ee[%d]", rec);

    const size_t start[2] = {(size_t)rec, 0}, count[2] = {1, NX};
    for (int f = 0; f < 6; f++) {
      double v[NX];
      NC(nc_inq_varid(ncid, field_names[f], &varid));
      NC(nc_get_vara_double(ncid, varid, start, count, v));
      for (int i = 0; i < NX; i++)
        TS_CHECK(v[i] == field_value(f, rec, i), "%s[%d][%d] = %g", field_names[f], rec, i, v[i]);
    }
    signed char regime[NX];
    NC(nc_inq_varid(ncid, "regime", &varid));
    NC(nc_get_vara_schar(ncid, varid, start, count, regime));
    for (int i = 0; i < NX; i++)
      TS_CHECK(regime[i] == regime_value(rec, i), "regime[%d][%d] = %d", rec, i, regime[i]);
  }
  NC(nc_close(ncid));
}

/* Only px and regime: the other field variables are absent, values still right. */
static void check_subset_file(const char *path)
{
  int ncid, varid;
  NC(nc_open(path, NC_NOWRITE, &ncid));
  TS_CHECK(dim_len(ncid, "time") == 2, "records %zu", dim_len(ncid, "time"));
  TS_CHECK(nc_inq_varid(ncid, "px", &varid) == NC_NOERR, "px present");
  TS_CHECK(nc_inq_varid(ncid, "regime", &varid) == NC_NOERR, "regime present");
  for (int f = 1; f < 6; f++)
    TS_CHECK(nc_inq_varid(ncid, field_names[f], &varid) == NC_ENOTVAR, "%s absent", field_names[f]);
  TS_CHECK(nc_inq_varid(ncid, "Fx", &varid) == NC_NOERR, "scalars present");
  double px[NX];
  const size_t start[2] = {1, 0}, count[2] = {1, NX};
  NC(nc_inq_varid(ncid, "px", &varid));
  NC(nc_get_vara_double(ncid, varid, start, count, px));
  for (int i = 0; i < NX; i++) TS_CHECK(px[i] == field_value(0, 1, i), "px[1][%d] = %g", i, px[i]);
  /* a status longer than the attribute is truncated, not rejected */
  char status[RS_OUTPUT_STATUS_LEN + 1];
  size_t len;
  NC(nc_inq_attlen(ncid, NC_GLOBAL, "status", &len));
  TS_CHECK(len == RS_OUTPUT_STATUS_LEN, "status length %zu", len);
  memset(status, 0, sizeof status);
  NC(nc_get_att_text(ncid, NC_GLOBAL, "status", status));
  TS_CHECK(strlen(status) == RS_OUTPUT_STATUS_LEN - 1 && strncmp(status, "failed: ", 8) == 0,
           "truncated status \"%.20s...\" (%zu chars)", status, strlen(status));
  NC(nc_close(ncid));
}

static void check_3d_units(const char *path)
{
  int ncid;
  NC(nc_open(path, NC_NOWRITE, &ncid));
  check_var_text(ncid, "Fx", "units", "N");
  check_var_text(ncid, "Fn", "units", "N");
  check_var_text(ncid, "frictional_power", "units", "N mm/s");
  check_var_text(ncid, "elastic_energy", "units", "N mm");
  check_var_text(ncid, "px", "units", "N/mm2");
  check_var_text(ncid, "Fy", "units", "N");
  check_var_text(ncid, "Mz", "units", "N mm");
  check_var_text(ncid, "slip_y", "units", "1");
  check_text_att(ncid, NC_GLOBAL, "status", "interrupted");
  /* the y components are the second halves of the record's arrays */
  int id, ndims;
  double v;
  const size_t at[3] = {0, 0, 2};
  NC(nc_inq_varid(ncid, "py", &id));
  NC(nc_inq_varndims(ncid, id, &ndims));
  TS_CHECK(ndims == 3, "py has %d dimensions", ndims);
  NC(nc_get_var1_double(ncid, id, at, &v));
  TS_CHECK(v == field_value(0, 0, NX + 2), "py(0, 0, 2) = %g", v);
  NC(nc_inq_varid(ncid, "upl_y", &id));
  NC(nc_get_var1_double(ncid, id, at, &v));
  TS_CHECK(v == field_value(3, 0, NX + 2), "upl_y(0, 0, 2) = %g", v);
  NC(nc_inq_varid(ncid, "Fy", &id));
  NC(nc_get_var1_double(ncid, id, at, &v));
  TS_CHECK(v == 7.5, "Fy(0) = %g", v);
  NC(nc_close(ncid));
}

int main(int argc, char **argv)
{
  const char *dir = argc > 1 ? argv[1] : "test_output_roundtrip.d";
  char full[512], subset[512], three_d[512], part[520];

  /* nested, possibly missing directories: mkdir -p */
  snprintf(full, sizeof full, "%s/deeper/still/full.nc", dir);
  write_file(full, ALL_FIELDS, 2, NREC, "complete");
  check_full_file(full);
  snprintf(part, sizeof part, "%s.part", full);
  TS_CHECK(access(part, F_OK) != 0, "no %s left behind", part);

  /* overwrite: a second run replaces the file (here with fewer records), then again */
  write_file(full, ALL_FIELDS, 2, 1, "running");
  {
    int ncid;
    NC(nc_open(full, NC_NOWRITE, &ncid));
    TS_CHECK(dim_len(ncid, "time") == 1, "overwritten file has %zu records", dim_len(ncid, "time"));
    NC(nc_close(ncid));
  }
  write_file(full, ALL_FIELDS, 2, NREC, "complete");
  check_full_file(full);

  char long_status[2 * RS_OUTPUT_STATUS_LEN];
  memset(long_status, 'x', sizeof long_status - 1);
  long_status[sizeof long_status - 1] = '\0';
  memcpy(long_status, "failed: ", 8);
  snprintf(subset, sizeof subset, "%s/subset.nc", dir);
  write_file(subset, RS_FIELD_PX | RS_FIELD_REGIME, 2, 2, long_status);
  check_subset_file(subset);

  snprintf(three_d, sizeof three_d, "%s/three_d.nc", dir);
  write_file(three_d, ALL_FIELDS, 3, 1, "interrupted");
  check_3d_units(three_d);

  /* close(NULL) is allowed */
  TS_CHECK(rs_output_close(NULL, NULL) == RS_OK, "close(NULL)");

  if (ts_failures) {
    fprintf(stderr, "%d check(s) failed\n", ts_failures);
    return 1;
  }
  printf("test_output_roundtrip: all checks passed\n");
  return 0;
}
