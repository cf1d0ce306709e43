/* Twin-disc rig memory (rollsim/rig.h). */
#include "rollsim/rig.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rs_rig_memory_create(rs_rig_memory *mem, double delay_1, double delay_2, double recovery,
                         rs_msg *msg)
{
  memset(mem, 0, sizeof *mem);
  mem->delay[0] = delay_1;
  mem->delay[1] = delay_2;
  mem->recovery = recovery;
  mem->cap = 1024;
  mem->t = malloc(mem->cap * sizeof *mem->t);
  mem->upl = malloc(mem->cap * sizeof *mem->upl);
  mem->ustar = malloc(mem->cap * sizeof *mem->ustar);
  if (!mem->t || !mem->upl || !mem->ustar) {
    rs_rig_memory_free(mem);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc memory");
  }
  return RS_OK;
}

void rs_rig_memory_free(rs_rig_memory *mem)
{
  free(mem->t);
  free(mem->upl);
  free(mem->ustar);
  memset(mem, 0, sizeof *mem);
}

int rs_rig_memory_record(rs_rig_memory *mem, double t, double upl, double ustar, rs_msg *msg)
{
  if (mem->n > mem->start && t <= mem->t[mem->n - 1]) {
    /* the same time again (a restart at a breakpoint) or an earlier one: replace */
    while (mem->n > mem->start && t < mem->t[mem->n - 1]) mem->n--;
    if (mem->n > mem->start && t == mem->t[mem->n - 1]) mem->n--;
  }
  /* Drop samples no lookup can reach any more (keep one before the oldest lookup). */
  const double oldest = t - fmax(mem->delay[0], mem->delay[1]);
  while (mem->n - mem->start >= 2 && mem->t[mem->start + 1] < oldest) mem->start++;
  if (mem->n == mem->cap) {
    if (mem->start > mem->cap / 2) { /* compact */
      const size_t live = mem->n - mem->start;
      memmove(mem->t, mem->t + mem->start, live * sizeof *mem->t);
      memmove(mem->upl, mem->upl + mem->start, live * sizeof *mem->upl);
      memmove(mem->ustar, mem->ustar + mem->start, live * sizeof *mem->ustar);
      mem->start = 0;
      mem->n = live;
    } else {
      const size_t cap = 2 * mem->cap;
      double *a = realloc(mem->t, cap * sizeof *a);
      if (a) mem->t = a;
      double *b = a ? realloc(mem->upl, cap * sizeof *b) : NULL;
      if (b) mem->upl = b;
      double *c = b ? realloc(mem->ustar, cap * sizeof *c) : NULL;
      if (!c)
        return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc memory");
      mem->ustar = c;
      mem->cap = cap;
    }
  }
  mem->t[mem->n] = t;
  mem->upl[mem->n] = upl;
  mem->ustar[mem->n] = ustar;
  mem->n++;
  return RS_OK;
}

/* Recorded exit state at time s, linear between samples; fresh (0) before the first
 * sample, the last sample after it. */
static void exit_state(const rs_rig_memory *mem, double s, double *upl, double *ustar)
{
  size_t lo = mem->start, hi = mem->n;
  if (hi == lo || s < mem->t[lo]) {
    *upl = *ustar = 0.0;
    return;
  }
  if (s >= mem->t[hi - 1]) {
    *upl = mem->upl[hi - 1];
    *ustar = mem->ustar[hi - 1];
    return;
  }
  hi--; /* invariant: t[lo] <= s < t[hi] */
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (mem->t[mid] <= s)
      lo = mid;
    else
      hi = mid;
  }
  const double w = (s - mem->t[lo]) / (mem->t[hi] - mem->t[lo]);
  *upl = mem->upl[lo] + w * (mem->upl[hi] - mem->upl[lo]);
  *ustar = mem->ustar[lo] + w * (mem->ustar[hi] - mem->ustar[lo]);
}

void rs_rig_memory_inflow(const rs_rig_memory *mem, double t, double *upl, double *ustar)
{
  double u[2], s[2];
  for (int d = 0; d < 2; d++) exit_state(mem, t - mem->delay[d], &u[d], &s[d]);
  *upl = mem->recovery * 0.5 * (u[0] + u[1]);
  *ustar = mem->recovery * 0.5 * (s[0] + s[1]);
}

double rs_rig_memory_max_step(const rs_rig_memory *mem)
{
  return 0.5 * fmin(mem->delay[0], mem->delay[1]);
}
