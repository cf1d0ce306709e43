/* Private helpers shared by the time-history writer (output.c) and the sweep
 * writer (output_sweep.c). */
#ifndef ROLLSIM_OUTPUT_INTERNAL_H
#define ROLLSIM_OUTPUT_INTERNAL_H

#include "rollsim/output.h"

/* "output file PATH: WHAT: netCDF message", RS_ERR_OUTPUT. */
int rs_output_nc_failure(rs_msg *msg, const char *path, const char *what, int err);
/* Text attribute without the terminating NUL. */
int rs_output_put_text(int ncid, int varid, const char *name, const char *text);
/* The status attribute text, NUL-padded to its fixed length RS_OUTPUT_STATUS_LEN. */
void rs_output_status_text(char buf[RS_OUTPUT_STATUS_LEN], const char *status);
/* mkdir -p for the directory part of path. */
int rs_output_make_parent_dirs(const char *path, rs_msg *msg);

#endif
