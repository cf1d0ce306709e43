/* Restart (issue 4 item 3): read the state of the DAE at the last record of a
 * previous run's netCDF file, to continue from it (`rollsim run CASE --restart OLD.nc`).
 * The state (traction, plastic displacement, accumulated plastic deformation per cell)
 * is taken from the (time, x) fields px, upl and ustar, so the old run must have
 * written all three (output.fields). */
#ifndef ROLLSIM_RESTART_H
#define ROLLSIM_RESTART_H

#include <stddef.h>
#include "rollsim/status.h"

/* Read the last record of the time-history file at path. The file's x coordinate must
 * match the new grid: nx cells and every x within 1e-12 relative (to max |x|). A file
 * whose status is still "running" (a killed run) is fine: its last complete record is
 * used. On success *t_last is that record's time (s) and px, upl, ustar [nx] its
 * state; if creepage is not NULL, the creepage of that record too (force control).
 * Returns RS_OK or RS_ERR_INPUT (missing or unreadable file, no records, a missing
 * field, a grid mismatch, non-finite values) with a message naming the file. */
int rs_restart_read(const char *path, size_t nx, const double *x, double *t_last, double *px,
                    double *upl, double *ustar, double *creepage, rs_msg *msg);

/* The history and status attributes of the file at path (malloc'ed; "" when absent),
 * for the history of a run that continues it. RS_ERR_INPUT when it cannot be read. */
int rs_restart_read_provenance(const char *path, char **history, char **status, rs_msg *msg);

#endif
