/* The command line's heap in transparent huge pages (see cli.h). */
#define _DEFAULT_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
#include <limits.h>
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#define RS_HEAP_HUGE 1
#endif

/* Why: a 3D steady chain touches tens of MiB while it starts (its model, the coarse grids',
 * the near field and its lines), and the first touch of each 4 KiB page is costly; in 2 MiB
 * pages it is some forty times cheaper per byte.
 * How: one arena for every thread (the second thread of a sweep line in two parts otherwise
 * takes memory of its own), the heap grown at once by RESERVE_MIB of address space advised
 * as huge pages, and never given back at its top (it would grow again in small pages):
 * touched memory then arrives 2 MiB at a time, untouched address space costs nothing.
 * The price: every block is carved from that heap, where the coarse grids' blocks, once
 * freed, are not big enough for the fine grid's, and a 2 MiB page counts whole in the
 * resident memory: peak memory is higher on fine grids.
 * Memory beyond the reserve keeps small pages. */
enum { RESERVE_MIB = 1024, DEFAULT_TOP_PAD = 128 * 1024 }; /* mallopt takes an int */

#ifdef RS_HEAP_HUGE
/* Whether the kernel makes huge pages on request ("always" or "madvise"). */
static int huge_pages_offered(void)
{
  FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
  char line[128] = "";
  if (!f) return 0;
  const int ok = fgets(line, sizeof line, f) != NULL;
  fclose(f);
  return ok && !strstr(line, "[never]");
}
#endif

void rs_cli_heap_setup(void)
{
#if defined(RS_HEAP_HUGE) && defined(MADV_HUGEPAGE)
  if (getenv("ROLLSIM_SMALL_PAGES") || !huge_pages_offered()) return;
  const uintptr_t huge = (uintptr_t)2 << 20;
  char *const before = sbrk(0);
  if (before == (char *)-1 || !mallopt(M_ARENA_MAX, 1) || !mallopt(M_TRIM_THRESHOLD, INT_MAX) ||
      !mallopt(M_MMAP_THRESHOLD, 32 << 20) || !mallopt(M_TOP_PAD, RESERVE_MIB << 20))
    return;
  void *volatile probe = malloc(huge); /* grows the heap by the reserve */
  free(probe);
  mallopt(M_TOP_PAD, DEFAULT_TOP_PAD);
  char *const after = sbrk(0);
  const uintptr_t from = ((uintptr_t)before + huge - 1) & ~(huge - 1);
  if (after != (char *)-1 && from + huge <= (uintptr_t)after)
    (void)madvise((void *)from, (uintptr_t)after - from, MADV_HUGEPAGE); /* only a hint */
#endif
}
