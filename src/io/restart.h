/* Restart (issue 4 item 3): read the state of the DAE at the last record of a
 * previous run's netCDF file, to continue from it (`rollsim run CASE --restart OLD.nc`).
 * The state (traction, plastic displacement, accumulated plastic deformation per cell)
 * is taken from the (time, x) fields px, upl and ustar, so the old run must have
 * written all three (output.fields). */
#ifndef ROLLSIM_RESTART_H
#define ROLLSIM_RESTART_H

#include <stddef.h>
#include "base/status.h"

/* The grid and state layout the file must match. */
typedef struct rs_restart_grid {
  size_t nx, ny;       /* cells along x and y (2D: ny = 1) */
  const double *x, *y; /* cell centres, mm [nx], [ny] (2D: y unused) */
  int ncomp;           /* tangential components: 1 (2D) or 2 (3D) */
  int nextra;          /* prescribed-force creepages to read: 0, 1 or 2 */
  int memory;          /* 1: also the friction-memory state, from the field mu */
} rs_restart_grid;

/* Read the last record of the time-history file at path. The file's x (and in 3D y)
 * coordinates must match the new grid: the same counts and every centre within 1e-12
 * relative (to the largest). A file whose status is still "running" (a killed run) is
 * fine: its last complete record is used. On success *t_last is that record's time (s),
 * p and upl [ncomp n] (x components first, then y: px/py, upl_x/upl_y in 3D) and ustar
 * [n] its state, n = nx ny; with g->memory mu [n] the friction-memory state (field mu);
 * extras [nextra] the creepage (and the lateral creepage) of
 * that record (force control). Returns RS_OK or RS_ERR_INPUT (missing or unreadable
 * file, no records, a missing field, a grid mismatch, non-finite values) with a message
 * naming the file. */
int rs_restart_read(const char *path, const rs_restart_grid *g, double *t_last, double *p,
                    double *upl, double *ustar, double *mu, double *extras, rs_msg *msg);

/* The surface temperature's modes at the last record (the variable temperature_modes of a
 * transient run with a temperature: block, docs/file-format.md): nmodes values per cell
 * (2 (K + 1), mode slowest, then y, then x) into modes [nmodes n]. RS_ERR_INPUT with a
 * message naming the file when it has none, another count of modes (the kernel of another
 * grid or temperature.kernel_tolerance), or non-finite values. */
int rs_restart_read_modes(const char *path, const rs_restart_grid *g, int nmodes, double *modes,
                          rs_msg *msg);

/* The history and status attributes of the file at path (malloc'ed; "" when absent),
 * for the history of a run that continues it. RS_ERR_INPUT when it cannot be read. */
int rs_restart_read_provenance(const char *path, char **history, char **status, rs_msg *msg);

#endif
