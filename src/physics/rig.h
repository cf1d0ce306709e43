/* Twin-disc rig memory (docs/model.md §8): the near-surface plastic state (u_pl, u*) that
 * leaves the contact at its trailing edge is carried around the discs and re-enters
 * at the leading edge one revolution later, reduced by a recovery factor.
 *
 * The state leaving the grid at time t is recorded (at every accepted time step) and
 * looked up at t - delay_d for disc d, delay_d = (2 pi R_d - L) / V with L the grid
 * length and V the rolling speed (the slip changes a disc's surface speed by ~s/2,
 * which shifts the return by that fraction of a revolution: neglected). u_pl and u*
 * are relative quantities of the two surfaces; the state is attributed half to each
 * disc surface, so the inflow is recovery * (exit(t - delay_1) + exit(t - delay_2)) / 2
 * (with equal radii: recovery * exit(t - delay)). Before a first revolution is
 * complete, the material entering is fresh (0). */
#ifndef ROLLSIM_RIG_H
#define ROLLSIM_RIG_H

#include <stddef.h>

#include "base/status.h"

typedef struct rs_rig_memory {
  int width;            /* values per sample: the state of the trailing column (2D: u_pl, u*) */
  double delay[2];      /* s, per disc */
  double recovery;      /* fraction of the state kept per revolution, [0, 1] */
  size_t start, n, cap; /* samples [start, n) of the arrays are live */
  double *t;            /* [cap] */
  double *value;        /* [cap][width] */
} rs_rig_memory;

int rs_rig_memory_create(rs_rig_memory *mem, int width, double delay_1, double delay_2,
                         double recovery, rs_msg *msg);
void rs_rig_memory_free(rs_rig_memory *mem);
/* Record the state leaving the contact at time t (width values; t not decreasing; a
 * repeated time replaces the last sample). Samples older than the longest delay are
 * dropped. */
int rs_rig_memory_record(rs_rig_memory *mem, double t, const double *state, rs_msg *msg);
/* State of the material entering the contact at time t (width values). */
void rs_rig_memory_inflow(const rs_rig_memory *mem, double t, double *state);
/* The exit state recorded at time s (width values; linear between samples, 0 before the
 * first sample): the raw record, without recovery or averaging over the discs. */
void rs_rig_memory_exit(const rs_rig_memory *mem, double s, double *state);
/* Longest time step that keeps every lookup inside the recorded past (s). */
double rs_rig_memory_max_step(const rs_rig_memory *mem);

#endif
