/* Writer for the crash-safety test (tests/check_output_crash.py): writes records in a
 * loop and prints the number of records completed (written and synced) after each one,
 * starting with 0 once the file exists. Every 5th record also rewrites the status
 * attribute, so kills land in header rewrites too. The values are a function of
 * (record, field, cell) that the checker recomputes:
 *   field f (px pn slip upl ustar tauc = 0..5) = 1e4*rec + 1e3*f + i,  regime = (rec+i) % 4
 *   time = 1e-3*rec, Fx = rec + 0.5, Fn = 2*rec + 1, creepage = -1e-6*rec,
 *   velocity = 1000 + rec, n_exterior/adhesion/slip/plastic = rec % 7/11/13/17,
 *   frictional_power = rec/4, plastic_power = rec/8, elastic_energy = rec/16;
 * case = "title: crash test\n" and 100 numbered comment lines (see below).
 * Usage: test_output_crash_writer [PATH [RECORDS [SLEEP_MS [NX]]]]
 * (defaults: test_output_crash_writer.nc 20 0 200) */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "io/case.h"
#include "io/output.h"

#define MAX_NX            1000
#define CASE_FILLER_LINES 100

int main(int argc, char **argv)
{
  const char *path = argc > 1 ? argv[1] : "test_output_crash_writer.nc";
  const long nrec = argc > 2 ? atol(argv[2]) : 20;
  const long sleep_ms = argc > 3 ? atol(argv[3]) : 0;
  const long nx = argc > 4 ? atol(argv[4]) : 200;
  if (nrec < 0 || sleep_ms < 0 || nx < 1 || nx > MAX_NX) {
    fprintf(stderr, "usage: %s [PATH [RECORDS [SLEEP_MS [NX<=%d]]]]\n", argv[0], MAX_NX);
    return 2;
  }

  /* A case text of ~6 kB: the header spans several I/O blocks, as with a real case. */
  static char case_text[8192];
  size_t used = (size_t)snprintf(case_text, sizeof case_text, "title: crash test\n");
  for (int k = 0; k < CASE_FILLER_LINES; k++)
    used += (size_t)snprintf(case_text + used, sizeof case_text - used,
                             "# line %03d of a long case text, so the header spans blocks\n", k);

  static double x[MAX_NX], fields[6][MAX_NX];
  static signed char regime[MAX_NX];
  for (long i = 0; i < nx; i++) x[i] = (double)i;
  rs_output_spec spec = {.path = path,
                         .title = "crash test",
                         .case_text = case_text,
                         .history = "test_output_crash_writer",
                         .dimension = 2,
                         .nx = (size_t)nx,
                         .x = x,
                         .fields = RS_FIELD_PX | RS_FIELD_PN | RS_FIELD_SLIP | RS_FIELD_UPL |
                                   RS_FIELD_USTAR | RS_FIELD_TAUC | RS_FIELD_REGIME};
  rs_output *out;
  rs_msg msg = {{0}};
  if (rs_output_create(&out, &spec, &msg) != RS_OK) {
    fprintf(stderr, "%s\n", msg.text);
    return 1;
  }
  printf("0\n");
  fflush(stdout);

  const struct timespec pause = {sleep_ms / 1000, (sleep_ms % 1000) * 1000000L};
  for (long rec = 0; rec < nrec; rec++) {
    for (int f = 0; f < 6; f++)
      for (long i = 0; i < nx; i++) fields[f][i] = 1e4 * (double)rec + 1e3 * f + (double)i;
    for (long i = 0; i < nx; i++) regime[i] = (signed char)((rec + i) % 4);
    const rs_record r = {.time = 1e-3 * (double)rec,
                         .Fx = (double)rec + 0.5,
                         .Fn = 2.0 * (double)rec + 1.0,
                         .creepage = -1e-6 * (double)rec,
                         .velocity = 1000.0 + (double)rec,
                         .n_exterior = (int)(rec % 7),
                         .n_adhesion = (int)(rec % 11),
                         .n_slip = (int)(rec % 13),
                         .n_plastic = (int)(rec % 17),
                         .frictional_power = (double)rec / 4.0,
                         .plastic_power = (double)rec / 8.0,
                         .elastic_energy = (double)rec / 16.0,
                         .px = fields[0],
                         .pn = fields[1],
                         .slip = fields[2],
                         .upl = fields[3],
                         .ustar = fields[4],
                         .tauc = fields[5],
                         .regime = regime};
    if (rs_output_write(out, &r, &msg) != RS_OK) {
      fprintf(stderr, "%s\n", msg.text);
      return 1;
    }
    printf("%zu\n", rs_output_records(out));
    fflush(stdout);
    if (rec % 5 == 4) {
      char status[64];
      snprintf(status, sizeof status, "running (record %ld)", rec + 1);
      if (rs_output_set_status(out, status, &msg) != RS_OK) {
        fprintf(stderr, "%s\n", msg.text);
        return 1;
      }
    }
    if (sleep_ms > 0) nanosleep(&pause, NULL);
  }
  if (rs_output_set_status(out, "complete", &msg) != RS_OK || rs_output_close(out, &msg) != RS_OK) {
    fprintf(stderr, "%s\n", msg.text);
    return 1;
  }
  return 0;
}
