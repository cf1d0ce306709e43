/* The wheel-rail contact of a case's profiles: block for `rollsim check` (docs/case-file.md
 * "profiles:", docs/model.md §20). */
#ifndef ROLLSIM_WHEEL_RAIL_H
#define ROLLSIM_WHEEL_RAIL_H

#include <signal.h>
#include <stdio.h>

#include "io/case.h"
#include "io/case_sweep.h"
#include "study/run.h"
#include "base/status.h"

/* With profiles.vertical_load: the patches, the load sharing and each patch's normal
 * solution, printed as `key: value  # comment` lines. Nothing without it. */
int rs_wheel_rail_print(const rs_case *c, FILE *out, rs_msg *msg);
/* 1 when the case's contact comes from its profiles (profiles.vertical_load given): the
 * contact: block's derived values (Hertz, the grid) do not describe it. */
int rs_wheel_rail_given(const rs_case *c);

/* rollsim sweep on profiles (rs_sweep.positions): at each wheelset position the patches, the
 * load sharing and each patch's steady tangential solution, written to one file
 * (docs/file-format.md "Wheel-rail sweep files"); with table, one line per position. A position
 * that fails gets NaN and the sweep goes on (RS_ERR_SOLVER at the end, the file's status
 * saying which). */
typedef struct rs_wr_sweep_opts {
  const char *output_path, *history, *case_text;
  FILE *table;                           /* NULL: print nothing */
  volatile sig_atomic_t *interrupt_flag; /* set by a signal: stop after the current position */
} rs_wr_sweep_opts;
typedef struct rs_wr_sweep_result {
  size_t done, failed;
  long newton;
  double wall_seconds;
  char file[1040], backup[1040]; /* the file written ("" if none), where an older one was kept */
} rs_wr_sweep_result;
int rs_wheel_rail_sweep(const rs_case *c, const rs_sweep *sw, const rs_wr_sweep_opts *o,
                        rs_wr_sweep_result *res, rs_msg *msg);

/* rollsim run on profiles: at the block's wheelset position, each loaded patch run as the case
 * says (steady or transient, with its plasticity, friction and temperature) on the patch's
 * model, its file OUT_patchK.nc a 3D run file over the patch's (x, s) (docs/file-format.md);
 * with out, one line per patch. Stops at the first patch that fails. */
typedef struct rs_wr_run_result {
  int patches, runs; /* patches found, patches run */
  long newton, steps;
  /* a moving wheelset (rs_wheel_rail_moving): the records written to file, where an older
   * file of that name was kept */
  size_t records;
  char file[1040], backup[1040];
} rs_wr_run_result;
/* 1 when a transient run moves the wheelset (profiles.lateral_displacement or profiles.yaw
 * a history): rs_wheel_rail_run then writes one file of the sweep file's layout over time
 * (docs/file-format.md "Wheel-rail sweep files"), the geometry updated every output
 * interval. */
int rs_wheel_rail_moving(const rs_case *c);
int rs_wheel_rail_run(const rs_case *c, const rs_run_opts *o, FILE *out, rs_wr_run_result *res,
                      rs_msg *msg);

#endif
