/* Private to the drivers: one continuation line of steady (or transient) points solved
 * in memory with the machinery of rollsim sweep (warm starts, continuation along the
 * rolling input, the same models), for fits and distributed sweeps. */
#ifndef ROLLSIM_SWEEP_LINES_H
#define ROLLSIM_SWEEP_LINES_H

#include <stddef.h>

#include "rollsim/model.h"
#include "rollsim/status.h"

/* The case at case_path with `sets` and key = values[j] for j = 0..n-1, in order (each
 * point warm-started from the previous one). d[j] receives point j's quantities, ok[j]
 * whether it converged (a failed point restarts the line cold). Returns RS_OK, or the
 * status of an input/internal error (message in msg). */
int rs_sweep_line_eval(const char *case_path, const char *const *sets, int nsets, const char *key,
                       const double *values, size_t n, rs_diag *d, int *ok, rs_msg *msg);

#endif
