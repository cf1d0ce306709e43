/* Private to the drivers: the sweep over MPI ranks (a task farm over continuation lines;
 * serial sweeps are the farm of one rank) and sweep parts for job arrays (rollsim sweep
 * --part K/N; rollsim merge joins them). */
#ifndef ROLLSIM_SWEEP_DIST_H
#define ROLLSIM_SWEEP_DIST_H

#include "io/case_sweep.h"
#include "study/run.h"
#include "study/sweep.h"
#include "study/mpi_session.h"

typedef struct rs_sweep_dist {
  const rs_mpi *mpi; /* NULL or size 1: no farm */
  int part, parts;   /* --part K/N (1 <= K <= N), or 0 */
  /* --resume: write into the existing file of this sweep (or part), computing only the
   * lines not complete in it (a line with any point missing is computed from its first
   * point: lines start from rest, so it gives the same numbers as in one go). */
  int resume;
  /* Called after each point written (points written so far, of the sweep's), or NULL. */
  void (*progress)(void *ctx, size_t done, size_t total);
  void *progress_ctx;
} rs_sweep_dist;

/* The sweep over MPI ranks, or one part of it. Rank 0 (or the part) writes the file;
 * results and statuses as rs_sweep_run. Every rank calls it. */
int rs_sweep_run_dist(const rs_sweep *s, const rs_case *c, const rs_run_opts *o,
                      const rs_sweep_dist *dist, rs_sweep_result *res, rs_msg *msg);

#endif
