/* rollsim merge OUT.nc PART.nc...: the parts of a sweep into one file (io/sweep_merge.h). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "io/sweep_merge.h"
#include "cli/cli.h"

#ifndef RS_VERSION
#define RS_VERSION "unknown"
#endif

int rs_cli_merge(int argc, char **argv)
{
  if (argc >= 1 && (!strcmp(argv[0], "--help") || !strcmp(argv[0], "-h"))) {
    rs_cli_help("merge", stdout);
    return RS_OK;
  }
  if (argc < 2) {
    fprintf(stderr, "rollsim merge: usage: rollsim merge OUT.nc PART.nc...\n");
    return RS_ERR_INPUT;
  }
  for (int i = 0; i < argc; i++)
    if (argv[i][0] == '-') {
      fprintf(stderr, "rollsim merge: unknown option '%s'\n", argv[i]);
      return RS_ERR_INPUT;
    }
  char history[2048];
  const time_t now = time(NULL);
  char date[64];
  strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
  int len = snprintf(history, sizeof history, "%s: rollsim %s merge", date, RS_VERSION);
  for (int i = 0; i < argc && len > 0 && (size_t)len < sizeof history; i++)
    len += snprintf(history + len, sizeof history - (size_t)len, " %s", argv[i]);
  rs_sweep_merge_result r;
  rs_msg msg = {{0}};
  const int status =
      rs_sweep_merge(argv[0], (const char *const *)(argv + 1), argc - 1, history, &r, &msg);
  if (status != RS_OK) {
    fprintf(stderr, "rollsim merge: %s\n", msg.text);
    return status;
  }
  printf("merged %d parts: %zu points (%zu solved, %zu failed) into %s%s%s%s\n", r.parts, r.npoints,
         r.points_done, r.points_failed, argv[0], *r.backup ? " (the previous file kept as " : "",
         r.backup, *r.backup ? ")" : "");
  return status;
}
