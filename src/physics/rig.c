/* Twin-disc rig memory (physics/rig.h). */
#include "physics/rig.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int rs_rig_memory_create(rs_rig_memory *mem, int width, double delay_1, double delay_2,
                         double recovery, rs_msg *msg)
{
  memset(mem, 0, sizeof *mem);
  mem->width = width;
  mem->delay[0] = delay_1;
  mem->delay[1] = delay_2;
  mem->recovery = recovery;
  mem->cap = 1024;
  mem->t = malloc(mem->cap * sizeof *mem->t);
  mem->value = malloc(mem->cap * (size_t)width * sizeof *mem->value);
  if (width < 1 || !mem->t || !mem->value) {
    rs_rig_memory_free(mem);
    return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc memory");
  }
  return RS_OK;
}

void rs_rig_memory_free(rs_rig_memory *mem)
{
  free(mem->t);
  free(mem->value);
  memset(mem, 0, sizeof *mem);
}

int rs_rig_memory_record(rs_rig_memory *mem, double t, const double *state, rs_msg *msg)
{
  const size_t w = (size_t)mem->width;
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
      memmove(mem->value, mem->value + mem->start * w, live * w * sizeof *mem->value);
      mem->start = 0;
      mem->n = live;
    } else {
      const size_t cap = 2 * mem->cap;
      double *a = realloc(mem->t, cap * sizeof *a);
      if (a) mem->t = a;
      double *b = a ? realloc(mem->value, cap * w * sizeof *b) : NULL;
      if (!b) return rs_msg_set(msg, RS_ERR_INTERNAL, "out of memory for the twin-disc memory");
      mem->value = b;
      mem->cap = cap;
    }
  }
  mem->t[mem->n] = t;
  memcpy(mem->value + mem->n * w, state, w * sizeof *state);
  mem->n++;
  return RS_OK;
}

/* Where the exit state at time s lies among the samples: fresh (no sample at or before
 * s: 0), one sample (at or after the last), or linear between samples lo and lo + 1. */
typedef struct bracket {
  int fresh;
  size_t lo;
  double f; /* weight of sample lo + 1 (0: sample lo alone) */
} bracket;

static bracket find(const rs_rig_memory *mem, double s)
{
  size_t lo = mem->start, hi = mem->n;
  if (hi == lo || s < mem->t[lo]) return (bracket){.fresh = 1};
  if (s >= mem->t[hi - 1]) return (bracket){.lo = hi - 1};
  hi--; /* invariant: t[lo] <= s < t[hi] */
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (mem->t[mid] <= s)
      lo = mid;
    else
      hi = mid;
  }
  return (bracket){.lo = lo, .f = (s - mem->t[lo]) / (mem->t[hi] - mem->t[lo])};
}

/* Component k of the exit state in bracket b (linear between samples). */
static double exit_value(const rs_rig_memory *mem, bracket b, int k)
{
  if (b.fresh) return 0.0;
  const double *a = mem->value + b.lo * (size_t)mem->width;
  if (b.f == 0.0) return a[k];
  return a[k] + b.f * (a[mem->width + k] - a[k]);
}

void rs_rig_memory_inflow(const rs_rig_memory *mem, double t, double *state)
{
  const bracket b0 = find(mem, t - mem->delay[0]), b1 = find(mem, t - mem->delay[1]);
  for (int k = 0; k < mem->width; k++)
    state[k] = mem->recovery * 0.5 * (exit_value(mem, b0, k) + exit_value(mem, b1, k));
}

void rs_rig_memory_exit(const rs_rig_memory *mem, double s, double *state)
{
  const bracket b = find(mem, s);
  for (int k = 0; k < mem->width; k++) state[k] = exit_value(mem, b, k);
}

double rs_rig_memory_max_step(const rs_rig_memory *mem)
{
  return 0.5 * fmin(mem->delay[0], mem->delay[1]);
}
