/* rs_restart_read (io/restart.h): the state at the last record of an output file.
 * A killed run's file is readable with every record written so far (see output.c), so
 * the last record is always complete. */
#define _POSIX_C_SOURCE 200809L
#include "io/restart.h"
#include "io/output_internal.h"

#include <math.h>
#include <netcdf.h>
#include <stdlib.h>
#include <string.h>

typedef struct state_field {
  const char *name;
  double *dst;
} state_field;

static int nc_fail(rs_msg *msg, const char *path, const char *what, int err)
{
  return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: %s: %s", path, what, nc_strerror(err));
}

/* The coordinate `name` of the file against the case's centres c[len]. */
static int check_coordinate(int ncid, const char *path, const char *name, int three, size_t len,
                            const double *c, rs_msg *msg)
{
  int err, dim, var;
  size_t len_old;
  if ((err = nc_inq_dimid(ncid, name, &dim)) || (err = nc_inq_dimlen(ncid, dim, &len_old)))
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "restart file %s: has no dimension %s (a %s run's file is needed: "
                      "contact.dimension must be that of the old run)",
                      path, name, name[0] == 'y' ? "3D" : "rollsim");
  if (len_old != len)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "restart file %s: its grid has %zu cells%s%s, the case has %zu "
                      "(grid.cells and grid.extent must be those of the old run)",
                      path, len_old, three ? " along " : "", three ? name : "", len);
  double *old = malloc((len ? len : 1) * sizeof *old);
  if (!old) return rs_msg_set(msg, RS_ERR_INTERNAL, "restart file %s: out of memory", path);
  if ((err = nc_inq_varid(ncid, name, &var)) || (err = nc_get_var_double(ncid, var, old))) {
    free(old);
    return nc_fail(msg, path, name[0] == 'y' ? "reading y" : "reading x", err);
  }
  double cmax = 0.0;
  for (size_t i = 0; i < len; i++) cmax = fmax(cmax, fabs(c[i]));
  int status = RS_OK;
  for (size_t i = 0; i < len && status == RS_OK; i++)
    if (!(fabs(old[i] - c[i]) <= 1e-12 * cmax))
      status = rs_msg_set(msg, RS_ERR_INPUT,
                          "restart file %s: its grid differs from the case's: %s[%zu] = %.17g mm "
                          "there, %.17g mm here (grid.cells, grid.extent and the contact size "
                          "must be those of the old run)",
                          path, name, i, old[i], c[i]);
  free(old);
  return status;
}

static int read_file(int ncid, const char *path, const rs_restart_grid *g, double *t_last,
                     double *p, double *upl, double *ustar, double *mu, double *extras, rs_msg *msg)
{
  const int three = g->ncomp == 2;
  const size_t n = g->nx * (three ? g->ny : 1);
  int err, dim_t, dim_y = -1, var, status;
  size_t nrec;
  if ((err = nc_inq_dimid(ncid, "time", &dim_t)) || (err = nc_inq_dimlen(ncid, dim_t, &nrec)))
    return nc_fail(msg, path, "not a rollsim time-history file (dimensions time and x)", err);
  if ((status = check_coordinate(ncid, path, "x", three, g->nx, g->x, msg)) != RS_OK) return status;
  if (three && (status = check_coordinate(ncid, path, "y", three, g->ny, g->y, msg)) != RS_OK)
    return status;
  if (!three && nc_inq_dimid(ncid, "y", &dim_y) == NC_NOERR)
    return rs_msg_set(msg, RS_ERR_INPUT,
                      "restart file %s: is a 3D run's file; the case is 2D (contact.dimension "
                      "must be that of the old run)",
                      path);
  if (three) nc_inq_dimid(ncid, "y", &dim_y);
  int dim_x;
  nc_inq_dimid(ncid, "x", &dim_x);
  if (nrec == 0) return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: holds no records", path);

  const size_t last = nrec - 1;
  if ((err = nc_inq_varid(ncid, "time", &var)) ||
      (err = nc_get_var1_double(ncid, var, &last, t_last)))
    return nc_fail(msg, path, "reading time", err);
  if (!isfinite(*t_last) || *t_last < 0.0)
    return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: invalid time %g s at its last record",
                      path, *t_last);

  /* The state fields and where they go. */
  const state_field fields2[4] = {{"px", p}, {"upl", upl}, {"ustar", ustar}, {"mu", mu}};
  const state_field fields3[6] = {{"px", p},          {"py", p + n},    {"upl_x", upl},
                                  {"upl_y", upl + n}, {"ustar", ustar}, {"mu", mu}};
  const state_field *fields = three ? fields3 : fields2;
  const int memory = g->memory != 0;
  const int nf = (three ? 5 : 3) + memory;
  const char *needed = three ? (memory ? "px, py, upl_x, upl_y, ustar and, with friction memory, mu"
                                       : "px, py, upl_x, upl_y and ustar")
                       : memory ? "px, upl, ustar and, with friction memory, mu"
                                : "px, upl and ustar";
  for (int f = 0; f < nf; f++) {
    const char *name = fields[f].name;
    if ((err = nc_inq_varid(ncid, name, &var)))
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: has no variable '%s' (a restart needs the state "
                        "fields %s: every transient file holds them; a steady run's file only "
                        "what its output.fields lists: add them there)",
                        path, name, needed);
    int ndims, dims[NC_MAX_VAR_DIMS];
    const int want = three ? 3 : 2;
    if ((err = nc_inq_varndims(ncid, var, &ndims)) || ndims != want ||
        (err = nc_inq_vardimid(ncid, var, dims)) || dims[0] != dim_t || dims[want - 1] != dim_x ||
        (three && dims[1] != dim_y))
      return rs_msg_set(msg, RS_ERR_INPUT, "restart file %s: variable '%s' is not a %s field", path,
                        name, three ? "(time, y, x)" : "(time, x)");
    const size_t start[3] = {last, 0, 0};
    const size_t count[3] = {1, three ? g->ny : g->nx, g->nx};
    double *dst = fields[f].dst;
    if ((err = nc_get_vara_double(ncid, var, start, count, dst)))
      return nc_fail(msg, path, name, err);
    for (size_t i = 0; i < n; i++)
      if (!isfinite(dst[i]))
        return rs_msg_set(msg, RS_ERR_INPUT,
                          "restart file %s: %s is not finite at cell %zu of the last record "
                          "(t = %g s)",
                          path, name, i, *t_last);
  }
  static const char *const extra_names[2] = {"creepage", "lateral_creepage"};
  for (int k = 0; k < g->nextra && k < 2; k++)
    if ((err = nc_inq_varid(ncid, extra_names[k], &var)) ||
        (err = nc_get_var1_double(ncid, var, &last, &extras[k])) || !isfinite(extras[k]))
      return rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: no valid %s at its last record (needed to continue "
                        "a run with a prescribed tangential force)",
                        path, extra_names[k]);
  return RS_OK;
}

int rs_restart_read(const char *path, const rs_restart_grid *g, double *t_last, double *p,
                    double *upl, double *ustar, double *mu, double *extras, rs_msg *msg)
{
  if (!path || !*path) return rs_msg_set(msg, RS_ERR_INPUT, "restart: no file given");
  int ncid;
  int err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) return nc_fail(msg, path, "cannot open", err);
  int status = read_file(ncid, path, g, t_last, p, upl, ustar, mu, extras, msg);
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

int rs_restart_read_modes(const char *path, const rs_restart_grid *g, int nmodes, double *modes,
                          rs_msg *msg)
{
  int ncid, dim, var, dim_t, err = nc_open(path, NC_NOWRITE, &ncid);
  if (err) return nc_fail(msg, path, "cannot open", err);
  const size_t ny = g->ncomp == 2 ? g->ny : 1, n = g->nx * ny;
  size_t len = 0, nrec = 0;
  int status = RS_OK;
  if (nc_inq_dimid(ncid, "temperature_mode", &dim) || nc_inq_dimlen(ncid, dim, &len) ||
      nc_inq_varid(ncid, "temperature_modes", &var) || nc_inq_dimid(ncid, "time", &dim_t) ||
      nc_inq_dimlen(ncid, dim_t, &nrec) || nrec == 0)
    status = rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: has no variable 'temperature_modes' (the surface "
                        "temperature's heat memory: a transient run with a temperature: block "
                        "writes it)",
                        path);
  else if (len != (size_t)nmodes)
    status = rs_msg_set(msg, RS_ERR_INPUT,
                        "restart file %s: holds %zu temperature modes per cell, the case has %d "
                        "(temperature.kernel_tolerance and the grid must be those of the old run)",
                        path, len, nmodes);
  if (status == RS_OK) {
    const size_t start[4] = {nrec - 1, 0, 0, 0};
    const size_t count[4] = {1, len, g->ncomp == 2 ? g->ny : g->nx, g->nx};
    if ((err = nc_get_vara_double(ncid, var, start, count, modes)))
      status = nc_fail(msg, path, "reading temperature_modes", err);
  }
  for (size_t i = 0; status == RS_OK && i < (size_t)nmodes * n; i++)
    if (!isfinite(modes[i]))
      status =
          rs_msg_set(msg, RS_ERR_INPUT,
                     "restart file %s: temperature_modes is not finite at its last record", path);
  nc_close(ncid);
  return status;
}
