/* Shared by the timing drivers in bench/: the median of repeated timings. */
#ifndef ROLLSIM_BENCH_UTIL_H
#define ROLLSIM_BENCH_UTIL_H

#include <stdlib.h>

static int bench_cmp(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Median of v[0..n-1] (sorts v in place; the lower middle for even n). */
static inline double bench_median(double *v, int n)
{
  qsort(v, (size_t)n, sizeof *v, bench_cmp);
  return v[(n - 1) / 2];
}

#endif
