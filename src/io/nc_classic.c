/* The end of a classic or 64-bit-offset netCDF file's fixed-size data, read from its
 * header (the netCDF classic format specification). netCDF reads bytes past the end of a
 * truncated file as zeros without an error, so a reader that must trust a file's points
 * (rollsim sweep --resume, rollsim status) compares this end with the file's size. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/output_internal.h"

typedef struct hdr {
  const unsigned char *p, *end;
  int offset64; /* CDF-2: 8-byte variable offsets */
  int bad;
} hdr;

static uint64_t get_u(hdr *h, int n)
{
  uint64_t v = 0;
  if (h->end - h->p < n) {
    h->bad = 1;
    return 0;
  }
  for (int k = 0; k < n; k++) v = v << 8 | h->p[k];
  h->p += n;
  return v;
}

static void skip(hdr *h, uint64_t n)
{
  n = (n + 3) / 4 * 4; /* padded to 4 bytes */
  if ((uint64_t)(h->end - h->p) < n)
    h->bad = 1;
  else
    h->p += n;
}

static void skip_name(hdr *h) { skip(h, get_u(h, 4)); }

static int type_size(uint64_t type)
{
  switch (type) {
  case 1:
  case 2: return 1; /* byte, char */
  case 3: return 2; /* short */
  case 4:
  case 5: return 4; /* int, float */
  case 6: return 8; /* double */
  default: return 0;
  }
}

/* An attribute list (ABSENT or NC_ATTRIBUTE nelems [attr...]). */
static void skip_atts(hdr *h)
{
  get_u(h, 4);
  const uint64_t n = get_u(h, 4);
  for (uint64_t k = 0; k < n && !h->bad; k++) {
    skip_name(h);
    const int size = type_size(get_u(h, 4));
    if (!size) h->bad = 1;
    skip(h, get_u(h, 4) * (uint64_t)size);
  }
}

int rs_nc_classic_data_end(const char *path, long long *data_end, long long *file_size)
{
  struct stat st;
  FILE *f = fopen(path, "rb");
  if (!f || fstat(fileno(f), &st) != 0) {
    if (f) fclose(f);
    return -1;
  }
  *file_size = (long long)st.st_size;
  /* the header is at most a few hundred kB (attributes, names) */
  const size_t want = st.st_size < (1 << 22) ? (size_t)st.st_size : (size_t)1 << 22;
  unsigned char *buf = malloc(want ? want : 1);
  const size_t got = buf ? fread(buf, 1, want, f) : 0;
  fclose(f);
  if (!buf || got < 8 || memcmp(buf, "CDF", 3) || (buf[3] != 1 && buf[3] != 2)) {
    free(buf);
    return -1;
  }
  hdr h = {.p = buf + 4, .end = buf + got, .offset64 = buf[3] == 2};
  get_u(&h, 4); /* numrecs */
  get_u(&h, 4); /* dimensions */
  const uint64_t ndims = get_u(&h, 4);
  for (uint64_t k = 0; k < ndims && !h.bad; k++) {
    skip_name(&h);
    get_u(&h, 4);
  }
  skip_atts(&h);
  get_u(&h, 4); /* variables */
  const uint64_t nvars = get_u(&h, 4);
  uint64_t end = (uint64_t)(h.p - buf);
  for (uint64_t k = 0; k < nvars && !h.bad; k++) {
    skip_name(&h);
    const uint64_t nd = get_u(&h, 4);
    for (uint64_t d = 0; d < nd && !h.bad; d++) get_u(&h, 4);
    skip_atts(&h);
    get_u(&h, 4); /* type */
    const uint64_t vsize = get_u(&h, 4), begin = get_u(&h, h.offset64 ? 8 : 4);
    if (begin + vsize > end) end = begin + vsize;
  }
  free(buf);
  if (h.bad) return -1;
  *data_end = (long long)end;
  return 0;
}
