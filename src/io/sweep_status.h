/* rollsim status FILE.nc: how far a sweep file got (io/sweep_status.c). */
#ifndef ROLLSIM_SWEEP_STATUS_H
#define ROLLSIM_SWEEP_STATUS_H

#include <stddef.h>
#include <time.h>

#include "base/status.h"

typedef struct rs_sweep_file_status {
  int sweep;              /* 1: a sweep file (the counts below are set) */
  size_t npoints;         /* points of the sweep, or of the part in a part file */
  size_t written, failed; /* of those: points written, and of them not converged */
  int part, parts;        /* --part K/N, or 0 */
  char status[256];       /* the status attribute */
  time_t mtime;           /* the file's last modification */
  int state;              /* RS_SWEEP_COMPLETE, _FAILED or _INCOMPLETE */
  char writer_host[160];  /* the writer attribute's host ("" in files without one) */
  long writer_pid;
  int writer_alive; /* 1 runs, 0 gone (both on this host), -1 cannot be checked */
} rs_sweep_file_status;

enum { RS_SWEEP_COMPLETE, RS_SWEEP_FAILED, RS_SWEEP_INCOMPLETE };

/* Read FILE's state: RS_OK, or RS_ERR_INPUT (message in msg) for a file that cannot be
 * read as a netCDF file of rollsim or is truncated (shorter than its header says; netCDF
 * would read the missing points as zeros). */
int rs_sweep_file_status_read(const char *path, rs_sweep_file_status *st, rs_msg *msg);
/* The one-line summary: "complete: 120 of 120 points", "incomplete: 104 of 120 points
 * (status: running: ...), last written at ...", "failed: ...". */
void rs_sweep_file_status_line(const rs_sweep_file_status *st, char *buf, size_t len);

#endif
