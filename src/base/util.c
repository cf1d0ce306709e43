/* Private helpers shared by several modules (util.h). */
#define _POSIX_C_SOURCE 200809L
#include "base/util.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <time.h>

double rs_wall_clock(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int rs_thread_num(void)
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

int rs_thread_count(void)
{
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

int rs_threads(int requested)
{
#ifdef _OPENMP
  return requested >= 2 && omp_get_max_threads() >= 2 ? 2 : 1;
#else
  (void)requested;
  return 1;
#endif
}
