/* Private helpers shared by several modules (util.h). */
#define _POSIX_C_SOURCE 200809L
#include "base/util.h"

#include <time.h>

double rs_wall_clock(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
