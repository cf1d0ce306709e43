/* rs_restart_read (rollsim/restart.h): the state at the last record of an output file.
 * A killed run's file is readable with every record written so far (see output.c), so
 * the last record is always complete. */
#define _POSIX_C_SOURCE 200809L
#include "rollsim/restart.h"
#include "io/output_internal.h"

#include <math.h>
#include <netcdf.h>
#include <stdlib.h>
#include <string.h>

/* The three state fields. */
static const char *const state_fields[3] = {"px", "upl", "ustar"};

static int nc_fail(rs_msg *msg, const char *path, const char *what, int err)
{
  return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: %s: %s", path, what, nc_strerror(err));
}

static int read_file(int ncid, const char *path, size_t nx, const double *x, double *t_last,
                     double *const state[3], double *creepage, double *xold, rs_msg *msg)
{
  int err, dim_x, dim_t, var;
  size_t len_x, nrec;
  if ((err = nc_inq_dimid(ncid, "x", &dim_x)) || (err = nc_inq_dimlen(ncid, dim_x, &len_x)) ||
      (err = nc_inq_dimid(ncid, "time", &dim_t)) || (err = nc_inq_dimlen(ncid, dim_t, &nrec)))
    return nc_fail(msg, path, "not a rollsim time-history file (dimensions time and x)", err);
  if (len_x != nx)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "restart file %s: its grid has %zu cells, the case has %zu "
                      "(grid.cells and grid.extent must be those of the old run)",
                      path, len_x, nx);
  if (nrec == 0) return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: holds no records", path);

  if ((err = nc_inq_varid(ncid, "x", &var)) || (err = nc_get_var_double(ncid, var, xold)))
    return nc_fail(msg, path, "reading x", err);
  double xmax = 0.0;
  for (size_t i = 0; i < nx; i++) xmax = fmax(xmax, fabs(x[i]));
  for (size_t i = 0; i < nx; i++)
    if (!(fabs(xold[i] - x[i]) <= 1e-12 * xmax))
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: its grid differs from the case's: x[%zu] = %.17g mm "
                        "there, %.17g mm here (grid.cells, grid.extent and the contact size "
                        "must be those of the old run)",
                        path, i, xold[i], x[i]);

  const size_t last = nrec - 1;
  if ((err = nc_inq_varid(ncid, "time", &var)) ||
      (err = nc_get_var1_double(ncid, var, &last, t_last)))
    return nc_fail(msg, path, "reading time", err);
  if (!isfinite(*t_last) || *t_last < 0.0)
    return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: invalid time %g s at its last record",
                      path, *t_last);

  for (int f = 0; f < 3; f++) {
    const char *name = state_fields[f];
    if ((err = nc_inq_varid(ncid, name, &var)))
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: has no variable '%s' (a restart needs the state "
                        "fields px, upl and ustar: every transient file holds them; a steady "
                        "run's file only what its output.fields lists: add %s there)",
                        path, name, name);
    int ndims, dims[NC_MAX_VAR_DIMS];
    if ((err = nc_inq_varndims(ncid, var, &ndims)) || ndims != 2 ||
        (err = nc_inq_vardimid(ncid, var, dims)) || dims[0] != dim_t || dims[1] != dim_x)
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: variable '%s' is not a (time, x) field", path, name);
    const size_t start[2] = {last, 0}, count[2] = {1, nx};
    double *dst = state[f];
    if ((err = nc_get_vara_double(ncid, var, start, count, dst)))
      return nc_fail(msg, path, name, err);
    for (size_t i = 0; i < nx; i++)
      if (!isfinite(dst[i]))
        return rs_msg_set(msg, RS_ERR_INPUT,
                          "restart file %s: %s is not finite at cell %zu of the last record "
                          "(t = %g s)",
                          path, name, i, *t_last);
  }
  if (creepage && ((err = nc_inq_varid(ncid, "creepage", &var)) ||
                   (err = nc_get_var1_double(ncid, var, &last, creepage)) || !isfinite(*creepage)))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "restart file %s: no valid creepage at its last record (needed to continue "
                      "a run with a prescribed tangential force)",
                      path);
  return RS_OK;
}

int rs_restart_read(const char *path, size_t nx, const double *x, double *t_last, double *px,
                    double *upl, double *ustar, double *creepage, rs_msg *msg)
{
  if (!path || !*path) return rs_msg_set(msg, RS_ERR_INPUT, "restart: no file given");
  int ncid;
  int err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) return nc_fail(msg, path, "cannot open", err);
  double *xold = malloc((nx ? nx : 1) * sizeof *xold);
  double *const state[3] = {px, upl, ustar};
  int status = xold ? read_file(ncid, path, nx, x, t_last, state, creepage, xold, msg)
                    : rs_msg_set(msg, RS_ERR_INTERNAL, "restart file %s: out of memory", path);
  free(xold);
  nc_close(ncid);
  return status;
}

int rs_restart_read_provenance(const char *path, char **history, char **status, rs_msg *msg)
{
  *history = *status = NULL;
  int ncid;
  int err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) return nc_fail(msg, path, "cannot open", err);
  *history = rs_output_get_text(ncid, NC_GLOBAL, "history");
  *status = rs_output_get_text(ncid, NC_GLOBAL, "status");
  nc_close(ncid);
  if (!*history || !*status) {
    free(*history);
    free(*status);
    *history = *status = NULL;
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory");
  }
  return RS_OK;
}
