/* rollsim merge OUT.nc PART.nc...: join the parts of a sweep (rollsim sweep --part K/N,
 * for job arrays) into the file the whole sweep would have written. */
#ifndef ROLLSIM_SWEEP_MERGE_H
#define ROLLSIM_SWEEP_MERGE_H

#include <stddef.h>

#include "base/status.h"

typedef struct rs_sweep_merge_result {
  size_t npoints, points_done, points_failed;
  int parts;
  char backup[1040]; /* an older OUT.nc kept under this name, or "" */
} rs_sweep_merge_result;

/* Checks: every part is a part (attributes part, parts) of the same case (equal case
 * text) and of the same N, each part once, and together they hold every point exactly
 * once; otherwise RS_ERR_INPUT naming the files, or the missing points with their swept
 * values, and nothing is written. */
int rs_sweep_merge(const char *out_path, const char *const *parts, int nparts, const char *history,
                   rs_sweep_merge_result *res, rs_msg *msg);

#endif
